"""Simulation results: the time history as NumPy arrays with names (states,
outputs, inputs, discrete variables), the events that fired, and a pandas
DataFrame when pandas is installed."""

from __future__ import annotations

import inspect
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ._values import check_finite, unknown_name

if TYPE_CHECKING:  # pragma: no cover
    from ._model import Inputs, Model

METHODS = ("dopri", "rk4", "sdirk3", "abm4", "abm2", "heun", "euler")


@dataclass(frozen=True)
class EventLog:
    """The events of one run in the order they fired: ``t`` (k,), ``name``
    (k names), the state just before and just after each event's action
    (``x_before``, ``x_after``, (k, n_states)) and the discrete variables
    (``d_before``, ``d_after``, (k, n_discrete)); ``declared``, the names of
    the model's events (fired or not)."""

    t: np.ndarray
    name: tuple[str, ...]
    x_before: np.ndarray
    x_after: np.ndarray
    d_before: np.ndarray
    d_after: np.ndarray
    declared: tuple[str, ...] = ()

    def __len__(self) -> int:
        return len(self.name)

    def only(self, name: str) -> EventLog:
        """The events named ``name`` (in the order they fired; none if it
        did not fire). ``KeyError`` if the model has no event of that name."""
        if self.declared and name not in self.declared:
            raise unknown_name("event", name, self.declared)
        keep = np.array([n == name for n in self.name], dtype=bool).reshape(-1)
        return EventLog(
            self.t[keep],
            tuple(n for n in self.name if n == name),
            self.x_before[keep],
            self.x_after[keep],
            self.d_before[keep],
            self.d_after[keep],
            self.declared,
        )


@dataclass(frozen=True)
class Simulation:
    """The time history of one run: ``t`` (n,), states ``x`` (n, n_states),
    outputs ``y`` (n, n_outputs), inputs ``u`` (n, n_inputs) and discrete
    variables ``d`` (n, n_discrete), the events that fired (:attr:`events`)
    and the integrator's counts. ``sim["name"]`` is the column of a state,
    output, input or discrete variable by name."""

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    u: np.ndarray
    state_names: tuple[str, ...]
    output_names: tuple[str, ...]
    input_names: tuple[str, ...]
    method: str
    #: Accepted steps.
    steps: int
    #: Trial steps rejected by error control (``dopri``).
    rejected_steps: int
    #: Derivative evaluations.
    evaluations: int
    #: Discrete variables at the output times (n, n_discrete).
    d: np.ndarray
    discrete_names: tuple[str, ...]
    #: The events that fired, in order.
    events: EventLog
    #: The terminal event that ended the run before ``t_end`` (its name),
    #: or ``None``; the last output is then at its instant.
    stopped_by: str | None = None

    def _columns(self) -> tuple[tuple[tuple[str, ...], np.ndarray], ...]:
        return (
            (self.state_names, self.x),
            (self.output_names, self.y),
            (self.input_names, self.u),
            (self.discrete_names, self.d),
        )

    def __getitem__(self, name: str) -> np.ndarray:
        for names, values in self._columns():
            if name in names:
                return values[:, names.index(name)]
        known = list(self.state_names + self.output_names + self.input_names + self.discrete_names)
        from ._values import unknown_name

        raise unknown_name("column", name, known)

    @property
    def final_state(self) -> np.ndarray:
        """The state at the last output time."""
        return self.x[-1].copy()

    def to_pandas(self) -> Any:
        """A pandas DataFrame indexed by time ``t`` with a column per state,
        output, input and discrete variable (needs pandas)."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("to_pandas needs pandas: pip install pandas") from None
        columns: dict[str, np.ndarray] = {}
        for names, values in self._columns():
            for k, n in enumerate(names):
                columns.setdefault(n, values[:, k])
        return pd.DataFrame(columns, index=pd.Index(self.t, name="t"))


def _input_table(inputs: tuple[Any, Any], names: tuple[str, ...]) -> tuple[np.ndarray, np.ndarray]:
    """The input table ``(times, values)`` as arrays (a vector of values is
    one column), every time and value finite (``ValueError`` naming the
    row and the input)."""
    tt = np.ascontiguousarray(inputs[0], dtype=np.float64)
    uu = np.ascontiguousarray(inputs[1], dtype=np.float64)
    if uu.ndim == 1:
        uu = uu.reshape(-1, 1)
    bad = np.flatnonzero(~np.isfinite(tt))
    if bad.size:
        raise ValueError(f"the input table's time #{bad[0]} is not finite: {tt.flat[bad[0]]}")
    back = np.flatnonzero(np.diff(tt) <= 0) if tt.ndim == 1 else np.array([], dtype=int)
    if back.size:
        k = int(back[0]) + 1
        raise ValueError(
            f"the input table's time #{k} ({tt[k]}) is not after time #{k - 1} ({tt[k - 1]}): "
            "times must increase (a step is two times a short interval apart, e.g. 1e-6 s: "
            "the run steps onto both)"
        )
    if uu.ndim == 2:
        check_finite(uu, "the input table's values", names, "input")
    return tt, uu


def _landing(times: np.ndarray, kinks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The output times with an input table's inner times added, so that
    the integrator steps onto the table's kinks (a step of an adaptive
    method across one loses accuracy, a fixed step's stages straddle it),
    and which of them were asked for."""
    extra = np.setdiff1d(kinks, times)
    merged = np.concatenate([times, extra])
    order = np.argsort(merged, kind="stable")
    asked = np.concatenate([np.ones(len(times), dtype=bool), np.zeros(len(extra), dtype=bool)])
    return np.ascontiguousarray(merged[order]), asked[order]


def _requested_rows(run: dict[str, Any], requested: np.ndarray) -> dict[str, Any]:
    """The run's rows at the times asked for (and, after a terminal event,
    its last row at the event's instant)."""
    n = len(run["t"])
    keep = requested[:n].copy()
    if run["terminal_event"] is not None and n:
        keep[n - 1] = True
    rows = {name: run[name][keep] for name in ("t", "x", "y", "d")}
    rows["u"] = run["u"][keep] if len(run["u"]) == n else run["u"]
    return {**run, **rows}


def _output_times(t0: float, t_end: float, t_eval: Any) -> np.ndarray:
    if t_eval is None:
        return np.linspace(t0, t_end, 1001)
    times = np.ascontiguousarray(np.atleast_1d(np.asarray(t_eval, dtype=np.float64)))
    if times.ndim != 1:
        raise ValueError("t_eval must be one-dimensional")
    if times.size and (np.any(np.diff(times) < 0) or times[0] < t0 or times[-1] > t_end):
        raise ValueError(f"t_eval must be sorted and within [t0, t_end] = [{t0}, {t_end}]")
    return times


#: How events are located: ``(event_tolerance, event_samples, zeno_events,
#: zeno_interval)``, as :meth:`Model.simulate` and studies take them.
EventSettings = tuple[float, int, int, float]


def event_settings(
    event_tolerance: float, event_samples: int, zeno_events: int, zeno_interval: float
) -> EventSettings:
    """The event settings, checked (``ValueError`` naming a wrong one)."""
    for name, value in (("event_tolerance", event_tolerance), ("zeno_interval", zeno_interval)):
        if not (value >= 0 and np.isfinite(value)):
            raise ValueError(f"{name} must be finite and not negative, not {value}")
    if not 0 <= event_samples <= 1000:
        raise ValueError(f"event_samples must be in 0..=1000, not {event_samples}")
    if zeno_events < 1:
        raise ValueError(f"zeno_events must be at least 1, not {zeno_events}")
    return (float(event_tolerance), int(event_samples), int(zeno_events), float(zeno_interval))


def simulate(
    model: Model,
    t_end: float,
    x0: Any,
    t0: float,
    method: str,
    rtol: float,
    atol: float,
    h: float | None,
    t_eval: Any,
    inputs: Inputs,
    max_steps: int,
    discrete0: Any = None,
    events: EventSettings = (0.0, 4, 100, 0.0),
    controller: Any = None,
    period: float | None = None,
) -> Simulation:
    """:meth:`Model.simulate` (see there)."""
    if method not in METHODS:
        raise ValueError(f"method {method!r} is not one of {', '.join(METHODS)}")
    t0, t_end = float(t0), float(t_end)
    if not (np.isfinite(t0) and np.isfinite(t_end) and t_end > t0):
        raise ValueError(f"t_end ({t_end}) must be finite and after t0 ({t0})")
    step = 1e-3 if h is None else float(h)
    if not (step > 0 and np.isfinite(step)):
        raise ValueError(f"h must be positive and finite, not {h}")
    if not (rtol > 0 and atol >= 0):
        raise ValueError("rtol must be positive and atol not negative")
    xv = model.initial_state() if x0 is None else model._state(x0, "x0")
    times = _output_times(t0, t_end, t_eval)
    d0 = None if discrete0 is None else model.discrete_vector(discrete0, "discrete0")
    table = None
    function = None
    requested = None
    native = model._native
    saved = native.inputs()
    sampled = _sampled(controller, period, inputs)
    if callable(inputs):
        _check_time_only(inputs)
        function = inputs
    elif isinstance(inputs, tuple) and len(inputs) == 2:
        table = _input_table(inputs, model.input_names)
        times, requested = _landing(times, table[0][(table[0] > t0) & (table[0] < t_end)])
    elif inputs is not None:
        model.set_inputs(inputs if isinstance(inputs, Mapping) else np.atleast_1d(inputs))
    try:
        run = native.simulate(
            method,
            t0,
            t_end,
            step,
            float(rtol),
            float(atol),
            times,
            xv,
            int(max_steps),
            table,
            function,
            d0,
            events,
            sampled,
        )
    finally:
        if inputs is not None:
            native.set_inputs(saved)
    if requested is not None:
        run = _requested_rows(run, requested)
    u = run["u"]
    if u.shape[1] != len(model.input_names):
        u = np.full((len(run["t"]), len(model.input_names)), np.nan)
    return Simulation(
        t=run["t"],
        x=run["x"],
        y=run["y"],
        u=u,
        state_names=model.state_names,
        output_names=model.output_names,
        input_names=model.input_names,
        method=method,
        steps=int(run["steps"]),
        rejected_steps=int(run["rejected_steps"]),
        evaluations=int(run["evaluations"]),
        d=run["d"],
        discrete_names=model.discrete_names,
        events=_event_log(run["events"], model),
        stopped_by=None if run["terminal_event"] is None else model.events[run["terminal_event"]].name,
    )


def _event_log(log: Mapping[str, Any], model: Model) -> EventLog:
    names = tuple(model.events[k].name for k in log["index"])
    declared = tuple(e.name for e in model.events)
    return EventLog(
        log["t"], names, log["x_before"], log["x_after"], log["d_before"], log["d_after"], declared
    )


def _check_time_only(function: Any) -> None:
    """A ValueError if ``function`` cannot be called with the time alone
    (``lambda t, x: ...`` is a state feedback, which an input cannot be)."""
    signature = _refused_signature(function, (0.0,))
    if signature is not None:
        raise ValueError(
            f"the inputs callable must take the time alone, u(t); its signature is {signature}. "
            "A feedback of the state belongs in the model (the gains as parameters), or in "
            "a sampled controller: simulate(..., controller=f, period=dt) with f(t, x, y)"
        )


def _refused_signature(function: Any, args: tuple[Any, ...]) -> str | None:
    """The signature of ``function`` if it cannot be called with ``args``
    (``None`` if it can, or has no signature to read, as some builtins)."""
    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):
        return None
    try:
        signature.bind(*args)
    except TypeError:
        return str(signature)
    return None


def _sampled(controller: Any, period: float | None, inputs: Any) -> tuple[Any, float] | None:
    """``(controller, period)`` checked for the native run, or ``None``
    without a controller; a ValueError naming what is wrong."""
    if controller is None:
        if period is not None:
            raise ValueError("period is the sample period of a controller: give controller= too")
        return None
    if not callable(controller):
        raise ValueError(f"controller must be callable as controller(t, x, y), not {controller!r}")
    if period is None or not (float(period) > 0 and np.isfinite(float(period))):
        raise ValueError(f"a controller needs its sample period: period= positive and finite, not {period}")
    if inputs is not None:
        raise ValueError("a controller sets the inputs from the start: leave inputs= out")
    signature = _refused_signature(controller, (0.0, None, None))
    if signature is not None:
        raise ValueError(
            "the controller must take (t, x, y): the time, the state and the outputs; "
            f"its signature is {signature}"
        )
    return controller, float(period)
