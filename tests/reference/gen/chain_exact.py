#!/usr/bin/env python3
"""Exact accelerations of the reference chains: du/dt at random states in
40-digit arithmetic (mpmath), so that a double-precision result can be
measured against the true value rather than against another rounded one.

Model: chain-planar-n and chain-spatial-n of models.md, written here
numerically from that text (nothing from autosim): body rotations as
products of axis rotations, each body's partial angular velocities (the
joint axes in N) and its mass center's partial velocities e_j x (G_i - O_j),
the accelerations with du/dt = 0 differentiated by hand, and Kane's
equations M du/dt = f summed body by body; the spring-dampers give
generalized force -k q_j - c u_j on u_j (the moment and its reaction
cancel on the speeds of the bodies above). Solved by mpmath's LU at 40
digits: with kappa(M) below 1e6 the result is exact to about 1e-33.

The states are uniform in [-2, 2] (Python's random, seeded); the inputs
(states and parameters) are the double-precision numbers written to the
file, taken exactly. Writes ../chain-spatial-20-exact.json (`write` makes
any chain-{planar,spatial}-n).

    python3 tests/reference/gen/chain_exact.py        # from the repository root

It first checks itself against the double-precision SymPy files
chain-spatial-{3,10}.json and chain-planar-10.json (their parameters).
"""
import json
import os
import platform
import random
import time

import mpmath
from mpmath import mp, mpf

HERE = os.path.dirname(os.path.abspath(__file__))
mp.dps = 40
G = 9.81


def parameters(n, spatial):
    """The chain's parameters as models.md defines them, computed in double
    precision (the values the model files write)."""
    p = {"k": 2.0, "c": 0.1, "g": G}
    if spatial:
        p["P"] = 0.0005
    for i in range(1, n + 1):
        m = 1 + 0.1 * (i % 5)
        length = 0.4 + 0.05 * (i % 3)
        p[f"m{i}"] = m
        p[f"L{i}"] = length
        p[f"Ixx{i}"] = m * length ** 2 / 12
        p[f"Iyy{i}"] = m * length ** 2 / 12 + 0.001
        p[f"Izz{i}"] = 0.002 + 0.0001 * i if spatial else 0.002
    return p


def rotation(axis, q):
    """The child's unit vectors in the parent's axes (columns), rotated by q
    about the common axis `axis` (0, 1, 2)."""
    c, s = mpmath.cos(q), mpmath.sin(q)
    r = mpmath.eye(3)
    a, b = (axis + 1) % 3, (axis + 2) % 3
    r[a, a], r[a, b], r[b, a], r[b, b] = c, -s, s, c
    return r


def cross(a, b):
    return mpmath.matrix([a[1] * b[2] - a[2] * b[1],
                          a[2] * b[0] - a[0] * b[2],
                          a[0] * b[1] - a[1] * b[0]])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def accelerations(n, spatial, p, q, u):
    """du/dt of the chain at coordinates q and speeds u (exact inputs)."""
    P = lambda name: mpf(p[name])
    q = [mpf(v) for v in q]
    u = [mpf(v) for v in u]
    axes = [i % 3 if spatial else 0 for i in range(n)]
    # kinematics, body by body: orientation R (body axes in N), joint axis
    # e (in N), joint point O, mass center G, angular velocity w
    R, e, O, Gc, w = [], [], [], [], []
    parent_r, parent_o, parent_w = mpmath.eye(3), mpmath.matrix([0, 0, 0]), mpmath.matrix([0, 0, 0])
    for i in range(n):
        axis = parent_r[:, axes[i]]
        if i > 0:
            parent_o = parent_o + parent_r * mpmath.matrix([0, 0, -P(f"L{i}")])
        r = parent_r * rotation(axes[i], q[i])
        R.append(r)
        e.append(axis)
        O.append(parent_o)
        Gc.append(parent_o + r * mpmath.matrix([0, 0, -P(f"L{i + 1}") / 2]))
        parent_w = parent_w + axis * u[i]
        w.append(parent_w)
        parent_r = r
    zero = mpmath.matrix([0, 0, 0])

    def velocity(point, bodies):
        """Velocity of a point carried by body `bodies - 1`."""
        v = zero
        for k in range(bodies):
            v = v + cross(e[k], point - O[k]) * u[k]
        return v

    v_o = [velocity(O[j], j) for j in range(n)]
    M = mpmath.zeros(n, n)
    f = mpmath.matrix([-P("k") * q[j] - P("c") * u[j] for j in range(n)])
    gravity = mpmath.matrix([0, 0, -P("g")])
    for i in range(n):
        m = P(f"m{i + 1}")
        body = mpmath.matrix([[P(f"Ixx{i + 1}"), P("P") if spatial else 0, 0],
                              [P("P") if spatial else 0, P(f"Iyy{i + 1}"), 0],
                              [0, 0, P(f"Izz{i + 1}")]])
        inertia = R[i] * body * R[i].T
        partial = [cross(e[j], Gc[i] - O[j]) for j in range(i + 1)]
        v_g = velocity(Gc[i], i + 1)
        # accelerations with du/dt = 0: e_j turns with body j - 1
        alpha = zero
        a = zero
        for j in range(i + 1):
            e_dot = cross(w[j - 1], e[j]) if j > 0 else zero
            alpha = alpha + e_dot * u[j]
            a = a + (cross(e_dot, Gc[i] - O[j]) + cross(e[j], v_g - v_o[j])) * u[j]
        torque = inertia * alpha + cross(w[i], inertia * w[i])
        for j in range(i + 1):
            f[j] += dot(partial[j], m * gravity - m * a) - dot(e[j], torque)
            for k in range(i + 1):
                M[j, k] += m * dot(partial[j], partial[k]) + dot(e[j], inertia * e[k])
    return mpmath.lu_solve(M, f)


def write(n, spatial, count, seed):
    name = f"chain-{'spatial' if spatial else 'planar'}-{n}-exact"
    p = parameters(n, spatial)
    rng = random.Random(seed)
    start = time.time()
    samples = []
    for _ in range(count):
        q = [rng.uniform(-2, 2) for _ in range(n)]
        u = [rng.uniform(-2, 2) for _ in range(n)]
        du = accelerations(n, spatial, p, q, u)
        samples.append({"t": 0.0, "q": q, "u": u, "dq": u,
                        "du": [float(v) for v in du]})
    data = {
        "model": name.removesuffix("-exact"),
        "generator": "tests/reference/gen/chain_exact.py: Kane's equations summed "
                     "body by body in 40-digit arithmetic, written from models.md",
        "versions": {"python": platform.python_version(), "mpmath": mpmath.__version__},
        "precision": "du is the 40-digit solution rounded once to double: "
                     "exact to half an ulp for the double inputs written here",
        "parameters": p,
        "seed": seed,
        "seconds": round(time.time() - start, 1),
        "samples": samples,
    }
    with open(os.path.join(HERE, "..", f"{name}.json"), "w") as out:
        json.dump(data, out, indent=1)
        out.write("\n")
    print(name, len(samples), "samples", data["seconds"], "s")


def check():
    """Agreement with the double-precision SymPy files at their samples
    (their own rounding limits it: 1.0e-13 for chain-planar-10)."""
    for n, spatial in [(3, True), (10, True), (10, False)]:
        name = f"chain-{'spatial' if spatial else 'planar'}-{n}"
        with open(os.path.join(HERE, "..", f"{name}.json")) as f:
            data = json.load(f)
        p = parameters(n, spatial) | {k: data["parameters"][k] for k in parameters(n, spatial)}
        worst = 0.0
        for s in data["samples"]:
            du = accelerations(n, spatial, p, s["q"], s["u"])
            scale = max(abs(v) for v in s["du"])
            worst = max(worst, max(abs(float(a) - b) for a, b in zip(du, s["du"])) / scale)
        print(f"{name}: largest difference from the SymPy file {worst:.1e}")
        assert worst < 2e-13, name


if __name__ == "__main__":
    check()
    write(20, True, 200, 20)
