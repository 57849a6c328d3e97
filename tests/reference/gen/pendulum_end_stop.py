#!/usr/bin/env python3
"""Independent reference for a pendulum striking an end stop.

Model (plain physics, written from this docstring, not from the engine):
a point mass on a massless rod of length L hinged in uniform gravity g,
its angle theta from hanging, theta'' = -w^2 sin(theta) with w^2 = g/L (the
full nonlinear pendulum). Released from rest at theta0. An end stop at
theta = -s: when theta falls through -s the rate is reversed and scaled by
the restitution e, theta' := -e theta'.

Between strikes the energy is conserved: theta'^2 = 4 w^2 (k^2 - sin^2(theta/2))
with k = sin(theta_max/2) < 1 (the swing). The time from theta = 0 to an
angle theta of the swing is F(asin(sin(theta/2)/k) | k^2)/w (the incomplete
elliptic integral of the first kind), so in closed form:

- first strike: from theta0 to -s takes (K(k^2) + F(phi_s | k^2))/w with
  k = sin(theta0/2), phi_s = asin(sin(s/2)/k); the rate there is
  -2 w sqrt(k^2 - sin^2(s/2));
- a rebound at rate r > 0 from -s swings with k^2 = sin^2(s/2) + r^2/(4 w^2)
  and returns to -s after 2 (K(k^2) + F(phi_s | k^2))/w, at rate -r.

The closed form is evaluated with mpmath in 40 digits (ellipk, ellipf) and
cross-checked here against a second method: mpmath's Taylor-series ODE
solver (odefun) with the strike located by findroot, for the first two
flights. No integrator of the engine is involved.

Writes ../pendulum-end-stop.json (tests/reference/): the parameters, the
initial state and the first ten strikes (time, rate before, rate after).
Run: python3 pendulum_end_stop.py (mpmath 1.3).
"""
import sys

import mpmath as mp
from reference_file import write_reference

mp.mp.dps = 40

PAR = dict(m="1", L="0.5", g="9.81", s="0.2", e="0.7", theta0="1")
P = {k: mp.mpf(v) for k, v in PAR.items()}
W = mp.sqrt(P["g"] / P["L"])
STRIKES = 10


def flight(k2):
    """Time from -s up to the swing's top and back to -s (or, halved, from
    the top to -s) for the swing of k^2."""
    phi_s = mp.asin(mp.sin(P["s"] / 2) / mp.sqrt(k2))
    return (mp.ellipk(k2) + mp.ellipf(phi_s, k2)) / W


def strikes():
    """The first STRIKES strikes (time, rate before) in closed form."""
    k2 = mp.sin(P["theta0"] / 2) ** 2
    t = flight(k2)
    rate = -2 * W * mp.sqrt(k2 - mp.sin(P["s"] / 2) ** 2)
    out = [(t, rate)]
    while len(out) < STRIKES:
        rebound = -P["e"] * rate
        k2 = mp.sin(P["s"] / 2) ** 2 + rebound**2 / (4 * W**2)
        t += 2 * flight(k2)
        rate = -rebound
        out.append((t, rate))
    return out


def cross_check(exact):
    """The first two strikes again by integrating the ODE (mpmath's Taylor
    series) and locating theta = -s with findroot near the closed form."""
    t0, x0 = mp.mpf(0), [P["theta0"], mp.mpf(0)]
    for t_exact, rate_exact in exact[:2]:
        sol = mp.odefun(lambda t, x: [x[1], -(W**2) * mp.sin(x[0])], t0, x0)
        t = mp.findroot(lambda t: sol(t)[0] + P["s"], t_exact)
        rate = sol(t)[1]
        err = max(abs(t - t_exact), abs(rate - rate_exact))
        print(f"cross-check: strike at {mp.nstr(t, 20)}, difference {mp.nstr(err, 3)}",
              file=sys.stderr)
        assert err < mp.mpf("1e-25"), err
        t0, x0 = t, [-P["s"], -P["e"] * rate]


def main():
    exact = strikes()
    cross_check(exact)
    doc = {
        "model": "pendulum with an end stop (see gen/pendulum_end_stop.py)",
        "generator": "tests/reference/gen/pendulum_end_stop.py",
        "method": "closed form between strikes (complete and incomplete elliptic "
                  "integrals of the first kind, mpmath, 40 digits), cross-checked "
                  "against mpmath's Taylor-series ODE solver for two strikes",
        "versions": {"python": sys.version.split()[0], "mpmath": mp.__version__},
        "parameters": {k: float(v) for k, v in P.items()},
        "state_names": ["theta", "rate"],
        "initial_state": [float(P["theta0"]), 0.0],
        "strikes": [{"t": float(t), "rate_before": float(r),
                     "rate_after": float(-P["e"] * r)} for t, r in exact],
    }
    write_reference(doc, "pendulum-end-stop.json")


if __name__ == "__main__":
    main()
