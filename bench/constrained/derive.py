"""SymPy's side of the constrained bench: derive each model of `models.py`
with `KanesMethod` (its constraints, dependent coordinates and speeds), emit
the C of its state derivative with SymPy's common-subexpression elimination
and C printer, count its operations, and draw random consistent states.

    python derive.py OUTDIR [MODEL ...]      (default: all three models)

Writes, for each model, into OUTDIR/MODEL/:
  rhs.c        void MODEL_rhs(const double *x, const double *p, double *dx)
               (and MODEL_eval, steps 1 and 2 below without the solve)
  derive.json  sizes, names, timings of each step, operation counts
  states.bin   NS random consistent states (float64, autosim's state order)
  params.bin   the parameter values, in the order of p

The C function does what autosim's generated `derivatives()` does, for the
same state x = [every coordinate, the independent speeds] (autosim's
STATE_NAMES) and the same output dx = [dq/dt of every coordinate, du/dt of the
independent speeds]:
  1. the dependent speeds from the velocity constraints, u_dep = A(q) u_ind
     (KanesMethod's A_rs, solved symbolically by KanesMethod);
  2. KanesMethod's mass matrix M (n x n: the dynamical equations of the
     independent speeds stacked on the time derivatives of the velocity
     constraints) and forcing f at (q, u), and dq/dt from the kinematic
     equations (kindiffdict);
  3. M du/dt = f solved numerically (LU with partial pivoting, lu.h) for
     every speed's du/dt; the independent ones are returned.
Steps 1 and 2 are one `sympy.cse` over every expression of step 2 with step
1's expressions in place of the dependent speeds, printed by SymPy's C99
printer (`sympy.ccode`), as pydy's C generator does. Parameters
are symbols, read from p at run time (as autosim's are; neither tool folds
the default values into the code).
"""

import json
from collections.abc import Callable
from typing import Any
import os
import sys
import time

import numpy as np
import sympy as sm
import sympy.physics.mechanics as me

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from models import MODELS, T, Model  # noqa: E402

NS = 1000  # states, as bench/peers
SEED = 20261203


def log(t0: float, msg: str) -> None:
    print(f"[{time.perf_counter() - t0:8.1f} s] {msg}", flush=True)


def c_name(s: sm.Basic) -> str:
    return str(s).replace("(t)", "")


def derive(model: Model, t0: float) -> dict[str, Any]:
    """KanesMethod's equations, as plain-symbol expressions."""
    times = {}
    t = time.perf_counter()
    kane = me.KanesMethod(
        model.frame,
        q_ind=model.q_ind,
        u_ind=model.u_ind,
        kd_eqs=model.kd,
        q_dependent=model.q_dep,
        configuration_constraints=model.config_con,
        u_dependent=model.u_dep,
        velocity_constraints=model.vel_con,
        **model.kane_options,
    )
    kane.kanes_equations(model.bodies, model.loads)
    M, f = kane.mass_matrix, kane.forcing
    times["kanes_equations_s"] = time.perf_counter() - t
    log(t0, f"{model.name}: Kane's equations, M {M.shape}")
    u_all = list(kane.u)  # u_ind then u_dep
    assert u_all[: len(model.u_ind)] == model.u_ind
    vel = sm.Matrix(model.vel_con)
    assert vel.subs({s: 0 for s in u_all}) == sm.zeros(
        len(model.vel_con), 1
    ), "velocity constraints with a term free of the speeds"
    # KanesMethod's own solution of the velocity constraints: u_dep = A_rs u_ind
    udep = kane._Ars * sm.Matrix(model.u_ind)
    kdd = kane.kindiffdict()
    qdot = [kdd[q.diff(T)] for q in model.state_q]
    # plain symbols: s_<state>, s_<dependent speed>, p_<parameter>
    sub = {s: sm.Symbol("s_" + c_name(s)) for s in model.state_q + u_all}
    sub |= {p: sm.Symbol("p_" + str(p)) for p in model.params}
    return dict(
        udep=[e.xreplace(sub) for e in udep],
        M=M.xreplace(sub),
        f=f.xreplace(sub),
        qdot=[e.xreplace(sub) for e in qdot],
        u_all=u_all,
        sub=sub,
        kane=kane,
        times=times,
    )


def lu_flops(n: int) -> dict[str, int]:
    """Operations of lu.h's solve of an n x n system."""
    adds = muls = divs = 0
    for k in range(n):
        rows = n - k - 1
        divs += rows
        muls += rows * (rows + 1)
        adds += rows * (rows + 1)
    for i in range(n):
        muls += n - 1 - i
        adds += n - 1 - i
        divs += 1
    return dict(adds=adds, muls=muls, divs=divs, total=adds + muls + divs)


def ops(pairs: list[tuple[sm.Symbol, sm.Expr]], exprs: list[sm.Expr]) -> int:
    return int(sum(sm.count_ops(e) for _, e in pairs) + sum(sm.count_ops(e) for e in exprs))


def emit_c(model: Model, eq: dict[str, Any], t0: float) -> tuple[str, dict[str, int], dict[str, float]]:
    """The C source of MODEL_eval (steps 1 and 2: M, f and dq/dt) and
    MODEL_rhs (MODEL_eval and step 3, the solve), and its operation counts."""
    n = eq["M"].shape[0]
    nq = len(model.state_q)
    ni = len(model.u_ind)
    times = {}
    lines = [
        f"/* {model.name}: generated by bench/constrained/derive.py with SymPy {sm.__version__} */",
        "#include <math.h>",
        '#include "lu.h"',
        "",
        f"void {model.name}_eval(const double *x, const double *p, double *M, double *f, double *dx) {{",
    ]
    for i, s in enumerate(model.state_q + model.u_ind):
        lines.append(f"  const double s_{c_name(s)} = x[{i}];")
    for i, p in enumerate(model.params):
        lines.append(f"  const double p_{p} = p[{i}];")
    # one cse over M, f and dq/dt with the dependent speeds' expressions in
    # place of their symbols (one pass, as pydy's generator: the
    # trigonometric calls and the dependent speeds are computed once)
    udep = {eq["sub"][s]: e for s, e in zip(model.u_dep, eq["udep"])}
    exprs = [e.xreplace(udep) for e in list(eq["M"]) + list(eq["f"]) + eq["qdot"]]
    t = time.perf_counter()
    rep, red = sm.cse(exprs, symbols=sm.numbered_symbols("a"))
    times["cse_s"] = time.perf_counter() - t
    log(t0, f"{model.name}: cse {times['cse_s']:.1f} s")
    for s, e in rep:
        lines.append(f"  const double {s} = {sm.ccode(e, standard='C99')};")
    for k, e in enumerate(red):
        target = f"M[{k}]" if k < n * n else f"f[{k - n * n}]" if k < n * n + n else f"dx[{k - n * n - n}]"
        lines.append(f"  {target} = {sm.ccode(e, standard='C99')};")
    # 3. M du/dt = f; the independent speeds come first in KanesMethod's u
    lines += [
        "}",
        "",
        f"void {model.name}_rhs(const double *x, const double *p, double *dx) {{",
        f"  double M[{n * n}], f[{n}], du[{n}];",
        f"  {model.name}_eval(x, p, M, f, dx);",
        f"  lu_solve({n}, M, f, du);",
    ]
    for i in range(ni):
        lines.append(f"  dx[{nq + i}] = du[{i}];")
    lines.append("}")
    counted = dict(
        after_cse=ops(rep, red),
        lu_solve=lu_flops(n)["total"],
        # without the substitution (which copies the dependent
        # speeds' trees into every use)
        before_cse=int(sum(sm.count_ops(e) for e in eq["udep"] + list(eq["M"]) + list(eq["f"]) + eq["qdot"])),
    )
    counted["total"] = counted["after_cse"] + counted["lu_solve"]
    counted["pow_calls"] = sum("pow(" in line for line in lines)
    return "\n".join(lines) + "\n", counted, times


def lambdified(model: Model, eq: dict[str, Any], exprs: sm.Matrix) -> Callable[..., Any]:
    args = [eq["sub"][s] for s in model.state_q] + [sm.Symbol("p_" + str(p)) for p in model.params]
    return sm.lambdify(args, exprs, "numpy")


def consistent_states(model: Model, eq: dict[str, Any], rng: np.random.Generator) -> np.ndarray:
    """NS states [q, u_ind] whose dependent coordinates close the configuration
    constraints (Newton to 1e-14 from a first guess on the assembly branch);
    the speeds need nothing: the dependent ones are solved inside both tools."""
    sub = eq["sub"]
    con = (
        sm.Matrix(model.config_con)
        .xreplace(sub)
        .xreplace({p: sm.Symbol("p_" + str(p)) for p in model.params})
    )
    jac = con.jacobian([sub[q] for q in model.q_dep])
    con_f, jac_f = lambdified(model, eq, con), lambdified(model, eq, jac)
    names = [c_name(q) for q in model.state_q]
    dep = [names.index(c_name(q)) for q in model.q_dep]
    pv = model.values
    states = np.zeros((NS, len(names) + len(model.u_ind)))
    for s in range(NS):
        x = draw(model.name, rng, pv)
        q = x[: len(names)]
        for _ in range(50):
            r = np.asarray(con_f(*q, *pv), float).ravel()
            if np.max(np.abs(r)) < 1e-15:
                break
            q[dep] -= np.linalg.solve(np.asarray(jac_f(*q, *pv), float), r)
        res = np.max(np.abs(np.asarray(con_f(*q, *pv), float)))
        assert res < 1e-14, f"{model.name}: state {s} not assembled ({res:.1e})"
        states[s] = x
    return states


def draw(name: str, rng: np.random.Generator, pv: list[float]) -> np.ndarray:
    """One random state with a first guess of the dependent coordinates."""
    if name == "four_bar":
        L0, L1, L2, L3 = pv[:4]
        q1 = rng.uniform(-np.pi, np.pi)
        # the branch of four_bar.md: the coupler tip E left of the line from
        # the crank tip B to the ground pin D (circle intersection)
        B = L1 * np.array([np.cos(q1), np.sin(q1)])
        D = np.array([L0, 0.0])
        d = np.linalg.norm(D - B)
        e = (D - B) / d
        a = (L2**2 - L3**2 + d * d) / (2 * d)
        E = B + a * e + np.sqrt(L2**2 - a * a) * np.array([-e[1], e[0]])
        return np.array(
            [
                q1,
                np.arctan2(E[1] - B[1], E[0] - B[0]) - q1,
                np.arctan2(E[1] - D[1], E[0] - D[0]),
                rng.uniform(-4, 4),
            ]
        )
    if name == "rolling_disc":
        x, y, psi, phi, theta = (
            rng.uniform(-2, 2),
            rng.uniform(-2, 2),
            rng.uniform(-np.pi, np.pi),
            rng.uniform(-1.2, 1.2),
            rng.uniform(-np.pi, np.pi),
        )
        return np.array(
            [
                x,
                y,
                pv[1] * np.cos(phi),
                psi,
                phi,
                theta,
                rng.uniform(-3, 3),
                rng.uniform(-10, 10),
                rng.uniform(-3, 3),
            ]
        )
    # bicycle: x y psi phi theta thetaR delta thetaF, u_phi u_thetaR u_delta;
    # pitch theta from 0; rear wheel rates for -7.5..7.5 m/s
    q = [
        rng.uniform(-5, 5),
        rng.uniform(-5, 5),
        rng.uniform(-np.pi, np.pi),
        rng.uniform(-0.6, 0.6),
        0.0,
        rng.uniform(-np.pi, np.pi),
        rng.uniform(-1, 1),
        rng.uniform(-np.pi, np.pi),
    ]
    return np.array(q + [rng.uniform(-2, 2), rng.uniform(-25, 25), rng.uniform(-3, 3)])


def main() -> None:
    out = sys.argv[1]
    names = sys.argv[2:] or list(MODELS)
    for name in names:
        t0 = time.perf_counter()
        model = MODELS[name]()
        log(t0, f"{name}: built")
        eq = derive(model, t0)
        source, counted, times = emit_c(model, eq, t0)
        d = os.path.join(out, name)
        os.makedirs(d, exist_ok=True)
        open(os.path.join(d, "rhs.c"), "w").write(source)
        rng = np.random.default_rng(SEED)
        t = time.perf_counter()
        states = consistent_states(model, eq, rng)
        times["states_s"] = time.perf_counter() - t
        states.tofile(os.path.join(d, "states.bin"))
        np.asarray(model.values, float).tofile(os.path.join(d, "params.bin"))
        info = dict(
            model=name,
            sympy=sm.__version__,
            numpy=np.__version__,
            states=NS,
            seed=SEED,
            state_names=[c_name(s) for s in model.state_q + model.u_ind],
            dependent_coordinates=[c_name(s) for s in model.q_dep],
            dependent_speeds=[c_name(s) for s in model.u_dep],
            n_speeds=len(eq["u_all"]),
            parameters=[str(p) for p in model.params],
            parameter_values=model.values,
            ops=counted,
            c_lines=source.count("\n"),
            times=eq["times"] | times | {"total_s": time.perf_counter() - t0},
        )
        json.dump(info, open(os.path.join(d, "derive.json"), "w"), indent=1)
        log(t0, f"{name}: {json.dumps(info['ops'])}")


if __name__ == "__main__":
    main()
