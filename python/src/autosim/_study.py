"""Studies: one model over a table of cases, run by the Rust runtime on
every core (:class:`Study`), with results as NumPy arrays and a pandas
DataFrame (:class:`StudyResults`).

A study is data: the model (pickled as the recipe to make it again), the
case table (:class:`Cases`), the run settings and what to :class:`Keep`.
Each case's values are computed from its index alone, so the same study
gives the same bits serially, on any number of threads, and in chunks run
in other processes or on other machines (:meth:`Study.run_dask`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple, Union

import numpy as np

from ._simulation import event_settings

if TYPE_CHECKING:  # pragma: no cover
    from ._model import Model

#: The integrators a study runs (explicit methods; see :meth:`Model.simulate`).
STUDY_METHODS = ("dopri", "rk4", "heun", "euler", "abm4", "abm2")
#: The statistics :meth:`Keep.statistic` takes.
STATISTICS = ("min", "max", "mean", "rms", "maxabs")


@dataclass(frozen=True)
class Distribution:
    """A distribution to draw a column from: :func:`uniform` or :func:`normal`."""

    kind: str
    a: float
    b: float


def uniform(low: float, high: float) -> Distribution:
    """Uniform on ``[low, high)``: finite bounds with ``low < high``, else a
    ValueError."""
    low, high = float(low), float(high)
    if not (np.isfinite(low) and np.isfinite(high) and low < high):
        raise ValueError(f"uniform({low}, {high}): the bounds must be finite with low < high")
    return Distribution("uniform", low, high)


def normal(mean: float, std_dev: float) -> Distribution:
    """Normal with this mean and standard deviation: a finite mean and a
    finite standard deviation of at least 0, else a ValueError."""
    mean, std_dev = float(mean), float(std_dev)
    if not (np.isfinite(mean) and np.isfinite(std_dev) and std_dev >= 0.0):
        raise ValueError(
            f"normal({mean}, {std_dev}): the mean must be finite and the standard deviation finite and at least 0"
        )
    return Distribution("normal", mean, std_dev)


def _floats(values: Any, what: str) -> list[float]:
    array = np.asarray(values, dtype=np.float64)
    if array.ndim != 1:
        raise ValueError(f"{what} must be one-dimensional, not of shape {array.shape}")
    return [float(v) for v in array]


@dataclass(frozen=True)
class Cases:
    """The table of cases: named columns that set the model's parameters,
    inputs, initial states or discrete variables' initial values
    (``parameter:NAME``, ``input:NAME``, ``state:NAME``, ``discrete:NAME``
    when a name is more than one), the product of factors
    like nested loops, the first outermost.

    >>> cases = Cases().grid("torque", [0.0, 0.5]).random(200, seed=7, m=uniform(0.5, 2.0))
    >>> len(cases), cases.names
    (400, ('torque', 'm'))

    Each method returns a new table. The runtime checks the table (a
    repeated column, a value that is not finite, a bad distribution raise
    ``ValueError``) when a :class:`Study` is made.
    """

    factors: tuple[tuple[Any, ...], ...] = ()
    names: tuple[str, ...] = ()
    lengths: tuple[int, ...] = ()

    def _with(self, names: Sequence[str], factor: tuple[Any, ...], length: int) -> Cases:
        return Cases(self.factors + (factor,), self.names + tuple(names), self.lengths + (length,))

    def grid(self, name: str, values: Iterable[float]) -> Cases:
        """The table times a grid axis: column ``name`` takes each of ``values``."""
        floats = _floats(list(values), f"the values of {name!r}")
        return self._with([name], ("grid", str(name), floats), len(floats))

    def rows(self, names: Any, values: Any = None) -> Cases:
        """The table times a list of rows: ``names`` (columns) and ``values``
        of shape ``(rows, len(names))``, or a pandas DataFrame (its columns
        and rows)."""
        if values is None and hasattr(names, "columns") and hasattr(names, "to_numpy"):
            values = names.to_numpy(dtype=np.float64)
            names = [str(c) for c in names.columns]
        names = [str(n) for n in names]
        array = np.asarray(values, dtype=np.float64)
        if array.ndim == 1 and len(names) == 1:
            array = array.reshape(-1, 1)
        if array.ndim != 2 or array.shape[1] != len(names):
            raise ValueError(f"rows of {names} must have shape (n, {len(names)}), not {array.shape}")
        flat = [float(v) for v in array.ravel()]
        return self._with(names, ("rows", names, flat), array.shape[0])

    def random(
        self,
        count: int,
        seed: int,
        columns: Mapping[str, Distribution] | None = None,
        **by_name: Distribution,
    ) -> Cases:
        """The table times ``count`` random draws of the columns (a mapping
        or keywords, each a :func:`uniform` or :func:`normal`). Draw ``k``
        comes from its own stream (ChaCha8, seed ``seed``, stream ``k``):
        the same at every point of a grid and on any number of threads or
        machines."""
        drawn = dict(columns or {}, **by_name)
        if not drawn:
            raise ValueError("random draws need at least one column")
        spec = []
        for name, d in drawn.items():
            if not isinstance(d, Distribution):
                raise TypeError(f"column {name!r}: give autosim.uniform(...) or autosim.normal(...)")
            spec.append((str(name), d.kind, d.a, d.b))
        return self._with(list(drawn), ("random", int(count), int(seed), spec), int(count))

    def __len__(self) -> int:
        return math.prod(self.lengths)


@dataclass(frozen=True)
class Keep:
    """What a study keeps of each run, by the name of a state, an output or
    a discrete variable; each item
    is one field of the results, named as the runtime names it:
    ``final:<state>``, ``<quantity>@<time>``, ``<statistic>:<quantity>``,
    ``history:<quantity>``.

    >>> keep = Keep().final_state().at([1.0], ["height"]).statistic("height", "max").history(["q"])
    """

    final: bool = False
    times: tuple[tuple[float, str], ...] = ()
    statistics: tuple[tuple[str, str], ...] = ()
    histories: tuple[str, ...] = ()

    def final_state(self) -> Keep:
        """Keep the final state (a field ``final:<state>`` per state)."""
        return Keep(True, self.times, self.statistics, self.histories)

    def at(self, times: Iterable[float], quantities: Iterable[str]) -> Keep:
        """Keep ``quantities`` (states, outputs or discrete variables) at each
        of ``times``, which
        must be output times of the run (``t0``, ``t_end``, or ``t0 +
        k*output_interval``)."""
        qs = list(quantities)
        added = tuple((float(t), str(q)) for t in times for q in qs)
        return Keep(self.final, self.times + added, self.statistics, self.histories)

    def statistic(self, quantity: str, statistic: str) -> Keep:
        """Keep a statistic of a state, output or discrete variable over the
        output times:
        ``"min"``, ``"max"``, ``"mean"``, ``"rms"`` or ``"maxabs"``."""
        if statistic not in STATISTICS:
            raise ValueError(f"statistic {statistic!r} is not one of {', '.join(STATISTICS)}")
        return Keep(self.final, self.times, self.statistics + ((str(quantity), statistic),), self.histories)

    def history(self, quantities: Iterable[str]) -> Keep:
        """Keep the whole time history of ``quantities`` (one value per
        output time)."""
        return Keep(
            self.final, self.times, self.statistics, self.histories + tuple(str(q) for q in quantities)
        )


class StudySummary(NamedTuple):
    """What :meth:`Study.run_in` did."""

    #: Cases in the study.
    cases: int
    #: Cases run by this call.
    ran: int
    #: Cases skipped because their shard was written before (a resumed study).
    skipped: int
    #: Cases of this call that failed.
    failed: int
    #: Wall-clock time of the call.
    seconds: float


@dataclass(frozen=True, eq=False)
class StudyResults:
    """The results of consecutive cases ``first_case ..
    first_case + len(results)``: the case table's values
    (:attr:`case_values`, one row per case), the kept values
    (:attr:`values`, NaN for a failed case) and each case's error
    (:attr:`errors`, ``None`` when it succeeded).

    ``results["name"]`` is a field (shape ``(n,)``, or ``(n, length)`` for a
    history) or a column of the case table; :meth:`to_pandas` gives a
    DataFrame. ``a == b`` compares every value's bits (NaN included);
    ``repr`` is one line (cases, failures, columns, fields).
    """

    first_case: int
    case_columns: tuple[str, ...]
    fields: tuple[tuple[str, int], ...]
    case_values: np.ndarray
    values: np.ndarray
    errors: tuple[str | None, ...]

    @classmethod
    def _from_native(cls, raw: Mapping[str, Any]) -> StudyResults:
        return cls(
            first_case=int(raw["first_case"]),
            case_columns=tuple(raw["case_columns"]),
            fields=tuple((str(n), int(k)) for n, k in raw["fields"]),
            case_values=raw["case_values"],
            values=raw["values"],
            errors=tuple(raw["errors"]),
        )

    def __len__(self) -> int:
        return len(self.errors)

    def __repr__(self) -> str:
        """A line, not the arrays: the cases, how many failed, the columns
        and fields (a field of several values with its length)."""
        fields = ", ".join(n if k == 1 else f"{n}[{k}]" for n, k in self.fields)
        end = self.first_case + len(self)
        return (
            f"<StudyResults: cases {self.first_case}..{end} ({len(self) - self.failures} ok, "
            f"{self.failures} failed); columns {', '.join(self.case_columns) or '(none)'}; "
            f"fields {fields or '(none)'}>"
        )

    @property
    def cases(self) -> np.ndarray:
        """The case indices."""
        return np.arange(self.first_case, self.first_case + len(self), dtype=np.int64)

    @property
    def ok(self) -> np.ndarray:
        """``True`` for each case that succeeded."""
        return np.array([e is None for e in self.errors], dtype=bool)

    @property
    def failures(self) -> int:
        """How many cases failed."""
        return sum(e is not None for e in self.errors)

    def field_span(self, name: str) -> tuple[int, int]:
        """Where field ``name`` starts in :attr:`values`' rows, and its length."""
        start = 0
        for n, length in self.fields:
            if n == name:
                return start, length
            start += length
        from ._values import unknown_name

        raise unknown_name("field", name, [n for n, _ in self.fields] + list(self.case_columns))

    def __getitem__(self, name: str) -> np.ndarray:
        if name in self.case_columns and name not in dict(self.fields):
            return self.case_values[:, self.case_columns.index(name)]
        start, length = self.field_span(name)
        if length == 1:
            return self.values[:, start]
        return self.values[:, start : start + length]

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, StudyResults):
            return NotImplemented
        bits = _bits
        return (
            self.first_case == other.first_case
            and self.case_columns == other.case_columns
            and self.fields == other.fields
            and self.errors == other.errors
            and bits(self.case_values) == bits(other.case_values)
            and bits(self.values) == bits(other.values)
        )

    __hash__ = None  # type: ignore[assignment]

    @staticmethod
    def concat(parts: Sequence[StudyResults]) -> StudyResults:
        """Results of consecutive chunks joined (each must start where the
        one before ends)."""
        if not parts:
            raise ValueError("no results to join")
        first = parts[0]
        end = first.first_case
        for p in parts:
            if p.first_case != end or p.fields != first.fields or p.case_columns != first.case_columns:
                raise ValueError(f"cases {p.first_case}.. do not follow cases {first.first_case}..{end}")
            end += len(p)
        return StudyResults(
            first_case=first.first_case,
            case_columns=first.case_columns,
            fields=first.fields,
            case_values=np.concatenate([p.case_values for p in parts]),
            values=np.concatenate([p.values for p in parts]),
            errors=tuple(e for p in parts for e in p.errors),
        )

    def columns(self) -> list[str]:
        """The column names of :meth:`to_pandas` (and of a CSV shard): the
        case table's, then each field (``name[k]`` for a field of several
        values), then ``ok`` and ``error``."""
        names = list(self.case_columns)
        for n, length in self.fields:
            names += [n] if length == 1 else [f"{n}[{k}]" for k in range(length)]
        return names + ["ok", "error"]

    def to_pandas(self) -> Any:
        """A pandas DataFrame indexed by ``case``, with the columns of
        :meth:`columns` (needs pandas)."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("to_pandas needs pandas: pip install pandas") from None
        names = self.columns()
        data: dict[str, Any] = {}
        for k, n in enumerate(names[: len(self.case_columns)]):
            data[n] = self.case_values[:, k]
        for k, n in enumerate(names[len(self.case_columns) : -2]):
            data[n] = self.values[:, k]
        data["ok"] = self.ok
        data["error"] = list(self.errors)
        return pd.DataFrame(data, index=pd.Index(self.cases, name="case"))


def _bits(a: np.ndarray) -> bytes:
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64).tobytes()


Chunk = Union[range, slice, tuple[int, int], None]


@dataclass(frozen=True, eq=False)
class Study:
    """A simulation study of ``model``: each case of ``cases`` sets the
    model's parameters, inputs and initial state, is simulated from ``t0``
    to ``t_end`` with ``method``, and keeps what ``keep`` says.

    The model's parameters and inputs as they are when the study is made
    are the defaults every case starts from (a copy is kept). ``method``:
    one of :data:`STUDY_METHODS` (``"dopri"`` adaptive with ``rtol``,
    ``atol`` and first trial step ``h``; the others fixed step ``h``);
    ``output_interval`` (default: ``t_end - t0``) spaces the output times
    at which :meth:`Keep.at` values, statistics and histories are taken.
    A model's events are located as :meth:`Model.simulate` locates them,
    with the same ``event_tolerance``, ``event_samples``, ``zeno_events``
    and ``zeno_interval``.

    Raises ``ValueError`` (the runtime's reason, naming the column, the
    quantity or the setting) when the study cannot run: a column that sets
    nothing, a quantity the model lacks, a time that is not an output time.
    """

    model: Model
    cases: Cases
    keep: Keep
    t_end: float
    t0: float = 0.0
    h: float = 1e-3
    output_interval: float | None = None
    method: str = "dopri"
    rtol: float = 1e-9
    atol: float = 1e-12
    max_steps: int = 10_000_000
    event_tolerance: float = 0.0
    event_samples: int = 4
    zeno_events: int = 100
    zeno_interval: float = 0.0
    _checked: tuple[Any, ...] = field(default=(), repr=False, compare=False)

    def __post_init__(self) -> None:
        if not (math.isfinite(self.t0) and math.isfinite(self.t_end) and self.t_end > self.t0):
            raise ValueError(f"a study's t_end ({self.t_end}) must be finite and after t0 ({self.t0})")
        if self.method not in STUDY_METHODS:
            raise ValueError(
                f"a study's method must be one of {', '.join(STUDY_METHODS)}, not {self.method!r}"
            )
        object.__setattr__(self, "model", self.model.copy())
        description, times, columns, fields = self.model._native.study_describe(self._spec(None, False))
        checked = (description, times, tuple(columns), tuple((n, int(k)) for n, k in fields))
        object.__setattr__(self, "_checked", checked)

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickles as its parts (the model as its recipe), checked again
        where it is unpickled."""
        return (
            _rebuild_study,
            (
                self.model,
                self.cases,
                self.keep,
                self.t_end,
                self.t0,
                self.h,
                self.output_interval,
                self.method,
                self.rtol,
                self.atol,
                self.max_steps,
                self.event_tolerance,
                self.event_samples,
                self.zeno_events,
                self.zeno_interval,
            ),
        )

    def _spec(self, threads: int | None, progress: bool) -> dict[str, Any]:
        if threads is not None and not (isinstance(threads, int) and threads >= 1):
            raise ValueError(f"threads must be None (every core) or at least 1, not {threads!r}")
        interval = self.t_end - self.t0 if self.output_interval is None else self.output_interval
        return {
            "factors": list(self.cases.factors),
            "t0": float(self.t0),
            "t_end": float(self.t_end),
            "h": float(self.h),
            "output_interval": float(interval),
            "max_steps": int(self.max_steps),
            "events": event_settings(
                self.event_tolerance, self.event_samples, self.zeno_events, self.zeno_interval
            ),
            "method": self.method,
            "rtol": float(self.rtol),
            "atol": float(self.atol),
            "final_state": self.keep.final,
            "at": list(self.keep.times),
            "statistics": list(self.keep.statistics),
            "history": list(self.keep.histories),
            "threads": threads,
            "progress": bool(progress),
        }

    def __len__(self) -> int:
        return len(self.cases)

    def describe(self) -> str:
        """What identifies the study (the runtime's ``Study::describe``: the
        model's name, the table, the task): equal for the same study in any
        process, and written in a folder's manifest."""
        return str(self._checked[0])

    @property
    def output_times(self) -> np.ndarray:
        """The output times of every run (the samples of a history)."""
        return np.array(self._checked[1])

    @property
    def case_columns(self) -> tuple[str, ...]:
        """The case table's columns."""
        return self._checked[2]  # type: ignore[no-any-return]

    @property
    def fields(self) -> tuple[tuple[str, int], ...]:
        """The kept fields: ``(name, values per case)``."""
        return self._checked[3]  # type: ignore[no-any-return]

    def _range(self, cases: Chunk) -> tuple[int, int]:
        n = len(self)
        if cases is None:
            return 0, n
        if isinstance(cases, tuple):
            start, end = cases
        elif isinstance(cases, (range, slice)):
            r = range(n)[cases] if isinstance(cases, slice) else cases
            if r.step != 1:
                raise ValueError("cases must be consecutive (a step of 1)")
            start, end = r.start, r.stop
        else:
            raise TypeError("cases must be a range, a slice or a (start, end) pair")
        if not 0 <= start <= end <= n:
            raise ValueError(f"cases {start}..{end} are not all in the table of {n} cases")
        return int(start), int(end)

    def run(self, cases: Chunk = None, *, threads: int | None = None, progress: bool = True) -> StudyResults:
        """Runs the cases (all, or a ``range``, ``slice`` or ``(start, end)``
        of consecutive indices) in one call with the GIL released, and
        returns their results. ``threads``: ``None`` every core, ``1``
        serially, ``n`` a pool of ``n``. ``progress`` draws a bar (cases,
        cases per second, ETA) on standard error when it is a terminal.

        Results never depend on ``threads`` or on how the cases are split:
        chunks joined with :meth:`StudyResults.concat` equal the whole.
        A failed case (a non-finite state, a failed step, a model error)
        has NaN values and its error in :attr:`StudyResults.errors`; the
        others run on. Ctrl-C stops the run (no case starts after it; those
        running finish) and raises ``KeyboardInterrupt``."""
        start, end = self._range(cases)
        raw = self.model._native.study_run(self._spec(threads, progress), start, end)
        return StudyResults._from_native(raw)

    def chunks(self, chunk_size: int) -> list[tuple[int, int]]:
        """The study's cases as consecutive ``(start, end)`` ranges of at most
        ``chunk_size`` cases."""
        if chunk_size < 1:
            raise ValueError("chunk_size must be at least 1")
        n = len(self)
        return [(s, min(s + chunk_size, n)) for s in range(0, n, chunk_size)]

    def run_dask(
        self, client: Any, *, chunk_size: int | None = None, threads: int | None = 1
    ) -> StudyResults:
        """Runs the study through a ``dask.distributed`` ``client`` in chunks
        of ``chunk_size`` cases (default: four chunks per worker thread),
        each chunk one task run by :meth:`run` on a worker with ``threads``
        (default 1: Dask's workers are the parallelism), and joins the
        results: the same bits as :meth:`run` here.

        The study is sent to the workers once (scattered): it pickles as
        the model's recipe, so each worker loads the model from its cache
        (``AUTOSIM_CACHE``), from the model's wheel if the model came
        from one, or builds it (which needs cargo there)."""
        if chunk_size is None:
            slots = max(1, sum(client.nthreads().values()))
            chunk_size = max(1, math.ceil(len(self) / (4 * slots)))
        remote = client.scatter(self, broadcast=True, hash=False)
        futures = [
            client.submit(_run_chunk, remote, start, end, threads, pure=False)
            for start, end in self.chunks(chunk_size)
        ]
        return StudyResults.concat(client.gather(futures))

    def run_in(
        self,
        folder: str | Path,
        *,
        shard_size: int = 10_000,
        threads: int | None = None,
        progress: bool = True,
    ) -> StudySummary:
        """Runs the study into ``folder``: a manifest (``study.toml``) and CSV
        shards of ``shard_size`` consecutive cases, each written whole and
        renamed into place, so memory holds one shard and a crash loses at
        most the shard in progress. Run it again on the same folder to
        resume (written shards are skipped; a folder holding another study
        is refused). Ctrl-C stops it between cases with
        ``KeyboardInterrupt``, dropping the shard in progress: the shards
        written stay whole and a later call resumes. :meth:`read` reads it
        back."""
        raw = self.model._native.study_run_in(self._spec(threads, progress), str(folder), int(shard_size))
        return StudySummary(
            int(raw["cases"]), int(raw["ran"]), int(raw["skipped"]), int(raw["failed"]), float(raw["seconds"])
        )

    def read(self, folder: str | Path) -> StudyResults:
        """The results of this study written to ``folder`` by :meth:`run_in`
        (every shard; the values read back with the same bits). Raises
        ``ValueError`` when the folder holds another study or a shard is
        missing."""
        raw, description = self.model._native.study_read(str(folder))
        what = _difference(description, self.describe())
        if what is not None:
            raise ValueError(f"{folder} holds a different study (its manifest differs: {what})")
        return StudyResults._from_native(raw)


def _difference(found: str, expected: str) -> str | None:
    """What differs between a folder's description and a study's, in the
    words of the Rust side's refusal (the model's line first, then the
    model as made, then the rest)."""
    if found == expected:
        return None
    found_lines, expected_lines = found.split("\n"), expected.split("\n")
    if found_lines[0] != expected_lines[0]:
        return (
            "the model: its name, or its generated code (another build of it: "
            "another model text, load options, or version of autosim)"
        )
    if found_lines[1:2] != expected_lines[1:2]:
        return "the model as made: its parameters, inputs, discrete variables or initial state"
    return "the study"


def _rebuild_study(model: Model, *args: Any) -> Study:
    return Study(model, *args)


def _run_chunk(study: Study, start: int, end: int, threads: int | None) -> StudyResults:
    """One chunk of a distributed study (what a Dask task runs)."""
    return study.run((start, end), threads=threads, progress=False)
