"""autosim from Python: multibody models written in the autosim language
(``.sim`` files) as fast NumPy objects.

>>> import autosim
>>> model = autosim.load("examples/models/pendulum.sim")  # doctest: +SKIP
>>> sim = model.simulate(2.0, model.state(q=0.5))          # doctest: +SKIP

:func:`load` and :func:`loads` run the autosim compiler in process, then
build the model's native module with cargo into the cache folder
(:func:`cache_dir`; ``AUTOSIM_CACHE`` overrides it) unless it is there
already: the first model of a cache takes under a minute (PyO3 is
compiled once), a new small model about a second, a model loaded before
about a millisecond. The result is a :class:`Model`.
"""

from __future__ import annotations

import difflib
import inspect
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ._build import cache_dir, find_cargo
from ._interface import Constraint, Event, Interface, Quantity
from ._linear import LinearModel
from ._model import Model, TrimResult
from ._simulation import METHODS, EventLog, Simulation
from ._study import (
    STUDY_METHODS,
    Cases,
    Distribution,
    Keep,
    Study,
    StudyResults,
    StudySummary,
    normal,
    uniform,
)
from .errors import AutosimError, BuildError, CompileError, SimulationError, ZenoError

__version__ = "0.1.0"

__all__ = [
    "AutosimError",
    "BuildError",
    "Cases",
    "CompileError",
    "Constraint",
    "Distribution",
    "Event",
    "EventLog",
    "Interface",
    "Keep",
    "LinearModel",
    "METHODS",
    "STUDY_METHODS",
    "Model",
    "Quantity",
    "Simulation",
    "SimulationError",
    "Study",
    "StudyResults",
    "StudySummary",
    "TrimResult",
    "ZenoError",
    "cache_dir",
    "find_cargo",
    "load",
    "loads",
    "normal",
    "uniform",
]


def _options(
    name: str | None,
    linearize: bool | None,
    lanes: bool | None,
    formulation: str | None,
    small: Sequence[str] | None,
    lock: Sequence[str] | None,
    outputs: Sequence[str] | None,
    threshold: int | None,
) -> dict[str, Any]:
    options: dict[str, Any] = {}
    for key, value in (
        ("name", name),
        ("linearize", linearize),
        ("lanes", lanes),
        ("formulation", formulation),
        ("small", list(small) if small is not None else None),
        ("lock", list(lock) if lock is not None else None),
        ("outputs", list(outputs) if outputs is not None else None),
        ("threshold", threshold),
    ):
        if value is not None:
            options[key] = value
    return options


def loads(
    text: str,
    *,
    path: str = "<string>",
    name: str | None = None,
    linearize: bool | None = True,
    lanes: bool | None = None,
    formulation: str | None = None,
    small: Sequence[str] | None = None,
    lock: Sequence[str] | None = None,
    outputs: Sequence[str] | None = None,
    threshold: int | None = None,
    quiet: bool = False,
) -> Model:
    """Compiles model ``text`` (named ``path`` in diagnostics) and returns
    it as a :class:`Model`.

    The options are the scene options of ``autosim::model!``: ``name`` (a
    new model name), ``linearize`` (generate :meth:`Model.linearize`; on by
    default here, ``None`` keeps the model's own setting), ``lanes``
    (generate the derivatives at four states per call, which
    :meth:`Model.derivatives` then uses for 2-D arrays of states and a
    study of a model without events for four cases at a time, whatever its
    method; ``None`` keeps the model's own setting), ``formulation``
    (``"auto"``, ``"mass_matrix"``, ``"recursive"``), ``small`` and
    ``lock`` (bodies or coordinates), ``outputs`` (keep only these),
    ``threshold`` (small-term threshold). ``quiet`` silences the two
    lines printed to stderr while a native module is built.

    Raises :class:`CompileError` (the compiler's spanned diagnostics) when
    the model has errors and :class:`BuildError` when its native module
    cannot be built (no cargo: the message says what to install).
    """
    from ._build import build

    options = _options(name, linearize, lanes, formulation, small, lock, outputs, threshold)
    module, _ = build(text, path, options, quiet=quiet)
    return Model._from_module(module, origin=("text", text, path, options))


def load(path: str | Path, **options: Any) -> Model:
    """Compiles the model file at ``path`` (the options as in
    :func:`loads`) and returns it as a :class:`Model`; a file loaded before
    with the same text and options comes from the cache."""
    known = [n for n in inspect.signature(loads).parameters if n not in ("text", "path")]
    for key in options:
        if key not in known:
            close = difflib.get_close_matches(key, known, n=1)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise TypeError(
                f"load() got an unexpected keyword argument {key!r}{hint} (its options: {', '.join(known)})"
            )
    file = Path(path)
    try:
        text = file.read_text(encoding="utf-8")
    except OSError as e:
        raise FileNotFoundError(f"cannot read model file {file}: {e.strerror}") from None
    model = loads(text, path=str(path), **options)
    model.source = file
    return model
