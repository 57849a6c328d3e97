"""Reference data for the Python package's checks against PyDy and SymPy
(python/tests/test_pydy.py): writes tests/reference/pydy/<model>.json.

Models, each built here from its own definition, never from autosim:

- ``n_link_pendulum_on_cart`` n = 1, 3, 5: PyDy's own model function
  (``pydy.models.n_link_pendulum_on_cart``, cart force F as the input);
- ``chain-spatial-3`` of ``tests/reference/models.md``: a SymPy
  ``KanesMethod`` model written below from that definition.

For each: the state, parameter and input names; parameter values (by
name); 12 random states with random inputs and the right-hand side
``dx/dt`` there (PyDy's ``generate_ode_function``, which solves
``M dx/dt = F`` numerically with the fastest generator that builds: Cython
if it compiles, else lambdify); a trajectory of 2 s from a non-trivial
state (``scipy.integrate.solve_ivp``, DOP853, rtol 1e-13, atol 1e-14,
sampled every 0.1 s); and ``A``, ``B`` of SymPy's ``Linearizer`` at a
non-zero operating point (all states and the input non-zero; not an
equilibrium, so the operating point includes ``dq/dt`` and ``du/dt``
there), evaluated after substituting the numbers.

Run from the repository root with PyDy, SymPy, SciPy, NumPy installed:
``python3 tests/reference/gen/pydy_models.py`` (about a minute).
"""

import json
import os
import platform
import time

import numpy as np
import pydy
import scipy
import sympy as sp
import sympy.physics.mechanics as me
from pydy.codegen.ode_function_generators import generate_ode_function
from pydy.models import n_link_pendulum_on_cart
from scipy.integrate import solve_ivp

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "pydy")


def chain_spatial(n):
    """chain-spatial-n of models.md as a SymPy KanesMethod (returns kane,
    coordinates, speeds, parameter symbols with values, no inputs)."""
    q = me.dynamicsymbols(f"q1:{n + 1}")
    u = me.dynamicsymbols(f"u1:{n + 1}")
    k, c, g = sp.symbols("k c g")
    values = {k: 2.0, c: 0.1, g: 9.81}
    N = me.ReferenceFrame("N")
    origin = me.Point("O")
    origin.set_vel(N, 0)
    parent, joint = N, origin
    bodies, loads = [], []
    P = sp.Symbol("P")
    values[P] = 0.0005
    for i in range(1, n + 1):
        m, L, Ixx, Iyy, Izz = sp.symbols(f"m{i} L{i} Ixx{i} Iyy{i} Izz{i}")
        mi = 1 + 0.1 * (i % 5)
        Li = 0.4 + 0.05 * (i % 3)
        values |= {m: mi, L: Li, Ixx: mi * Li**2 / 12, Iyy: mi * Li**2 / 12 + 0.001, Izz: 0.002 + 0.0001 * i}
        axis = [parent.x, parent.y, parent.z][(i - 1) % 3]
        B = parent.orientnew(f"B{i}", "Axis", [q[i - 1], axis])
        B.set_ang_vel(parent, u[i - 1] * axis)
        origin = joint
        cm = origin.locatenew(f"G{i}", -L / 2 * B.z)
        cm.v2pt_theory(origin, N, B)
        inertia = me.inertia(B, Ixx, Iyy, Izz, P, 0, 0)
        bodies.append(me.RigidBody(f"B{i}", cm, B, m, (inertia, cm)))
        loads.append((cm, -m * g * N.z))
        torque = (-k * q[i - 1] - c * u[i - 1]) * axis
        loads.append((B, torque))
        if parent is not N:
            loads.append((parent, -torque))
        nxt = origin.locatenew(f"J{i + 1}", -L * B.z)
        nxt.v2pt_theory(origin, N, B)
        parent, joint = B, nxt
    kd = [qi.diff() - ui for qi, ui in zip(q, u)]
    kane = me.KanesMethod(N, q_ind=q, u_ind=u, kd_eqs=kd)
    kane.kanes_equations(bodies, loads)
    return kane, q, u, values, []


def pendulum_on_cart(n):
    """PyDy's model (returns kane, coordinates, speeds, parameter values by
    symbol, inputs)."""
    system = n_link_pendulum_on_cart(n, cart_force=True, joint_torques=False)
    kane = system.eom_method
    q = list(kane.q)
    u = list(kane.u)
    rng = np.random.default_rng(100 + n)
    values = {}
    for s in sorted(system.constants_symbols, key=str):
        name = str(s)
        values[s] = 9.81 if name == "g" else float(rng.uniform(0.4, 1.5))
    F = me.dynamicsymbols("F")
    return kane, q, u, values, [F]


def ode_function(kane, values, inputs):
    """The fastest generate_ode_function that builds: (function, generator)."""
    constants = list(values)
    for generator in ("cython", "lambdify"):
        try:
            f = generate_ode_function(
                kane.forcing_full,
                kane.q,
                kane.u,
                constants,
                mass_matrix=kane.mass_matrix_full,
                specifieds=inputs or None,
                generator=generator,
            )
            return f, generator, constants
        except Exception as e:  # a missing C compiler or Cython
            print(f"  {generator} generator failed: {e}")
    raise RuntimeError("no PyDy generator works")


def linearized(kane, q, u, values, inputs, x_op, r_op, dx_op):
    """A, B of SymPy's Linearizer at the operating point (not an
    equilibrium: the derivatives of the coordinates and speeds there,
    ``dx_op``, are part of it)."""
    linearizer = kane.to_linearizer()
    op = dict(zip(q, x_op[: len(q)])) | dict(zip(u, x_op[len(q) :]))
    op |= {qi.diff(): v for qi, v in zip(q, dx_op[: len(q)])}
    op |= {ui.diff(): v for ui, v in zip(u, dx_op[len(q) :])}
    op |= dict(zip(inputs, r_op))
    op |= values
    A, B = linearizer.linearize(op_point=op, A_and_B=True, simplify=False)
    A = np.array(sp.N(A.subs(op)), dtype=float)
    B = np.array(sp.N(B.subs(op)), dtype=float) if inputs else np.zeros((len(x_op), 0))
    return A, B, [str(s) for s in linearizer.r]


def main():
    os.makedirs(OUT, exist_ok=True)
    cases = [(f"n-link-pendulum-on-cart-{n}", lambda n=n: pendulum_on_cart(n)) for n in (1, 3, 5)]
    cases.append(("chain-spatial-3", lambda: chain_spatial(3)))
    for name, make in cases:
        started = time.time()
        kane, q, u, values, inputs = make()
        f, generator, constants = ode_function(kane, values, inputs)
        p = np.array([values[c] for c in constants])
        nx, ni = len(q) + len(u), len(inputs)
        rng = np.random.default_rng(7)
        samples = []
        for _ in range(12):
            x = rng.uniform(-1.5, 1.5, nx)
            r = rng.uniform(-3.0, 3.0, ni)
            args = (x, 0.0, r, p) if ni else (x, 0.0, p)
            samples.append({"x": x.tolist(), "inputs": r.tolist(), "dxdt": np.asarray(f(*args)).tolist()})
        x0 = rng.uniform(-0.8, 0.8, nx)
        r0 = rng.uniform(-2.0, 2.0, ni)
        times = np.linspace(0.0, 2.0, 21)

        def rhs(t, x):
            return f(x, t, r0, p) if ni else f(x, t, p)

        traj = solve_ivp(rhs, (0.0, 2.0), x0, method="DOP853", t_eval=times, rtol=1e-13, atol=1e-14)
        x_op = rng.uniform(-1.0, 1.0, nx)
        r_op = rng.uniform(-2.0, 2.0, ni)
        dx_op = np.asarray(f(x_op, 0.0, r_op, p) if ni else f(x_op, 0.0, p))
        A, B, r_names = linearized(kane, q, u, values, inputs, x_op, r_op, dx_op)
        data = {
            "model": name,
            "generator": "tests/reference/gen/pydy_models.py",
            "ode_generator": generator,
            "versions": {
                "python": platform.python_version(),
                "sympy": sp.__version__,
                "pydy": pydy.__version__,
                "numpy": np.__version__,
                "scipy": scipy.__version__,
            },
            "states": [str(s).replace("(t)", "") for s in list(q) + list(u)],
            "inputs": [str(s).replace("(t)", "") for s in inputs],
            "parameters": {str(c): float(values[c]) for c in constants},
            "samples": samples,
            "trajectory": {
                "x0": x0.tolist(),
                "inputs": r0.tolist(),
                "t": times.tolist(),
                "x": traj.y.T.tolist(),
                "method": "solve_ivp DOP853 rtol 1e-13 atol 1e-14",
            },
            "linear": {
                "x": x_op.tolist(),
                "inputs": r_op.tolist(),
                "input_order": r_names,
                "A": A.tolist(),
                "B": B.tolist(),
            },
        }
        with open(os.path.join(OUT, f"{name}.json"), "w") as out:
            json.dump(data, out, indent=1)
        print(f"{name}: {generator}, {time.time() - started:.1f} s")


if __name__ == "__main__":
    main()
