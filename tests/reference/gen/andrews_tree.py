"""Independent check of the multibody (tree + loop closure) description of
Andrews' squeezing mechanism in andrews.md, with sympy.physics.mechanics.

The tree (all rotations about axis 3, plane n1-n2, no gravity):

  K1  parent N,  joint [0, 0, 0],    rotate 3, q = beta     (absolute)
  K2  parent K1, joint [rr, 0, 0],   rotate 3, q = Theta    (relative to K1)
  K3  parent N,  joint [xb, yb, 0],  rotate 3, q = gamma    (absolute)
  K5  parent N,  joint [xa, ya, 0],  rotate 3, q = delta    (absolute)
  K4  parent K5, joint [zt, 0, 0],   rotate 3, q = Phi      (relative to K5)
  K7  parent N,  joint [xa, ya, 0],  rotate 3, q = epsilon  (absolute)
  K6  parent K7, joint [0, -u, 0],   rotate 3, q = Omega    (relative to K7)

Loop closures: E2 = E3, E2 = E4, E2 = E6 (n1 and n2 components), with
E2 = [-d, 0, 0] in K2, E3 = [0, -ss, 0] in K3, E4 = [0, -e, 0] in K4,
E6 = [zf, 0, 0] in K6.  Spring between D = [sd, -sc, 0] in K3 and the fixed
point C = [xc, yc, 0] in N; driving torque mom n3 on K1 (reaction on N).

Two independent routes, both from the same tree:
  A. KanesMethod with the 6 configuration constraints and their 6 velocity
     constraints (independent speed: beta' ; dependent: the other six).
  B. KanesMethod of the open tree (7 free speeds) + Lagrange multipliers for
     the loop closures, solved numerically.
Both are compared with the published initial accelerations; route B (fast
numerical functions) is also integrated to t = 0.03 s and compared with the
test set's reference solution.

Run:  .venv/bin/python andrews_tree.py
"""
import json
import os
import time

import numpy as np
import sympy as sm
import sympy.physics.mechanics as me
from scipy.integrate import solve_ivp

t0_wall = time.time()
# ---- parameters (numbers, substituted from the start) ------------------------
P = dict(
    m1=.04325, m2=.00365, m3=.02373, m4=.00706, m5=.07050, m6=.00706, m7=.05498,
    I1=2.194e-6, I2=4.410e-7, I3=5.255e-6, I4=5.667e-7, I5=1.169e-5, I6=5.667e-7, I7=1.912e-5,
    xa=-.06934, ya=-.00227, xb=-.03635, yb=.03273, xc=.014, yc=.072,
    d=28e-3, da=115e-4, e=2e-2, ea=1421e-5, rr=7e-3, ra=92e-5,
    ss=35e-3, sa=1874e-5, sb=1043e-5, sc=18e-3, sd=2e-2,
    ta=2308e-5, tb=916e-5, u=4e-2, ua=1228e-5, ub=449e-5,
    zf=2e-2, zt=4e-2, fa=1421e-5, mom=0.033, c0=4530.0, l0=0.07785,
)
S = {k: sm.Float(v, 30) if isinstance(v, float) else v for k, v in P.items()}
globals().update({k: S[k] for k in S})

Q0 = [-0.0617138900142764496358948458001, 0.0, 0.455279819163070380255912382449,
      0.222668390165885884674473185609, 0.487364979543842550225598953530,
      -0.222668390165885884674473185609, 1.23054744454982119249735015568]
BETA_DD_PUB = 14222.4439199541138705911625887
THETA_DD_PUB = -10666.8329399655854029433719415
BETA_003, THETA_003 = 0.1581077119629904e+02, -0.1575637105984298e+02

names = ["beta", "Theta", "gamma", "Phi", "delta", "Omega", "epsilon"]
q = me.dynamicsymbols("beta Theta gamma Phi delta Omega epsilon")
w = me.dynamicsymbols("u_beta u_Theta u_gamma u_Phi u_delta u_Omega u_epsilon")
beta, Theta, gamma_, Phi, delta, Omega, epsilon = q

N = me.ReferenceFrame("N")
O = me.Point("O")
O.set_vel(N, 0)


def body_frame(name, parent_frame, angle):
    F = me.ReferenceFrame(name)
    F.orient_axis(parent_frame, parent_frame.z, angle)
    return F


def vec(F, x, y):
    return x * F.x + y * F.y


K1 = body_frame("K1", N, beta)
K2 = body_frame("K2", K1, Theta)
K3 = body_frame("K3", N, gamma_)
K5 = body_frame("K5", N, delta)
K4 = body_frame("K4", K5, Phi)
K7 = body_frame("K7", N, epsilon)
K6 = body_frame("K6", K7, Omega)

# body origins = joint points (positions from O)
o1 = O
o2 = O.locatenew("o2", vec(K1, rr, 0))
o3 = O.locatenew("o3", vec(N, xb, yb))
o5 = O.locatenew("o5", vec(N, xa, ya))
o4 = o5.locatenew("o4", vec(K5, zt, 0))
o7 = O.locatenew("o7", vec(N, xa, ya))
o6 = o7.locatenew("o6", vec(K7, 0, -u))

# mass centers, in each body's axes from its origin
cm = [
    o1.locatenew("c1", vec(K1, ra, 0)),
    o2.locatenew("c2", vec(K2, -da, 0)),
    o3.locatenew("c3", vec(K3, sa, sb)),
    o4.locatenew("c4", vec(K4, 0, -(e - ea))),
    o5.locatenew("c5", vec(K5, ta, tb)),
    o6.locatenew("c6", vec(K6, zf - fa, 0)),
    o7.locatenew("c7", vec(K7, ua, ub)),
]
frames = [K1, K2, K3, K4, K5, K6, K7]
masses = [m1, m2, m3, m4, m5, m6, m7]
inert = [I1, I2, I3, I4, I5, I6, I7]

# loop-closure points and spring points
E2 = o2.locatenew("E2", vec(K2, -d, 0))
E3 = o3.locatenew("E3", vec(K3, 0, -ss))
E4 = o4.locatenew("E4", vec(K4, 0, -e))
E6 = o6.locatenew("E6", vec(K6, zf, 0))
D = o3.locatenew("D", vec(K3, sd, -sc))
C = O.locatenew("C", vec(N, xc, yc))
C.set_vel(N, 0)

qd_to_u = {qi.diff(): wi for qi, wi in zip(q, w)}
kd = [qi.diff() - wi for qi, wi in zip(q, w)]
# angular velocities follow from orient_axis (dq/dt); express with u
for F in frames:
    F.set_ang_vel(N, F.ang_vel_in(N).subs(qd_to_u))
for pnt in cm + [D]:
    pnt.set_vel(N, pnt.pos_from(O).dt(N).subs(qd_to_u))

bodies = []
for i in range(7):
    Ic = me.inertia(frames[i], 0, 0, inert[i])  # only I33 matters in the plane
    bodies.append(me.RigidBody(f"K{i+1}", cm[i], frames[i], masses[i], (Ic, cm[i])))

r_dc = D.pos_from(C)
L = sm.sqrt(r_dc.dot(N.x)**2 + r_dc.dot(N.y)**2)
spring_force = -c0 * (L - l0) / L * r_dc          # on D; reaction on C (fixed)
loads = [(D, spring_force), (K1, mom * N.z)]      # torque on K1; reaction on N

closure = []
for Ek in (E3, E4, E6):
    rel = E2.pos_from(Ek)                         # pos(E2, Ek)
    closure += [rel.dot(N.x), rel.dot(N.y)]
g = sm.Matrix(closure)
gdot = g.diff(me.dynamicsymbols._t).subs(qd_to_u)

# check: this g equals the test set's g (same ordering and sign) -----------------
gts = sm.Matrix([
    rr*sm.cos(beta) - d*sm.cos(beta+Theta) - ss*sm.sin(gamma_) - xb,
    rr*sm.sin(beta) - d*sm.sin(beta+Theta) + ss*sm.cos(gamma_) - yb,
    rr*sm.cos(beta) - d*sm.cos(beta+Theta) - e*sm.sin(Phi+delta) - zt*sm.cos(delta) - xa,
    rr*sm.sin(beta) - d*sm.sin(beta+Theta) + e*sm.cos(Phi+delta) - zt*sm.sin(delta) - ya,
    rr*sm.cos(beta) - d*sm.cos(beta+Theta) - zf*sm.cos(Omega+epsilon) - u*sm.sin(epsilon) - xa,
    rr*sm.sin(beta) - d*sm.sin(beta+Theta) - zf*sm.sin(Omega+epsilon) + u*sm.cos(epsilon) - ya,
])
rng = np.random.default_rng(0)
gdiff = sm.lambdify(q, g - gts, "numpy")
print("tree closure g minus test-set g at random q: max",
      max(np.max(np.abs(np.array(gdiff(*rng.uniform(-3, 3, 7)), dtype=float))) for _ in range(5)))

qs = {qi: sm.Float(v, 30) for qi, v in zip(q, Q0)}
print("|g(q0)| tree:", float(max(abs(x) for x in g.subs(qs))))

report = {}


def compare_published(acc):
    """Print beta'' and Theta'' of the accelerations acc (at t = 0) beside the
    published values; return their relative errors."""
    errs = []
    for k, pub in ((0, BETA_DD_PUB), (1, THETA_DD_PUB)):
        err = abs(acc[k] - pub) / abs(pub)
        errs.append(err)
        print(f"  {names[k]}'' = {acc[k]!r}  published {pub!r}  rel err {err:.2e}")
    return errs


# ---- route A: KanesMethod with configuration and velocity constraints -------
tA = time.time()
u_ind = [w[0]]
u_dep = w[1:]
kane = me.KanesMethod(N, q_ind=[q[0]], u_ind=u_ind, kd_eqs=kd,
                      q_dependent=q[1:], configuration_constraints=list(g),
                      u_dependent=u_dep, velocity_constraints=list(gdot))
kane.kanes_equations(bodies, loads)
MM = kane.mass_matrix      # 7x7: 1 dynamic row + 6 velocity-constraint derivatives
FF = kane.forcing
sub0 = {**qs, **{wi: 0 for wi in w}}
MM0 = np.array(MM.subs(sub0).evalf(30), dtype=float)
FF0 = np.array(FF.subs(sub0).evalf(30), dtype=float).ravel()
acc = np.linalg.solve(MM0, FF0)
print(f"route A (KanesMethod with constraints), {time.time()-tA:.1f} s:")
eA = compare_published(acc)
print("  other accelerations:", acc[2:])
report["kane_constrained"] = {"acc0": acc.tolist(), "rel_err": eA}

# ---- route B: open-tree KanesMethod + Lagrange multipliers --------------------
tB = time.time()
kt = me.KanesMethod(N, q_ind=q, u_ind=w, kd_eqs=kd)
kt.kanes_equations(bodies, loads)
Mt = kt.mass_matrix
Ft = kt.forcing
G = g.jacobian(q)
gamma_rhs = -(G.diff(me.dynamicsymbols._t).subs(qd_to_u) * sm.Matrix(w))  # -(dG/dt) u
fM = sm.lambdify(q, Mt, "numpy", cse=True)
fF = sm.lambdify(q + w, Ft, "numpy", cse=True)
fG = sm.lambdify(q, G, "numpy", cse=True)
fgam = sm.lambdify(q + w, gamma_rhs, "numpy", cse=True)
fg = sm.lambdify(q, g, "numpy")


def acc_tree(qv, uv):
    Mn = np.array(fM(*qv), dtype=float)
    Fn = np.array(fF(*qv, *uv), dtype=float).ravel()
    Gn = np.array(fG(*qv), dtype=float)
    gam = np.array(fgam(*qv, *uv), dtype=float).ravel()
    A = np.block([[Mn, Gn.T], [Gn, np.zeros((6, 6))]])
    sol = np.linalg.solve(A, np.concatenate([Fn, gam]))
    return sol[:7], sol[7:]


accB, lamB = acc_tree(np.array(Q0), np.zeros(7))
print(f"route B (tree + Lagrange multipliers), {time.time()-tB:.1f} s:")
eB = compare_published(accB)
print("  multipliers (forces at E2 from the closures, sign of the tree's G):", lamB)
report["tree_multipliers"] = {"acc0": accB.tolist(), "rel_err": eB, "lambda0": lamB.tolist()}

# dependent-speed Jacobian along the way (for choosing independent speeds)

def rhs(t, y):
    a, _ = acc_tree(y[:7], y[7:])
    return np.concatenate([y[7:], a])


tI = time.time()
y0 = np.concatenate([Q0, np.zeros(7)])
sol = solve_ivp(rhs, (0, 0.03), y0, method="DOP853", rtol=1e-13, atol=1e-15, dense_output=True)
yf = sol.y[:, -1]
eb = abs(yf[0] - BETA_003) / abs(BETA_003)
et = abs(yf[1] - THETA_003) / abs(THETA_003)
print(f"tree integrated to 0.03 s (DOP853 rtol 1e-13, {sol.nfev} evals, {time.time()-tI:.1f} s),"
      f" |g| at end {np.max(np.abs(np.array(fg(*yf[:7]), dtype=float))):.1e}")
print(f"  beta(0.03)  = {yf[0]!r}  test set {BETA_003!r}  rel err {eb:.2e}")
print(f"  Theta(0.03) = {yf[1]!r}  test set {THETA_003!r}  rel err {et:.2e}")
# conditioning of the dependent block of G (columns 2..7) along the trajectory
ts = np.linspace(0, 0.03, 3001)
smin = []
for tt in ts:
    qq = sol.sol(tt)[:7]
    sv = np.linalg.svd(np.array(fG(*qq), dtype=float)[:, 1:], compute_uv=False)
    smin.append(sv[-1] / sv[0])
smin = np.array(smin)
print(f"  beta as the independent coordinate: min over [0, 0.03] of "
      f"sigma_min/sigma_max of dg/d(q_dep) = {smin.min():.3e} at t = {ts[smin.argmin()]:.5f}")
report["t0.03"] = {"q": yf[:7].tolist(), "u": yf[7:].tolist(), "rel_err_beta": eb, "rel_err_Theta": et,
                   "min_rel_singular_value_dep_jacobian": float(smin.min())}
json.dump(report, open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "andrews-tree.json"), "w"), indent=1)
print(f"total {time.time()-t0_wall:.1f} s")
