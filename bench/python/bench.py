"""autosim from Python against PyDy on the same machine: per-call
overhead, many states in one call, a 10-s simulation, and the load time of
a cached model. Not a test: run it under the machine's build lock, nothing
else running, from the repository root with the package and PyDy installed
(the shared environment of `cargo test --test python` has them, plus
`pip install pydy cython sympy`):

    target/python-env/bin/python bench/python/bench.py

Models: PyDy's `n_link_pendulum_on_cart` n = 1, 3, 5 (PyDy builds its own;
autosim loads `python/tests/models/n_link_pendulum_on_cart_<n>.sim`, the
same system, checked equal in python/tests/test_pydy.py). Contenders:

- autosim: `model.rhs(t, x)` (the `solve_ivp` signature, the fast path),
  `model.derivatives(t, x)` (checked arguments), `model.derivatives(t, X)`
  for 10^5 states in one call, `model.simulate` (Dormand–Prince 5(4) in
  Rust);
- PyDy: `generate_ode_function` with the Cython generator (its fastest)
  and with lambdify (SymPy lambdified with NumPy); one state per call, so
  10^5 states is a Python loop; the simulation is `solve_ivp(RK45)` on it
  (the same Dormand–Prince 5(4) pair), also with autosim's `rhs`.

Every timing is the median of interleaved rounds. Results are printed as
a Markdown table (paste into bench/python/results.md).
"""

from __future__ import annotations

import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

import autosim
import numpy as np
from pydy.codegen.ode_function_generators import generate_ode_function
from pydy.models import n_link_pendulum_on_cart
from scipy.integrate import solve_ivp

REPO = Path(__file__).resolve().parents[2]
ROUNDS = 7


def median_time(function, repeat: int) -> float:
    """Seconds per call: the median over ROUNDS of `repeat` calls."""
    samples = []
    for _ in range(ROUNDS):
        start = time.perf_counter()
        for _ in range(repeat):
            function()
        samples.append((time.perf_counter() - start) / repeat)
    return statistics.median(samples)


def main() -> None:
    print(
        f"python {platform.python_version()}, numpy {np.__version__}, {platform.processor() or platform.machine()}, autosim {autosim.__version__}"
    )
    rows = []
    for n in (1, 3, 5):
        system = n_link_pendulum_on_cart(n, cart_force=True, joint_torques=False)
        kane = system.eom_method
        constants = sorted(system.constants_symbols, key=str)
        specified = sorted(system.specifieds_symbols, key=str)
        pydy = {}
        for generator in ("cython", "lambdify"):
            start = time.perf_counter()
            pydy[generator] = generate_ode_function(
                kane.forcing_full,
                kane.q,
                kane.u,
                constants,
                mass_matrix=kane.mass_matrix_full,
                specifieds=specified,
                generator=generator,
            )
            pydy[generator + " build"] = time.perf_counter() - start
        model = autosim.load(REPO / f"python/tests/models/n_link_pendulum_on_cart_{n}.sim", quiet=True)
        rng = np.random.default_rng(n)
        values = {str(c): float(rng.uniform(0.5, 1.5)) for c in constants}
        values["g"] = 9.81
        model.parameters.set(values)
        p = np.array([values[str(c)] for c in constants])
        r = np.array([0.3])
        model.set_inputs(r)
        nx = model.n_states
        # PyDy's states are absolute angles, ours relative: the timings do not
        # care, the values were checked in test_pydy.py.
        x = rng.uniform(-1, 1, nx)
        many = rng.uniform(-1, 1, (100_000, nx))

        cy, la = pydy["cython"], pydy["lambdify"]
        call = {
            "autosim rhs": median_time(lambda: model.rhs(0.0, x), 20_000),
            "autosim derivatives": median_time(lambda: model.derivatives(0.0, x), 20_000),
            "PyDy cython": median_time(lambda: cy(x, 0.0, r, p), 20_000),
            "PyDy lambdify": median_time(lambda: la(x, 0.0, r, p), 2_000),
        }
        small = many[:2_000]
        per_state = {
            "autosim vectorized": median_time(lambda: model.derivatives(0.0, many), 3) / len(many),
            "PyDy cython loop": median_time(lambda: [cy(row, 0.0, r, p) for row in small], 3) / len(small),
            "PyDy lambdify loop": median_time(lambda: [la(row, 0.0, r, p) for row in small[:500]], 3) / 500,
        }
        x0 = np.zeros(nx)
        x0[1] = 0.5
        t_eval = np.linspace(0.0, 10.0, 1001)
        tol = dict(rtol=1e-8, atol=1e-10)
        sim = {
            "autosim simulate": median_time(lambda: model.simulate(10.0, x0, t_eval=t_eval, **tol), 3),
            "solve_ivp(autosim rhs)": median_time(
                lambda: solve_ivp(model.rhs, (0, 10), x0, t_eval=t_eval, **tol), 1
            ),
            "solve_ivp(PyDy cython)": median_time(
                lambda: solve_ivp(lambda t, y: cy(y, t, r, p), (0, 10), x0, t_eval=t_eval, **tol), 1
            ),
        }
        rows.append((n, nx, call, per_state, sim, pydy["cython build"], pydy["lambdify build"]))

    cached = []
    path = REPO / "python/tests/models/n_link_pendulum_on_cart_5.sim"
    for _ in range(ROUNDS):
        out = subprocess.run(
            [
                sys.executable,
                "-c",
                "import time, autosim, sys\n"
                "t = time.perf_counter(); autosim.load(sys.argv[1], quiet=True); print(time.perf_counter() - t)",
                str(path),
            ],
            capture_output=True,
            text=True,
            check=True,
            env=dict(os.environ),
        )
        cached.append(float(out.stdout))
    import_time = []
    for _ in range(ROUNDS):
        out = subprocess.run(
            [
                sys.executable,
                "-c",
                "import time; t = time.perf_counter(); import autosim; print(time.perf_counter() - t)",
            ],
            capture_output=True,
            text=True,
            check=True,
        )
        import_time.append(float(out.stdout))

    print(
        "\n| n | states | per call: autosim rhs / derivatives | PyDy Cython | PyDy lambdify | ratio Cython/rhs |"
    )
    print("| --- | --- | --- | --- | --- | --- |")
    for n, nx, call, _, _, _, _ in rows:
        print(
            f"| {n} | {nx} | {call['autosim rhs'] * 1e6:.2f} / {call['autosim derivatives'] * 1e6:.2f} µs | {call['PyDy cython'] * 1e6:.2f} µs | {call['PyDy lambdify'] * 1e6:.1f} µs | {call['PyDy cython'] / call['autosim rhs']:.1f}× |"
        )
    print(
        "\n| n | 10^5 states: autosim, one call | PyDy Cython, loop | PyDy lambdify, loop | ratio Cython/autosim |"
    )
    print("| --- | --- | --- | --- | --- |")
    for n, _nx, _, ps, _, _, _ in rows:
        print(
            f"| {n} | {ps['autosim vectorized'] * 1e9:.1f} ns/state | {ps['PyDy cython loop'] * 1e9:.0f} ns/state | {ps['PyDy lambdify loop'] * 1e9:.0f} ns/state | {ps['PyDy cython loop'] / ps['autosim vectorized']:.0f}× |"
        )
    print(
        "\n| n | 10 s, RK45/DP5(4) rtol 1e-8: autosim simulate | solve_ivp(autosim rhs) | solve_ivp(PyDy Cython) | ratio PyDy/simulate |"
    )
    print("| --- | --- | --- | --- | --- |")
    for n, _nx, _, _, s, _, _ in rows:
        print(
            f"| {n} | {s['autosim simulate'] * 1e3:.2f} ms | {s['solve_ivp(autosim rhs)'] * 1e3:.1f} ms | {s['solve_ivp(PyDy cython)'] * 1e3:.1f} ms | {s['solve_ivp(PyDy cython)'] / s['autosim simulate']:.0f}× |"
        )
    print(
        "\nPyDy code generation (s): "
        + ", ".join(f"n={n}: Cython {cb:.1f}, lambdify {lb:.2f}" for n, _, _, _, _, cb, lb in rows)
    )
    print(
        f"cached autosim.load of n_link_pendulum_on_cart_5.sim in a fresh process: median {statistics.median(cached) * 1e3:.1f} ms "
        f"(rounds {', '.join(f'{c * 1e3:.1f}' for c in cached)}); import autosim itself: median {statistics.median(import_time) * 1e3:.0f} ms"
    )


if __name__ == "__main__":
    main()
