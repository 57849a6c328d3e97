"""Andrews' squeezing mechanism in the test set's own formulation.

Hairer & Wanner, Solving ODEs II, sec. VII.7 (the "seven body mechanism"),
and the `andrews` problem of the Bari/CWI IVP test set.  The index-3 DAE is

    q' = v,   M(q) w = f(q, v) - G(q)^T lambda,   g(q) = 0,   v' = w

with q = (beta, Theta, gamma, Phi, delta, Omega, epsilon) (7 angles) and 6
multipliers.  Here it is implemented in plain numpy from the published
equations and solved in its index-1 form:

    [ M   G^T ] [ w      ]   [ f          ]
    [ G   0   ] [ lambda ] = [ -g_qq(v,v) ]

where g_qq(v, v) = (d/dt G) v is the velocity-quadratic part of g''.
Checks: (1) the two published initial accelerations and the multipliers,
(2) G and g_qq against finite differences of g, (3) integration to t = 0.03 s
compared with the test set's reference solution (PSIDE, rtol = atol = 1e-14).

Run:  .venv/bin/python andrews_testset.py
"""
import json
import os
import sys

import numpy as np
from scipy.integrate import solve_ivp

# ---- data (test set) -------------------------------------------------------
m1, m2, m3, m4, m5, m6, m7 = .04325, .00365, .02373, .00706, .07050, .00706, .05498
I1, I2, I3, I4, I5, I6, I7 = 2.194e-6, 4.410e-7, 5.255e-6, 5.667e-7, 1.169e-5, 5.667e-7, 1.912e-5
xa, ya = -.06934, -.00227
xb, yb = -.03635, .03273
xc, yc = .014, .072
d, da, e, ea = 28e-3, 115e-4, 2e-2, 1421e-5
rr, ra = 7e-3, 92e-5
ss, sa, sb, sc, sd = 35e-3, 1874e-5, 1043e-5, 18e-3, 2e-2
ta, tb = 2308e-5, 916e-5
u, ua, ub = 4e-2, 1228e-5, 449e-5
zf, zt, fa = 2e-2, 4e-2, 1421e-5
mom, c0, l0 = 0.033, 4530.0, 0.07785

NAMES = ["beta", "Theta", "gamma", "Phi", "delta", "Omega", "epsilon"]

Q0 = np.array([
    -0.0617138900142764496358948458001,
    0.0,
    0.455279819163070380255912382449,
    0.222668390165885884674473185609,
    0.487364979543842550225598953530,
    -0.222668390165885884674473185609,
    1.23054744454982119249735015568,
])
# published initial accelerations (nonzero ones) and multipliers
W0_PUB = {0: 14222.4439199541138705911625887, 1: -10666.8329399655854029433719415}
LAM0_PUB = np.array([98.5668703962410896057654982170,
                     -6.12268834425566265503114393122, 0, 0, 0, 0])

# reference solution at t = 0.03 (test set, all 27 components: q, v, w, lambda)
Y_REF_003 = np.array([
    0.1581077119629904e+02, -0.1575637105984298e+02, 0.4082224013073101e-01,
    -0.5347301163226948e+00, 0.5244099658805304e+00, 0.5347301163226948e+00,
    0.1048080741042263e+01,
    0.1139920302151208e+04, -0.1424379294994111e+04, 0.1103291221937134e+02,
    0.1929337464421385e+02, 0.5735699284790808e+00, -0.1929337464421385e+02,
    0.3231791658026955e+00,
    -0.2463176316945196e+05, 0.5185037701610329e+05, 0.3241025686413781e+06,
    0.5667493645176213e+06, 0.1674362929479361e+05, -0.5667493645176222e+06,
    0.9826520791458422e+04,
    0.1991753333731910e+03, -0.2975531228015052e+02, 0.2306654119098399e+02,
    0.3145271365475927e+02, 0.2264249232082739e+02, 0.1161740700019673e+02,
])


# ---- the published equations ----------------------------------------------
def mass_matrix(q):
    th, ph, om = q[1], q[3], q[5]
    M = np.zeros((7, 7), dtype=np.result_type(q, float))
    M[0, 0] = m1 * ra**2 + m2 * (rr**2 - 2 * da * rr * np.cos(th) + da**2) + I1 + I2
    M[0, 1] = M[1, 0] = m2 * (da**2 - da * rr * np.cos(th)) + I2
    M[1, 1] = m2 * da**2 + I2
    M[2, 2] = m3 * (sa**2 + sb**2) + I3
    M[3, 3] = m4 * (e - ea)**2 + I4
    M[3, 4] = M[4, 3] = m4 * ((e - ea)**2 + zt * (e - ea) * np.sin(ph)) + I4
    M[4, 4] = (m4 * (zt**2 + 2 * zt * (e - ea) * np.sin(ph) + (e - ea)**2)
               + m5 * (ta**2 + tb**2) + I4 + I5)
    M[5, 5] = m6 * (zf - fa)**2 + I6
    M[5, 6] = M[6, 5] = m6 * ((zf - fa)**2 - u * (zf - fa) * np.sin(om)) + I6
    M[6, 6] = (m6 * ((zf - fa)**2 - 2 * u * (zf - fa) * np.sin(om) + u**2)
               + m7 * (ua**2 + ub**2) + I6 + I7)
    return M


def spring(q):
    """Spring between D (on body 3) and the fixed point C: (xd, yd, F) with
    F = -c0 (L - l0) / L, the force on D being F (D - C)."""
    ga = q[2]
    xd = sd * np.cos(ga) + sc * np.sin(ga) + xb
    yd = sd * np.sin(ga) - sc * np.cos(ga) + yb
    L = np.hypot(xd - xc, yd - yc)
    return xd, yd, L, -c0 * (L - l0) / L


def forcing(q, v):
    th, ga, ph, om = q[1], q[2], q[3], q[5]
    bp, tp, pp, dp, op, ep = v[0], v[1], v[3], v[4], v[5], v[6]
    xd, yd, L, F = spring(q)
    fx, fy = F * (xd - xc), F * (yd - yc)
    return np.array([
        mom - m2 * da * rr * tp * (tp + 2 * bp) * np.sin(th),
        m2 * da * rr * bp**2 * np.sin(th),
        fx * (sc * np.cos(ga) - sd * np.sin(ga)) + fy * (sd * np.cos(ga) + sc * np.sin(ga)),
        m4 * zt * (e - ea) * dp**2 * np.cos(ph),
        -m4 * zt * (e - ea) * pp * (pp + 2 * dp) * np.cos(ph),
        -m6 * u * (zf - fa) * ep**2 * np.cos(om),
        m6 * u * (zf - fa) * op * (op + 2 * ep) * np.cos(om),
    ])


def constraints(q):
    be, th, ga, ph, de, om, ep = q
    ex = rr * np.cos(be) - d * np.cos(be + th)
    ey = rr * np.sin(be) - d * np.sin(be + th)
    return np.array([
        ex - ss * np.sin(ga) - xb,
        ey + ss * np.cos(ga) - yb,
        ex - e * np.sin(ph + de) - zt * np.cos(de) - xa,
        ey + e * np.cos(ph + de) - zt * np.sin(de) - ya,
        ex - zf * np.cos(om + ep) - u * np.sin(ep) - xa,
        ey - zf * np.sin(om + ep) + u * np.cos(ep) - ya,
    ])


def jacobian(q):
    be, th, ga, ph, de, om, ep = q
    sbt, cbt = np.sin(be + th), np.cos(be + th)
    spd, cpd = np.sin(ph + de), np.cos(ph + de)
    soe, coe = np.sin(om + ep), np.cos(om + ep)
    G = np.zeros((6, 7), dtype=np.result_type(q, float))
    for r in (0, 2, 4):
        G[r, 0] = -rr * np.sin(be) + d * sbt
        G[r, 1] = d * sbt
    for r in (1, 3, 5):
        G[r, 0] = rr * np.cos(be) - d * cbt
        G[r, 1] = -d * cbt
    G[0, 2] = -ss * np.cos(ga)
    G[1, 2] = -ss * np.sin(ga)
    G[2, 3] = -e * cpd
    G[2, 4] = -e * cpd + zt * np.sin(de)
    G[3, 3] = -e * spd
    G[3, 4] = -e * spd - zt * np.cos(de)
    G[4, 5] = zf * soe
    G[4, 6] = zf * soe - u * np.cos(ep)
    G[5, 5] = -zf * coe
    G[5, 6] = -zf * coe - u * np.sin(ep)
    return G


def gqq(q, v):
    """(dG/dt) v: the part of g'' quadratic in the speeds (derived by hand)."""
    be, th, ga, ph, de, om, ep = q
    bp, tp, gp, pp, dp, op, epp = v
    bt2 = (bp + tp)**2
    pd2 = (pp + dp)**2
    oe2 = (op + epp)**2
    ax = -rr * np.cos(be) * bp**2 + d * np.cos(be + th) * bt2
    ay = -rr * np.sin(be) * bp**2 + d * np.sin(be + th) * bt2
    return np.array([
        ax + ss * np.sin(ga) * gp**2,
        ay - ss * np.cos(ga) * gp**2,
        ax + e * np.sin(ph + de) * pd2 + zt * np.cos(de) * dp**2,
        ay - e * np.cos(ph + de) * pd2 + zt * np.sin(de) * dp**2,
        ax + zf * np.cos(om + ep) * oe2 + u * np.sin(ep) * epp**2,
        ay + zf * np.sin(om + ep) * oe2 - u * np.cos(ep) * epp**2,
    ])


def gauss_solve(A, b):
    """Gaussian elimination with partial pivoting in A's own precision
    (numpy.linalg has no long double)."""
    A = A.copy()
    b = b.copy()
    n = len(b)
    for k in range(n):
        p = k + np.argmax(np.abs(A[k:, k]))
        if p != k:
            A[[k, p]] = A[[p, k]]
            b[[k, p]] = b[[p, k]]
        f = A[k + 1:, k] / A[k, k]
        A[k + 1:, k:] -= np.outer(f, A[k, k:])
        b[k + 1:] -= f * b[k]
    x = np.zeros_like(b)
    for k in range(n - 1, -1, -1):
        x[k] = (b[k] - A[k, k + 1:] @ x[k + 1:]) / A[k, k]
    return x


def accelerations(q, v):
    """Index-1 solve: returns (w, lambda)."""
    M, G = mass_matrix(q), jacobian(q)
    A = np.zeros((13, 13), dtype=M.dtype)
    A[:7, :7] = M
    A[:7, 7:] = G.T
    A[7:, :7] = G
    rhs = np.concatenate([forcing(q, v), -gqq(q, v)])
    sol = np.linalg.solve(A, rhs) if A.dtype == np.float64 else gauss_solve(A, rhs)
    return sol[:7], sol[7:]


def rk8_fixed(y0, t1, n):
    """Fixed-step 8th-order Runge-Kutta (the 12-stage DOP853 tableau) in the
    precision of y0; used in long double to check the adaptive runs."""
    from scipy.integrate._ivp import dop853_coefficients as c
    ns = c.N_STAGES
    A = c.A[:ns, :ns].astype(y0.dtype)
    B = c.B.astype(y0.dtype)
    C = c.C[:ns].astype(y0.dtype)
    h = y0.dtype.type(t1) / n
    y = y0.copy()
    K = np.zeros((ns, len(y0)), dtype=y0.dtype)
    for i in range(n):
        for s in range(ns):
            K[s] = rhs(i * h + C[s] * h, y + h * (A[s, :s] @ K[:s]))
        y = y + h * (B @ K)
    return y


def rhs(t, y):
    w, _ = accelerations(y[:7], y[7:])
    return np.concatenate([y[7:], w])


# ---- checks ----------------------------------------------------------------
def check_derivatives():
    """G and g_qq against central differences of g (sanity of the hand work)."""
    rng = np.random.default_rng(1)
    q = Q0 + 0.3 * rng.standard_normal(7)
    v = rng.standard_normal(7)
    h = 1e-5
    Gfd = np.column_stack([(constraints(q + h * np.eye(7)[k]) - constraints(q - h * np.eye(7)[k])) / (2 * h)
                           for k in range(7)])
    # g_qq(v, v) = d^2/ds^2 g(q + s v) at s = 0
    h2 = 1e-4  # second difference: balance truncation (h^2) and roundoff (eps/h^2)
    qfd = (constraints(q + h2 * v) - 2 * constraints(q) + constraints(q - h2 * v)) / h2**2
    return (np.max(np.abs(Gfd - jacobian(q))) / np.max(np.abs(jacobian(q))),
            np.max(np.abs(qfd - gqq(q, v))) / np.max(np.abs(gqq(q, v))))


def main():
    out = {}
    eG, eQ = check_derivatives()
    print(f"finite-difference check: G rel err {eG:.1e}, g_qq rel err {eQ:.1e}")

    print(f"|g(q0)| = {np.max(np.abs(constraints(Q0))):.2e}")
    w0, lam0 = accelerations(Q0, np.zeros(7))
    out["initial"] = {"q": Q0.tolist(), "w": w0.tolist(), "lambda": lam0.tolist()}
    print("initial accelerations and multipliers:")
    for k in range(7):
        pub = W0_PUB.get(k, 0.0)
        if pub:
            print(f"  {NAMES[k]}'' = {w0[k]!r:>24}  published {pub!r}  rel err {abs(w0[k]-pub)/abs(pub):.2e}")
        else:
            print(f"  {NAMES[k]}'' = {w0[k]!r:>24}  published 0")
    for k in range(6):
        pub = LAM0_PUB[k]
        msg = f"rel err {abs(lam0[k]-pub)/abs(pub):.2e}" if pub else "published 0"
        print(f"  lambda{k+1} = {lam0[k]!r:>24}  {msg}")

    y0 = np.concatenate([Q0, np.zeros(7)])
    results = {}
    for method, rtol in (("DOP853", 1e-13), ("Radau", 1e-12)):
        sol = solve_ivp(rhs, (0.0, 0.03), y0, method=method, rtol=rtol, atol=rtol * 1e-2)
        y = sol.y[:, -1]
        w, lam = accelerations(y[:7], y[7:])
        full = np.concatenate([y, w, lam])
        rel = np.abs(full - Y_REF_003) / np.maximum(np.abs(Y_REF_003), 1e-300)
        results[method] = full
        print(f"{method} rtol={rtol:g}: {sol.nfev} evaluations, |g| at end {np.max(np.abs(constraints(y[:7]))):.1e}")
        print(f"  beta(0.03)  = {y[0]!r}  ref {Y_REF_003[0]!r}  rel err {rel[0]:.2e}")
        print(f"  Theta(0.03) = {y[1]!r}  ref {Y_REF_003[1]!r}  rel err {rel[1]:.2e}")
        print(f"  max rel err: q {rel[:7].max():.1e}, v {rel[7:14].max():.1e}, "
              f"w {rel[14:21].max():.1e}, lambda {rel[21:].max():.1e}")
        out[f"t0.03_{method}"] = {"y": full.tolist(), "rel_err_vs_testset": rel.tolist(), "nfev": int(sol.nfev)}
    diff = np.max(np.abs(results["DOP853"][:14] - results["Radau"][:14]) / np.abs(Y_REF_003[:14]))
    print(f"DOP853 vs Radau, q and v: max rel diff {diff:.1e}")

    # extended precision (x87 long double, eps 1.1e-19), fixed steps, two step sizes
    if "--no-longdouble" not in sys.argv:
        yl0 = np.concatenate([Q0, np.zeros(7)]).astype(np.longdouble)
        ys = {}
        for n in (1500, 3000):
            ys[n] = rk8_fixed(yl0, 0.03, n)
            print(f"long double RK8, {n} steps: beta = {ys[n][0]:.19g}, Theta = {ys[n][1]:.19g}")
        conv = np.max(np.abs(ys[1500][:7] - ys[3000][:7]) / np.abs(Y_REF_003[:7]))
        yl = ys[3000]
        rel_ld = np.abs(yl[:14] - Y_REF_003[:14]) / np.abs(Y_REF_003[:14])
        vs_dop = np.abs(yl[:14] - results["DOP853"][:14]) / np.abs(Y_REF_003[:14])
        print(f"  step halving changes q by {conv:.1e} (relative); vs test set: beta {rel_ld[0]:.2e}, "
              f"Theta {rel_ld[1]:.2e}; vs DOP853 (double): max over q {vs_dop[:7].max():.1e}")
        out["t0.03_longdouble_rk8"] = {"q": [repr(float(x)) for x in yl[:7]],
                                       "q_str": [f"{x:.19g}" for x in yl[:7]],
                                       "v_str": [f"{x:.19g}" for x in yl[7:14]],
                                       "step_halving_rel_change_q": float(conv),
                                       "rel_err_vs_testset": rel_ld.astype(float).tolist()}
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "andrews.json"), "w") as fh:
        json.dump(out, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
