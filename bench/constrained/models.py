"""The three constrained models of `examples/models/` built with
sympy.physics.mechanics, for `derive.py`: the four-bar, the rolling disc and
the Whipple bicycle, from the definitions in `tests/reference/gen/four_bar.md`,
`rolling_disc.md` and `bicycle.md` (the same trees, frames, constraints and
dependent coordinates and speeds as the `.sim` files), with every parameter a
symbol (its value is passed at run time, as autosim's are).

Each builder returns a `Model`: the coordinates and speeds, in the order of
autosim's state (`STATE_NAMES`: every coordinate, then the independent
speeds), and what `KanesMethod` needs.
"""

from dataclasses import dataclass, field

import sympy as sm
import sympy.physics.mechanics as me

T = me.dynamicsymbols._t


@dataclass
class Model:
    """One model, ready for `KanesMethod`."""

    name: str
    frame: me.ReferenceFrame
    q_ind: list
    q_dep: list
    u_ind: list
    u_dep: list
    kd: list
    config_con: list
    vel_con: list
    bodies: list
    loads: list
    params: list
    values: list
    # autosim's state order: the coordinates by name (the speeds follow as u_ind)
    state_q: list
    kane_options: dict = field(default_factory=dict)


def _symbols(spec: list[tuple[str, float]]) -> tuple[list[sm.Symbol], list[float]]:
    """Parameter symbols and values from [(name, value), ...]."""
    return [sm.Symbol(n) for n, _ in spec], [float(v) for _, v in spec]


def four_bar() -> Model:
    """examples/models/four_bar.sim (tests/reference/gen/four_bar.md)."""
    params, values = _symbols(
        [
            ("L0", 1.0),
            ("L1", 0.3),
            ("L2", 1.0),
            ("L3", 0.8),
            ("m1", 1.0),
            ("m2", 2.0),
            ("m3", 1.5),
            ("Iyy", 0.001),
            ("k", 5.0),
            ("q10", 0.2),
            ("g", 9.81),
        ]
    )
    L0, L1, L2, L3, m1, m2, m3, Iyy, k, q10, g = params
    q1, q2, q3 = me.dynamicsymbols("q1 q2 q3")
    u1, u2, u3 = me.dynamicsymbols("u1 u2 u3")
    N, C, K, R = (me.ReferenceFrame(n) for n in "NCKR")
    C.orient_axis(N, N.x, q1)
    K.orient_axis(C, C.x, q2)
    R.orient_axis(N, N.x, q3)
    C.set_ang_vel(N, u1 * N.x)
    K.set_ang_vel(C, u2 * C.x)
    R.set_ang_vel(N, u3 * N.x)
    A = me.Point("A")
    A.set_vel(N, 0)
    D = A.locatenew("D", L0 * N.y)
    D.set_vel(N, 0)
    B = A.locatenew("B", L1 * C.y)
    E = B.locatenew("E", L2 * K.y)
    Tip = D.locatenew("T", L3 * R.y)
    cms = [
        A.locatenew("Ccm", L1 / 2 * C.y),
        B.locatenew("Kcm", L2 / 2 * K.y),
        D.locatenew("Rcm", L3 / 2 * R.y),
    ]
    for pt, base, fr in [(B, A, C), (E, B, K), (Tip, D, R)] + list(zip(cms, [A, B, D], [C, K, R])):
        pt.v2pt_theory(base, N, fr)
    loop = E.pos_from(A) - Tip.pos_from(A)
    vloop = E.vel(N) - Tip.vel(N)
    bodies = [
        me.RigidBody(f"{fr.name}b", cm, fr, m, (me.inertia(fr, m * L**2 / 12, Iyy, m * L**2 / 12), cm))
        for fr, cm, m, L in [(C, cms[0], m1, L1), (K, cms[1], m2, L2), (R, cms[2], m3, L3)]
    ]
    loads = [(b.masscenter, -b.mass * g * N.z) for b in bodies]
    loads += [(C, -k * (q1 - q10) * N.x), (N, k * (q1 - q10) * N.x)]
    return Model(
        name="four_bar",
        frame=N,
        q_ind=[q1],
        q_dep=[q2, q3],
        u_ind=[u1],
        u_dep=[u2, u3],
        kd=[q1.diff(T) - u1, q2.diff(T) - u2, q3.diff(T) - u3],
        config_con=[loop.dot(N.y), loop.dot(N.z)],
        vel_con=[vloop.dot(N.y), vloop.dot(N.z)],
        bodies=bodies,
        loads=loads,
        params=params,
        values=values,
        state_q=[q1, q2, q3],
        # as the reference: the dependent speeds' only denominator is the
        # loop's determinant L2 L3 sin(q1 + q2 - q3)
        kane_options=dict(constraint_solver="CRAMER"),
    )


def rolling_disc() -> Model:
    """examples/models/rolling_disc.sim (tests/reference/gen/rolling_disc.md)."""
    params, values = _symbols([("m", 1.0), ("r", 0.5), ("g", 9.81)])
    m, r, g = params
    x, y, z, psi, phi, theta = me.dynamicsymbols("x y z psi phi theta")
    ux, uy, uz, u4, u5, u6 = me.dynamicsymbols("ux uy uz u4 u5 u6")
    N, A, L, D = (me.ReferenceFrame(n) for n in "NALD")
    A.orient_axis(N, N.z, psi)
    L.orient_axis(A, A.x, phi)
    D.orient_axis(L, L.y, theta)
    w_kin = D.ang_vel_in(N)
    kd = [
        x.diff(T) - ux,
        y.diff(T) - uy,
        z.diff(T) - uz,
        w_kin.dot(D.x) - u4,
        w_kin.dot(D.y) - u5,
        w_kin.dot(D.z) - u6,
    ]
    D.set_ang_vel(N, u4 * D.x + u5 * D.y + u6 * D.z)
    O = me.Point("O")
    O.set_vel(N, 0)
    centre = O.locatenew("Dc", x * N.x + y * N.y + z * N.z)
    centre.set_vel(N, ux * N.x + uy * N.y + uz * N.z)
    slip = centre.vel(N) + D.ang_vel_in(N).cross(-r * L.z)  # material point at the contact
    disc = me.RigidBody(
        "disc", centre, D, m, (me.inertia(D, m * r**2 / 4, m * r**2 / 2, m * r**2 / 4), centre)
    )
    return Model(
        name="rolling_disc",
        frame=N,
        q_ind=[x, y, psi, phi, theta],
        q_dep=[z],
        u_ind=[u4, u5, u6],
        u_dep=[ux, uy, uz],
        kd=kd,
        config_con=[z - r * sm.cos(phi)],
        # n1, n2: rolling; n3: the touch constraint's time derivative
        vel_con=[slip.dot(N.x), slip.dot(N.y), slip.dot(N.z)],
        bodies=[disc],
        loads=[(centre, -m * g * N.z)],
        params=params,
        values=values,
        state_q=[x, y, z, psi, phi, theta],
        # as the reference: LU would divide 0 by 0 at theta = 0
        kane_options=dict(kd_eqs_solver="CRAMER"),
    )


BICYCLE_PARAMETERS = [
    ("w", 1.02),
    ("c", 0.08),
    ("lambda", 0.3141592653589793),
    ("g", 9.81),
    ("rR", 0.3),
    ("mR", 2),
    ("IRxx", 0.0603),
    ("IRyy", 0.12),
    ("xB", 0.3),
    ("zB", -0.9),
    ("mB", 85),
    ("IBxx", 9.2),
    ("IByy", 11),
    ("IBzz", 2.8),
    ("IBxz", 2.4),
    ("xH", 0.9),
    ("zH", -0.7),
    ("mH", 4),
    ("IHxx", 0.05892),
    ("IHyy", 0.06),
    ("IHzz", 0.00708),
    ("IHxz", -0.00756),
    ("rF", 0.35),
    ("mF", 3),
    ("IFxx", 0.1405),
    ("IFyy", 0.28),
    # the model's inputs (roll and steer torques), zero in the bench as in autosim's default
    ("T_phi", 0.0),
    ("T_delta", 0.0),
]


def bicycle() -> Model:
    """examples/models/bicycle.sim (tests/reference/gen/bicycle.md): the
    benchmark's Whipple bicycle, n1 forward, n2 left, n3 up."""
    params, values = _symbols(BICYCLE_PARAMETERS)
    P = dict(zip([n for n, _ in BICYCLE_PARAMETERS], params))
    names = ["x", "y", "psi", "phi", "theta", "thetaR", "delta", "thetaF"]
    q = me.dynamicsymbols(" ".join(names))
    u = me.dynamicsymbols(" ".join("u_" + n for n in names))
    x, y, psi, phi, theta, thetaR, delta, thetaF = q
    qd2u = {qi.diff(T): ui for qi, ui in zip(q, u)}
    N, Y, R, B, RW, FW = (me.ReferenceFrame(n) for n in ["N", "Y", "R", "B", "RW", "FW"])
    Y.orient_axis(N, N.z, psi)
    R.orient_axis(Y, Y.x, phi)
    B.orient_axis(R, R.y, theta)
    RW.orient_axis(B, B.y, thetaR)
    # The steer: delta about d = sin(lambda) b1 - cos(lambda) b3 with H = B at
    # delta = 0. (orient_axis about d itself would divide by |d| =
    # sqrt(sin^2 + cos^2), a symbol expression here.) S.3 = -d, so delta about
    # d is -delta about S.3; H turns back by lambda.
    lam = P["lambda"]
    S = me.ReferenceFrame("S")
    S.orient_axis(B, B.y, -lam)
    Hs = me.ReferenceFrame("Hs")
    Hs.orient_axis(S, S.z, -delta)
    H = me.ReferenceFrame("H")
    H.orient_axis(Hs, Hs.y, lam)
    FW.orient_axis(H, H.y, thetaF)
    for fr in (Y, R, B, RW, S, Hs, H, FW):
        fr.set_ang_vel(N, fr.ang_vel_in(N).subs(qd2u))
    O = me.Point("O")
    O.set_vel(N, 0)
    contact = O.locatenew("P", x * N.x + y * N.y)  # rear contact, Y's origin
    hub_r = contact.locatenew("Bo", P["rR"] * R.z)
    steer = hub_r.locatenew("Ho", (P["w"] + P["c"]) * B.x - P["rR"] * B.z)
    hub_f = steer.locatenew("Fo", -P["c"] * H.x + P["rF"] * H.z)
    cm_b = hub_r.locatenew("Bcm", P["xB"] * B.x + (-P["zB"] - P["rR"]) * B.z)
    cm_h = steer.locatenew("Hcm", (P["xH"] - P["w"] - P["c"]) * H.x - P["zH"] * H.z)
    for pt in (contact, hub_r, steer, hub_f, cm_b, cm_h):
        pt.set_vel(N, pt.pos_from(O).dt(N).subs(qd2u))
    # inertia(frame, ixx, iyy, izz, ixy, iyz, izx)
    bodies = [
        me.RigidBody(
            "B", cm_b, B, P["mB"], (me.inertia(B, P["IBxx"], P["IByy"], P["IBzz"], 0, 0, -P["IBxz"]), cm_b)
        ),
        me.RigidBody("RW", hub_r, RW, P["mR"], (me.inertia(RW, P["IRxx"], P["IRyy"], P["IRxx"]), hub_r)),
        me.RigidBody(
            "H", cm_h, H, P["mH"], (me.inertia(H, P["IHxx"], P["IHyy"], P["IHzz"], 0, 0, -P["IHxz"]), cm_h)
        ),
        me.RigidBody("FW", hub_f, FW, P["mF"], (me.inertia(FW, P["IFxx"], P["IFyy"], P["IFxx"]), hub_f)),
    ]
    d = sm.sin(lam) * B.x - sm.cos(lam) * B.z
    loads = [(b.masscenter, -b.mass * P["g"] * N.z) for b in bodies]
    loads += [(B, P["T_phi"] * R.x), (Y, -P["T_phi"] * R.x), (H, P["T_delta"] * d), (B, -P["T_delta"] * d)]
    axle_n3 = H.y.dot(N.z)
    ground = hub_f.pos_from(O).dot(N.z) - P["rF"] * sm.sqrt(1 - axle_n3**2)
    v_rear = hub_r.vel(N) + RW.ang_vel_in(N).cross(contact.pos_from(hub_r))
    to_front = P["rF"] * H.y.cross(H.y.cross(N.z)) / sm.sqrt(1 - axle_n3**2)
    v_front = hub_f.vel(N) + FW.ang_vel_in(N).cross(to_front)
    # the order of bicycle.md: each constraint's dependent speed at its pivot
    vel_con = [
        v_rear.dot(N.x),
        v_rear.dot(N.y),
        v_front.dot(Y.y),
        ground.diff(T).subs(qd2u),
        v_front.dot(Y.x),
    ]
    return Model(
        name="bicycle",
        frame=N,
        q_ind=[x, y, psi, phi, thetaR, delta, thetaF],
        q_dep=[theta],
        u_ind=[u[3], u[5], u[6]],
        u_dep=[u[0], u[1], u[2], u[4], u[7]],
        kd=[qi.diff(T) - ui for qi, ui in zip(q, u)],
        config_con=[ground],
        vel_con=vel_con,
        bodies=bodies,
        loads=loads,
        params=params,
        values=values,
        state_q=list(q),
    )


MODELS = {"four_bar": four_bar, "rolling_disc": rolling_disc, "bicycle": bicycle}
