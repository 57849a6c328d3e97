"""The package against PyDy and SymPy on the same systems, written
independently: PyDy's ``n_link_pendulum_on_cart`` (n = 1, 3, 5) as
``python/tests/models/n_link_pendulum_on_cart_<n>.sim`` and the
chain-spatial-3 of ``tests/reference/models.md`` (a SymPy ``KanesMethod``
model in the generator). Reference data: ``tests/reference/pydy/*.json``
from ``tests/reference/gen/pydy_models.py``.

PyDy measures each link's angle from the ground; the ``.sim`` files turn
each link relative to the previous one, so PyDy's states are ``S x`` of
ours, ``S`` summing the relative angles (and rates) of the links.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Callable

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import autosim

CASES = {
    "n-link-pendulum-on-cart-1": "python/tests/models/n_link_pendulum_on_cart_1.sim",
    "n-link-pendulum-on-cart-3": "python/tests/models/n_link_pendulum_on_cart_3.sim",
    "n-link-pendulum-on-cart-5": "python/tests/models/n_link_pendulum_on_cart_5.sim",
    "chain-spatial-3": "examples/models/chain_spatial_3.sim",
}


def reference(repo: Path, name: str) -> dict:
    return json.loads((repo / "tests" / "reference" / "pydy" / f"{name}.json").read_text())


def coordinates_map(name: str, n_states: int) -> np.ndarray:
    """``S`` with PyDy's state = ``S`` ours (identity for the chain)."""
    if not name.startswith("n-link"):
        return np.eye(n_states)
    half = n_states // 2
    block = np.eye(half)
    block[1:, 1:] = np.tril(np.ones((half - 1, half - 1)))
    s = np.zeros((n_states, n_states))
    s[:half, :half] = block
    s[half:, half:] = block
    return s


def setup(
    repo: Path, load_model: Callable[..., autosim.Model], name: str
) -> tuple[autosim.Model, dict, np.ndarray]:
    ref = reference(repo, name)
    model = load_model(CASES[name])
    model.parameters.set(ref["parameters"])
    assert set(model.parameter_names) == set(ref["parameters"]), "every parameter mapped by name"
    return model, ref, coordinates_map(name, model.n_states)


@pytest.mark.parametrize("name", CASES)
def test_right_hand_side_matches_pydy(
    repo: Path, load_model: Callable[..., autosim.Model], name: str
) -> None:
    model, ref, s = setup(repo, load_model, name)
    s_inv = np.linalg.inv(s)
    worst = 0.0
    for sample in ref["samples"]:
        x = s_inv @ np.array(sample["x"])
        got = s @ model.derivatives(0.0, x, u=sample["inputs"] or None)
        want = np.array(sample["dxdt"])
        worst = max(worst, float(np.max(np.abs(got - want)) / np.max(np.abs(want))))
    print(f"{name}: right-hand side, worst relative difference {worst:.2e}")
    assert worst < 1e-12


@pytest.mark.parametrize("name", CASES)
def test_trajectories_match_pydy(repo: Path, load_model: Callable[..., autosim.Model], name: str) -> None:
    model, ref, s = setup(repo, load_model, name)
    s_inv = np.linalg.inv(s)
    traj = ref["trajectory"]
    x0 = s_inv @ np.array(traj["x0"])
    want = np.array(traj["x"])
    inputs = traj["inputs"] or None
    sim = model.simulate(2.0, x0, t_eval=traj["t"], rtol=1e-12, atol=1e-14, inputs=inputs)
    ours = (s @ sim.x.T).T
    if inputs is not None:
        model.set_inputs(inputs)
    ivp = solve_ivp(model.rhs, (0.0, 2.0), x0, method="DOP853", t_eval=traj["t"], rtol=1e-13, atol=1e-14)
    theirs = (s @ ivp.y).T
    simulate_error = float(np.max(np.abs(ours - want)))
    ivp_error = float(np.max(np.abs(theirs - want)))
    print(f"{name}: trajectory over 2 s, simulate {simulate_error:.1e}, solve_ivp {ivp_error:.1e}")
    assert simulate_error < 1e-8
    assert ivp_error < 1e-9


@pytest.mark.parametrize("name", CASES)
def test_linearization_matches_sympy_linearizer(
    repo: Path, load_model: Callable[..., autosim.Model], name: str
) -> None:
    model, ref, s = setup(repo, load_model, name)
    lin_ref = ref["linear"]
    x = np.linalg.inv(s) @ np.array(lin_ref["x"])
    assert np.all(np.abs(lin_ref["x"]) > 1e-3), "a non-zero operating point"
    a, b, _, _ = model.linearize(0.0, x, u=lin_ref["inputs"] or None)
    a_pydy = s @ a @ np.linalg.inv(s)
    b_pydy = s @ b
    want_a, want_b = np.array(lin_ref["A"]), np.array(lin_ref["B"]).reshape(b_pydy.shape)
    err_a = float(np.max(np.abs(a_pydy - want_a)) / np.max(np.abs(want_a)))
    err_b = (
        float(np.max(np.abs(b_pydy - want_b)) / max(np.max(np.abs(want_b)), 1e-300)) if want_b.size else 0.0
    )
    print(f"{name}: A {err_a:.1e}, B {err_b:.1e} (relative to the largest entry)")
    assert err_a < 1e-10
    assert err_b < 1e-10
