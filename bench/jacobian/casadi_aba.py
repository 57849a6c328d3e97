"""Forward dynamics of chain-planar-n / chain-spatial-n (shared/reference-models.md)
as Featherstone's articulated-body algorithm written in CasADi SX: the
hand-structured `aba` of the CasADi peer in ../shared/bench/casadi/cas_aba.py
(copied here with its helpers and ../shared/bench/perf/params.py, the 6x6
assembly of two of them shared as `symmetric6`, so
this benchmark runs from the repository alone; that ABA is cross-checked there
against Pinocchio to 1e-10). `casadi_jacobian.py` differentiates it.

Parameters are baked in as numbers (as in Pinocchio's model); joint torque
tau = -K_SPRING q - C_DAMP v is computed inside; gravity G along -n3.
Spatial vectors (angular; linear), body-fixed frames, Plucker transforms
X = [E 0; -E rx E], E = parent->child coordinates; only the upper triangle of
symmetric 6x6 inertias is computed, the articulated inertia's joint-axis row
and column are set to exactly zero (I^a S = 0 holds identically).
"""

import casadi as ca

# ---------------------------------------------------------------- parameters
K_SPRING = 2.0  # N m / rad
C_DAMP = 0.1  # N m s / rad
G = 9.81  # m / s^2, along -n3
P_SPATIAL = 0.0005


def body_params(kind, i):
    """Numeric parameters of body i (1-based) of chain-<kind>-n."""
    m = 1.0 + 0.1 * (i % 5)
    L = 0.4 + 0.05 * (i % 3)
    ixx = m * L * L / 12.0
    iyy = m * L * L / 12.0 + 0.001
    if kind == "planar":
        izz = 0.002
        p = 0.0
        axis = 1
    else:
        izz = 0.002 + 0.0001 * i
        p = P_SPATIAL
        axis = ((i - 1) % 3) + 1
    return {"m": m, "L": L, "Ixx": ixx, "Iyy": iyy, "Izz": izz, "P": p, "axis": axis}


# ---------------------------------------------------------------- small helpers
# Scalars are Python floats (constants, folded by Python) or casadi SX (symbolic);
# CasADi simplifies x*0, x*1, x+0 on the fly, so constant zeros prune the graph.
def skew(r):
    return [[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def mv(A, x):
    return [sum_(A[j][k] * x[k] for k in range(3)) for j in range(3)]


def mtv(A, x):  # A^T x
    return [sum_(A[k][j] * x[k] for k in range(3)) for j in range(3)]


def sum_(it):
    acc = 0.0
    for t in it:
        acc = acc + t
    return acc


def mm(A, B):
    return [[sum_(A[j][l] * B[l][k] for l in range(3)) for k in range(3)] for j in range(3)]


def mtm_sym(A, B):
    """A^T B, known to be symmetric: upper triangle computed, lower mirrored."""
    R = [[None] * 3 for _ in range(3)]
    for j in range(3):
        for k in range(j, 3):
            R[j][k] = sum_(A[l][j] * B[l][k] for l in range(3))
            R[k][j] = R[j][k]
    return R


def mtm(A, B):
    return [[sum_(A[l][j] * B[l][k] for l in range(3)) for k in range(3)] for j in range(3)]


def rotE(axis, c, s):
    """Parent->child coordinate transform for a rotation of the child by q about the
    parent's coordinate axis (0, 1, 2): E = R(q)^T."""
    if axis == 0:
        return [[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]]
    if axis == 1:
        return [[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]]
    return [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]


def symmetric6(A, B, C):
    """The symmetric 6x6 matrix [A B; B^T C] from its 3x3 blocks."""
    out = [[None] * 6 for _ in range(6)]
    for j in range(3):
        for k in range(3):
            out[j][k] = A[j][k]
            out[j][k + 3] = B[j][k]
            out[j + 3][k] = B[k][j]
            out[j + 3][k + 3] = C[j][k]
    return out


def body_spatial_inertia(kind, i):
    """6x6 spatial inertia of body i about its origin, in its axes (Featherstone mcI)."""
    bp = body_params(kind, i)
    m, L = bp["m"], bp["L"]
    c = [0.0, 0.0, -L / 2]
    Ic = [[bp["Ixx"], bp["P"], 0.0], [bp["P"], bp["Iyy"], 0.0], [0.0, 0.0, bp["Izz"]]]
    cx = skew(c)
    A = [[Ic[j][k] - m * sum(cx[j][l] * cx[l][k] for l in range(3)) for k in range(3)] for j in range(3)]
    B = [[m * cx[j][k] for k in range(3)] for j in range(3)]
    C = [[m if j == k else 0.0 for k in range(3)] for j in range(3)]
    return symmetric6(A, B, C)


def chain(kind, n):
    """Per body: axis index (0..2), joint offset r in parent coords, 6x6 inertia."""
    out = []
    prevL = 0.0
    for i in range(1, n + 1):
        bp = body_params(kind, i)
        out.append({"axis": bp["axis"] - 1, "r": [0.0, 0.0, -prevL], "I": body_spatial_inertia(kind, i)})
        prevL = bp["L"]
    return out


# spatial motion transform X = [E 0; -E rx E] applied to motion / its transpose to force
def xmotion(E, r, m):
    w, vl = m[:3], m[3:]
    return mv(E, w) + mv(E, [vl[j] - x for j, x in enumerate(cross(r, w))])


def xtforce(E, r, f):
    n_, fl = mtv(E, f[:3]), mtv(E, f[3:])
    rf = cross(r, fl)
    return [n_[j] + rf[j] for j in range(3)] + fl


def crm_times(v, m):  # v x m (motion cross product)
    w, vl = v[:3], v[3:]
    a = cross(w, m[:3])
    b = cross(w, m[3:])
    c = cross(vl, m[:3])
    return a + [b[j] + c[j] for j in range(3)]


def crf_times(v, f):  # v x* f (force cross product)
    w, vl = v[:3], v[3:]
    a = cross(w, f[:3])
    b = cross(vl, f[3:])
    return [a[j] + b[j] for j in range(3)] + cross(w, f[3:])


def sym6_times(I, x):
    return [sum_(I[j][k] * x[k] for k in range(6)) for j in range(6)]


def congruence(E, r, I):
    """X^T I X for symmetric 6x6 I (child coords) -> parent coords; rotation first
    (blocks E^T A E etc.), then the shift of origin by r; upper triangles only."""
    A = [row[:3] for row in I[:3]]
    B = [row[3:] for row in I[:3]]
    C = [row[3:] for row in I[3:]]
    A1 = mtm_sym(E, mm(A, E))
    B1 = mtm(E, mm(B, E))
    C1 = mtm_sym(E, mm(C, E))
    rx = skew(r)
    K = mm(rx, [[B1[k][j] for k in range(3)] for j in range(3)])  # rx B1^T
    rC = mm(rx, C1)  # rx C1
    rCr = [[None] * 3 for _ in range(3)]
    for j in range(3):
        for k in range(j, 3):
            rCr[j][k] = sum_(rC[j][l] * rx[l][k] for l in range(3))
            rCr[k][j] = rCr[j][k]
    B2 = [[B1[j][k] + rC[j][k] for k in range(3)] for j in range(3)]  # B1 + rx C1
    A2 = [[None] * 3 for _ in range(3)]
    for j in range(3):
        for k in range(j, 3):
            A2[j][k] = A1[j][k] + K[j][k] + K[k][j] - rCr[j][k]
            A2[k][j] = A2[j][k]
    return symmetric6(A2, B2, C1)


# ---------------------------------------------------------------- ABA (hand-structured)
def aba(kind, n, q, v):
    bodies = chain(kind, n)
    tau = [-K_SPRING * q[i] - C_DAMP * v[i] for i in range(n)]
    E, vel, cbias, IA, pA = [], [], [], [], []
    for i, b in enumerate(bodies):
        a = b["axis"]
        Ei = rotE(a, ca.cos(q[i]), ca.sin(q[i]))
        E.append(Ei)
        Sqd = [0.0] * 6
        Sqd[a] = v[i]
        if i == 0:
            vi = Sqd
            ci = [0.0] * 6
        else:
            vi = xmotion(Ei, b["r"], vel[i - 1])
            vi[a] = vi[a] + v[i]
            ci = crm_times(vi, Sqd)
        vel.append(vi)
        cbias.append(ci)
        IA.append([row[:] for row in b["I"]])
        pA.append(crf_times(vi, sym6_times(b["I"], vi)))
    U, Dinv, u = [None] * n, [None] * n, [None] * n
    for i in reversed(range(n)):
        a = bodies[i]["axis"]
        Ui = [IA[i][j][a] for j in range(6)]
        Dinv[i] = 1.0 / Ui[a]
        u[i] = tau[i] - pA[i][a]
        U[i] = Ui
        if i == 0:
            continue
        UD = [Ui[j] * Dinv[i] for j in range(6)]
        Ia = [[0.0] * 6 for _ in range(6)]
        for j in range(6):
            for k in range(j, 6):
                if j == a or k == a:
                    continue  # I^a S = 0: the joint-axis row and column vanish
                Ia[j][k] = IA[i][j][k] - UD[j] * Ui[k]
                Ia[k][j] = Ia[j][k]
        uD = u[i] * Dinv[i]
        Iac = sym6_times(Ia, cbias[i])
        pa = [pA[i][j] + Iac[j] + Ui[j] * uD for j in range(6)]
        r = bodies[i]["r"]
        T = congruence(E[i], r, Ia)
        for j in range(6):
            for k in range(6):
                IA[i - 1][j][k] = IA[i - 1][j][k] + T[j][k]
        f = xtforce(E[i], r, pa)
        pA[i - 1] = [pA[i - 1][j] + f[j] for j in range(6)]
    acc = [0.0, 0.0, 0.0, 0.0, 0.0, G]  # base acceleration = -gravity
    qdd = []
    for i, b in enumerate(bodies):
        a = b["axis"]
        ap = xmotion(E[i], b["r"], acc)
        ap = [ap[j] + cbias[i][j] for j in range(6)]
        qi = (u[i] - sum_(U[i][j] * ap[j] for j in range(6))) * Dinv[i]
        ap[a] = ap[a] + qi
        acc = ap
        qdd.append(qi)
    return qdd
