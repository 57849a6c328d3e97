#!/usr/bin/env python3
"""Independent reference data for a thin uniform disc rolling without slip on
the horizontal plane z = 0.

Model (see rolling_disc.md): translations x, y, z of the centre along n1, n2,
n3 (speeds ux, uy, uz = dx/dt, dy/dt, dz/dt), then body-fixed 3-1-2 rotations
psi (yaw, about n3), phi (lean, about the once-rotated axis 1), theta (spin,
about the twice-rotated axis 2 = symmetry axis d2); speeds u4, u5, u6 = the
components of D's angular velocity in N along d1, d2, d3.
Holonomic: z - r cos(phi) = 0. Rolling: v_centre + w_D x (-r l3) = 0.

Formulation 1: sympy.physics.mechanics.KanesMethod, q_ind = [x, y, psi, phi,
theta], q_dep = [z], u_ind = [u4, u5, u6], u_dep = [ux, uy, uz]. Its 6x6 mass
matrix holds the 3 dynamical equations and the 3 acceleration constraints, so
M^-1 f gives du/dt of ALL speeds.

Formulation 2 (cross-check, numpy only): Newton-Euler of the disc with the
contact force as unknown (9x9 linear system: m a = F - m g n3,
I alpha + w x I w = rho x F, a + alpha x rho + w x d(rho)/dt = 0).

Writes ../rolling-disc.json (tests/reference/); shared pieces are in common.py.
"""
import time

import numpy as np
import sympy as sp
import sympy.physics.mechanics as me

from common import header, integrate, integrate_checked, lambdifier, sample, \
    trajectory_head, trajectory_records, write_reference

T0 = time.time()


def stage(msg):
    print(f"[{time.time() - T0:7.1f} s] {msg}", flush=True)

PAR = dict(m=1.0, r=0.5, g=9.81)
PNAMES = ["m", "r", "g"]
PV = np.array([PAR[n] for n in PNAMES])
QN = ["x", "y", "z", "psi", "phi", "theta"]
UN = ["ux", "uy", "uz", "u4", "u5", "u6"]

# ---------------------------------------------------------------------------
# Formulation 1: Kane's method with constraints
# ---------------------------------------------------------------------------
x, y, z, psi, phi, theta = me.dynamicsymbols("x y z psi phi theta")
ux, uy, uz, u4, u5, u6 = me.dynamicsymbols("ux uy uz u4 u5 u6")
m, r, g = sp.symbols(PNAMES)
t = me.dynamicsymbols._t
qs = [x, y, z, psi, phi, theta]
us = [ux, uy, uz, u4, u5, u6]

N = me.ReferenceFrame("N")
A = me.ReferenceFrame("A")     # after yaw
L = me.ReferenceFrame("L")     # after yaw and lean
D = me.ReferenceFrame("D")     # the disc
A.orient_axis(N, N.z, psi)
L.orient_axis(A, A.x, phi)
D.orient_axis(L, L.y, theta)
# check: the chain equals sympy's own body-fixed '312' sequence
D2 = me.ReferenceFrame("D2")
D2.orient_body_fixed(N, (psi, phi, theta), "312")
assert sp.simplify(D.dcm(N) - D2.dcm(N)) == sp.zeros(3, 3)
# check: right-handed (lean phi > 0 tilts l3 towards -a2; l3 . n3 = cos phi)
assert sp.simplify(L.z.dot(A.y) + sp.sin(phi)) == 0
assert sp.simplify(L.z.dot(N.z) - sp.cos(phi)) == 0

stage("frames checked")
w_kin = D.ang_vel_in(N)          # psi' n3 + phi' a1 + theta' l2
kd = [x.diff(t) - ux, y.diff(t) - uy, z.diff(t) - uz,
      w_kin.dot(D.x) - u4, w_kin.dot(D.y) - u5, w_kin.dot(D.z) - u6]
D.set_ang_vel(N, u4 * D.x + u5 * D.y + u6 * D.z)

O = me.Point("O")
O.set_vel(N, 0)
Dc = O.locatenew("Dc", x * N.x + y * N.y + z * N.z)
Dc.set_vel(N, ux * N.x + uy * N.y + uz * N.z)
rho = -r * L.z                   # centre -> contact point P
vP = Dc.vel(N) + D.ang_vel_in(N).cross(rho)   # velocity of D's material point at P
vel_con = [vP.dot(N.x), vP.dot(N.y), vP.dot(N.z)]
config_con = [z - r * sp.cos(phi)]

I_D = me.inertia(D, m * r**2 / 4, m * r**2 / 2, m * r**2 / 4)
disc = me.RigidBody("disc", Dc, D, m, (I_D, Dc))
loads = [(Dc, -m * g * N.z)]

stage("constraints built")
t_der = time.time()
KM = me.KanesMethod(N, q_ind=[x, y, psi, phi, theta], u_ind=[u4, u5, u6],
                    kd_eqs=kd, q_dependent=[z], configuration_constraints=config_con,
                    u_dependent=[ux, uy, uz], velocity_constraints=vel_con,
                    kd_eqs_solver="CRAMER")
# (the default LU solve of the kinematic equations pivots on an entry that
#  vanishes at theta = 0, giving 0/0 there; Cramer's rule leaves only the
#  genuine 3-1-2 singularity cos(phi) = 0 in the denominators)
KM.kanes_equations([disc], loads)
Mk = KM.mass_matrix          # 6x6, rows: 3 dynamic + 3 acceleration constraints
fk = KM.forcing
assert Mk.shape == (6, 6)
# the order of KM.u is u_ind + u_dep
assert list(KM.u) == [u4, u5, u6, ux, uy, uz]
kdd = KM.kindiffdict()
derivation_s = time.time() - t_der

stage("kane done")
# the n3 velocity constraint is d/dt of the holonomic one along the kinematics
chk = (config_con[0].diff(t) - vel_con[2]).subs(kdd)
assert sp.simplify(chk) == 0

stage("holonomic/velocity consistency checked")
lam = lambdifier(qs, us, [m, r, g], first_index=0)

t_lam = time.time()
M_f = lam(Mk)
f_f = lam(fk)
qdot_f = lam(sp.Matrix([kdd[q.diff(t)] for q in qs]))
Bv = sp.Matrix(vel_con).jacobian(us)
assert sp.simplify(sp.Matrix(vel_con) - Bv * sp.Matrix(us)) == sp.zeros(3, 1)
Bv_f = lam(Bv)
vcon_f = lam(sp.Matrix(vel_con))
con_f = lam(sp.Matrix(config_con))
conJ_f = lam(sp.Matrix(config_con).jacobian([z]))
KE_f = lam(disc.kinetic_energy(N))
VG_f = lam(m * g * Dc.pos_from(O).dot(N.z))
stage("lambdified")
lambdify_s = time.time() - t_lam
# kane order of udot is [u4, u5, u6, ux, uy, uz]; reorder to UN order
PERM = [3, 4, 5, 0, 1, 2]


def kane_udot(q, u):
    sol = np.linalg.solve(M_f(q, u, PV), f_f(q, u, PV).ravel())
    return sol[PERM]


def kane_qdot(q, u):
    return qdot_f(q, u, PV).ravel()


def energy(q, u):
    ke, vg = float(KE_f(q, u, PV)), float(VG_f(q, u, PV))
    return ke + vg, ke, vg


def solve_dep_q(qi, guess=0.0):
    """qi = [x, y, psi, phi, theta] -> full q, z by Newton."""
    q = np.array([qi[0], qi[1], guess, qi[2], qi[3], qi[4]], float)
    for _ in range(20):
        res = con_f(q, np.zeros(6), PV).ravel()
        if abs(res[0]) < 1e-16:
            break
        q[2] -= res[0] / conJ_f(q, np.zeros(6), PV)[0, 0]
    return q


def dep_u(q, uind):
    """uind = [u4, u5, u6] -> full u in UN order, from the velocity constraints."""
    Bm = Bv_f(q, np.zeros(6), PV)
    udep = np.linalg.solve(Bm[:, :3], -Bm[:, 3:] @ np.asarray(uind))
    return np.concatenate([udep, uind])


# ---------------------------------------------------------------------------
# Formulation 2: Newton-Euler with the contact force as unknown (numpy only)
# ---------------------------------------------------------------------------
def Rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def Rx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])


def Ry(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1.0, 0], [-s, 0, c]])


def skew(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def ne_frames(q):
    """Columns are the unit vectors of A, L, D expressed in N."""
    NA = Rz(q[3])
    NL = NA @ Rx(q[4])
    ND = NL @ Ry(q[5])
    return NA, NL, ND


def ne_angle_rates(q, u):
    NA, NL, ND = ne_frames(q)
    w = ND @ u[3:]
    # w = psi' n3 + phi' a1 + theta' l2
    Mrates = np.column_stack([[0, 0, 1.0], NA[:, 0], NL[:, 1]])
    return np.linalg.solve(Mrates, w)


def ne_dep_u(q, uind):
    NA, NL, ND = ne_frames(q)
    w = ND @ np.asarray(uind)
    vc = -np.cross(w, -PAR["r"] * NL[:, 2])
    return np.concatenate([vc, uind])


def ne_qdot(q, u):
    return np.concatenate([u[:3], ne_angle_rates(q, u)])


def ne_udot(q, u):
    mm, rr, gg = PAR["m"], PAR["r"], PAR["g"]
    NA, NL, ND = ne_frames(q)
    w = ND @ u[3:]
    psid, phid, _ = ne_angle_rates(q, u)
    wL = psid * np.array([0, 0, 1.0]) + phid * NA[:, 0]
    l3 = NL[:, 2]
    rh = -rr * l3
    rhd = -rr * np.cross(wL, l3)
    IN = ND @ np.diag([mm * rr**2 / 4, mm * rr**2 / 2, mm * rr**2 / 4]) @ ND.T
    # unknowns X = [a (3), alpha (3), F (3)], all in N components
    S = np.zeros((9, 9))
    b = np.zeros(9)
    S[0:3, 0:3] = mm * np.eye(3)
    S[0:3, 6:9] = -np.eye(3)
    b[0:3] = [0, 0, -mm * gg]
    S[3:6, 3:6] = IN
    S[3:6, 6:9] = -skew(rh)
    b[3:6] = -np.cross(w, IN @ w)
    S[6:9, 0:3] = np.eye(3)
    S[6:9, 3:6] = -skew(rh)          # alpha x rho = -rho x alpha
    b[6:9] = -np.cross(w, rhd)
    X = np.linalg.solve(S, b)
    # d/dt (w . d_i) = alpha . d_i  (since w . (w x d_i) = 0)
    return np.concatenate([X[0:3], ND.T @ X[3:6]])


def ne_energy(q, u):
    mm, rr, gg = PAR["m"], PAR["r"], PAR["g"]
    Id = np.diag([mm * rr**2 / 4, mm * rr**2 / 2, mm * rr**2 / 4])
    return 0.5 * mm * u[:3] @ u[:3] + 0.5 * u[3:] @ Id @ u[3:] + mm * gg * q[2]


# ---------------------------------------------------------------------------
# Samples and cross-check
# ---------------------------------------------------------------------------
SEED = 20240612
rng = np.random.default_rng(SEED)
samples = []
mx = dict(du_abs=0.0, du_rel=0.0, dq_abs=0.0, udep_abs=0.0, energy_abs=0.0,
          con=0.0, vcon=0.0)
n_random = 200
# extra states at special angles (0, +-pi/2, pi) where a careless symbolic
# solve could divide 0 by 0
special = [([0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 8.0, 0.5]),
           ([0.0, 0.0, 0.0, 0.3, 0.0], [0.0, 8.0, 0.5]),
           ([1.0, -1.0, np.pi / 2, 0.3, np.pi / 2], [0.7, -3.0, 0.2]),
           ([0.0, 0.0, np.pi, -0.5, np.pi], [-0.4, 2.0, 1.5]),
           ([0.0, 0.0, -np.pi / 2, 0.0, -np.pi / 2], [1.0, 1.0, 1.0])]
n_check = n_random + len(special)
for i in range(n_check):
    if i < n_random:
        qi = [rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-np.pi, np.pi),
              rng.uniform(-1.2, 1.2), rng.uniform(-np.pi, np.pi)]
        uind = [rng.uniform(-3, 3), rng.uniform(-10, 10), rng.uniform(-3, 3)]
    else:
        qi, uind = special[i - n_random]
    q = solve_dep_q(qi)
    u = dep_u(q, uind)
    mx["udep_abs"] = max(mx["udep_abs"], np.max(np.abs(u - ne_dep_u(q, uind))))
    rc = abs(float(con_f(q, u, PV)[0, 0]))
    rv = float(np.max(np.abs(vcon_f(q, u, PV))))
    mx["con"], mx["vcon"] = max(mx["con"], rc), max(mx["vcon"], rv)
    dq = kane_qdot(q, u)
    du = kane_udot(q, u)
    d = np.max(np.abs(du - ne_udot(q, u)))
    mx["du_abs"] = max(mx["du_abs"], d)
    mx["du_rel"] = max(mx["du_rel"], d / np.max(np.abs(du)))
    mx["dq_abs"] = max(mx["dq_abs"], np.max(np.abs(dq - ne_qdot(q, u))))
    E_, ke, vg = energy(q, u)
    mx["energy_abs"] = max(mx["energy_abs"], abs(E_ - ne_energy(q, u)))
    assert np.all(np.isfinite(du)) and np.all(np.isfinite(dq))
    if i < 8:
        samples.append(sample(q, u, dq, du, (E_, ke, vg), rc, rv))
mx = {k_: float(v) for k_, v in mx.items()}
print("cross-check over", n_check, "states:", mx)


# ---------------------------------------------------------------------------
# Reduced ODE in y = [x, y, psi, phi, theta, u4, u5, u6]
# ---------------------------------------------------------------------------
def full_state(yv, which="kane"):
    q = solve_dep_q([yv[0], yv[1], yv[2], yv[3], yv[4]])
    u = dep_u(q, yv[5:]) if which == "kane" else ne_dep_u(q, yv[5:])
    return q, u


def rhs(_t, yv, which="kane"):
    q, u = full_state(yv, which)
    if which == "kane":
        dq, du = kane_qdot(q, u), kane_udot(q, u)
    else:
        dq, du = ne_qdot(q, u), ne_udot(q, u)
    return np.concatenate([dq[[0, 1, 3, 4, 5]], du[3:]])


# main trajectory ------------------------------------------------------------
Y0 = [0.0, 0.0, 0.0, 0.3, 0.0, 0.0, 8.0, 0.5]
t_int = time.time()
ts, Y, nfev, traj_ne, traj_err, traj_err_tight = integrate_checked(
    rhs, Y0, 5.0, 0.1, cross="ne")
records, E0, drift, tcon, tvcon = trajectory_records(
    ts, Y, full_state, energy, con_f, vcon_f, PV)
phis = Y[:, 3]
print(f"trajectory: nfev {nfev}, E0 {E0:.15g}, max|E-E0| {drift:.3e} "
      f"(rel {drift/abs(E0):.3e}), kane vs NE {traj_ne:.3e}, tol 1e-12 vs 1e-13 "
      f"{traj_err:.3e}, tol 2.5e-14 vs 1e-13 {traj_err_tight:.3e}, phi range [{phis.min():.4f}, {phis.max():.4f}], "
      f"con {tcon:.1e}, vcon {tvcon:.1e}, {time.time()-t_int:.1f} s")


# ---------------------------------------------------------------------------
# Steady turning: constant lean phi0, yaw rate Omega, spin rate theta'
#   (I_a + m r^2) w2 Omega cos(phi0) - I_d Omega^2 sin(phi0) cos(phi0)
#       + m g r sin(phi0) = 0,   w2 = theta' + Omega sin(phi0)
#   thin disc I_a = m r^2/2, I_d = m r^2/4:
#   w2 = (r Omega^2 sin(phi0) cos(phi0)/4 - g sin(phi0)) / (1.5 r Omega cos(phi0))
# ---------------------------------------------------------------------------
def steady_w2(phi0, Om):
    rr, gg = PAR["r"], PAR["g"]
    return ((rr * Om**2 * np.sin(phi0) * np.cos(phi0) / 4 - gg * np.sin(phi0))
            / (1.5 * rr * Om * np.cos(phi0)))


cases_in = [(0.2, -0.5), (-0.3, 1.0), (0.6, -4.0)]
steady = []
for phi0, Om in cases_in:
    w2 = steady_w2(phi0, Om)
    thd = w2 - Om * np.sin(phi0)
    yv0 = [0.0, 0.0, 0.0, phi0, 0.0, 0.0, w2, Om * np.cos(phi0)]
    q0, u0 = full_state(yv0)
    du0 = kane_udot(q0, u0)
    # steady motion at theta = 0: centre acceleration r w2 Omega a2 (a2 = n2
    # at psi = 0); u4 = -Omega cos(phi0) sin(theta) => du4/dt = -Omega cos(phi0) theta'
    du_expected = np.array([0.0, PAR["r"] * w2 * Om, 0.0,
                            -Om * np.cos(phi0) * thd, 0.0, 0.0])
    inst_err = float(np.max(np.abs(du0 - du_expected)))
    tt, YY, nf = integrate(rhs, yv0, 5.0, 0.05)
    dev_phi = float(np.max(np.abs(YY[:, 3] - phi0)))
    rates = np.array([kane_qdot(*full_state(yy)) for yy in YY])
    dev_psid = float(np.max(np.abs(rates[:, 3] - Om)))
    dev_thd = float(np.max(np.abs(rates[:, 5] - thd)))
    Rc = PAR["r"] * w2 / Om
    xa = Rc * np.sin(Om * tt)
    ya = Rc * (1 - np.cos(Om * tt))
    dev_xy = float(np.max(np.abs(np.column_stack([YY[:, 0] - xa, YY[:, 1] - ya]))))
    dev_ang = float(max(np.max(np.abs(YY[:, 2] - Om * tt)),
                        np.max(np.abs(YY[:, 4] - thd * tt))))
    print(f"steady phi0={phi0} Omega={Om}: w2={w2:.6f} theta'={thd:.6f} "
          f"inst du err {inst_err:.1e}; over 5 s: |phi-phi0| {dev_phi:.1e}, "
          f"|psi'-Om| {dev_psid:.1e}, |theta'-s| {dev_thd:.1e}, xy vs circle {dev_xy:.1e},"
          f" angles vs linear {dev_ang:.1e}")
    steady.append({
        "phi0": phi0, "psi_dot0": Om, "theta_dot0": float(thd),
        "spin_about_d2_w2": float(w2),
        "centre_speed": float(PAR["r"] * w2),
        "centre_circle_radius_signed": float(Rc),
        "initial_q": q0.tolist(), "initial_u": u0.tolist(),
        "initial_du": du0.tolist(),
        "check_instantaneous_du_vs_analytic": inst_err,
        "check_5s_max_abs_phi_minus_phi0": dev_phi,
        "check_5s_max_abs_psidot_minus_psi_dot0": dev_psid,
        "check_5s_max_abs_thetadot_minus_theta_dot0": dev_thd,
        "check_5s_max_abs_xy_vs_analytic_circle": dev_xy,
        "check_5s_max_abs_psi_theta_vs_linear": dev_ang,
    })

out = header(
    model="rolling_disc",
    generator="sympy.physics.mechanics KanesMethod with configuration and "
              "velocity (rolling) constraints; du/dt (all speeds) = M^-1 f, "
              "M = [dynamic eqs; acceleration constraints]",
    spec="refgen/rolling_disc.md") | {
    "coordinates": QN,
    "speeds": UN,
    "independent_coordinates": ["x", "y", "psi", "phi", "theta"],
    "dependent_coordinates": ["z"],
    "independent_speeds": ["u4", "u5", "u6"],
    "dependent_speeds": ["ux", "uy", "uz"],
    "speed_definitions": "ux, uy, uz = dx/dt, dy/dt, dz/dt; w_D/N = u4 d1 + u5 d2 + u6 d3",
    "rotation": "body-fixed 3-1-2: psi about n3, phi about a1, theta about l2 (= d2)",
    "parameter_names": PNAMES,
    "inputs": [],
    "parameters": PAR,
    "inertia_about_cm": "diag(m r^2/4, m r^2/2, m r^2/4) in D axes",
    "constraints": {
        "configuration": "z - r cos(phi) = 0",
        "velocity": "v_centre + w_D x (-r l3) = 0 (n1, n2, n3 components)"},
    "energy_definition": "0.5 m |v_centre|^2 + 0.5 w.I.w + m g z",
    "derivation_s": round(derivation_s, 3),
    "lambdify_s": round(lambdify_s, 3),
    "sampling": {"rng": "numpy default_rng", "seed": SEED,
                 "x, y": "uniform [-2, 2]", "psi, theta": "uniform [-pi, pi]",
                 "phi": "uniform [-1.2, 1.2]",
                 "u4, u6": "uniform [-3, 3]", "u5": "uniform [-10, 10]",
                 "dependent": "z by Newton; ux, uy, uz from the velocity constraints"},
    "cross_check": {
        "method": "Newton-Euler with the contact force as unknown (9x9 numpy "
                  "solve), hand-written rotation matrices and Euler-rate inversion",
        "states": f"{n_random} random (the first 8 are the samples) + "
                  f"{len(special)} at special angles (0, +-pi/2, pi)",
        "max_abs_diff_du": mx["du_abs"], "max_rel_diff_du": mx["du_rel"],
        "max_abs_diff_dq": mx["dq_abs"],
        "max_abs_diff_dependent_speeds": mx["udep_abs"],
        "max_abs_diff_energy": mx["energy_abs"],
        "max_configuration_residual": mx["con"],
        "max_velocity_residual": mx["vcon"]},
    "samples": samples,
    "trajectory": trajectory_head(
        integrator="scipy solve_ivp DOP853, rtol = atol = 1e-13, reduced ODE in "
                   "[x, y, psi, phi, theta, u4, u5, u6]; restarted every 0.1 s so "
                   "each record is a step end; z, ux, uy, uz reconstructed",
        records=records, t_end=5.0, dt=0.1, nfev=nfev, drift=drift) | {
        "energy_max_rel_drift": float(drift / abs(E0)),
        "max_configuration_residual": float(tcon),
        "max_velocity_residual": float(tvcon),
        "phi_range": [float(phis.min()), float(phis.max())],
        "max_abs_diff_vs_newton_euler_rhs_trajectory": traj_ne,
        "max_abs_diff_vs_tol_1e-12_run": traj_err,
        "max_abs_diff_vs_tol_2.5e-14_run": traj_err_tight,
        "records": records},
    "steady_precession": {
        "condition": "(I_a + m r^2) w2 Omega cos(phi0) - I_d Omega^2 sin(phi0) "
                     "cos(phi0) + m g r sin(phi0) = 0 with I_a = m r^2/2, "
                     "I_d = m r^2/4, Omega = psi_dot0, w2 = theta_dot0 + Omega "
                     "sin(phi0) (= u5); thin disc: w2 = (r Omega^2 sin(phi0) "
                     "cos(phi0)/4 - g sin(phi0)) / (1.5 r Omega cos(phi0))",
        "initial_state": "x = y = psi = theta = 0, z = r cos(phi0); u4 = 0, u5 = w2, "
                         "u6 = Omega cos(phi0); ux = r w2, uy = uz = 0",
        "check": "integrated 5 s (DOP853, 1e-13, records every 0.05 s)",
        "cases": steady},
    "runtime_s": round(time.time() - T0, 1),
}
write_reference(out, "rolling-disc.json", T0)
