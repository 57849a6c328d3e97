"""Events from Python (``examples/models/bouncing_ball.sim`` and a terminal
event written here): the discrete variables and events on the model, the
bounce times against their analytic values, SciPy's ``solve_ivp`` with
``events`` as a second, independent formulation, the discrete variables'
history, their initial values set by the caller, a terminal event, and the
Zeno error naming the event."""

from __future__ import annotations

from typing import Callable

import numpy as np
import pytest

import autosim

G = 9.81
H0 = 1.0
T1 = np.sqrt(2.0 * H0 / G)


def bounce_times(e: float, n: int) -> np.ndarray:
    """The analytic instants of the first ``n`` bounces from rest at ``H0``:
    the first fall takes ``t1 = sqrt(2 H0/g)``, the flight after bounce ``k``
    ``2 e^k t1``."""
    flights = [T1] + [2.0 * e**k * T1 for k in range(1, n)]
    return np.cumsum(flights)


def apex_heights(e: float, n: int) -> np.ndarray:
    """The analytic apex after each of the first ``n`` bounces: ``e^(2k) H0``."""
    return np.array([e ** (2 * k) * H0 for k in range(1, n + 1)])


@pytest.fixture
def ball(load_model: Callable[..., autosim.Model]) -> autosim.Model:
    return load_model("examples/models/bouncing_ball.sim")


def test_the_model_lists_its_discrete_variables_and_events(ball: autosim.Model) -> None:
    assert ball.discrete_names == ("resting",)
    assert ball.discrete_units == ("",)
    assert ball.discrete[0].default == 0.0
    assert "rests on the floor" in ball.discrete[0].doc
    assert list(ball.initial_discrete()) == [0.0]
    assert [(e.name, e.direction, e.stop, e.unit) for e in ball.events] == [
        ("bounce", "falling", False, "m"),
        ("apex", "falling", False, "m/s"),
    ]
    doc = type(ball).__doc__ or ""
    assert "Discrete variables:" in doc
    assert "bounce (falling)" in doc


def test_bounce_times_and_apex_heights_match_the_analytic_ones(ball: autosim.Model) -> None:
    e = 0.8
    ball.parameters["e"] = e
    sim = ball.simulate(3.7, method="dopri", rtol=1e-12, atol=1e-12)
    bounces, apexes = sim.events.only("bounce"), sim.events.only("apex")
    assert len(bounces) >= 10 and len(apexes) >= 10
    assert np.abs(bounces.t[:10] - bounce_times(e, 10)).max() < 1e-10
    assert np.abs(apexes.x_before[:10, 0] - apex_heights(e, 10)).max() < 1e-10
    # The reset: the speed reversed and scaled by e, the height kept.
    np.testing.assert_allclose(bounces.x_after[:, 1], -e * bounces.x_before[:, 1], rtol=1e-15)
    np.testing.assert_array_equal(bounces.x_after[:, 0], bounces.x_before[:, 0])
    assert sim.stopped_by is None and sim.t[-1] == 3.7
    with pytest.raises(KeyError, match="did you mean 'bounce'"):
        sim.events.only("bounse")
    with pytest.raises(ValueError, match="zeno_events must be at least 1, not 0"):
        ball.simulate(1.0, zeno_events=0)
    with pytest.raises(ValueError, match="event_samples must be in 0..=1000, not -1"):
        ball.simulate(1.0, event_samples=-1)


@pytest.mark.parametrize("method", ["rk4", "abm4", "heun", "sdirk3"])
def test_every_fixed_step_method_locates_the_bounces(ball: autosim.Model, method: str) -> None:
    # Free fall is a quadratic in time: these methods and the cubic Hermite
    # interpolant the driver locates crossings on are exact for it, so the
    # instants are as accurate as rounding allows, at a coarse step.
    sim = ball.simulate(3.7, method=method, h=1e-2)
    bounces = sim.events.only("bounce")
    assert np.abs(bounces.t[:10] - bounce_times(0.8, 10)).max() < 1e-10


def scipy_bounce_times(e: float, n: int) -> np.ndarray:
    """The first ``n`` bounces by SciPy alone: ``solve_ivp`` (DOP853) on the
    free fall ``h' = v, v' = -g`` with a terminal event at ``h = 0``
    (falling), restarted from ``(0, -e v)`` after each."""
    from scipy.integrate import solve_ivp

    def floor(t: float, y: np.ndarray) -> float:
        return float(y[0])

    floor.terminal = True  # type: ignore[attr-defined]
    floor.direction = -1  # type: ignore[attr-defined]
    t, y = 0.0, np.array([H0, 0.0])
    times: list[float] = []
    while len(times) < n:
        run = solve_ivp(
            lambda _t, s: [s[1], -G], (t, t + 10.0), y, method="DOP853", events=floor, rtol=1e-13, atol=1e-13
        )
        t = float(run.t_events[0][0])
        v = float(run.y_events[0][0][1])
        times.append(t)
        y = np.array([0.0, -e * v])
    return np.array(times)


def test_the_bounces_agree_with_scipy_solve_ivp_events(ball: autosim.Model) -> None:
    pytest.importorskip("scipy")
    e = 0.8
    reference = scipy_bounce_times(e, 10)
    # SciPy's own accuracy, against the analytic instants.
    assert np.abs(reference - bounce_times(e, 10)).max() < 1e-10
    sim = ball.simulate(3.7, method="dopri", rtol=1e-12, atol=1e-12)
    assert np.abs(sim.events.only("bounce").t[:10] - reference).max() < 1e-10


def test_the_resting_mode_is_a_discrete_trajectory(ball: autosim.Model) -> None:
    ball.parameters["v_min"] = 0.5
    sim = ball.simulate(6.0, method="dopri", rtol=1e-10, atol=1e-10)
    # Rebounds 0.8^k 4.43 m/s fall below 0.5 m/s at bounce 10.
    bounces = sim.events.only("bounce")
    assert len(bounces) == 10
    assert list(bounces.d_before[:, 0]) == [0.0] * 10
    assert list(bounces.d_after[:, 0]) == [0.0] * 9 + [1.0]
    resting = sim["resting"]
    assert set(resting) == {0.0, 1.0}
    assert np.all(resting[sim.t < bounces.t[-1]] == 0.0)
    assert np.all(resting[sim.t > bounces.t[-1]] == 1.0)
    # At rest on the floor (where the last bounce was located: rounding).
    after = sim.t > bounces.t[-1]
    assert np.all(sim["v"][after] == 0.0) and np.abs(sim["h"][after]).max() < 1e-12
    if pytest.importorskip("pandas"):
        assert "resting" in sim.to_pandas().columns


def test_initial_discrete_values_are_the_callers(ball: autosim.Model) -> None:
    held = ball.simulate(1.0, discrete0={"resting": 1.0})
    assert len(held.events) == 0
    assert np.all(held["h"] == 1.0) and np.all(held["resting"] == 1.0)
    same = ball.simulate(1.0, discrete0=[1.0])
    np.testing.assert_array_equal(same.x, held.x)
    assert list(ball.initial_discrete()) == [0.0], "the model's own values are untouched"
    with pytest.raises(KeyError, match="did you mean 'resting'"):
        ball.simulate(1.0, discrete0={"rested": 1.0})
    with pytest.raises(ValueError, match="discrete0"):
        ball.simulate(1.0, discrete0=[1.0, 0.0])


FALL = """
/// A ball dropped from `h0` until it reaches the floor.
model Fall;
parameters { g = 9.81 [m/s^2], h0 = 2 [m] }
body Ball { translate: 3, q: [h], u: [v], mass: 1 [kg], inertia: 0, initial: [h0] }
gravity = -g*n3;
/// The floor: the run ends there.
event floor [m] { indicator: h, direction: falling, stop: true }
"""


def test_a_terminal_event_ends_the_run_at_its_instant() -> None:
    fall = autosim.loads(FALL, quiet=True)
    assert [(e.name, e.stop) for e in fall.events] == [("floor", True)]
    sim = fall.simulate(5.0, t_eval=np.linspace(0.0, 5.0, 11), method="dopri", rtol=1e-12, atol=1e-12)
    landing = np.sqrt(2.0 * 2.0 / G)
    assert sim.stopped_by == "floor"
    assert abs(sim.t[-1] - landing) < 1e-12 and sim.events.t[0] == sim.t[-1]
    assert abs(sim["h"][-1]) < 1e-12
    assert list(sim.t[:-1]) == [0.0, 0.5]


def test_chattering_raises_the_zeno_error_naming_the_event(ball: autosim.Model) -> None:
    ball.parameters["e"], ball.parameters["v_min"] = 0.9, 0.0
    # Infinitely many bounces before t1 (1 + 2e/(1 - e)).
    limit = T1 * (1.0 + 2.0 * 0.9 / 0.1)
    with pytest.raises(autosim.ZenoError) as raised:
        ball.simulate(20.0, method="dopri", rtol=1e-10, atol=1e-10)
    error = raised.value
    assert isinstance(error, autosim.SimulationError)
    assert error.event == "bounce" and "bounce" in str(error)
    assert 7.0 < error.t < limit and error.events == 101
    with pytest.raises(ValueError, match="zeno_events"):
        ball.simulate(1.0, zeno_events=0)


STOP = """
/// A mass on a spring `k`; a second spring `k_stop` acts while `engaged`.
model EndStop;
parameters { m = 2 [kg], k = 50 [N/m], k_stop = 150 [N/m], c = 0 [N*s/m] }
/// 1 while the mass presses the stop's spring, 0 otherwise.
discrete engaged = 0;
body Mass { translate: 1, q: [x], u: [v], mass: m, inertia: 0 }
input push [N] = 0;
force spring { on: Mass.cm, vector: -(k + engaged*k_stop)*x*n1 }
force damper { on: Mass.cm, vector: -c*v*n1 }
force pushed { on: Mass.cm, vector: push*n1 }
/// The stop engages when the mass reaches it.
event contact [m] { indicator: x, direction: rising, set: { engaged: 1 } }
output spring_force [N] = (k + engaged*k_stop)*x;
"""


def test_evaluations_read_the_discrete_values_given_and_only_for_that_call() -> None:
    stop = autosim.loads(STOP, quiet=True, linearize=True)
    x = stop.state(x=0.1, v=0.0)
    # Free: a = -k x / m; engaged: a = -(k + k_stop) x / m (Newton, by hand).
    assert stop.derivatives(0.0, x)[1] == pytest.approx(-50.0 * 0.1 / 2.0, rel=1e-15)
    engaged = stop.derivatives(0.0, x, discrete={"engaged": 1.0})
    assert engaged[1] == pytest.approx(-200.0 * 0.1 / 2.0, rel=1e-15)
    np.testing.assert_array_equal(stop.derivatives(0.0, x, discrete=[1.0]), engaged)
    assert list(stop.initial_discrete()) == [0.0], "the model's own values are untouched"
    rows = stop.derivatives(0.0, np.array([x, 2 * x]), discrete={"engaged": 1.0})
    np.testing.assert_array_equal(rows[0], engaged)
    assert stop.outputs(0.0, x, discrete=[1.0])[0] == pytest.approx(20.0, rel=1e-15)
    assert stop.forcing(0.0, x, discrete=[1.0])[0] == pytest.approx(-20.0, rel=1e-15)
    assert stop.mass_matrix(0.0, x, discrete=[1.0])[0, 0] == 2.0
    # The natural frequency of each mode: sqrt(k/m), then sqrt((k + k_stop)/m).
    for value, k in ((0.0, 50.0), (1.0, 200.0)):
        eigenvalues, _ = stop.modes(discrete={"engaged": value})
        np.testing.assert_allclose(np.abs(eigenvalues.imag), np.sqrt(k / 2.0), rtol=1e-12)
        assert stop.linearize(discrete=[value]).C[0, 0] == pytest.approx(k, rel=1e-15)
    # Trim: the push that holds the engaged mass at x = 0.1 is (k + k_stop) x.
    held = stop.copy()
    trimmed = held.trim(x, free_states=[], free_inputs=["push"], steady=["v"], discrete={"engaged": 1.0})
    assert trimmed.inputs["push"] == pytest.approx(20.0, rel=1e-12)
    with pytest.raises(KeyError, match="did you mean 'engaged'"):
        stop.derivatives(0.0, x, discrete={"engage": 1.0})
    with pytest.raises(ValueError, match="discrete"):
        stop.linearize(discrete=[1.0, 0.0])
    assert list(stop.initial_discrete()) == [0.0], "a failed call restores nothing it did not change"
