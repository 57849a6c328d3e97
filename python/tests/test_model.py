"""The model object: names and units, parameters and inputs, evaluation
(single and vectorized), linearization, constraints, simulation, inputs
over time, SciPy and python-control interop, and the errors users get."""

from __future__ import annotations

import json
import pydoc
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import autosim

PENDULUM = "examples/models/pendulum.sim"
FOUR_BAR = "examples/models/four_bar.sim"

Load = Callable[..., autosim.Model]


def test_names_units_and_help(load_model: Load) -> None:
    model = load_model(PENDULUM)
    assert model.name == "Pendulum"
    assert model.state_names == ("q", "u")
    assert model.state_units == ("rad", "rad/s")
    assert model.parameter_names == ("m", "L", "g")
    assert model.parameters.units == ("kg", "m", "m/s^2")
    assert model.input_names == ("torque",)
    assert model.output_names == ("height",)
    assert model.output_units == ("m",)
    text = pydoc.render_doc(model, renderer=pydoc.plaintext)  # type: ignore[attr-defined]
    for line in ("q [rad]", "m = 1.3 [kg]  Bob mass.", "torque = 0 [N m]", "height [m]"):
        assert line in text, line


def test_parameters_by_name_dict_and_vector(load_model: Load) -> None:
    model = load_model(PENDULUM)
    assert dict(model.parameters) == {"m": 1.3, "L": 0.7, "g": 9.81}
    x = model.state(q=0.4)
    model.parameters["L"] = 1.4
    model.parameters.set(g=9.0)
    model.parameters.set({"m": 2.0})
    assert list(model.parameters.vector) == [2.0, 1.4, 9.0]
    # u' = (torque - m g L sin q) / (m L^2)
    assert model.derivatives(0.0, x)[1] == pytest.approx(-9.0 * np.sin(0.4) / 1.4, rel=1e-15)
    model.parameters.vector = [1.0, 1.0, 1.0]
    assert model.derivatives(0.0, x)[1] == pytest.approx(-np.sin(0.4), rel=1e-15)


def test_bad_input_names_the_thing(load_model: Load) -> None:
    model = load_model(PENDULUM)
    with pytest.raises(KeyError, match="'Lx'.*did you mean 'L'"):
        model.parameters["Lx"] = 1.0
    with pytest.raises(ValueError, match="'g' must be finite"):
        model.parameters["g"] = float("nan")
    with pytest.raises(ValueError, match=r"x must have shape \(2,\)"):
        model.derivatives(0.0, [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"x must have shape \(n, 2\)"):
        model.derivatives(0.0, np.zeros((4, 3)))
    with pytest.raises(ValueError, match="parameter vector"):
        model.parameters.vector = [1.0]
    with pytest.raises(KeyError, match="state 'w'"):
        model.state(w=1.0)
    with pytest.raises(ValueError, match="method 'rk5'"):
        model.simulate(1.0, method="rk5")
    with pytest.raises(ValueError, match="t_eval"):
        model.simulate(1.0, t_eval=[0.5, 0.2])
    assert dict(model.parameters) == {"m": 1.3, "L": 0.7, "g": 9.81}, "nothing changed"


def test_vectorized_derivatives_and_outputs_equal_single_calls(load_model: Load) -> None:
    model = load_model("python/tests/models/n_link_pendulum_on_cart_3.sim")
    rng = np.random.default_rng(1)
    xs = rng.uniform(-1, 1, (50, model.n_states))
    us = rng.uniform(-1, 1, (50, 1))
    many = model.derivatives(0.0, xs, u=us)
    outs = model.outputs(0.0, xs, u=us)
    for k in range(50):
        assert np.array_equal(many[k], model.derivatives(0.0, xs[k], u=us[k]))
        assert np.array_equal(outs[k], model.outputs(0.0, xs[k]))
    assert many.shape == (50, model.n_states) and outs.shape == (50, 1)


def test_vectorized_derivatives_through_lanes_equal_single_calls(load_model: Load, repo: Path) -> None:
    """A model loaded with ``lanes=True`` takes the states of a 2-D call four at a
    time (``derivatives_batch``); the bits and the first failing row are
    those of one call per row."""
    model = autosim.load(repo / "python/tests/models/n_link_pendulum_on_cart_3.sim", lanes=True, quiet=True)
    plain = load_model("python/tests/models/n_link_pendulum_on_cart_3.sim")
    xs = np.random.default_rng(3).uniform(-1, 1, (23, model.n_states))
    many = model.derivatives(0.0, xs)
    for k in range(23):
        assert np.array_equal(many[k], model.derivatives(0.0, xs[k]))
        assert np.array_equal(many[k], plain.derivatives(0.0, xs[k]))
    xs[9, -1] = 1e200  # a speed whose square overflows: a non-finite derivative
    xs[17, -1] = 1e200
    with pytest.raises(autosim.SimulationError) as failed:
        model.derivatives(0.0, xs)
    with pytest.raises(autosim.SimulationError) as single:
        model.derivatives(0.0, xs[9])
    assert str(failed.value) == f"row 9: {single.value}"


DRIVEN = """
model Driven;
parameters { m = 1.3 [kg], L = 0.7 [m], g = 9.81 [m/s^2], A = 2.0 [N m], w = 3.0 [rad/s] }
input torque [N m];
body Rod { rotate: 1, q: [q], u: [u], mass: m, cm: [0, 0, -L], inertia: 0 }
moment drive { on: Rod, reaction: N, about: n1, magnitude: A*sin(w*t) + torque }
gravity = -g*n3;
"""


def test_rows_at_their_own_times_and_inputs_through_lanes_equal_single_calls() -> None:
    """With a time or an input row per state row, a ``lanes=True`` model
    computes four rows per call, each lane at its own time with its own
    inputs: the bits of one call per row, and of the model without lanes."""
    lanes = autosim.loads(DRIVEN, lanes=True, quiet=True)
    plain = autosim.loads(DRIVEN, quiet=True)
    rng = np.random.default_rng(5)
    xs = rng.uniform(-1, 1, (23, lanes.n_states))
    ts = rng.uniform(0.0, 5.0, 23)
    us = rng.uniform(-1, 1, (23, 1))
    cases: list[tuple[Any, Any]] = [(ts, None), (0.3, us), (ts, us)]
    for t, u in cases:
        many = lanes.derivatives(t, xs, u=u)
        assert np.array_equal(many, plain.derivatives(t, xs, u=u))
        for k in range(23):
            tk = t[k] if isinstance(t, np.ndarray) else t
            one = plain.derivatives(tk, xs[k], u=None if u is None else u[k])
            assert np.array_equal(many[k], one)
    # Not vacuous: the times and the inputs matter.
    assert not np.array_equal(lanes.derivatives(ts, xs), lanes.derivatives(0.3, xs))
    assert not np.array_equal(lanes.derivatives(0.3, xs, u=us), lanes.derivatives(0.3, xs))


def test_mass_matrix_and_forcing_give_the_accelerations(load_model: Load) -> None:
    model = load_model("python/tests/models/n_link_pendulum_on_cart_5.sim")
    x = np.random.default_rng(2).uniform(-1, 1, model.n_states)
    m = model.mass_matrix(0.0, x)
    f = model.forcing(0.0, x, u=[0.7])
    assert np.allclose(m, m.T, rtol=0, atol=1e-15)
    du = model.derivatives(0.0, x, u=[0.7])[model.n_states - model.n_speeds :]
    assert np.allclose(m @ du, f, rtol=1e-12, atol=1e-12)


def test_an_input_given_to_an_evaluation_holds_for_that_call_only(load_model: Load) -> None:
    model = load_model(PENDULUM)
    x = model.state(q=0.3, u=0.1)
    model.inputs["torque"] = 0.25
    # The torque's angular acceleration is torque / (m L^2) (m = 1.3 kg, L = 0.7 m).
    pushed = model.derivatives(0.0, x, u=[1.25])[1] - model.derivatives(0.0, x)[1]
    assert pushed == pytest.approx(1.0 / (1.3 * 0.49), rel=1e-12)
    for call in (
        lambda: model.derivatives(0.0, x, u={"torque": 2.0}),
        lambda: model.outputs(0.0, x, u=2.0),
        lambda: model.derivatives(0.0, np.array([x, x]), u=[2.0]),
        lambda: model.derivatives(0.0, np.array([x, x]), u=[[2.0], [3.0]]),
        lambda: model.forcing(0.0, x, u=[2.0]),
        lambda: model.linearize(0.0, x, u=[2.0]),
    ):
        call()
        assert model.inputs["torque"] == 0.25
    with pytest.raises(ValueError):
        model.derivatives(0.0, x, u=[1.0, 2.0])
    assert model.inputs["torque"] == 0.25, "a failed call restores nothing it did not change"


def test_unknown_names_suggest_the_closest_whatever_the_case(load_model: Load) -> None:
    model = load_model(PENDULUM)
    with pytest.raises(KeyError, match="did you mean 'm'"):
        model.parameters.set(M=2.0)
    with pytest.raises(KeyError, match="did you mean 'torque'"):
        model.inputs["torq"] = 1.0
    with pytest.raises(KeyError, match="did you mean 'L'"):
        model.parameters["l"]


def test_linearization_against_central_differences_and_control(load_model: Load) -> None:
    model = load_model(PENDULUM)
    x = model.state(q=2.0, u=0.5)
    lin = model.linearize(0.0, x, u=0.3)
    h = 1e-6
    fd = np.column_stack(
        [(model.derivatives(0, x + h * e) - model.derivatives(0, x - h * e)) / (2 * h) for e in np.eye(2)]
    )
    assert np.allclose(lin.A, fd, rtol=1e-8, atol=1e-8)
    assert lin.B[1, 0] == pytest.approx(1.0 / (1.3 * 0.7**2), rel=1e-14)
    assert np.array_equal(model.jacobian(0.0, x), lin.A)
    values, _ = model.linearize(0.0, model.state(q=0.0)).modes()
    assert np.allclose(values, [-1j * np.sqrt(9.81 / 0.7), 1j * np.sqrt(9.81 / 0.7)])
    control = pytest.importorskip("control")
    ss = model.to_control(0.0, model.state(q=0.0))
    assert isinstance(ss, control.StateSpace)
    assert np.allclose(np.sort_complex(control.poles(ss)), np.sort_complex(values))


def test_simulate_methods_agree_and_match_solve_ivp(load_model: Load) -> None:
    model = load_model(PENDULUM)
    x0 = model.state(q=1.0)
    times = np.linspace(0.0, 3.0, 31)
    ref = solve_ivp(model.rhs, (0, 3), x0, method="DOP853", t_eval=times, rtol=1e-13, atol=1e-14)
    for method, tol in (("dopri", 1e-8), ("rk4", 1e-8), ("abm4", 1e-7), ("sdirk3", 1e-4), ("heun", 1e-4)):
        sim = model.simulate(3.0, x0, method=method, h=1e-3, t_eval=times)
        assert sim.t.shape == (31,) and sim.x.shape == (31, 2) and sim.y.shape == (31, 1)
        assert np.max(np.abs(sim.x - ref.y.T)) < tol, method
    radau = solve_ivp(
        model.rhs, (0, 3), x0, method="Radau", jac=model.jacobian, rtol=1e-10, atol=1e-12, t_eval=times
    )
    assert np.max(np.abs(radau.y - ref.y)) < 1e-7
    sim = model.simulate(3.0, x0)
    assert sim.t[0] == 0.0 and sim.t[-1] == 3.0 and len(sim.t) == 1001
    assert np.allclose(sim["height"], -0.7 * np.cos(sim["q"]), rtol=1e-14, atol=1e-15)
    assert sim.evaluations > 0 and sim.steps > 0


def test_inputs_constant_table_and_callable(load_model: Load) -> None:
    model = load_model(PENDULUM)
    times = np.linspace(0.0, 2.0, 21)
    constant = model.simulate(2.0, t_eval=times, inputs=0.5)
    table = model.simulate(2.0, t_eval=times, inputs=(np.array([0.0, 2.0]), np.array([[0.5], [0.5]])))
    function = model.simulate(2.0, t_eval=times, inputs=lambda t: [0.5])
    assert np.max(np.abs(table.x - constant.x)) < 1e-12
    assert np.max(np.abs(function.x - constant.x)) < 1e-12
    assert np.all(constant["torque"] == 0.5)
    assert model.inputs["torque"] == 0.0, "the run's inputs do not stay"
    ramp = model.simulate(2.0, t_eval=times, inputs=([0.0, 2.0], [0.0, 1.0]), method="rk4", h=1e-3)
    assert np.allclose(ramp["torque"], times / 2, rtol=0, atol=1e-15)
    by_function = model.simulate(2.0, t_eval=times, inputs=lambda t: t / 2, method="rk4", h=1e-3)
    assert np.max(np.abs(by_function.x - ramp.x)) < 1e-13

    # A state feedback is not an input: said before the run, with the way.
    with pytest.raises(ValueError, match="must take the time alone"):
        model.simulate(1.0, inputs=lambda t, x: -x[0])
    model.simulate(0.1, inputs=lambda t, *rest: [0.0])  # the time alone binds

    def broken(t: float) -> list:
        raise RuntimeError("no input today")

    with pytest.raises(RuntimeError, match="no input today"):
        model.simulate(1.0, inputs=broken)
    # A NaN from the callable is the callable's, not the model's.
    with pytest.raises(ValueError, match=r"returned NaN for input #0"):
        model.simulate(1.0, inputs=lambda t: [float("nan")])


def test_pandas_when_installed(load_model: Load) -> None:
    pd = pytest.importorskip("pandas")
    sim = load_model(PENDULUM).simulate(1.0, t_eval=[0.0, 0.5, 1.0])
    frame = sim.to_pandas()
    assert isinstance(frame, pd.DataFrame)
    assert list(frame.columns) == ["q", "u", "height", "torque"]
    assert frame.index.name == "t" and len(frame) == 3


def test_constrained_model_assembles_and_keeps_its_constraints(load_model: Load) -> None:
    model = load_model(FOUR_BAR)
    assert model.dependent_coordinates == ("q2", "q3")
    assert model.independent_states == ("q1", "u1")
    assert [c.name for c in model.interface.constraints] == ["loop_n2", "loop_n3"]
    x = model.assemble(model.initial_state())
    residuals = model.outputs(0.0, x)[
        [model.output_names.index("loop_n2"), model.output_names.index("loop_n3")]
    ]
    assert np.max(np.abs(residuals)) < 1e-12
    sim = model.simulate(2.0, x, rtol=1e-10, atol=1e-12)
    assert np.max(np.abs(sim["loop_n2"])) < 1e-9
    energy = sim["energy"]
    assert np.max(np.abs(energy - energy[0])) < 1e-6 * max(1.0, abs(energy[0]))
    lin = model.linearize(0.0, x)
    assert lin.state_names == ("q1", "u1") and lin.A.shape == (2, 2)
    with pytest.raises(ValueError, match="position constraints"):
        model.jacobian(0.0, x)


def test_singular_state_raises_simulation_error() -> None:
    model = autosim.loads(
        """
        model Bead;
        parameters { m = 1 [kg] }
        body B { translate: 1, mass: m, inertia: 0 }
        """,
        quiet=True,
    )
    model.parameters["m"] = 0.0
    with pytest.raises(autosim.SimulationError, match="mass matrix is singular"):
        model.derivatives(0.0, [0.0, 0.0])
    with pytest.raises(autosim.SimulationError, match="singular"):
        model.simulate(1.0)


def test_compile_errors_carry_the_spanned_diagnostic() -> None:
    text = "model Bad;\nbody B { rotat: 3, mass: 1 }\n"
    with pytest.raises(autosim.CompileError) as caught:
        autosim.loads(text, path="bad.sim", quiet=True)
    message = str(caught.value)
    assert message.startswith("bad.sim:2:10: error: unknown body option `rotat`"), message
    assert "2 | body B { rotat: 3, mass: 1 }" in message
    assert "^^^^^" in message
    assert "help: did you mean `rotate`?" in message
    assert isinstance(caught.value, ValueError)
    with pytest.raises(ValueError, match='formulation "fast"'):
        autosim.loads("model M;", quiet=True, formulation="fast")


def test_user_code_and_f32_models_are_refused_clearly(repo) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(autosim.CompileError, match="calls user code"):
        autosim.load(repo / "examples/models/satellite.sim", quiet=True)
    with pytest.raises(autosim.CompileError, match="f32"):
        autosim.load(repo / "examples/models/chain_planar_2_f32.sim", quiet=True)


def test_cache_second_load_imports_and_a_changed_text_rebuilds(tmp_path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    monkeypatch.setenv("AUTOSIM_CACHE", str(autosim.cache_dir()))
    source = tmp_path / "spring.sim"
    text = "model Spring;\nparameters { k = 4 [N/m] }\nbody B { translate: 1, mass: 1, inertia: 0 }\nforce s { on: B, vector: -k*q1*n1 }\n"
    source.write_text(text)
    autosim.load(source, quiet=True)
    built = sorted((autosim.cache_dir() / "models").iterdir(), key=lambda p: p.stat().st_mtime)[-1]
    stamp = built.stat().st_mtime_ns
    again = autosim.load(source, quiet=True)
    assert built.stat().st_mtime_ns == stamp, "the second load built nothing"
    assert np.array_equal(again.derivatives(0, [0.1, 0.0]), [0.0, -0.4])
    source.write_text(text.replace("k = 4", "k = 9"))
    changed = autosim.load(source, quiet=True)
    assert np.array_equal(changed.derivatives(0, [0.1, 0.0]), [0.0, -0.9])


def test_missing_cargo_is_a_clear_error(tmp_path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    monkeypatch.setenv("PATH", str(tmp_path))
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.delenv("CARGO", raising=False)
    with pytest.raises(autosim.BuildError, match="Install Rust"):
        fresh = f"// {tmp_path}\nmodel Fresh;\nbody B {{ translate: 1, mass: 1, inertia: 0 }}\n"
        autosim.loads(fresh, quiet=True)


def test_interface_json_round_trips(load_model: Load) -> None:
    model = load_model(FOUR_BAR)
    data = json.loads(model._native.interface())
    assert data["name"] == "FourBar" and data["dependent_coordinates"] == [1, 2]


def test_copies_are_independent_and_threads_can_share_the_work(load_model: Load) -> None:
    from concurrent.futures import ThreadPoolExecutor

    model = load_model(PENDULUM)
    other = model.copy()
    other.parameters["L"] = 2.0
    assert model.parameters["L"] == 0.7
    xs = np.random.default_rng(3).uniform(-1, 1, (20_000, 2))
    copies = [model.copy() for _ in range(4)]
    with ThreadPoolExecutor(4) as pool:
        parts = list(pool.map(lambda k: copies[k].derivatives(0.0, xs[k::4]), range(4)))
    whole = model.derivatives(0.0, xs)
    for k in range(4):
        assert np.array_equal(parts[k], whole[k::4])


def test_trim_finds_the_static_equilibrium(load_model: Load) -> None:
    model = load_model(PENDULUM)
    model.inputs["torque"] = 2.0
    found = model.trim(model.state(q=0.1), free_states=["q"], steady=["u"])
    # torque = m g L sin q at rest
    assert found.x[0] == pytest.approx(np.arcsin(2.0 / (1.3 * 9.81 * 0.7)), rel=1e-12)
    assert found.residual <= 1e-10 and found.iterations > 0
    assert np.max(np.abs(model.derivatives(0.0, found.x))) < 1e-10
    # The torque that holds q = 0.5, found by freeing the input instead.
    held = model.trim(model.state(q=0.5), free_states=[], free_inputs=["torque"], steady=["u"])
    assert held.inputs["torque"] == pytest.approx(1.3 * 9.81 * 0.7 * np.sin(0.5), rel=1e-12)
    assert model.inputs["torque"] == held.inputs["torque"]
    with pytest.raises(KeyError, match="state 'qq'"):
        model.trim(free_states=["qq"], steady=["u"])
    with pytest.raises(autosim.SimulationError):
        model.trim(model.state(q=0.0), free_states=["u"], steady=["u"])


def test_a_pickled_model_is_the_same_model_in_another_process(load_model: Load, tmp_path) -> None:  # type: ignore[no-untyped-def]
    import pickle
    import subprocess
    import sys

    model = load_model(PENDULUM)
    model.parameters["L"] = 1.7
    model.inputs["torque"] = 0.25
    x = model.state(q=0.8, u=-0.3)
    (tmp_path / "model.pickle").write_bytes(pickle.dumps(model))
    script = (
        "import pickle, sys\n"
        "model = pickle.loads(open(sys.argv[1], 'rb').read())\n"
        "print(model.parameters['L'], model.inputs['torque'], *model.derivatives(0.0, [0.8, -0.3]))\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", script, str(tmp_path / "model.pickle")], capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr
    values = [float(v) for v in run.stdout.split()]
    assert values[:2] == [1.7, 0.25]
    assert values[2:] == list(model.derivatives(0.0, x))


def test_a_misspelled_load_option_is_named_with_the_fix(repo: Path) -> None:
    with pytest.raises(
        TypeError,
        match=r"load\(\) got an unexpected keyword argument 'linearise'; did you mean 'linearize'\?",
    ):
        autosim.load(repo / PENDULUM, linearise=True)


def test_t_end_must_be_after_t0(load_model: Load) -> None:
    model = load_model(PENDULUM)
    for t_end in (1.0, 0.5):
        with pytest.raises(ValueError, match=r"t_end \(.*\) must be finite and after t0 \(1.0\)"):
            model.simulate(t_end, t0=1.0)


def test_an_input_table_that_is_not_finite_is_refused_naming_row_and_input(load_model: Load) -> None:
    model = load_model(PENDULUM)
    with pytest.raises(
        ValueError, match=r"input table's values row 1 is not finite in input 'torque' \(#0\): nan"
    ):
        model.simulate(1.0, inputs=([0.0, 1.0], np.array([[1.0], [np.nan]])))
    with pytest.raises(ValueError, match=r"row 2 is not finite in input 'torque'"):
        model.simulate(1.0, inputs=([0.0, 0.5, 1.0], [0.0, 1.0, np.inf]))
    with pytest.raises(ValueError, match=r"input table's time #1 is not finite: nan"):
        model.simulate(1.0, inputs=([0.0, np.nan], np.ones((2, 1))))


def test_a_state_that_is_not_finite_is_refused_naming_the_state(load_model: Load) -> None:
    model = load_model(PENDULUM)
    x = np.array([0.3, np.nan])
    for call in (
        lambda: model.derivatives(0.0, x),
        lambda: model.outputs(0.0, x),
        lambda: model.linearize(0.0, x),
        lambda: model.mass_matrix(0.0, x),
        lambda: model.forcing(0.0, x),
        lambda: model.assemble(x),
        lambda: model.trim(x, free_states=["q"], steady=["u"]),
    ):
        with pytest.raises(ValueError, match=r"^x is not finite in state 'u' \(#1\): nan$"):
            call()
    with pytest.raises(ValueError, match=r"^x0 is not finite in state 'u' \(#1\): nan$"):
        model.simulate(1.0, x)
    rows = np.zeros((4, 2))
    rows[2, 0] = np.inf
    with pytest.raises(ValueError, match=r"^x row 2 is not finite in state 'q' \(#0\): inf$"):
        model.derivatives(0.0, rows)
    inputs = np.zeros((4, 1))
    inputs[3, 0] = np.nan
    with pytest.raises(ValueError, match=r"^u row 3 is not finite in input 'torque' \(#0\): nan$"):
        model.outputs(0.0, np.zeros((4, 2)), inputs)


def test_a_misspelling_far_from_every_name_finds_the_doc_that_names_it(load_model: Load) -> None:
    model = load_model(PENDULUM)
    with pytest.raises(KeyError, match=r"'Lenght' is not one .*; did you mean 'L' \('Rod length.'\)\?"):
        model.parameters["Lenght"] = 2.0
    with pytest.raises(KeyError) as nothing_close:
        model.parameters["xyzzy"]
    assert (
        str(nothing_close.value)
        == "\"parameter 'xyzzy' is not one of the model's parameters ['m', 'L', 'g']\""
    )


SPRING = """
model Spring;
parameters { m = 2 [kg], k = 8 [N/m] }
input force [N];
body Cart { translate: 1, q: [x], u: [v], mass: m }
force spring { on: Cart, along: n1, magnitude: -k*x + force }
output pull [N] = -k*x;
"""


def test_a_sampled_controller_matches_the_exact_zero_order_hold() -> None:
    """A state feedback sampled every 50 ms on a mass and spring: at the
    sample instants the state follows the exact discretization
    ``z⁺ = Φ z + Γ u`` (``Φ``, ``Γ`` from the matrix exponential, SciPy),
    whatever the method; the controller runs once per sample, at t0 and
    every period, and sees the state and outputs there."""
    linalg = pytest.importorskip("scipy.linalg")
    model = autosim.loads(SPRING, quiet=True)
    m, k, period, gains = 2.0, 8.0, 0.05, np.array([3.0, 1.5])
    calls: list[tuple[float, float]] = []

    def controller(t: float, x: np.ndarray, y: np.ndarray) -> float:
        calls.append((t, y[0] + k * x[0]))  # the output is -k x
        return float(-gains @ x)

    a = np.array([[0.0, 1.0, 0.0], [-k / m, 0.0, 1.0 / m], [0.0, 0.0, 0.0]])
    step = linalg.expm(a * period)
    z = np.array([0.3, 0.0])
    exact = [z]
    for _ in range(40):
        z = step[:2, :2] @ z + step[:2, 2] * float(-gains @ z)
        exact.append(z)
    samples = np.arange(41) * period
    for method, options in [("dopri", {"rtol": 1e-12, "atol": 1e-14}), ("rk4", {"h": 1e-3})]:
        calls.clear()
        run = model.simulate(
            2.0, [0.3, 0.0], t_eval=samples, controller=controller, period=period, method=method, **options
        )
        assert np.max(np.abs(run.x - np.array(exact))) < 1e-9, method
        assert np.allclose([t for t, _ in calls], samples, rtol=0, atol=1e-12), method
        assert max(abs(seen) for _, seen in calls) < 1e-12, "the outputs are the state's"
        # The inputs reported at a sample instant are the new ones.
        assert np.allclose(run["force"], -(run.x @ gains), rtol=0, atol=1e-12), method


def test_a_controller_is_checked_before_the_run() -> None:
    model = autosim.loads(SPRING, quiet=True)
    with pytest.raises(ValueError, match="must take \\(t, x, y\\)"):
        model.simulate(1.0, controller=lambda t, x: 0.0, period=0.1)
    with pytest.raises(ValueError, match="sample period"):
        model.simulate(1.0, controller=lambda t, x, y: 0.0)
    with pytest.raises(ValueError, match="give controller= too"):
        model.simulate(1.0, period=0.1)
    with pytest.raises(ValueError, match="leave inputs= out"):
        model.simulate(1.0, controller=lambda t, x, y: 0.0, period=0.1, inputs=1.0)
    with pytest.raises(ValueError, match="the controller returned 2 values at t = 0"):
        model.simulate(1.0, controller=lambda t, x, y: [0.0, 1.0], period=0.1)

    def broken(t: float, x: np.ndarray, y: np.ndarray) -> float:
        if t > 0.25:
            raise RuntimeError("controller fault")
        return 0.0

    with pytest.raises(RuntimeError, match="controller fault"):
        model.simulate(1.0, controller=broken, period=0.1)


def test_a_run_steps_onto_its_input_tables_times() -> None:
    """Dormand–Prince across a table's kink loses accuracy: the run lands
    on every time of the table, so two output times give the end that a
    dense output grid containing the kinks gives."""
    model = autosim.loads(SPRING, quiet=True)
    table = ([0.0, 0.3, 0.300001, 1.1, 1.4], [0.0, 0.0, 5.0, 5.0, -2.0])
    ends = [
        model.simulate(2.0, [0.1, 0.0], t_eval=t_eval, inputs=table, rtol=1e-10, atol=1e-12)
        for t_eval in ([0.0, 2.0], np.linspace(0.0, 2.0, 2001), [0.0, 0.3, 0.300001, 1.1, 1.4, 2.0])
    ]
    assert len(ends[0].t) == 2 and ends[0].t[-1] == 2.0
    for run in ends[1:]:
        assert np.max(np.abs(run.x[-1] - ends[0].x[-1])) < 1e-9, (run.x[-1], ends[0].x[-1])
    with pytest.raises(ValueError, match=r"time #2 \(1.0\) is not after time #1 \(1.0\)"):
        model.simulate(2.0, inputs=([0.0, 1.0, 1.0], [0.0, 0.0, 1.0]))
