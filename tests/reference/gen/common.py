"""Pieces shared by the constrained-model reference generators four_bar.py and
rolling_disc.py: numeric functions from sympy expressions, the restarted
DOP853 trajectory runs and their checks, and the JSON layout.

Each script imports this module by name; Python puts the running script's
own folder first on sys.path, so `python3 tests/reference/gen/<name>.py` from
the repository root and `python3 <name>.py` from this folder both find it.
"""
import json
import os
import platform
import time

import numpy as np
import scipy
import sympy as sp
import sympy.physics.mechanics as me
from scipy.integrate import solve_ivp

HERE = os.path.dirname(os.path.abspath(__file__))

# names of the energy terms a sample records, in the order energy(q, u)
# returns them (a model without a spring stops after the gravity potential)
ENERGY_KEYS = ("energy", "kinetic_energy", "gravity_potential", "spring_potential")


def lambdifier(qs, us, psym, first_index):
    """lam(expr) -> f(q, u, p) for numpy arrays q, u, p.

    The coordinates qs and speeds us are replaced by plain symbols Q<i>, U<i>
    (i counted from first_index) before sympy.lambdify with common
    subexpressions; psym are the parameter symbols. The names fix sympy's
    term order and with it the last bits of the numbers, so a script keeps
    the first_index it was written with.
    """
    qsym = sp.symbols(f"Q{first_index}:{first_index + len(qs)}")
    usym = sp.symbols(f"U{first_index}:{first_index + len(us)}")
    rep = dict(zip(qs, qsym)) | dict(zip(us, usym))

    def lam(expr):
        return sp.lambdify((qsym, usym, psym), me.msubs(expr, rep), modules="numpy",
                           cse=True)

    return lam


def sample(q, u, dq, du, energies, rc, rv):
    """One entry of "samples" (at t = 0, no inputs); energies as energy(q, u)
    returns them (see ENERGY_KEYS), rc and rv the configuration and velocity
    constraint residuals."""
    return ({"t": 0.0, "q": q.tolist(), "u": u.tolist(), "inputs": {},
             "dq": dq.tolist(), "du": du.tolist()}
            | dict(zip(ENERGY_KEYS, energies))
            | {"configuration_residual": float(rc), "velocity_residual": float(rv)})


# ---------------------------------------------------------------------------
# Trajectories of the reduced ODE (independent coordinates and speeds)
# ---------------------------------------------------------------------------
def integrate(rhs, y0, t_end, dt, which="kane", tol=1e-13):
    """scipy DOP853 with rtol = atol = tol, restarted every dt so each record
    is a step end (no dense-output interpolation). rhs(t, y, which) is the
    reduced ODE with the formulation `which`. Returns ts, Y (a row a record)
    and the number of rhs evaluations."""
    ts = np.round(np.arange(0, t_end + dt / 2, dt), 10)
    y = np.array(y0, float)
    out = [y.copy()]
    nfev = 0
    for a, b in zip(ts[:-1], ts[1:]):
        s = solve_ivp(rhs, (a, b), y, method="DOP853", rtol=tol, atol=tol,
                      args=(which,))
        assert s.success, s.message
        nfev += s.nfev
        y = s.y[:, -1]
        out.append(y.copy())
    return ts, np.array(out), nfev


def integrate_checked(rhs, y0, t_end, dt, cross):
    """The reference run (Kane, tol 1e-13) and its three checks. Returns ts,
    Y, nfev and max |Y - Y_other| against the same run with the cross-check
    formulation's rhs (which=cross), with tol 1e-12 and with tol 2.5e-14."""
    ts, Y, nfev = integrate(rhs, y0, t_end, dt)

    def diff(which, tol):
        return float(np.max(np.abs(Y - integrate(rhs, y0, t_end, dt, which, tol)[1])))

    return ts, Y, nfev, diff(cross, 1e-13), diff("kane", 1e-12), diff("kane", 2.5e-14)


def trajectory_records(ts, Y, full_state, energy, con_f, vcon_f, pv):
    """The records of a run, each with the full state full_state(y) = (q, u)
    and its total energy (energy(q, u)[0]). Returns the records, the initial
    energy E0, max |E - E0| and the largest configuration and velocity
    residuals (con_f, vcon_f at parameters pv) along the run."""
    records = []
    E0 = None
    drift = con = vcon = 0.0
    for tt, y in zip(ts, Y):
        q, u = full_state(y)
        E_ = energy(q, u)[0]
        E0 = E_ if E0 is None else E0
        drift = max(drift, abs(E_ - E0))
        con = max(con, float(np.max(np.abs(con_f(q, u, pv)))))
        vcon = max(vcon, float(np.max(np.abs(vcon_f(q, u, pv)))))
        records.append({"t": float(tt), "q": q.tolist(), "u": u.tolist(), "energy": E_})
    return records, E0, drift, con, vcon


# ---------------------------------------------------------------------------
# Output
# ---------------------------------------------------------------------------
def header(model, generator, spec):
    """The first keys of a reference file: model, generator, the versions of
    the programs that made it, and its specification."""
    return {"model": model, "generator": generator,
            "versions": {"python": platform.python_version(), "sympy": sp.__version__,
                         "numpy": np.__version__, "scipy": scipy.__version__},
            "spec": spec}


def trajectory_head(integrator, records, t_end, dt, nfev, drift):
    """The first keys of a file's "trajectory": how it was integrated, the
    initial state, the record times, the cost and max |E - E0|."""
    return {"integrator": integrator,
            "q0": records[0]["q"], "u0": records[0]["u"], "t_end": t_end, "dt": dt,
            "nfev": int(nfev),
            "energy_max_abs_drift": float(drift)}


def write_reference(out, filename, t0):
    """Write out as tests/reference/<filename> and say so, with the time since
    t0 (the script's start)."""
    with open(os.path.join(HERE, "..", filename), "w") as fh:
        json.dump(out, fh, indent=1)
    print(f"wrote {filename} in {time.time() - t0:.1f} s")
