#!/usr/bin/env python3
"""Independent reference data for the planar four-bar linkage (crank-rocker).

Model (see fourbar.md): crank C (q1, absolute), coupler K (q2, relative to C),
rocker R (q3, absolute), all rotations about axis 1, motion in the n2-n3 plane.
Loop closure: coupler tip E == rocker tip (n2 and n3 components).

Formulation 1: sympy.physics.mechanics.KanesMethod with q_ind=[q1],
q_dep=[q2,q3], u_ind=[u1], u_dep=[u2,u3], configuration and velocity
constraints. Its mass matrix (3x3) holds the 1 dynamical equation plus the 2
acceleration constraints, so M^-1 f gives du/dt of ALL speeds.

Formulation 2 (cross-check, numpy only): Newton-Euler for three free planar
bodies (mass-centre position + absolute angle each, 9 coordinates) joined by
four pins (8 constraint equations), solved as a Lagrange-multiplier KKT system.

Writes ../four-bar.json (tests/reference/); shared pieces are in common.py.
"""
import time

import numpy as np
import sympy as sp
import sympy.physics.mechanics as me

from common import header, integrate_checked, lambdifier, sample, \
    trajectory_head, trajectory_records, write_reference

T0 = time.time()

# ---------------------------------------------------------------------------
# Parameters
# ---------------------------------------------------------------------------
PAR = dict(L0=1.0, L1=0.3, L2=1.0, L3=0.8, m1=1.0, m2=2.0, m3=1.5,
           k=5.0, q10=0.2, g=9.81)
PNAMES = ["L0", "L1", "L2", "L3", "m1", "m2", "m3", "k", "q10", "g"]
PV = np.array([PAR[n] for n in PNAMES])
IYY = 0.001  # inertia about each bar's own long axis (irrelevant in plane)

# Grashof / crank-rocker check --------------------------------------------
lengths = {"ground L0": PAR["L0"], "crank L1": PAR["L1"],
           "coupler L2": PAR["L2"], "rocker L3": PAR["L3"]}
ls = sorted(lengths.values())
grashof = ls[0] + ls[3] <= ls[1] + ls[2]
shortest = min(lengths, key=lengths.get)
assert grashof and shortest == "crank L1", "not a Grashof crank-rocker"
# |B - D| ranges over [L0 - L1, L0 + L1] as the crank turns; the triangle
# B-E-D must never degenerate: |L2 - L3| < |BD| < L2 + L3 for every q1.
assert abs(PAR["L2"] - PAR["L3"]) < PAR["L0"] - PAR["L1"]
assert PAR["L0"] + PAR["L1"] < PAR["L2"] + PAR["L3"]

# ---------------------------------------------------------------------------
# Formulation 1: Kane's method with constraints (sympy.physics.mechanics)
# ---------------------------------------------------------------------------
q1, q2, q3 = me.dynamicsymbols("q1 q2 q3")
u1, u2, u3 = me.dynamicsymbols("u1 u2 u3")
L0, L1, L2, L3, m1, m2, m3, k, q10, g = sp.symbols(PNAMES)
t = me.dynamicsymbols._t

N = me.ReferenceFrame("N")
C = me.ReferenceFrame("C")
K = me.ReferenceFrame("K")
R = me.ReferenceFrame("R")
C.orient_axis(N, N.x, q1)
K.orient_axis(C, C.x, q2)
R.orient_axis(N, N.x, q3)
# sanity: right-handed rotation about axis 1 sends x2 -> cos q x2 + sin q x3
assert sp.simplify(C.y.dot(N.z) - sp.sin(q1)) == 0
assert sp.simplify(C.y.dot(N.y) - sp.cos(q1)) == 0
# angular velocities in terms of the generalized speeds
C.set_ang_vel(N, u1 * N.x)
K.set_ang_vel(C, u2 * C.x)
R.set_ang_vel(N, u3 * N.x)

A = me.Point("A")
A.set_vel(N, 0)
Dp = me.Point("D")
Dp.set_pos(A, L0 * N.y)
Dp.set_vel(N, 0)
B = A.locatenew("B", L1 * C.y)
E = B.locatenew("E", L2 * K.y)
Rt = Dp.locatenew("Rtip", L3 * R.y)
Ccm = A.locatenew("Ccm", L1 / 2 * C.y)
Kcm = B.locatenew("Kcm", L2 / 2 * K.y)
Rcm = Dp.locatenew("Rcm", L3 / 2 * R.y)
Ccm.v2pt_theory(A, N, C)
B.v2pt_theory(A, N, C)
Kcm.v2pt_theory(B, N, K)
E.v2pt_theory(B, N, K)
Rcm.v2pt_theory(Dp, N, R)
Rt.v2pt_theory(Dp, N, R)

loop = E.pos_from(A) - Rt.pos_from(A)
config_con = [loop.dot(N.y), loop.dot(N.z)]
vloop = E.vel(N) - Rt.vel(N)
vel_con = [vloop.dot(N.y), vloop.dot(N.z)]
# the velocity constraints must be the time derivative of the configuration
# constraints (with dq/dt = u)
qd2u = {q1.diff(t): u1, q2.diff(t): u2, q3.diff(t): u3}
for c, v in zip(config_con, vel_con):
    assert sp.simplify(c.diff(t).subs(qd2u) - v) == 0


def bar(name, frame, cm, m, L):
    I = me.inertia(frame, m * L**2 / 12, IYY, m * L**2 / 12)
    return me.RigidBody(name, cm, frame, m, (I, cm))


bodies = [bar("Cb", C, Ccm, m1, L1), bar("Kb", K, Kcm, m2, L2),
          bar("Rb", R, Rcm, m3, L3)]
loads = [(Ccm, -m1 * g * N.z), (Kcm, -m2 * g * N.z), (Rcm, -m3 * g * N.z),
         (C, -k * (q1 - q10) * N.x), (N, k * (q1 - q10) * N.x)]

kd = [q1.diff(t) - u1, q2.diff(t) - u2, q3.diff(t) - u3]
t_der = time.time()
KM = me.KanesMethod(N, q_ind=[q1], u_ind=[u1], kd_eqs=kd,
                    q_dependent=[q2, q3], configuration_constraints=config_con,
                    u_dependent=[u2, u3], velocity_constraints=vel_con,
                    constraint_solver="CRAMER")
# (Cramer's rule: the only denominator of the dependent-speed solution is the
#  determinant ~ L2 L3 sin(q3 - q1 - q2), the genuine singularity, which never
#  vanishes on this crank-rocker; sympy's default LU would pivot on sin(q1+q2))
fr, frstar = KM.kanes_equations(bodies, loads)
Mk = KM.mass_matrix      # 3x3: dynamics (1 row) + acceleration constraints
fk = KM.forcing
assert Mk.shape == (3, 3)
derivation_s = time.time() - t_der

qs = [q1, q2, q3]
us = [u1, u2, u3]
lam = lambdifier(qs, us, [L0, L1, L2, L3, m1, m2, m3, k, q10, g], first_index=1)

t_lam = time.time()
M_f = lam(Mk)
f_f = lam(fk)
con_f = lam(sp.Matrix(config_con))
conJ_f = lam(sp.Matrix(config_con).jacobian([q2, q3]))
Bvel = sp.Matrix(vel_con).jacobian(us)      # velocity constraints are linear
assert sp.simplify(sp.Matrix(vel_con) - Bvel * sp.Matrix(us)) == sp.zeros(2, 1)
Bvel_f = lam(Bvel)
vcon_f = lam(sp.Matrix(vel_con))

# energy (sympy expressions, independent of the Kane machinery)
KE = sum(bd.kinetic_energy(N) for bd in bodies)
VG = (m1 * g * Ccm.pos_from(A).dot(N.z) + m2 * g * Kcm.pos_from(A).dot(N.z)
      + m3 * g * Rcm.pos_from(A).dot(N.z))
VS = k * (q1 - q10) ** 2 / 2
KE_f, VG_f, VS_f = lam(KE), lam(VG), lam(VS)
lambdify_s = time.time() - t_lam


def kane_udot(q, u):
    return np.linalg.solve(M_f(q, u, PV), f_f(q, u, PV).ravel())


def energy(q, u):
    ke, vg, vs = float(KE_f(q, u, PV)), float(VG_f(q, u, PV)), float(VS_f(q, u, PV))
    return ke + vg + vs, ke, vg, vs


# ---------------------------------------------------------------------------
# Dependent coordinates and speeds on the chosen branch
# ---------------------------------------------------------------------------
def closed_form_dep(q1v):
    """Circle intersection on the branch ((D-B) x (E-B)) . n1 > 0."""
    Bp = PAR["L1"] * np.array([np.cos(q1v), np.sin(q1v)])     # (n2, n3)
    Dv = np.array([PAR["L0"], 0.0])
    d = np.linalg.norm(Dv - Bp)
    e = (Dv - Bp) / d
    nperp = np.array([-e[1], e[0]])       # e rotated +90 deg about n1
    a = (PAR["L2"] ** 2 - PAR["L3"] ** 2 + d * d) / (2 * d)
    h = np.sqrt(PAR["L2"] ** 2 - a * a)
    Ev = Bp + a * e + h * nperp
    thK = np.arctan2(Ev[1] - Bp[1], Ev[0] - Bp[0])      # absolute coupler angle
    q3v = np.arctan2(Ev[1] - Dv[1], Ev[0] - Dv[0])
    return thK - q1v, q3v


def solve_dep_q(q1v, guess=None):
    """Newton on the two loop equations for (q2, q3), to ~1e-16."""
    qd = np.array(closed_form_dep(q1v) if guess is None else guess, float)
    for _ in range(20):
        q = np.array([q1v, qd[0], qd[1]])
        r = con_f(q, np.zeros(3), PV).ravel()
        if np.max(np.abs(r)) < 2e-16:
            break
        qd = qd - np.linalg.solve(conJ_f(q, np.zeros(3), PV), r)
    q = np.array([q1v, qd[0], qd[1]])
    return q


def branch_sign(q):
    Bp = PAR["L1"] * np.array([np.cos(q[0]), np.sin(q[0])])
    Ev = Bp + PAR["L2"] * np.array([np.cos(q[0] + q[1]), np.sin(q[0] + q[1])])
    Dv = np.array([PAR["L0"], 0.0])
    a, b = Dv - Bp, Ev - Bp
    return a[0] * b[1] - a[1] * b[0]


def dep_u(q, u1v):
    Bm = Bvel_f(q, np.zeros(3), PV)
    ud = np.linalg.solve(Bm[:, 1:], -Bm[:, 0] * u1v)
    return np.array([u1v, ud[0], ud[1]])


# ---------------------------------------------------------------------------
# Formulation 2: planar Newton-Euler + Lagrange multipliers (numpy only)
# ---------------------------------------------------------------------------
def dae_udot(q, u):
    Lc, Lk, Lr, Lg = PAR["L1"], PAR["L2"], PAR["L3"], PAR["L0"]
    th = np.array([q[0], q[0] + q[1], q[2]])           # absolute angles
    om = np.array([u[0], u[0] + u[1], u[2]])
    half = np.array([Lc, Lk, Lr]) / 2
    mass = np.array([PAR["m1"], PAR["m2"], PAR["m3"]])
    Izz = mass * np.array([Lc, Lk, Lr]) ** 2 / 12       # about axis 1
    e = np.stack([np.cos(th), np.sin(th)], 1)           # along-bar unit vectors
    ep = np.stack([-np.sin(th), np.cos(th)], 1)         # e rotated +90 deg
    # generalized coordinates p = [yC, zC, thC, yK, zK, thK, yR, zR, thR]
    # point of body b at signed distance s from its mass centre along e_b:
    # pos = cm_b + s e_b ; acc = a_cm_b + s (thdd_b ep_b - om_b^2 e_b)
    # pins: (body, s) == (body, s) or fixed point
    pins = [((0, -half[0]), None),                 # A: crank base = origin
            ((1, -half[1]), (0, +half[0])),        # B: coupler base = crank tip
            ((2, -half[2]), None),                 # D: rocker base = (L0, 0)
            ((1, +half[1]), (2, +half[2]))]        # E: coupler tip = rocker tip
    J = np.zeros((8, 9))
    gam = np.zeros(8)
    for i, (pa, pb) in enumerate(pins):
        for sign, pt in ((1.0, pa), (-1.0, pb)):
            if pt is None:
                continue
            b, s = pt
            J[2 * i:2 * i + 2, 3 * b:3 * b + 2] += sign * np.eye(2)
            J[2 * i:2 * i + 2, 3 * b + 2] += sign * s * ep[b]
            gam[2 * i:2 * i + 2] += sign * s * om[b] ** 2 * e[b]
    Mm = np.diag(np.concatenate([[mass[b], mass[b], Izz[b]] for b in range(3)]))
    Q = np.concatenate([[0.0, -mass[b] * PAR["g"], 0.0] for b in range(3)])
    Q[2] += -PAR["k"] * (q[0] - PAR["q10"])            # spring on crank
    KKT = np.zeros((17, 17))
    KKT[:9, :9] = Mm
    KKT[:9, 9:] = -J.T
    KKT[9:, :9] = J
    sol = np.linalg.solve(KKT, np.concatenate([Q, gam]))
    thdd = sol[[2, 5, 8]]
    return np.array([thdd[0], thdd[1] - thdd[0], thdd[2]])


def dae_energy(q, u):
    Lc, Lk, Lr = PAR["L1"], PAR["L2"], PAR["L3"]
    th = np.array([q[0], q[0] + q[1], q[2]])
    om = np.array([u[0], u[0] + u[1], u[2]])
    mass = np.array([PAR["m1"], PAR["m2"], PAR["m3"]])
    e = lambda a: np.array([np.cos(a), np.sin(a)])
    ep = lambda a: np.array([-np.sin(a), np.cos(a)])
    base = [np.zeros(2), Lc * e(th[0]), np.array([PAR["L0"], 0.0])]
    vbase = [np.zeros(2), Lc * om[0] * ep(th[0]), np.zeros(2)]
    Ls = [Lc, Lk, Lr]
    E_ = 0.0
    for b in range(3):
        cm = base[b] + Ls[b] / 2 * e(th[b])
        v = vbase[b] + Ls[b] / 2 * om[b] * ep(th[b])
        E_ += 0.5 * mass[b] * v @ v + 0.5 * mass[b] * Ls[b] ** 2 / 12 * om[b] ** 2
        E_ += mass[b] * PAR["g"] * cm[1]
    return E_ + 0.5 * PAR["k"] * (q[0] - PAR["q10"]) ** 2


# ---------------------------------------------------------------------------
# Branch description
# ---------------------------------------------------------------------------
q_at0 = solve_dep_q(0.0)
assert 0 < q_at0[2] < np.pi
grid = np.linspace(-np.pi, np.pi, 3601)
qg = np.array([solve_dep_q(a) for a in grid])
thK_g = qg[:, 0] + qg[:, 1]
assert all(branch_sign(qq) > 0 for qq in qg)
branch = {
    "rule": "assembly mode with ((D - B) x (E - B)) . n1 > 0, i.e. the coupler "
            "tip E lies to the left of the directed line from the crank tip B "
            "to the ground pin D (seen along -n1 with n2 right, n3 up); "
            "continuous for all q1 because |L2-L3| < |BD| < L2+L3 always",
    "at_q1_0": {"q": list(map(float, q_at0)),
                "E_n2_n3": [float(PAR["L1"] + PAR["L2"] * np.cos(q_at0[1])),
                            float(PAR["L2"] * np.sin(q_at0[1]))]},
    "q3_range_over_full_crank_turn": [float(qg[:, 2].min()), float(qg[:, 2].max())],
    "coupler_absolute_angle_q1_plus_q2_range": [float(thK_g.min()), float(thK_g.max())],
    "angle_representation": "q3 = atan2(E_n3 - D_n3, E_n2 - D_n2) in (-pi, pi]; "
                            "q2 = atan2(E - B) - q1 (coupler absolute angle in "
                            "(-pi, pi], which on this branch stays inside (0, pi))",
}
print("branch at q1=0:", q_at0, " q3 range", branch["q3_range_over_full_crank_turn"])

# ---------------------------------------------------------------------------
# Samples
# ---------------------------------------------------------------------------
SEED = 20240611
rng = np.random.default_rng(SEED)
samples = []
max_abs_diff = 0.0
max_rel_diff = 0.0
max_con = 0.0
max_vcon = 0.0
max_ediff = 0.0
n_check = 200
for i in range(n_check):
    q1v = rng.uniform(-np.pi, np.pi)
    u1v = rng.uniform(-4.0, 4.0)
    q = solve_dep_q(q1v)
    u = dep_u(q, u1v)
    rc = np.max(np.abs(con_f(q, u, PV)))
    rv = np.max(np.abs(vcon_f(q, u, PV)))
    max_con, max_vcon = max(max_con, rc), max(max_vcon, rv)
    ud_k = kane_udot(q, u)
    ud_d = dae_udot(q, u)
    diff = np.max(np.abs(ud_k - ud_d))
    max_abs_diff = max(max_abs_diff, diff)
    max_rel_diff = max(max_rel_diff, diff / np.max(np.abs(ud_k)))
    E_, ke, vg, vs = energy(q, u)
    max_ediff = max(max_ediff, abs(E_ - dae_energy(q, u)))
    if i < 8:
        samples.append(sample(q, u, u, ud_k, (E_, ke, vg, vs), rc, rv))
print(f"cross-check over {n_check} states: max|du_kane - du_dae| = {max_abs_diff:.3e}"
      f" (rel {max_rel_diff:.3e}), energy diff {max_ediff:.3e}, "
      f"config res {max_con:.2e}, vel res {max_vcon:.2e}")


# ---------------------------------------------------------------------------
# Trajectory: reduced ODE in (q1, u1), dependent quantities reconstructed
# ---------------------------------------------------------------------------
def full_state(y):
    q = solve_dep_q(y[0])
    u = dep_u(q, y[1])
    return q, u


def rhs(_t, y, which="kane"):
    q, u = full_state(y)
    ud = kane_udot(q, u) if which == "kane" else dae_udot(q, u)
    return [u[0], ud[0]]


# from q1 = 0.5, u1 = 0: 10 s, recorded every 0.1 s
ts, Y, nfev, traj_dae_diff, traj_err_est, traj_err_tight = integrate_checked(
    rhs, [0.5, 0.0], 10.0, 0.1, cross="dae")
records, E0, max_drift, traj_con, traj_vcon = trajectory_records(
    ts, Y, full_state, energy, con_f, vcon_f, PV)
kin_scale = max(energy(*full_state(y))[1] for y in Y)
q1s = Y[:, 0]
print(f"trajectory: nfev {nfev}, E0 {E0:.15g}, max |E-E0| {max_drift:.3e} "
      f"(rel to |E0| {max_drift/abs(E0):.3e}, rel to max KE {max_drift/kin_scale:.3e}),"
      f" kane vs dae traj {traj_dae_diff:.3e}, tol 1e-12 vs 1e-13 {traj_err_est:.3e},"
      f" tol 2.5e-14 vs 1e-13 {traj_err_tight:.3e},"
      f" q1 range [{q1s.min():.4f}, {q1s.max():.4f}]")

out = header(
    model="fourbar",
    generator="sympy.physics.mechanics KanesMethod with configuration and "
              "velocity constraints; du/dt (all speeds) = M^-1 f, M = "
              "[dynamic eq; acceleration constraints]",
    spec="refgen/fourbar.md") | {
    "coordinates": ["q1", "q2", "q3"],
    "speeds": ["u1", "u2", "u3"],
    "independent_coordinates": ["q1"],
    "dependent_coordinates": ["q2", "q3"],
    "independent_speeds": ["u1"],
    "dependent_speeds": ["u2", "u3"],
    "parameter_names": PNAMES + ["Iyy"],
    "inputs": [],
    "parameters": PAR | {"Iyy": IYY},
    "inertia_about_cm": "C: diag(m1 L1^2/12, Iyy, m1 L1^2/12); K: diag(m2 L2^2/12, "
                        "Iyy, m2 L2^2/12); R: diag(m3 L3^2/12, Iyy, m3 L3^2/12)",
    "grashof": {"s_plus_l": ls[0] + ls[3], "p_plus_q": ls[1] + ls[2],
                "shortest_link": shortest, "type": "crank-rocker",
                "lengths_changed": False},
    "branch": branch,
    "configuration_constraints": [
        "L1 cos q1 + L2 cos(q1+q2) - L0 - L3 cos q3 = 0  (n2)",
        "L1 sin q1 + L2 sin(q1+q2) - L3 sin q3 = 0  (n3)"],
    "energy_definition": "kinetic + sum m_i g z_i (z of mass centre along n3, "
                         "from N origin) + 0.5 k (q1 - q10)^2",
    "derivation_s": round(derivation_s, 3),
    "lambdify_s": round(lambdify_s, 3),
    "sampling": {"rng": "numpy default_rng", "seed": SEED,
                 "q1": "uniform [-pi, pi]", "u1": "uniform [-4, 4]",
                 "dependent": "q2, q3 by Newton from the closed-form branch "
                              "solution; u2, u3 from the velocity constraints"},
    "cross_check": {
        "method": "planar Newton-Euler of 3 free bodies + 4 pins (8 Lagrange "
                  "multipliers), numpy KKT solve",
        "states": n_check,
        "max_abs_diff_du": float(max_abs_diff),
        "max_rel_diff_du": float(max_rel_diff),
        "max_abs_diff_energy": float(max_ediff),
        "max_configuration_residual": float(max_con),
        "max_velocity_residual": float(max_vcon)},
    "samples": samples,
    "trajectory": trajectory_head(
        integrator="scipy solve_ivp DOP853, rtol = atol = 1e-13, reduced ODE "
                   "in (q1, u1); restarted every 0.1 s so each record is a "
                   "step end (no dense-output interpolation); q2, q3, u2, u3 "
                   "reconstructed on the branch",
        records=records, t_end=10.0, dt=0.1, nfev=nfev, drift=max_drift) | {
        "energy_max_rel_drift_vs_E0": float(max_drift / abs(E0)),
        "energy_max_drift_vs_max_kinetic": float(max_drift / kin_scale),
        "max_configuration_residual": float(traj_con),
        "max_velocity_residual": float(traj_vcon),
        "max_abs_diff_vs_dae_rhs_trajectory": traj_dae_diff,
        "max_abs_diff_vs_tol_1e-12_run": traj_err_est,
        "max_abs_diff_vs_tol_2.5e-14_run": traj_err_tight,
        "records": records},
    "runtime_s": round(time.time() - T0, 1),
}
write_reference(out, "four-bar.json", T0)
