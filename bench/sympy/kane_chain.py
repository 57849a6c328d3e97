#!/usr/bin/env python3
"""SymPy (sympy.physics.mechanics.KanesMethod) derivation time for chain-spatial-n.

Builds chain-spatial-n of shared/reference-models.md with symbolic parameters (as the
reference-data generator did), derives Kane's equations, extracts M(q) and f(q, u), and
reports the time of each step. Each n runs in a fresh Python process (no SymPy cache carried
over from a smaller model). Optionally lambdifies M and f and checks du = M^-1 f against the
reference samples in shared/reference/chain-spatial-n.json.

    python3 bench/sympy/kane_chain.py 1 2 3 5            # derivation + check
    python3 bench/sympy/kane_chain.py --no-check 10      # derivation only

One JSON line per n on stdout:
    {"model": "chain-spatial-5", "n": 5, "setup_s": ..., "kanes_equations_s": ...,
     "mass_matrix_forcing_s": ..., "derive_s": ..., "lambdify_s": ..., "check": ...}
derive_s = setup_s + kanes_equations_s + mass_matrix_forcing_s (symbols, frames, points,
bodies, loads; Kane's equations; M and f as explicit matrices).
"""

import argparse
import json
import os
import subprocess
import sys
import time

REF_DIR = os.environ.get("REF_DIR", "/work/shared/reference")


def derive(n):
    """Returns (kane, q, u, params, times) for chain-spatial-n."""
    import sympy as sm
    import sympy.physics.mechanics as me

    times = {}
    t0 = time.perf_counter()
    q = me.dynamicsymbols(f"q1:{n + 1}")
    u = me.dynamicsymbols(f"u1:{n + 1}")
    k, c, g, P = sm.symbols("k c g P")
    m = sm.symbols(f"m1:{n + 1}")
    L = sm.symbols(f"L1:{n + 1}")
    Ixx = sm.symbols(f"Ixx1:{n + 1}")
    Iyy = sm.symbols(f"Iyy1:{n + 1}")
    Izz = sm.symbols(f"Izz1:{n + 1}")

    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    unit = lambda F, a: (F.x, F.y, F.z)[a]  # noqa: E731

    bodies, loads = [], []
    parent, joint = N, O
    for i in range(n):
        a = i % 3  # axis 1, 2, 3, 1, ... (0-based)
        B = me.ReferenceFrame(f"B{i + 1}")
        # Rotation about the parent's axis a_i by q_i; u_i = dq_i/dt.
        B.orient_axis(parent, unit(parent, a), q[i])
        B.set_ang_vel(parent, u[i] * unit(parent, a))
        # Joint point: N's origin for B1, (0, 0, -L_(i-1)) in B(i-1) otherwise.
        if i > 0:
            Jp = joint.locatenew(f"J{i + 1}", -L[i - 1] * parent.z)
            Jp.v2pt_theory(joint, N, parent)
        else:
            Jp = joint
        G = Jp.locatenew(f"G{i + 1}", -L[i] / 2 * B.z)
        G.v2pt_theory(Jp, N, B)
        # Inertia dyadic about the mass center: [[Ixx, P, 0], [P, Iyy, 0], [0, 0, Izz]]
        # (sympy's ixy is the dyadic component, i.e. the matrix entry).
        I = me.inertia(B, Ixx[i], Iyy[i], Izz[i], P, 0, 0)
        bodies.append(me.RigidBody(f"Body{i + 1}", G, B, m[i], (I, G)))
        loads.append((G, -m[i] * g * N.z))
        T = (-k * q[i] - c * u[i]) * unit(parent, a)
        loads.append((B, T))
        if parent is not N:
            loads.append((parent, -T))
        parent, joint = B, Jp
    kd = [q[i].diff() - u[i] for i in range(n)]
    kane = me.KanesMethod(N, q_ind=q, u_ind=u, kd_eqs=kd)
    t1 = time.perf_counter()
    kane.kanes_equations(bodies, loads)
    t2 = time.perf_counter()
    M = kane.mass_matrix
    f = kane.forcing
    t3 = time.perf_counter()
    times["setup_s"] = t1 - t0
    times["kanes_equations_s"] = t2 - t1
    times["mass_matrix_forcing_s"] = t3 - t2
    times["derive_s"] = t3 - t0
    params = dict(k=k, c=c, g=g, P=P, m=m, L=L, Ixx=Ixx, Iyy=Iyy, Izz=Izz)
    return (M, f), q, u, params, times


def check(n, Mf, q, u, params, result):
    import numpy as np
    import sympy as sm

    path = os.path.join(REF_DIR, f"chain-spatial-{n}.json")
    if not os.path.exists(path):
        result["check"] = f"skipped (no {path})"
        return
    with open(path) as fh:
        ref = json.load(fh)
    vals = ref["parameters"]
    M, f = Mf
    # Parameter values: the ones in the file (they match reference-models.md).
    subs = {params["k"]: vals["k"], params["c"]: vals["c"], params["g"]: vals["g"],
            params["P"]: vals["P"]}
    for i in range(n):
        for name in ("m", "L", "Ixx", "Iyy", "Izz"):
            subs[params[name][i]] = vals[f"{name}{i + 1}"]
    t0 = time.perf_counter()
    qs, us = sm.symbols(f"qq1:{n + 1}"), sm.symbols(f"uu1:{n + 1}")
    rep = dict(zip(q, qs)) | dict(zip(u, us))
    Mn = M.xreplace(subs).xreplace(rep)
    fn = f.xreplace(subs).xreplace(rep)
    fM = sm.lambdify([qs, us], Mn, "numpy", cse=True)
    ff = sm.lambdify([qs, us], fn, "numpy", cse=True)
    result["lambdify_s"] = time.perf_counter() - t0
    worst = 0.0
    for s in ref["samples"]:
        du = np.linalg.solve(np.asarray(fM(s["q"], s["u"]), float),
                             np.asarray(ff(s["q"], s["u"]), float).ravel())
        exp = np.asarray(s["du"])
        worst = max(worst, float(np.max(np.abs(du - exp)) / np.max(np.abs(exp))))
    result["check"] = {"samples": len(ref["samples"]), "max_rel_err_du": worst,
                       "status": "pass" if worst <= 1e-9 else "FAIL"}
    result["reference_derivation_s"] = ref.get("derivation_s")
    result["reference_lambdify_s"] = ref.get("lambdify_s")


def single(n, do_check):
    import sympy

    Mf, q, u, params, times = derive(n)
    result = {"model": f"chain-spatial-{n}", "n": n, **{k: round(v, 4) for k, v in times.items()},
              "sympy": sympy.__version__, "python": sys.version.split()[0]}
    if do_check:
        check(n, Mf, q, u, params, result)
        if "lambdify_s" in result:
            result["lambdify_s"] = round(result["lambdify_s"], 4)
    print(json.dumps(result), flush=True)
    ok = not isinstance(result.get("check"), dict) or result["check"]["status"] == "pass"
    return 0 if ok else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("n", type=int, nargs="*", default=[1, 2, 3, 5])
    ap.add_argument("--no-check", action="store_true", help="skip lambdify + reference check")
    ap.add_argument("--single", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.single:
        return single(args.n[0], not args.no_check)
    rc = 0
    for n in args.n:  # fresh interpreter per model
        cmd = [sys.executable, os.path.abspath(__file__), "--single", str(n)]
        if args.no_check:
            cmd.append("--no-check")
        rc |= subprocess.call(cmd)
    return rc


if __name__ == "__main__":
    sys.exit(main())
