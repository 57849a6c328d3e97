"""Joint reactions of chain-planar-n and chain-spatial-n (tests/reference/models.md)
from Pinocchio's RNEA, independent of autosim.

The chains are built from the plain-physics definitions in models.md (not
from autosim's model files). At 50 random states (q in [-pi, pi], u in
[-2, 2]) the joint torques are the springs' -k q - c u; the accelerations
come from Pinocchio's ABA, then RNEA with them gives `data.f[i]`, the
spatial force the parent exerts on body i through joint i, about the joint
frame's origin (body i's origin, the joint point) in body i's axes. The
springs are applied loads in autosim's model, so the joint's own reaction
is `data.f[i]` less the spring torque along the joint axis (S_i tau_i);
both are written.

Run: python3 tests/reference/gen/pinocchio_reactions.py  (needs the
Python registry's `pin` and `numpy`); writes
tests/reference/reactions-chain-{planar,spatial}-5.json.
"""
import json
import os
import platform

import numpy as np
import pinocchio as pin

HERE = os.path.dirname(os.path.abspath(__file__))
N_LINKS = 5
N_SAMPLES = 50
K, C, G, P = 2.0, 0.1, 9.81, 0.0005


def link(i, spatial):
    """Mass, length and inertia about the mass center of link i (1-based)."""
    m = 1 + 0.1 * (i % 5)
    length = 0.4 + 0.05 * (i % 3)
    ixx = m * length**2 / 12
    iyy = ixx + 0.001
    if spatial:
        izz = 0.002 + 0.0001 * i
        inertia = np.array([[ixx, P, 0.0], [P, iyy, 0.0], [0.0, 0.0, izz]])
    else:
        inertia = np.diag([ixx, iyy, 0.002])
    return m, length, inertia


def chain(spatial):
    model = pin.Model()
    parent, offset = 0, 0.0
    axes = []
    for i in range(1, N_LINKS + 1):
        axis = (i - 1) % 3 if spatial else 0
        joint = [pin.JointModelRX, pin.JointModelRY, pin.JointModelRZ][axis]()
        placement = pin.SE3(np.eye(3), np.array([0.0, 0.0, -offset]))
        jid = model.addJoint(parent, joint, placement, f"q{i}")
        m, length, inertia = link(i, spatial)
        model.appendBodyToJoint(jid, pin.Inertia(m, np.array([0.0, 0.0, -length / 2]), inertia),
                                pin.SE3.Identity())
        parent, offset = jid, length
        axes.append(axis)
    model.gravity = pin.Motion(np.array([0.0, 0.0, -G, 0.0, 0.0, 0.0]))
    return model, axes


def generate(spatial):
    model, axes = chain(spatial)
    data = model.createData()
    rng = np.random.default_rng(27 + int(spatial))
    samples = []
    for _ in range(N_SAMPLES):
        q = rng.uniform(-np.pi, np.pi, N_LINKS)
        u = rng.uniform(-2.0, 2.0, N_LINKS)
        tau = -K * q - C * u
        du = pin.aba(model, data, q, u, tau).copy()
        tau_back = pin.rnea(model, data, q, u, du)
        assert np.max(np.abs(tau_back - tau)) < 1e-10 * (1 + np.max(np.abs(tau)))
        spatial_forces, reactions = [], []
        for i in range(1, N_LINKS + 1):
            f = data.f[i]
            force, moment = f.linear.copy(), f.angular.copy()
            spatial_forces.append({"force": force.tolist(), "moment": moment.tolist()})
            moment[axes[i - 1]] -= tau[i - 1]
            reactions.append({"force": force.tolist(), "moment": moment.tolist()})
        samples.append({"q": q.tolist(), "u": u.tolist(), "du": du.tolist(),
                        "tau": tau.tolist(), "pinocchio_f": spatial_forces,
                        "reactions": reactions})
    name = f"chain-{'spatial' if spatial else 'planar'}-{N_LINKS}"
    out = {
        "model": name,
        "generator": "tests/reference/gen/pinocchio_reactions.py",
        "versions": {"pinocchio": pin.__version__, "numpy": np.__version__,
                     "python": platform.python_version()},
        "definition": "reactions[i]: force and moment (about body i's origin) the parent "
                      "exerts on body i through its joint, in body i's axes, without the "
                      "spring (an applied load); pinocchio_f[i] is RNEA's data.f[i] (with "
                      "the spring torque along the joint axis)",
        "samples": samples,
    }
    path = os.path.join(HERE, "..", f"reactions-{name}.json")
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1)
    print(path)


if __name__ == "__main__":
    generate(False)
    generate(True)
