"""Named vectors of a model (its parameters, its inputs): read and set by
name, as a dict, or as a vector, with checks that name what is wrong."""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterator, Mapping, MutableMapping, Sequence
from typing import Callable, Union

import numpy as np

from ._interface import Quantity

ArrayLike = Union[Sequence[float], np.ndarray]


def unknown_name(kind: str, name: str, names: Sequence[str], docs: Sequence[str] = ()) -> KeyError:
    """A KeyError naming ``name``, the known names and the closest of them
    (spelled alike whatever the case, or one the start of the other), or
    when none is, those whose doc comment (``docs``, one per name) has a
    word spelled alike (``"Lenght"``: ``L``, "Cable length"); only the
    known names when nothing is close."""
    close = _close_names(name, names)
    if close:
        hint = f"; did you mean {', '.join(repr(c) for c in close)}?"
    else:
        by_doc = _close_docs(name, names, docs)
        hint = f"; did you mean {', '.join(f'{n!r} ({d!r})' for n, d in by_doc)}?" if by_doc else ""
    return KeyError(f"{kind} {name!r} is not one of the model's {kind}s {list(names)}{hint}")


def _close_names(name: str, names: Sequence[str]) -> list[str]:
    """Up to three of ``names`` spelled like ``name`` whatever the case, or
    one the start of the other."""
    by_lower = {n.lower(): n for n in names}
    close = [by_lower[c] for c in difflib.get_close_matches(name.lower(), list(by_lower), n=3)]
    lower = name.lower()
    close += [
        n
        for n in names
        if n not in close
        and min(len(n), len(name)) >= 2
        and (n.lower().startswith(lower) or lower.startswith(n.lower()))
    ][: 3 - len(close)]
    return close


def _close_docs(name: str, names: Sequence[str], docs: Sequence[str]) -> list[tuple[str, str]]:
    """Up to three ``(name, doc)`` whose doc has a word spelled like ``name``."""
    found = []
    for n, doc in zip(names, docs):
        words = re.findall(r"[a-z]{3,}", doc.lower())
        if difflib.get_close_matches(name.lower(), words, n=1, cutoff=0.75):
            found.append((n, doc.strip()))
    return found[:3]


def as_vector(values: ArrayLike, length: int, what: str) -> np.ndarray:
    """``values`` as a float64 vector of ``length`` entries, or a ValueError
    naming ``what``."""
    try:
        v = np.ascontiguousarray(values, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ValueError(f"{what} must be numbers: {e}") from None
    if v.ndim != 1 or v.shape[0] != length:
        raise ValueError(f"{what} must have shape ({length},), not {v.shape}")
    return v


def check_finite(values: np.ndarray, what: str, names: Sequence[str], kind: str) -> None:
    """A ValueError naming the first entry of ``values`` (a vector, or rows
    of one) that is NaN or infinite: ``what``, its row for rows, and the
    ``kind`` and name of its column (``names``)."""
    finite = np.isfinite(values)
    if finite.all():
        return
    at = tuple(int(k) for k in np.argwhere(~finite)[0])
    column = at[-1]
    label = names[column] if column < len(names) else f"#{column}"
    row = f" row {at[0]}" if len(at) == 2 else ""
    raise ValueError(f"{what}{row} is not finite in {kind} {label!r} (#{column}): {values[at]}")


class NamedValues(MutableMapping[str, float]):
    """A model's parameters or inputs: a mutable mapping name → value
    (``model.parameters["m"] = 2.0``), in declaration order, plus
    :attr:`vector` and :meth:`set`. Every change reaches the model at once
    (parameters recompute the model's constants)."""

    def __init__(
        self,
        kind: str,
        quantities: tuple[Quantity, ...],
        read: Callable[[], np.ndarray],
        write: Callable[[np.ndarray], None],
        finite: bool,
    ) -> None:
        self._kind = kind
        self._quantities = quantities
        self._names = tuple(q.name for q in quantities)
        self._index = {n: k for k, n in enumerate(self._names)}
        self._read = read
        self._write = write
        self._finite = finite

    @property
    def names(self) -> tuple[str, ...]:
        """The names, in declaration order."""
        return self._names

    @property
    def units(self) -> tuple[str, ...]:
        """The units, in declaration order."""
        return tuple(q.unit for q in self._quantities)

    @property
    def defaults(self) -> dict[str, float]:
        """The values the model declares."""
        return {q.name: q.default for q in self._quantities}

    @property
    def vector(self) -> np.ndarray:
        """The values as a vector (declaration order; a copy)."""
        return np.array(self._read(), dtype=np.float64)

    @vector.setter
    def vector(self, values: ArrayLike) -> None:
        v = as_vector(values, len(self._names), f"{self._kind} vector")
        self._check(v)
        self._write(v)

    def set(self, values: Mapping[str, float] | ArrayLike | None = None, **by_name: float) -> None:
        """Sets values from a mapping or keywords (by name; the others keep
        theirs) or a whole vector."""
        if values is not None and not isinstance(values, Mapping):
            self.vector = values
            values = {}
        changes = dict(values or {}, **by_name)
        v = self._read().copy()
        for name, value in changes.items():
            if name not in self._index:
                raise self._unknown(name)
            try:
                v[self._index[name]] = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"{self._kind} {name!r} must be a number, not {value!r}") from None
        self._check(v)
        self._write(v)

    def _check(self, v: np.ndarray) -> None:
        if not self._finite:
            return
        bad = [n for n, x in zip(self._names, v) if not np.isfinite(x)]
        if bad:
            raise ValueError(f"{self._kind} {', '.join(repr(b) for b in bad)} must be finite")

    def _unknown(self, name: str) -> KeyError:
        return unknown_name(self._kind, name, self._names, [q.doc for q in self._quantities])

    def __getitem__(self, name: str) -> float:
        if name not in self._index:
            raise self._unknown(name)
        return float(self._read()[self._index[name]])

    def __setitem__(self, name: str, value: float) -> None:
        self.set({name: value})

    def __delitem__(self, name: str) -> None:
        raise TypeError(f"a model's {self._kind}s cannot be removed")

    def __iter__(self) -> Iterator[str]:
        return iter(self._names)

    def __len__(self) -> int:
        return len(self._names)

    def __repr__(self) -> str:
        values = self._read()
        inner = ", ".join(f"{n}={v:g}" for n, v in zip(self._names, values))
        return f"{self._kind}s({inner})"
