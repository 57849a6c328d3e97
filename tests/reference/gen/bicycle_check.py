"""Independent check of the Whipple-bicycle tree of bicycle.md with
sympy.physics.mechanics (KanesMethod with one holonomic and four
nonholonomic constraints), against the Meijaard, Papadopoulos, Ruina &
Schwab (2007) benchmark.

Frames (ours): n1 forward (at yaw 0), n2 LEFT, n3 UP, gravity -g n3.
Benchmark axes: x forward, y right, z down  ->  (x, y, z)_bench = (x, -y, -z)_ours.

Tree (every q has u = dq/dt):
  Y   parent N, translate [1, 2] (x, y: rear contact point), rotate 3 (psi)     massless
  R   parent Y, rotate 1 (phi, roll)                                          massless
  B   parent R, joint [0, 0, rR], rotate 2 (theta, pitch)                     rear frame
  RW  parent B, joint [0, 0, 0], rotate 2 (thetaR)                            rear wheel
  H   parent B, joint [w + c, 0, -rR], rotate about [sin(lam), 0, -cos(lam)]   front frame
      (delta, steer; axes = B's at delta = 0)
  FW  parent H, joint [-c, 0, rF], rotate 2 (thetaF)                          front wheel

Run:  .venv/bin/python bicycle_check.py
"""
import json
import os
import sys
import time

import mpmath as mp
import numpy as np
import sympy as sm
import sympy.physics.mechanics as me
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

T0 = time.time()


def log(*a):
    print(f"[{time.time() - T0:7.1f} s]", *a, flush=True)


# ---- benchmark parameters (Table 1), exact decimals --------------------------
def F(s):
    return sm.Float(s, 40)


par = dict(w="1.02", c="0.08", rR="0.3", mR="2", IRxx="0.0603", IRyy="0.12",
           xB="0.3", zB="-0.9", mB="85", IBxx="9.2", IByy="11", IBzz="2.8", IBxz="2.4",
           xH="0.9", zH="-0.7", mH="4", IHxx="0.05892", IHyy="0.06", IHzz="0.00708", IHxz="-0.00756",
           rF="0.35", mF="3", IFxx="0.1405", IFyy="0.28")
p = {k: F(v) for k, v in par.items()}
lam = sm.pi / 10
g = sm.Symbol("g")
G_VAL = "9.81"

PUB = dict(
    M=[[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]],
    C1=[[0, 33.86641391492494], [-0.85035641456978, 1.68540397397560]],
    K0=[[-80.95, -2.59951685249872], [-2.59951685249872, -0.80329488458618]],
    K2=[[0, 76.59734589573222], [0, 2.65431523794604]],
    weave=4.29238253634111, capsize=6.02426201538837,
)

# ---- coordinates and speeds --------------------------------------------------
qnames = ["x", "y", "psi", "phi", "theta", "thetaR", "delta", "thetaF"]
q = me.dynamicsymbols(" ".join(qnames))
u = me.dynamicsymbols(" ".join("u_" + n for n in qnames))
x, y, psi, phi, theta, thetaR, delta, thetaF = q
t = me.dynamicsymbols._t
qd2u = {qi.diff(t): ui for qi, ui in zip(q, u)}

# ---- frames and points ---------------------------------------------------------
N = me.ReferenceFrame("N")
Yf = me.ReferenceFrame("Y")
Yf.orient_axis(N, N.z, psi)
Rf = me.ReferenceFrame("R")
Rf.orient_axis(Yf, Yf.x, phi)
Bf = me.ReferenceFrame("B")
Bf.orient_axis(Rf, Rf.y, theta)
RWf = me.ReferenceFrame("RW")
RWf.orient_axis(Bf, Bf.y, thetaR)
steer_axis = sm.sin(lam) * Bf.x - sm.cos(lam) * Bf.z     # unit, forward-down
Hf = me.ReferenceFrame("H")
Hf.orient_axis(Bf, steer_axis, delta)
FWf = me.ReferenceFrame("FW")
FWf.orient_axis(Hf, Hf.y, thetaF)
for fr in (Yf, Rf, Bf, RWf, Hf, FWf):
    fr.set_ang_vel(N, fr.ang_vel_in(N).subs(qd2u))

O = me.Point("O")
O.set_vel(N, 0)
P = O.locatenew("P", x * N.x + y * N.y)                   # Y and R origin: rear contact
Bo = P.locatenew("Bo", p["rR"] * Rf.z)                    # rear hub (B, RW origin)
Ho = Bo.locatenew("Ho", (p["w"] + p["c"]) * Bf.x - p["rR"] * Bf.z)  # steer axis at ground level
Fo = Ho.locatenew("Fo", -p["c"] * Hf.x + p["rF"] * Hf.z)  # front hub (FW origin)
Bcm = Bo.locatenew("Bcm", p["xB"] * Bf.x + (-p["zB"] - p["rR"]) * Bf.z)
Hcm = Ho.locatenew("Hcm", (p["xH"] - p["w"] - p["c"]) * Hf.x + (-p["zH"]) * Hf.z)


def setvel(pt):
    pt.set_vel(N, pt.pos_from(O).dt(N).subs(qd2u))


for pt in (P, Bo, Ho, Fo, Bcm, Hcm):
    setvel(pt)

# ---- bodies (inertia dyadics in body axes, ours = benchmark with y, z flipped) -
IB = me.inertia(Bf, p["IBxx"], p["IByy"], p["IBzz"], 0, 0, -p["IBxz"])   # ixx, iyy, izz, ixy, iyz, izx
IH = me.inertia(Hf, p["IHxx"], p["IHyy"], p["IHzz"], 0, 0, -p["IHxz"])
IR = me.inertia(RWf, p["IRxx"], p["IRyy"], p["IRxx"])
IFw = me.inertia(FWf, p["IFxx"], p["IFyy"], p["IFxx"])
bodies = [
    me.RigidBody("B", Bcm, Bf, p["mB"], (IB, Bcm)),
    me.RigidBody("RW", Bo, RWf, p["mR"], (IR, Bo)),
    me.RigidBody("H", Hcm, Hf, p["mH"], (IH, Hcm)),
    me.RigidBody("FW", Fo, FWf, p["mF"], (IFw, Fo)),
]
loads = [(b.masscenter, -b.mass * g * N.z) for b in bodies]

# ---- constraints ---------------------------------------------------------------
# holonomic: height of the front contact point = 0
f2 = Hf.y                                                  # front axle
f2n3 = f2.dot(N.z)
hol = Fo.pos_from(O).dot(N.z) - p["rF"] * sm.sqrt(1 - f2n3**2)
# rear contact: velocity of the rear wheel's material point at P
v_rc = Bo.vel(N) + RWf.ang_vel_in(N).cross(P.pos_from(Bo))
# front contact: material point of FW at the lowest point of the rim
rc_front = p["rF"] * (f2.cross(f2.cross(N.z))) / sm.sqrt(1 - f2n3**2)   # from the hub
v_fc = Fo.vel(N) + FWf.ang_vel_in(N).cross(rc_front)
# rear: n1, n2 components; front: components along the heading Y.x and the
# horizontal lateral direction Y.y (the same conditions as n1, n2; this choice
# and this order make the symbolic LU pivots of Kane's dependent-speed solve
# nonzero at every yaw angle and near upright)
nonhol_rear = [v_rc.dot(N.x), v_rc.dot(N.y)]
nonhol_front = [v_fc.dot(Yf.y), v_fc.dot(Yf.x)]
hol_dot = hol.diff(t).subs(qd2u)
vel_cons = nonhol_rear + [nonhol_front[0], hol_dot, nonhol_front[1]]

ui_names = ["u_phi", "u_thetaR", "u_delta"]
u_ind = [u[3], u[5], u[6]]
u_dep = [u[0], u[1], u[2], u[4], u[7]]
q_ind = [q[i] for i in (0, 1, 2, 3, 5, 6, 7)]
q_dep = [theta]
kd = [qi.diff(t) - ui for qi, ui in zip(q, u)]

log("forming Kane's equations (1 holonomic, 4 nonholonomic constraints)")
kane = me.KanesMethod(N, q_ind=q_ind, u_ind=u_ind, kd_eqs=kd, q_dependent=q_dep,
                      configuration_constraints=[hol], u_dependent=u_dep,
                      velocity_constraints=vel_cons)
kane.kanes_equations(bodies, loads)
log("Kane's equations formed")
# kane.mass_matrix u' = kane.forcing: rows 0..2 are the dynamic equations of
# the independent speeds (u_phi, u_thetaR, u_delta), rows 3..7 the time
# derivatives of the velocity constraints
MMfull = kane.mass_matrix
FFfull = kane.forcing
k_d, f_d = MMfull[:3, :], FFfull[:3, :]
k_dnh, f_dnh = MMfull[3:, :], FFfull[3:, :]
Bmat = sm.Matrix(vel_cons).jacobian(u)                     # velocity constraints B(q) u = 0
assert sm.Matrix(vel_cons).subs({ui: 0 for ui in u}) == sm.zeros(5, 1)
# order of kane.u: u_ind then u_dep
ku = list(kane.u)
log("u order in Kane:", [str(s).replace("(t)", "") for s in ku])

# energy
KE = sum(b.kinetic_energy(N) for b in bodies)
PE = sum(b.mass * g * b.masscenter.pos_from(O).dot(N.z) for b in bodies)

args = list(q) + list(u) + [g]

# ---- high-precision linearization (mpmath) ----------------------------------------
mp.mp.dps = 50
log("lambdifying (mpmath)")
mp_kd = sm.lambdify(args, k_d, "mpmath", cse=True)
mp_fd = sm.lambdify(args, f_d, "mpmath", cse=True)
mp_kdnh = sm.lambdify(args, k_dnh, "mpmath", cse=True)
mp_fdnh = sm.lambdify(args, f_dnh, "mpmath", cse=True)
mp_B = sm.lambdify(args, Bmat, "mpmath", cse=True)
mp_hol = sm.lambdify(args, hol, "mpmath")
mp_dhol = sm.lambdify(args, hol.diff(theta), "mpmath")
log("done")

rR = mp.mpf(par["rR"])
gv = mp.mpf(G_VAL)
IDX_IND = [ku.index(s) for s in u_ind]
IDX_DEP = [ku.index(s) for s in u_dep]
UI = [u.index(s) for s in u_ind]   # positions in our u ordering
UD = [u.index(s) for s in u_dep]


def tomat(a):
    return mp.matrix(a.tolist() if hasattr(a, "tolist") else a)


def pitch(ph, de, gval=gv):
    """Solve the holonomic constraint for theta (Newton)."""
    th = mp.mpf(0)
    for _ in range(100):
        qq = [0, 0, 0, ph, th, 0, de, 0]
        h = mp_hol(*qq, *([0] * 8), gval)
        th_new = th - h / mp_dhol(*qq, *([0] * 8), gval)
        if abs(th_new - th) < mp.mpf(10) ** (-mp.mp.dps + 5):
            return th_new
        th = th_new
    raise RuntimeError("pitch Newton did not converge")


def residual(s, sd, sdd, v, gval=gv):
    """Roll and steer rows of Kane's equations, k_d u' - f_d, for the state
    roll = s[0], steer = s[1] with rates sd, accelerations sdd, rear wheel rate
    v/rR and no rear wheel acceleration; pitch, dependent speeds and dependent
    accelerations from the constraints."""
    th = pitch(s[0], s[1], gval)
    qq = [0, 0, 0, s[0], th, 0, s[1], 0]
    uu = [mp.mpf(0)] * 8
    uu[3], uu[5], uu[6] = sd[0], v / rR, sd[1]
    Bm = tomat(mp_B(*qq, *uu, gval))
    Bi = mp.matrix([[Bm[r, c] for c in UI] for r in range(5)])
    Bd = mp.matrix([[Bm[r, c] for c in UD] for r in range(5)])
    ud = mp.lu_solve(Bd, -(Bi * mp.matrix([uu[c] for c in UI])))
    for k, c in enumerate(UD):
        uu[c] = ud[k]
    a = list(qq) + list(uu) + [gval]
    # accelerations in Kane's u order
    udot = [mp.mpf(0)] * 8
    udot[IDX_IND[0]], udot[IDX_IND[1]], udot[IDX_IND[2]] = sdd[0], mp.mpf(0), sdd[1]
    Kn = tomat(mp_kdnh(*a))
    Fn = tomat(mp_fdnh(*a))
    Kni = mp.matrix([[Kn[r, c] for c in IDX_IND] for r in range(5)])
    Knd = mp.matrix([[Kn[r, c] for c in IDX_DEP] for r in range(5)])
    ad = mp.lu_solve(Knd, Fn - Kni * mp.matrix([udot[c] for c in IDX_IND]))
    for k, c in enumerate(IDX_DEP):
        udot[c] = ad[k]
    Kd = tomat(mp_kd(*a))
    Fd = tomat(mp_fd(*a))
    res = Kd * mp.matrix(udot) - Fd
    return [res[0], res[2]], th, uu


def jac(fun, n=2, h=mp.mpf("1e-18")):
    cols = []
    for k in range(n):
        e = [mp.mpf(0)] * n
        e[k] = h
        rp = fun([+ek for ek in e])
        rm = fun([-ek for ek in e])
        cols.append([(rp[i] - rm[i]) / (2 * h) for i in range(2)])
    return [[cols[c][r] for c in range(n)] for r in range(2)]


z2 = [mp.mpf(0), mp.mpf(0)]
log("linearizing")
th0 = pitch(0, 0)
log(f"nominal pitch at zero roll and steer: {mp.nstr(th0, 20)}")
Mlin = jac(lambda e: residual(z2, z2, e, mp.mpf(0))[0])
K_v0 = jac(lambda e: residual(e, z2, z2, mp.mpf(0))[0])
K0 = [[K_v0[i][j] / gv for j in range(2)] for i in range(2)]
K_v1 = jac(lambda e: residual(e, z2, z2, mp.mpf(1))[0])
K2 = [[K_v1[i][j] - gv * K0[i][j] for j in range(2)] for i in range(2)]
C1 = jac(lambda e: residual(z2, e, z2, mp.mpf(1))[0])
# consistency at another speed (exact structure: C = v C1, K = g K0 + v^2 K2)
v3 = mp.mpf(3)
K_v3 = jac(lambda e: residual(e, z2, z2, v3)[0])
C_v3 = jac(lambda e: residual(z2, e, z2, v3)[0])
M_v3 = jac(lambda e: residual(z2, z2, e, v3)[0])
struct_err = max(
    max(abs(K_v3[i][j] - gv * K0[i][j] - v3**2 * K2[i][j]) for i in range(2) for j in range(2)),
    max(abs(C_v3[i][j] - v3 * C1[i][j]) for i in range(2) for j in range(2)),
    max(abs(M_v3[i][j] - Mlin[i][j]) for i in range(2) for j in range(2)))
log(f"structure check at v = 3 (M, C = v C1, K = g K0 + v^2 K2): max abs deviation {mp.nstr(struct_err, 3)}")

pitch_samples = []
for ph_s, de_s in (("0.05", "0"), ("0", "0.1"), ("0.1", "0.2"), ("0.3", "-0.5"), ("0", "1.0")):
    th_s = pitch(mp.mpf(ph_s), mp.mpf(de_s))
    pitch_samples.append({"roll": float(ph_s), "steer": float(de_s), "pitch": mp.nstr(th_s, 25)})
    print(f"  pitch(roll = {ph_s}, steer = {de_s}) = {mp.nstr(th_s, 20)}")

report = {"pitch_samples": pitch_samples, "frames": "ours: n1 forward, n2 left, n3 up; benchmark (x,y,z) = (x,-y,-z) ours",
          "nominal_pitch": mp.nstr(th0, 25)}
errs = {}
print("\nlinear model (ours)  vs  published:")
for name, mat in (("M", Mlin), ("C1", C1), ("K0", K0), ("K2", K2)):
    report[name] = [[mp.nstr(mat[i][j], 25) for j in range(2)] for i in range(2)]
    for i in range(2):
        for j in range(2):
            ours = mat[i][j]
            pub = PUB[name][i][j]
            if pub == 0:
                err = float(abs(ours))
                kind = "abs"
            else:
                err = float(abs(ours - mp.mpf(repr(pub))) / abs(pub))
                kind = "rel"
            errs[f"{name}[{i}][{j}]"] = err
            print(f"  {name}[{i}][{j}] = {mp.nstr(ours, 20):>26}   published {pub!r:>20}   {kind} err {err:.1e}")
report["linear_errors_vs_published"] = errs


# ---- weave and capsize speeds --------------------------------------------------------
def charpoly(v):
    """Coefficients a4..a0 of det(M s^2 + v C1 s + g K0 + v^2 K2)."""
    A2 = mp.matrix(Mlin)
    A1 = v * mp.matrix(C1)
    A0 = gv * mp.matrix(K0) + v**2 * mp.matrix(K2)

    def det2(Pm):
        return Pm[0, 0] * Pm[1, 1] - Pm[0, 1] * Pm[1, 0]

    # det(A2 s^2 + A1 s + A0) = sum over column choices
    def mixed(X, Y):
        return X[0, 0] * Y[1, 1] + Y[0, 0] * X[1, 1] - X[0, 1] * Y[1, 0] - Y[0, 1] * X[1, 0]

    a4 = det2(A2)
    a3 = mixed(A2, A1)
    a2 = mixed(A2, A0) + det2(A1)
    a1 = mixed(A1, A0)
    a0 = det2(A0)
    return a4, a3, a2, a1, a0


def hurwitz(v):
    a4, a3, a2, a1, a0 = charpoly(v)
    return a3 * a2 * a1 - a4 * a1**2 - a0 * a3**2   # zero at a pure imaginary pair


def capsize_fn(v):
    return charpoly(v)[4]                           # zero at a zero eigenvalue


def eig(v):
    a = [float(c) for c in charpoly(mp.mpf(v))]
    return np.roots(a)


v_weave = mp.findroot(hurwitz, (mp.mpf("4.0"), mp.mpf("4.6")), solver="anderson", verify=False)
v_caps = mp.findroot(capsize_fn, (mp.mpf("5.5"), mp.mpf("6.5")), solver="anderson", verify=False)
# confirm the roots: sign changes just around them, and real parts of the eigenvalues
for name, fn, r in (("weave", hurwitz, v_weave), ("capsize", capsize_fn, v_caps)):
    dv = r * mp.mpf("1e-30")
    assert fn(r - dv) * fn(r + dv) < 0, name
ew = abs(v_weave - mp.mpf(repr(PUB["weave"]))) / PUB["weave"]
ec = abs(v_caps - mp.mpf(repr(PUB["capsize"]))) / PUB["capsize"]
print(f"\nweave speed   {mp.nstr(v_weave, 20)}  published {PUB['weave']!r}  rel err {float(ew):.1e}")
print(f"capsize speed {mp.nstr(v_caps, 20)}  published {PUB['capsize']!r}  rel err {float(ec):.1e}")
for vv in (0.0, 3.0, 4.0, 5.0, 7.0):
    print(f"  eigenvalues at v = {vv}: {np.sort_complex(eig(vv))}")
report["weave_speed"] = mp.nstr(v_weave, 25)
report["capsize_speed"] = mp.nstr(v_caps, 25)
report["weave_rel_err"] = float(ew)
report["capsize_rel_err"] = float(ec)
report["eigenvalues"] = {str(vv): [[float(z.real), float(z.imag)] for z in np.sort_complex(eig(vv))]
                         for vv in (0.0, 3.0, 5.0)}

# ---- nonlinear simulation (numpy) ---------------------------------------------------
log("lambdifying (numpy) for the nonlinear runs")
np_MM = sm.lambdify(args, MMfull, "numpy", cse=True)
np_FF = sm.lambdify(args, FFfull, "numpy", cse=True)
np_B = sm.lambdify(args, Bmat, "numpy", cse=True)
np_hol = sm.lambdify(args, hol, "numpy")
np_E = sm.lambdify(args, KE + PE, "numpy", cse=True)
gnum = float(G_VAL)
perm = [u.index(s) for s in ku]    # Kane order -> our order index
log("done")


def consistent_state(phi0, v):
    th = float(pitch(mp.mpf(phi0), mp.mpf(0)))
    qq = np.array([0, 0, 0, phi0, th, 0, 0, 0], dtype=float)
    uu = np.zeros(8)
    uu[5] = v / float(par["rR"])
    Bm = np.array(np_B(*qq, *uu, gnum), dtype=float)
    uu[UD] = np.linalg.solve(Bm[:, UD], -Bm[:, UI] @ uu[UI])
    return qq, uu


def rhs(tt, yy):
    qq, uu = yy[:8], yy[8:]
    a = list(qq) + list(uu) + [gnum]
    Mm = np.array(np_MM(*a), dtype=float)
    Ff = np.array(np_FF(*a), dtype=float).ravel()
    ud_k = np.linalg.solve(Mm, Ff)   # Kane's order
    ud = np.empty(8)
    ud[perm] = ud_k
    return np.concatenate([uu, ud])


def energy(yy):
    return float(np_E(*yy[:8], *yy[8:], gnum))


def constraint_res(yy):
    a = list(yy[:8]) + list(yy[8:]) + [gnum]
    return abs(float(np_hol(*a))), float(np.max(np.abs(np.array(np_B(*a), dtype=float) @ yy[8:])))


sim = {}
ROLL_LIMIT = 1.0   # rad: stop a falling bicycle here (lying flat is singular)


def fall(tt, yy):
    return abs(yy[3]) - ROLL_LIMIT


fall.terminal = True

for v, dt_out in ((5.0, 0.5), (3.0, 0.25)):
    t_eval = np.arange(0.0, 10.0 + 1e-9, dt_out)
    q0, u0 = consistent_state(0.05, v)
    y0 = np.concatenate([q0, u0])
    runs = {}
    for rtol in (1e-10, 1e-12):
        log(f"integrating v = {v} m/s, roll0 = 0.05 rad, DOP853 rtol {rtol:g}")
        sol = solve_ivp(rhs, (0, 10), y0, method="DOP853", rtol=rtol, atol=rtol * 1e-2,
                        t_eval=t_eval, events=fall)
        runs[rtol] = sol
        log(f"  status {sol.status}, {sol.nfev} evaluations, t_end {sol.t[-1]}")
    sol = runs[1e-12]
    n = min(len(runs[1e-10].t), len(sol.t))
    diff = np.max(np.abs(runs[1e-10].y[3, :n] - sol.y[3, :n]))
    E0 = energy(sol.y[:, 0])
    Es = np.array([energy(sol.y[:, k]) for k in range(sol.y.shape[1])])
    drift = np.max(np.abs(Es - E0)) / abs(E0)
    KE0 = E0 - float(sm.lambdify(args, PE, "numpy")(*sol.y[:8, 0], *sol.y[8:, 0], gnum))
    drift_ke = np.max(np.abs(Es - E0)) / abs(KE0)
    hres, nres = constraint_res(sol.y[:, -1])
    roll = sol.y[3]
    print(f"\nv = {v} m/s, roll(0) = 0.05 rad (pitch(0) = {q0[4]!r}):")
    for tt, r, st in zip(sol.t, roll, sol.y[6]):
        print(f"  t = {tt:5.2f}  roll = {r: .15e}  steer = {st: .15e}")
    t_fall = None
    if len(sol.t_events[0]):
        t_fall = float(sol.t_events[0][0])
        print(f"  |roll| reached {ROLL_LIMIT} rad at t = {t_fall!r} s (integration stopped: the bicycle falls)")
    else:
        print(f"  max |roll| over the last 2 s: {np.max(np.abs(roll[sol.t >= 8.0])):.3e}")
    print(f"  energy: E(0) = {E0!r} J, max |E - E0| / |E0| = {drift:.1e} "
          f"(relative to kinetic energy {drift_ke:.1e}); rtol 1e-10 vs 1e-12 roll diff {diff:.1e}")
    print(f"  constraint residuals at the end: holonomic {hres:.1e} m, velocity {nres:.1e} m/s")
    sim[f"v{v:g}"] = {
        "v": v, "roll0": 0.05, "integrator": "scipy DOP853 rtol 1e-12 atol 1e-14",
        "initial_q": [repr(float(z)) for z in q0], "initial_u": [repr(float(z)) for z in u0],
        "q_names": qnames, "u_names": ["u_" + n for n in qnames],
        "t": sol.t.tolist(), "roll": [repr(float(z)) for z in roll],
        "steer": [repr(float(z)) for z in sol.y[6]],
        "pitch": [repr(float(z)) for z in sol.y[4]],
        "yaw": [repr(float(z)) for z in sol.y[2]],
        "t_roll_reaches_1rad": t_fall,
        "energy_rel_drift": float(drift), "energy_rel_drift_vs_kinetic": float(drift_ke),
        "roll_maxdiff_rtol1e-10_vs_1e-12": float(diff),
        "final_constraint_residuals": [hres, nres],
        "final_t": float(sol.t[-1]),
        "final_state": [repr(float(z)) for z in sol.y[:, -1]],
    }

# small-amplitude nonlinear run against the linear model (consistency of the two)
from scipy.linalg import expm
v = 5.0
eps = 1e-6
Mn = np.array(mp.matrix(Mlin).tolist(), dtype=float)
Cn = np.array(mp.matrix(C1).tolist(), dtype=float)
Kn = gnum * np.array(mp.matrix(K0).tolist(), dtype=float) + v**2 * np.array(mp.matrix(K2).tolist(), dtype=float)
Alin = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.linalg.solve(Mn, Kn), -np.linalg.solve(Mn, v * Cn)]])
q0, u0 = consistent_state(eps, v)
ts = np.array([1.0, 2.0, 3.0, 5.0])
sol = solve_ivp(rhs, (0, 5), np.concatenate([q0, u0]), method="DOP853", rtol=1e-12, atol=1e-16, t_eval=ts)
lin = np.array([expm(Alin * tt) @ np.array([eps, 0, 0, 0]) for tt in ts])
rel = np.max(np.abs(sol.y[3] - lin[:, 0])) / eps
print(f"\nnonlinear vs linear model, v = 5, roll0 = 1e-6: max |roll_nl - roll_lin| / roll0 = {rel:.1e} (t = 1, 2, 3, 5 s)")
sim["small_amplitude_vs_linear"] = {"v": v, "roll0": eps, "t": ts.tolist(),
                                    "roll_nonlinear": sol.y[3].tolist(), "roll_linear": lin[:, 0].tolist(),
                                    "max_diff_over_roll0": float(rel)}
report["nonlinear"] = sim
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bicycle.json"), "w") as fh:
    json.dump(report, fh, indent=1)
log("wrote bicycle.json")
