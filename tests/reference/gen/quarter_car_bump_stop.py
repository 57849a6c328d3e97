#!/usr/bin/env python3
"""Independent reference for a quarter car hitting its bump stop.

Model (plain physics, written from this docstring, not from the engine):
a wheel (mass mu, height zu) on a tire spring (kt, free length Lt) over a
flat road at height 0, and a body (mass ms, height zs) on the suspension
spring and damper (ks, cs, free length Ls) between them; gravity g. The
suspension's compression is c = Ls - (zs - zu). Beyond the bump stop's gap
(c > gap) a bump stop spring kb pushes the body up and the wheel down with
kb (c - gap). States x = (zu, zs, vu, vs).

    mu vu' = -kt (zu - Lt) - F_s - mu g,   ms vs' = F_s - ms g,
    F_s = ks (Ls - (zs - zu)) - cs (vs - vu) + contact kb (c - gap),

with the mode `contact` (0 or 1) switched by the events "bump" (c - gap
rising through 0: contact := 1) and "rebound" (c - gap falling through 0:
contact := 0).

In each mode the system is linear with a constant term, X' = M X for
X = (x, 1), so its solution is exact: X(t) = expm(M t) X(0), computed with
mpmath in 40 digits. Each switching instant is located by scanning the
exact solution every 1 ms for a sign change of c - gap and then bisecting
to 1e-30 s; the state there starts the next mode. No integrator of the
engine is involved.

Writes ../quarter-car-bump-stop.json (tests/reference/): the parameters,
the initial state, every switch (time, event, state) and the state at the
sample times. Run: python3 quarter_car_bump_stop.py (mpmath 1.3).
"""
import sys

import mpmath as mp
from reference_file import write_reference

mp.mp.dps = 40

PAR = dict(ms=300, mu=40, ks=20000, cs=1500, kt=200000, Ls="0.4", Lt="0.3",
           g="9.81", kb=200000, gap="0.2")
P = {k: mp.mpf(v) for k, v in PAR.items()}
# Released at static equilibrium without the bump stop, the body moving
# down at 1 m/s (a pothole's rebound).
STATIC_TIRE = (P["ms"] + P["mu"]) * P["g"] / P["kt"]
STATIC_SUSPENSION = P["ms"] * P["g"] / P["ks"]
ZU0 = P["Lt"] - STATIC_TIRE
ZS0 = ZU0 + P["Ls"] - STATIC_SUSPENSION
X0 = [ZU0, ZS0, mp.mpf(0), mp.mpf(-1)]
T_END = mp.mpf("1.5")
SAMPLES = [mp.mpf(k) / 10 for k in range(1, 16)]
SCAN = mp.mpf("0.001")


def system(contact):
    """M of X' = M X, X = (zu, zs, vu, vs, 1), in one mode."""
    ms, mu, ks, cs, kt = P["ms"], P["mu"], P["ks"], P["cs"], P["kt"]
    kb = P["kb"] * contact
    # F_s = ks (Ls - zs + zu) - cs (vs - vu) + kb (Ls - zs + zu - gap)
    fs = {0: ks + kb, 1: -(ks + kb), 2: cs, 3: -cs,
          4: ks * P["Ls"] + kb * (P["Ls"] - P["gap"])}
    m = mp.zeros(5, 5)
    m[0, 2] = 1
    m[1, 3] = 1
    for j, v in fs.items():
        m[2, j] -= v / mu
        m[3, j] += v / ms
    m[2, 0] -= kt / mu
    m[2, 4] += kt * P["Lt"] / mu - P["g"]
    m[3, 4] -= P["g"]
    return m


def flow(m, x, t):
    """The exact state after time t in the mode of M."""
    col = mp.matrix([*x, 1])
    out = mp.expm(m * t) * col
    return [out[i] for i in range(4)]


def indicator(x):
    return P["Ls"] - (x[1] - x[0]) - P["gap"]


def next_switch(m, x, t0, direction):
    """The first time after t0 (before T_END) where c - gap crosses zero in
    `direction` (+1 rising, -1 falling), by scanning and bisection."""
    step_m = mp.expm(m * SCAN)
    col = mp.matrix([*x, 1])
    t, g = mp.mpf(0), indicator(x)
    while t0 + t < T_END:
        nxt = step_m * col
        g_next = indicator([nxt[i] for i in range(4)])
        if (direction > 0 and g < 0 <= g_next) or (direction < 0 and g > 0 >= g_next):
            a, b = t, t + SCAN
            while b - a > mp.mpf("1e-30"):
                c = (a + b) / 2
                gc = indicator(flow(m, x, c))
                if (gc >= 0) == (direction > 0):
                    b = c
                else:
                    a = c
            return t0 + b, flow(m, x, b)
        col, t, g = nxt, t + SCAN, g_next
    return None


def main():
    x, t, contact = list(X0), mp.mpf(0), 0
    pieces = []  # (start time, start state, mode)
    switches = []
    while True:
        pieces.append((t, list(x), contact))
        hit = next_switch(system(contact), x, t, +1 if contact == 0 else -1)
        if hit is None:
            break
        t, x = hit
        switches.append({"t": float(t), "event": "bump" if contact == 0 else "rebound",
                         "state": [float(v) for v in x]})
        contact = 1 - contact
        print(f"{switches[-1]['event']:8s} at t = {mp.nstr(t, 20)}", file=sys.stderr)

    def state_at(ts):
        start, x0, mode = max((p for p in pieces if p[0] <= ts), key=lambda p: p[0])
        return [float(v) for v in flow(system(mode), x0, ts - start)]

    doc = {
        "model": "quarter car with a bump stop (see gen/quarter_car_bump_stop.py)",
        "generator": "tests/reference/gen/quarter_car_bump_stop.py",
        "method": "exact solution of each linear mode (mpmath expm, 40 digits); "
                  "switches by a 1 ms scan and bisection to 1e-30 s",
        "versions": {"python": sys.version.split()[0], "mpmath": mp.__version__},
        "parameters": {k: float(v) for k, v in P.items()},
        "state_names": ["zu", "zs", "vu", "vs"],
        "initial_state": [float(v) for v in X0],
        "switches": switches,
        "samples": [{"t": float(ts), "state": state_at(ts)} for ts in SAMPLES],
    }
    write_reference(doc, "quarter-car-bump-stop.json")


if __name__ == "__main__":
    main()
