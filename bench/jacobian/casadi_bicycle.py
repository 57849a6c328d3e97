"""CasADi's Jacobians of the Whipple bicycle's SymPy equations, generated as
C: the peer of autosim's `linearize()` of examples/models/bicycle.sim.

Usage: python casadi_bicycle.py GEN_DIR STATES_DIR

The equations: sympy.physics.mechanics KanesMethod on the tree of
tests/reference/gen/bicycle_check.py (its model-building part, executed from
that file up to where it forms Kane's equations, so the two cannot drift:
one holonomic constraint, the front contact's height, with the pitch theta
dependent; four nonholonomic ones, rolling without slip), plus the model's
two inputs as loads: the roll torque T_phi on the rear frame B (reaction on
the heading frame Y) about R's axis 1, the steer torque T_delta on the front
frame H (reaction on B) about the steer axis. g = 9.81.

autosim's state x (11): q = (x, y, psi, phi, theta, thetaR, delta, thetaF)
and the independent speeds (u_phi, u_thetaR, u_delta); inputs
w = (T_phi, T_delta); outputs y = (speed, potential, ground):
speed = rR (u_theta + u_thetaR), potential = sum of m g z of the mass centres,
ground = h(q), the holonomic constraint's residual (autosim adds the residual
of each position constraint to the outputs; its row of C vanishes on the
constraint, up to rounding).
From SymPy's mass matrix and forcing (rows 0..2: the dynamic equations
K_i du_i/dt + K_d du_d/dt = f_d; rows 3..7: the velocity constraints'
derivatives B_i du_i/dt + B_d du_d/dt = f_nh, B = [B_i B_d] the velocity
constraint matrix) the state derivative is built in CasADi SX: dependent
speeds u_d = -B_d^-1 B_i u_i, independent accelerations from
(K_i - K_d B_d^-1 B_i) du_i/dt = f_d - K_d B_d^-1 f_nh (Gaussian elimination
without pivoting, as SymPy's own symbolic LU solve in KanesMethod; the
constraint order of bicycle_check.py keeps its pivots nonzero), dq/dt = u.
The linear states are x without theta, which follows the others through the
holonomic constraint h(q) = 0: dtheta/dq_j = -h_qj / h_theta. CasADi's
`jacobian` then gives A = df/dx T, B = df/dw, C = dy/dx T, D = dy/dw
(T maps the linear states to x; rows of A: the linear states' derivatives),
what autosim's `linearize()` documents. Written into GEN_DIR as
bicycle.c/.h/.json by casadi_jacobian.emit; STATES_DIR/bicycle.txt gets 1000
consistent states: roll in [-0.3, 0.3], steer in [-0.5, 0.5], heading, wheel
angles in [-pi, pi], x, y in [-1, 1], the pitch solved from h = 0 (Newton),
u_phi, u_delta in [-1, 1], forward speed rR u_thetaR in [2, 8] m/s.
"""

import math
import os
import sys
import time
import types

import casadi as ca
import numpy as np
import sympy as sm
import sympy.physics.mechanics as me
from sympy.printing.lambdarepr import LambdaPrinter

from casadi_jacobian import STATES, emit, write_states

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.path.join(HERE, "..", "..", "tests", "reference", "gen", "bicycle_check.py")
MARKER = "log(\"forming Kane's equations"
G_VALUE = 9.81
THETA = 4  # the dependent coordinate's index in q
LINEAR = [i for i in range(11) if i != THETA]

# lambdify prints math.sin(...), sqrt(...): give it CasADi's functions under those names.
CASADI = {
    "math": types.SimpleNamespace(sin=ca.sin, cos=ca.cos, tan=ca.tan, sqrt=ca.sqrt, pi=math.pi),
    "sqrt": ca.sqrt,
}


def tree() -> dict:
    """bicycle_check.py's definitions (frames, points, bodies, gravity loads,
    constraints, coordinate and speed lists), executed up to MARKER."""
    with open(CHECK) as fh:
        text = fh.read()
    if MARKER not in text:
        sys.exit(f"{CHECK}: no line starting {MARKER!r}; update casadi_bicycle.py")
    ns: dict = {"__name__": "bicycle_check_tree"}
    exec(compile(text[: text.index(MARKER)], CHECK, "exec"), ns)  # noqa: S102 (our own script)
    return ns


def equations(ns: dict, w: sm.Matrix) -> tuple[me.KanesMethod, sm.Matrix, sm.Matrix]:
    """Kane's mass matrix and forcing (in KanesMethod's speed order) with the inputs' loads."""
    Rf, Bf, Hf, Yf = ns["Rf"], ns["Bf"], ns["Hf"], ns["Yf"]
    t_phi, t_delta = w
    axis = ns["steer_axis"]
    loads = ns["loads"] + [
        (Bf, t_phi * Rf.x),
        (Yf, -t_phi * Rf.x),
        (Hf, t_delta * axis),
        (Bf, -t_delta * axis),
    ]
    kane = me.KanesMethod(
        ns["N"],
        q_ind=ns["q_ind"],
        u_ind=ns["u_ind"],
        kd_eqs=ns["kd"],
        q_dependent=ns["q_dep"],
        configuration_constraints=[ns["hol"]],
        u_dependent=ns["u_dep"],
        velocity_constraints=ns["vel_cons"],
    )
    kane.kanes_equations(ns["bodies"], loads)
    return kane, kane.mass_matrix, kane.forcing


def lu_solve(a: list[list], rhs: list[list]) -> list[list]:
    """Solves a z = rhs (lists of SX rows) by Gaussian elimination without pivoting."""
    n = len(a)
    a = [row[:] for row in a]
    rhs = [row[:] for row in rhs]
    for k in range(n):
        inv = 1 / a[k][k]
        for i in range(k + 1, n):
            f = a[i][k] * inv
            a[i] = [a[i][j] - f * a[k][j] if j > k else 0 for j in range(n)]
            rhs[i] = [rhs[i][j] - f * rhs[k][j] for j in range(len(rhs[i]))]
    z = [None] * n
    for i in reversed(range(n)):
        acc = rhs[i]
        for j in range(i + 1, n):
            acc = [acc[c] - a[i][j] * z[j][c] for c in range(len(acc))]
        z[i] = [v / a[i][i] for v in acc]
    return z


def build(gen_dir: str, states_dir: str) -> dict:
    t0 = time.perf_counter()
    ns = tree()
    q, u, g = ns["q"], ns["u"], ns["g"]
    w = sm.Matrix(sm.symbols("T_phi T_delta"))
    kane, mm, ff = equations(ns, w)
    ku = list(kane.u)
    ind = [ku.index(s) for s in ns["u_ind"]]  # Kane columns of the independent speeds
    dep = [ku.index(s) for s in ns["u_dep"]]
    assert ind == [0, 1, 2], ind
    assert not mm[3:, :].has(*u), "the velocity constraint matrix depends on the speeds"
    bodies = ns["bodies"]
    speed = ns["p"]["rR"] * (u[4] + u[5])
    potential = sum(b.mass * g * b.masscenter.pos_from(ns["O"]).dot(ns["N"].z) for b in bodies)
    hol = ns["hol"]
    dhol = [hol.diff(qj) for qj in q]
    t_sympy = time.perf_counter() - t0

    args = list(q) + list(u) + [g] + list(w)
    exprs = list(mm) + list(ff) + [speed, potential, hol] + dhol
    fn = sm.lambdify(args, exprs, modules=[CASADI], printer=LambdaPrinter, cse=True)
    x = ca.SX.sym("x", 11)
    wx = ca.SX.sym("w", 2)
    qx = [x[i] for i in range(8)]
    ui = [x[8 + i] for i in range(3)]
    our_ind = [u.index(s) for s in ns["u_ind"]]  # positions in q / u order
    our_dep = [u.index(s) for s in ns["u_dep"]]
    # the constraint matrix first (no speeds in it): dependent speeds
    at_rest = fn(*qx, *([0.0] * 8), G_VALUE, wx[0], wx[1])
    rows = lambda flat, r0, r1: [[flat[8 * r + c] for c in range(8)] for r in range(r0, r1)]
    bmat = rows(at_rest, 3, 8)
    bi = [[r[c] for c in ind] for r in bmat]
    bd = [[r[c] for c in dep] for r in bmat]
    z = lu_solve(bd, [[-sum(bi[r][k] * ui[k] for k in range(3))] for r in range(5)])
    ufull = [None] * 8
    for k, pos in enumerate(our_ind):
        ufull[pos] = ui[k]
    for k, pos in enumerate(our_dep):
        ufull[pos] = z[k][0]
    e = fn(*qx, *ufull, G_VALUE, wx[0], wx[1])
    mmx, ffx = rows(e, 0, 8), e[64:72]
    y = e[72:75]
    h_q = e[75:83]
    # independent accelerations
    kin = [[mmx[r][c] for c in ind] for r in range(3)]
    kd = [[mmx[r][c] for c in dep] for r in range(3)]
    bmat = mmx[3:8]
    bi = [[r[c] for c in ind] for r in bmat]
    bd = [[r[c] for c in dep] for r in bmat]
    zz = lu_solve(bd, [bi[r] + [ffx[3 + r]] for r in range(5)])  # B_d^-1 [B_i f_nh]
    kr = [[kin[r][c] - sum(kd[r][k] * zz[k][c] for k in range(5)) for c in range(3)] for r in range(3)]
    fr = [[ffx[r] - sum(kd[r][k] * zz[k][3] for k in range(5))] for r in range(3)]
    udot = [v[0] for v in lu_solve(kr, fr)]
    f = ca.vertcat(*ufull, *udot)
    yv = ca.vertcat(*y)
    # linear states -> x: theta follows through h(q) = 0
    t_map = ca.SX.zeros(11, 10)
    for k, i in enumerate(LINEAR):
        t_map[i, k] = 1
        if i < 8:
            t_map[THETA, k] = -h_q[i] / h_q[THETA]
    fl = f[LINEAR]
    a = ca.mtimes(ca.jacobian(fl, x), t_map)
    b = ca.jacobian(fl, wx)
    c = ca.mtimes(ca.jacobian(yv, x), t_map)
    d = ca.jacobian(yv, wx)
    t_sx = time.perf_counter() - t0 - t_sympy
    info = emit(
        "bicycle",
        [x, wx],
        [a, b, c, d],
        {"nx": 11, "nw": 2, "nlin": 10, "ny": 3},
        gen_dir,
        {"t_sympy_s": t_sympy, "t_build_sx_s": t_sx, "sympy": sm.__version__},
    )
    states(ns, args, states_dir)
    return info


def states(ns: dict, args: list, states_dir: str) -> None:
    """STATES consistent states (the pitch from the holonomic constraint)."""
    q = ns["q"]
    hol = sm.lambdify(args, ns["hol"], "numpy")
    dhol = sm.lambdify(args, ns["hol"].diff(q[THETA]), "numpy")
    rng = np.random.default_rng(20261203)
    r_rear = float(ns["p"]["rR"])
    rows = []
    for _ in range(STATES):
        qq = np.array(
            [
                rng.uniform(-1, 1),
                rng.uniform(-1, 1),
                rng.uniform(-np.pi, np.pi),
                rng.uniform(-0.3, 0.3),
                0.0,
                rng.uniform(-np.pi, np.pi),
                rng.uniform(-0.5, 0.5),
                rng.uniform(-np.pi, np.pi),
            ]
        )
        for _ in range(50):
            a = list(qq) + [0.0] * 8 + [G_VALUE, 0.0, 0.0]
            step = float(hol(*a)) / float(dhol(*a))
            qq[THETA] -= step
            if abs(step) < 1e-15:
                break
        else:
            sys.exit("pitch: Newton did not converge")
        rows.append(list(qq) + [rng.uniform(-1, 1), rng.uniform(2, 8) / r_rear, rng.uniform(-1, 1)])
    write_states(os.path.join(states_dir, "bicycle.txt"), rows)


def main() -> None:
    gen_dir, states_dir = sys.argv[1:3]
    info = build(gen_dir, states_dir)
    print(
        f"bicycle: SymPy {info['t_sympy_s']:.1f} s, SX + jacobian {info['t_build_sx_s']:.2f} s, "
        f"Function + cse {info['t_function_cse_s']:.2f} s, codegen {info['t_codegen_s']:.2f} s, "
        f"{info['casadi_ops']} operations",
        flush=True,
    )


if __name__ == "__main__":
    main()
