"""The object a loaded model is: :class:`Model`."""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from types import ModuleType
from typing import Any, Callable, NamedTuple, Union

import numpy as np

from ._interface import Event, Interface, Quantity
from ._linear import LinearModel
from ._simulation import Simulation, event_settings, simulate
from ._values import ArrayLike, NamedValues, as_vector, check_finite, unknown_name


class TrimResult(NamedTuple):
    """What :meth:`Model.trim` found."""

    #: The trimmed state.
    x: np.ndarray
    #: The inputs after the trim (by name).
    inputs: dict[str, float]
    #: Newton iterations.
    iterations: int
    #: The largest steady derivative at the end.
    residual: float


Inputs = Union[
    None, float, ArrayLike, Mapping[str, float], tuple[ArrayLike, ArrayLike], Callable[[float], Any]
]

#: Discrete values: a mapping by name (the others at their initial values)
#: or a vector in declaration order.
Discrete = Union[None, Mapping[str, float], ArrayLike]


class Model:
    """A compiled autosim model (from :func:`autosim.load` or
    :func:`autosim.loads`).

    States, parameters, inputs, outputs and discrete variables are named,
    with units (:attr:`states`, :attr:`parameters`, :attr:`inputs`,
    :attr:`outputs_info`, :attr:`discrete`); :attr:`events` lists the
    model's events.
    Every method takes NumPy arrays (or sequences) of float64; states are
    ordered as :attr:`state_names` says: the generalized coordinates, then
    the independent speeds, then the model's extra states.

    A model object is not thread-safe: give each thread its own
    (:meth:`copy`). The vectorized calls release the GIL.
    """

    def __init__(
        self,
        native: Any,
        interface: Interface,
        source: Path | None = None,
        origin: tuple[Any, ...] | None = None,
    ) -> None:
        self._native = native
        #: How to make this model again in another process (pickling):
        #: ``("text", text, path, options)`` or ``("module", module_name)``.
        self._origin = origin
        self.interface = interface
        #: The file the model was loaded from (``None`` for text).
        self.source = source
        self.parameters = NamedValues(
            "parameter", interface.parameters, native.parameters, native.set_parameters, True
        )
        self.inputs = NamedValues("input", interface.inputs, native.inputs, native.set_inputs, True)
        self._nx = len(interface.states)
        self._state_index = {s.name: k for k, s in enumerate(interface.states)}

    @classmethod
    def _from_module(
        cls, module: ModuleType, source: Path | None = None, origin: tuple[Any, ...] | None = None
    ) -> Model:
        interface = Interface.from_json(module.INTERFACE)
        doc = _model_doc(interface)
        kind = type(interface.name, (cls,), {"__doc__": doc, "__module__": "autosim.models"})
        if origin is None:
            package = module.__name__.rpartition(".")[0]
            origin = ("module", package) if package else None
        return kind(module.prototype.copy(), interface, source, origin)

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickles as the recipe to make the model again (its text and load
        options, or the package of its wheel) with its parameters and
        inputs: a process that unpickles it loads the model from its cache
        (building it if the cache lacks it) or imports the wheel, so Dask
        or multiprocessing workers get the same model."""
        if self._origin is None:
            raise TypeError(
                f"{self.name} cannot be pickled: it was not made by autosim.load, loads or a model wheel"
            )
        return (_rebuild, (self._origin, self.parameters.vector, self.inputs.vector, self.source))

    # ----- names ---------------------------------------------------------

    @property
    def name(self) -> str:
        """The model's name as written in its source."""
        return self.interface.name

    @property
    def states(self) -> tuple[Quantity, ...]:
        """The states (name, unit, kind) in state-vector order."""
        return self.interface.states

    @property
    def state_names(self) -> tuple[str, ...]:
        """Names of the states, in state-vector order."""
        return tuple(s.name for s in self.interface.states)

    @property
    def state_units(self) -> tuple[str, ...]:
        """Units of the states."""
        return tuple(s.unit for s in self.interface.states)

    @property
    def outputs_info(self) -> tuple[Quantity, ...]:
        """The outputs (name, unit, doc)."""
        return self.interface.outputs

    @property
    def output_names(self) -> tuple[str, ...]:
        """Names of the outputs."""
        return tuple(o.name for o in self.interface.outputs)

    @property
    def output_units(self) -> tuple[str, ...]:
        """Units of the outputs."""
        return tuple(o.unit for o in self.interface.outputs)

    @property
    def parameter_names(self) -> tuple[str, ...]:
        """Names of the parameters, in declaration order."""
        return self.parameters.names

    @property
    def input_names(self) -> tuple[str, ...]:
        """Names of the inputs, in declaration order."""
        return self.inputs.names

    @property
    def n_states(self) -> int:
        """Length of the state vector."""
        return self._nx

    @property
    def n_speeds(self) -> int:
        """Number of independent generalized speeds (the mass matrix's size)."""
        return self.interface.n_speeds

    @property
    def discrete(self) -> tuple[Quantity, ...]:
        """The discrete variables (name, unit, initial value as ``default``,
        doc), in declaration order: the modes event actions set."""
        return self.interface.discrete

    @property
    def discrete_names(self) -> tuple[str, ...]:
        """Names of the discrete variables, in declaration order."""
        return tuple(d.name for d in self.interface.discrete)

    @property
    def discrete_units(self) -> tuple[str, ...]:
        """Units of the discrete variables."""
        return tuple(d.unit for d in self.interface.discrete)

    @property
    def events(self) -> tuple[Event, ...]:
        """The events (name, direction, whether they stop the run, doc), in
        declaration order."""
        return self.interface.events

    def initial_discrete(self) -> np.ndarray:
        """The discrete variables' initial values written in the model (what
        the evaluations read when their ``discrete`` argument is not given,
        and where :meth:`simulate` starts them unless told otherwise)."""
        return np.array(self._native.discrete())

    def discrete_vector(self, values: Mapping[str, float] | ArrayLike, what: str = "discrete") -> np.ndarray:
        """A vector of discrete values: a mapping by name (the others at
        their initial values) or a vector in declaration order (``what``
        names the argument in the error for a wrong length)."""
        if isinstance(values, Mapping):
            d = self.initial_discrete()
            names = self.discrete_names
            for name, value in values.items():
                if name not in names:
                    raise unknown_name("discrete variable", name, names)
                d[names.index(name)] = float(value)
            return d
        return as_vector(values, len(self.interface.discrete), what)

    @contextmanager
    def _inputs_set(self, u: Inputs) -> Iterator[None]:
        """The inputs at ``u`` inside the block (``None``: unchanged), the
        model's own again after it."""
        if u is None:
            yield
            return
        held = self._native.inputs()
        self.set_inputs(u)
        try:
            yield
        finally:
            self._native.set_inputs(held)

    @contextmanager
    def _discrete_set(self, values: Discrete) -> Iterator[None]:
        """The discrete variables at ``values`` inside the block (``None``:
        unchanged), their initial values again after it."""
        if values is None:
            yield
            return
        initial = self._native.discrete()
        self._native.set_discrete(self.discrete_vector(values))
        try:
            yield
        finally:
            self._native.set_discrete(initial)

    def _state(self, x: ArrayLike, what: str = "x") -> np.ndarray:
        """``x`` as a state vector: its length and every entry finite
        checked (``ValueError`` naming ``what`` and the state)."""
        xv = as_vector(x, self._nx, what)
        check_finite(xv, what, self.state_names, "state")
        return xv

    def state_index(self, name: str) -> int:
        """Position of state ``name`` in the state vector."""
        if name not in self._state_index:
            raise unknown_name("state", name, self.state_names)
        return self._state_index[name]

    def state(self, values: Mapping[str, float] | None = None, **by_name: float) -> np.ndarray:
        """A state vector: the model's initial state with the named entries
        replaced (``model.state(q=0.3)``)."""
        x = self.initial_state()
        for name, value in dict(values or {}, **by_name).items():
            x[self.state_index(name)] = float(value)
        return x

    def initial_state(self) -> np.ndarray:
        """The initial state written in the model (zeros where none)."""
        return np.array(self._native.initial_state())

    def copy(self) -> Model:
        """An independent copy (same parameters and inputs), e.g. for another
        thread."""
        return type(self)(self._native.copy(), self.interface, self.source, self._origin)

    # ----- evaluation ----------------------------------------------------

    def set_inputs(self, u: Inputs) -> None:
        """Sets the inputs: a mapping by name, a vector, or a number (for a
        model with one input)."""
        if u is None:
            return
        if isinstance(u, Mapping):
            self.inputs.set(u)
        else:
            self.inputs.vector = np.atleast_1d(np.asarray(u, dtype=np.float64))

    def _rows(self, t: Any, x: Any, u: Any, outputs: bool) -> np.ndarray:
        xs = np.ascontiguousarray(x, dtype=np.float64)
        if xs.ndim != 2 or xs.shape[1] != self._nx:
            raise ValueError(f"x must have shape (n, {self._nx}), not {xs.shape}")
        check_finite(xs, "x", self.state_names, "state")
        ts = np.ascontiguousarray(np.atleast_1d(np.asarray(t, dtype=np.float64)))
        us = None
        if u is not None:
            us = np.ascontiguousarray(u, dtype=np.float64)
            if us.ndim != 2:
                raise ValueError(f"u must have shape (n, {len(self.input_names)})")
            check_finite(us, "u", self.input_names, "input")
        return self._native.many(ts, xs, us, outputs)

    def derivatives(
        self, t: float | ArrayLike, x: ArrayLike, u: Any = None, *, discrete: Discrete = None
    ) -> np.ndarray:
        """``dx/dt`` at time ``t`` and state ``x``.

        ``x`` of shape ``(n_states,)`` gives one derivative; of shape
        ``(n, n_states)`` one per row, computed in one call with the GIL
        released (``t`` then one time or one per row, ``u`` one input row
        for all or one per row). ``u`` (a vector, mapping or number) gives
        the inputs for this call only (the model's own are unchanged, as
        for ``discrete``); rows of ``u`` apply to their row only. With one time and no rows of ``u`` the rows go
        through the model's ``derivatives_batch``: a model whose settings
        have ``lanes: true`` computes four rows per call in vector
        instructions, with the same bits as one call per row; with a time
        or inputs per row, such a model computes four rows per call too,
        each at its own time with its own inputs. A failing row raises
        :class:`SimulationError` naming the first such row. ``discrete``
        (a mapping by name, the others at their initial values, or a
        vector) gives the discrete variables for this call only; without
        it the equations read their initial values.
        """
        return self._evaluate(t, x, u, discrete, outputs=False)

    def outputs(
        self, t: float | ArrayLike, x: ArrayLike, u: Any = None, *, discrete: Discrete = None
    ) -> np.ndarray:
        """The outputs at ``(t, x)`` (rows of a 2-D ``x``, ``u`` and
        ``discrete`` as in :meth:`derivatives`)."""
        return self._evaluate(t, x, u, discrete, outputs=True)

    def _evaluate(self, t: Any, x: ArrayLike, u: Any, discrete: Discrete, outputs: bool) -> np.ndarray:
        if u is None and discrete is None and type(x) is np.ndarray and x.shape == (self._nx,):
            # One state as a vector, nothing set for the call: straight to
            # the native call (it checks that every entry is finite).
            one = self._native.outputs if outputs else self._native.derivatives
            return one(float(t), x if x.dtype == np.float64 else x.astype(np.float64))
        xs = np.asarray(x, dtype=np.float64)
        # Rows of `u` go to the native loop; one input vector holds for the call.
        u_rows = xs.ndim == 2 and u is not None and not isinstance(u, Mapping) and np.ndim(u) == 2
        with self._discrete_set(discrete), self._inputs_set(None if u_rows else u):
            if xs.ndim == 2:
                return self._rows(t, xs, u if u_rows else None, outputs)
            one = self._native.outputs if outputs else self._native.derivatives
            return one(float(t), self._state(xs))  # type: ignore[arg-type]

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """``dx/dt`` with the signature of :func:`scipy.integrate.solve_ivp`'s
        ``fun(t, y)`` (the current inputs held); with ``vectorized=True``,
        ``y`` of shape ``(n_states, k)`` gives ``k`` columns."""
        if y.ndim == 1:
            return self._native.derivatives(t, y)
        return self._native.many(np.array([float(t)]), np.ascontiguousarray(y.T), None, False).T

    def jacobian(self, t: float, y: np.ndarray) -> np.ndarray:
        """``∂(dx/dt)/∂x`` from the symbolic linearization, with the
        signature of ``solve_ivp``'s ``jac(t, y)`` (for ``Radau``, ``BDF``,
        ``LSODA``). Models with position constraints have no Jacobian in
        the full state (their linearization is in the independent states)."""
        if self.interface.dependent_coordinates:
            raise ValueError(
                f"{self.name} has position constraints: its linearization is in the "
                "independent states only; use linearize()"
            )
        return self.linearize(t, y).A

    def mass_matrix(self, t: float, x: ArrayLike, *, discrete: Discrete = None) -> np.ndarray:
        """The mass matrix ``M(q)`` of ``M du/dt = f`` (``n_speeds`` square;
        for constrained models in the independent speeds' equations as
        generated; ``discrete`` as in :meth:`derivatives`)."""
        with self._discrete_set(discrete):
            return self._native.mass_matrix(float(t), self._state(x))

    def forcing(self, t: float, x: ArrayLike, u: Any = None, *, discrete: Discrete = None) -> np.ndarray:
        """The forcing vector ``f(q, u, t)`` of ``M du/dt = f`` (with inputs
        ``u`` for this call, or the current inputs; ``discrete`` as in
        :meth:`derivatives`)."""
        with self._discrete_set(discrete), self._inputs_set(u):
            return self._native.forcing(float(t), self._state(x))

    def linearize(
        self, t: float = 0.0, x: ArrayLike | None = None, u: Any = None, *, discrete: Discrete = None
    ) -> LinearModel:
        """The linear model ``dx/dt ≈ A δx + B δu``, ``y ≈ C δx + D δu`` about
        ``(t, x, u)`` (defaults: time 0, the initial state, the current
        inputs; ``u`` holds for this call only), from symbolic derivatives
        of the equations, with the
        discrete variables at ``discrete`` (as in :meth:`derivatives`;
        default their initial values): a model with modes is linearized
        in the mode given. For models with
        position constraints the states are the independent ones
        (:attr:`LinearModel.state_names`). Models compiled with
        ``linearize=False`` raise ``ValueError``."""
        linear = self.interface.linear_states
        if linear is None:
            raise ValueError(f"{self.name} was loaded without its linearization: load it with linearize=True")
        xv = self.initial_state() if x is None else self._state(x)
        with self._discrete_set(discrete), self._inputs_set(u):
            a, b, c, d = self._native.linearize(float(t), xv, len(linear))
        names = self.state_names
        return LinearModel(
            a,
            b,
            c,
            d,
            tuple(names[k] for k in linear),
            tuple(self.state_units[k] for k in linear),
            self.input_names,
            self.output_names,
        )

    def modes(
        self, t: float = 0.0, x: ArrayLike | None = None, u: Any = None, *, discrete: Discrete = None
    ) -> Any:
        """Eigenvalues and eigenvectors of ``A`` at ``(t, x, u)``
        (:meth:`LinearModel.modes`; ``discrete`` as in :meth:`linearize`)."""
        return self.linearize(t, x, u, discrete=discrete).modes()

    def trim(
        self,
        x: ArrayLike | None = None,
        *,
        free_states: Sequence[str],
        steady: Sequence[str],
        free_inputs: Sequence[str] = (),
        t: float = 0.0,
        tolerance: float = 1e-10,
        max_iterations: int = 50,
        max_step: float = 1.0,
        discrete: Discrete = None,
    ) -> TrimResult:
        """Trims the model (the runtime's damped Newton on the symbolic
        linearization, as SD/FAST's ``sdstatic``/``sdsteady``): from ``x``
        (default: the initial state) and the current inputs, changes the
        states named in ``free_states`` and the inputs in ``free_inputs``
        until the time derivatives of the states in ``steady`` vanish
        (to ``tolerance``); everything else is held. Static equilibrium:
        the coordinates free, the speeds steady. Each Newton step moves an
        unknown by at most ``max_step`` times ``max(1, |value|)``. The model
        keeps the trimmed inputs. ``discrete`` gives the discrete variables
        (as in :meth:`derivatives`). Raises :class:`autosim.errors.SimulationError` naming the
        residuals when Newton's method does not converge or the free
        variables do not control the steady derivatives."""
        xv = self.initial_state() if x is None else self._state(x)
        for name in list(free_states) + list(steady):
            self.state_index(name)
        for name in free_inputs:
            if name not in self.input_names:
                raise unknown_name("input", name, self.input_names)
        with self._discrete_set(discrete):
            done = self._native.trim(
                float(t),
                xv,
                list(free_states),
                list(free_inputs),
                list(steady),
                float(tolerance),
                int(max_iterations),
                float(max_step),
            )
        if done is None:
            raise ValueError(f"{self.name} was loaded without its linearization: load it with linearize=True")
        trimmed, iterations, residual = done
        return TrimResult(trimmed, dict(self.inputs), int(iterations), float(residual))

    def assemble(self, x: ArrayLike | None = None, t: float = 0.0) -> np.ndarray:
        """``x`` (default: the initial state) with its dependent coordinates
        solved from the position constraints, the others held; unchanged for
        models without position constraints."""
        xv = self.initial_state() if x is None else self._state(x)
        return self._native.assemble(float(t), xv)

    @property
    def dependent_coordinates(self) -> tuple[str, ...]:
        """States solved from the position constraints (empty for trees)."""
        return tuple(self.state_names[k] for k in self.interface.dependent_coordinates)

    @property
    def independent_states(self) -> tuple[str, ...]:
        """States the integrators and the linear model carry freely: all but
        the dependent coordinates."""
        dep = set(self.interface.dependent_coordinates)
        return tuple(n for k, n in enumerate(self.state_names) if k not in dep)

    def simulate(
        self,
        t_end: float,
        x0: ArrayLike | None = None,
        *,
        t0: float = 0.0,
        method: str = "dopri",
        rtol: float = 1e-9,
        atol: float = 1e-12,
        h: float | None = None,
        t_eval: ArrayLike | None = None,
        inputs: Inputs = None,
        max_steps: int = 10_000_000,
        discrete0: Mapping[str, float] | ArrayLike | None = None,
        event_tolerance: float = 0.0,
        event_samples: int = 4,
        zeno_events: int = 100,
        zeno_interval: float = 0.0,
        controller: Callable[[float, np.ndarray, np.ndarray], Any] | None = None,
        period: float | None = None,
    ) -> Simulation:
        """Integrates from ``x0`` (default: the initial state) at ``t0`` to
        ``t_end`` with the Rust integrators, the GIL released.

        ``method``: ``"dopri"`` (Dormand–Prince 5(4), adaptive: ``rtol``,
        ``atol``, ``h`` its first trial step), ``"rk4"``, ``"heun"``,
        ``"euler"``, ``"abm4"``, ``"abm2"`` (fixed step ``h``), ``"sdirk3"``
        (stiff, fixed step ``h``). ``h`` defaults to 1e-3 s (fixed-step
        methods take the largest step not above ``h`` that divides each
        interval between output times). ``t_eval``: the output times
        (default: 1001 evenly spaced from ``t0`` to ``t_end``).
        ``inputs``: ``None`` holds the current inputs; a number, vector or
        mapping sets them for the run (the model's inputs are restored
        afterwards, as for the other forms); a pair ``(times, values)`` with
        ``values`` of shape ``(len(times), n_inputs)`` interpolates linearly
        in time (held beyond the ends); a callable ``u(t)`` returning the
        input vector is called at every evaluation (slow: it runs Python
        at every integrator stage). Models with position constraints are
        assembled first and projected after every step.

        ``controller`` with ``period``: a discrete-time controller
        ``controller(t, x, y)`` called at ``t0`` and every ``period`` after
        (never between, whatever the method) with the time, the state and
        the outputs, returning the inputs (a number for one input, or a
        vector in :attr:`input_names` order) held until the next sample,
        as a real controller's zero-order hold; the steps land on the
        sample instants, and the outputs reported at one already use its
        new inputs (``inputs`` must then be ``None``). A controller with
        states of its own keeps them itself (a closure or an object's
        ``__call__``).

        Events (models with ``event`` items) are located in every method, as
        the Rust run driver does: after each step the indicators are
        sampled on the step's interpolant (``event_samples`` interior
        points and the end), a crossing is located to ``event_tolerance``
        seconds (0: to the rounding of the time), the state moves there,
        the action runs and the integrator restarts. ``discrete0`` (a
        mapping by name or a vector) sets the discrete variables' initial
        values (default: the model's). The result lists the events
        (:attr:`Simulation.events`), the discrete variables at the output
        times, and the terminal event that ended the run
        (:attr:`Simulation.stopped_by`; the last output is at its instant).
        More than ``zeno_events`` events in a chain, each within
        ``zeno_interval`` seconds of the one before (0: a thousandth of the
        run), raise :class:`autosim.errors.ZenoError` naming the event.

        Raises :class:`autosim.errors.SimulationError` when the model or the
        integrator fails (the message names the time and the state), and
        ``ValueError`` for ``t_end`` not after ``t0`` or a state or input
        table value that is not finite. Ctrl-C stops the run within about
        0.1 s and raises ``KeyboardInterrupt``.
        """
        events = event_settings(event_tolerance, event_samples, zeno_events, zeno_interval)
        return simulate(
            self,
            t_end,
            x0,
            t0,
            method,
            rtol,
            atol,
            h,
            t_eval,
            inputs,
            max_steps,
            discrete0,
            events,
            controller,
            period,
        )

    def study(self, cases: Any, keep: Any, t_end: float, **settings: Any) -> Any:
        """A :class:`autosim.Study` of this model (its parameters and inputs
        as they are now): ``cases`` (:class:`autosim.Cases`), ``keep``
        (:class:`autosim.Keep`), ``t_end`` and the settings of
        :class:`autosim.Study` (``t0``, ``h``, ``output_interval``,
        ``method``, ``rtol``, ``atol``, ``max_steps``, ``event_tolerance``,
        ``event_samples``, ``zeno_events``, ``zeno_interval``). Run it with
        :meth:`autosim.Study.run`."""
        from ._study import Study

        return Study(self, cases, keep, t_end, **settings)

    def to_control(
        self, t: float = 0.0, x: ArrayLike | None = None, u: Any = None, *, discrete: Discrete = None
    ) -> Any:
        """The linear model as a python-control ``StateSpace`` (needs the
        ``control`` package; arguments as :meth:`linearize`)."""
        return self.linearize(t, x, u, discrete=discrete).to_control()

    def __repr__(self) -> str:
        return (
            f"<autosim model {self.name}: {self._nx} states, "
            f"{len(self.parameter_names)} parameters, {len(self.input_names)} inputs, "
            f"{len(self.output_names)} outputs>"
        )


def _rebuild(
    origin: tuple[Any, ...], parameters: np.ndarray, inputs: np.ndarray, source: Path | None
) -> Model:
    """A pickled model made again (see :meth:`Model.__reduce__`)."""
    if origin[0] == "text":
        from . import loads

        _, text, path, options = origin
        model = loads(text, path=path, quiet=True, **options)
    else:
        import importlib

        model = importlib.import_module(origin[1]).load()
    model.parameters.vector = parameters
    model.inputs.vector = inputs
    model.source = source
    return model


def _model_doc(interface: Interface) -> str:
    """The docstring ``help(model)`` shows: the model's docs and its states,
    parameters, inputs, outputs and discrete variables with units, and its
    events."""
    lines = [f"autosim model {interface.name}."]
    if interface.doc:
        lines += ["", interface.doc]
    sections: list[tuple[str, Sequence[Quantity | Event]]] = [
        ("States", interface.states),
        ("Parameters", interface.parameters),
        ("Inputs", interface.inputs),
        ("Outputs", interface.outputs),
        ("Discrete variables", interface.discrete),
        ("Events", interface.events),
    ]
    for title, items in sections:
        if items:
            lines += ["", f"{title}:"]
            lines += [f"    {q.describe()}" for q in items]
    if interface.constraints:
        lines += ["", "Constraints:"]
        lines += [
            f"    {c.name} ({c.kind}; determines {c.dependent_coordinate or c.dependent_speed})"
            for c in interface.constraints
        ]
    lines += ["", "Methods: see autosim.Model (derivatives, outputs, linearize, simulate, ...)."]
    return "\n".join(lines)
