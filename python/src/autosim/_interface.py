"""A model's interface as the compiler describes it (names, units, defaults
and docs of its states, parameters, inputs, outputs and discrete variables;
its constraints and events)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Quantity:
    """A named value of a model: a state, parameter, input or output."""

    #: Name as written in the model.
    name: str
    #: Unit text (empty when the model gives none).
    unit: str
    #: Default value (parameters and inputs), initial value (discrete
    #: variables); 0 for states and outputs.
    default: float = 0.0
    #: The model's doc comment for it (empty when none).
    doc: str = ""
    #: ``"parameter"``, ``"input"``, ``"output"``, ``"discrete"``, or for
    #: states ``"coordinate"``, ``"speed"`` or ``"extra"``.
    kind: str = ""

    def describe(self) -> str:
        """One line: name, unit, default and doc."""
        unit = f" [{self.unit}]" if self.unit else ""
        default = f" = {self.default:g}" if self.kind in ("parameter", "input", "discrete") else ""
        doc = f"  {self.doc.splitlines()[0]}" if self.doc else ""
        return f"{self.name}{default}{unit}{doc}"


@dataclass(frozen=True)
class Constraint:
    """A constraint of a model (position or speed) and what it determines."""

    name: str
    kind: str
    dependent_speed: str
    dependent_coordinate: str | None
    doc: str = ""


@dataclass(frozen=True)
class Event:
    """An event of a model: its indicator's sign change in ``direction``
    (``"rising"``, ``"falling"`` or ``"either"``) fires its actions."""

    name: str
    direction: str
    #: The run ends at the event (a terminal event).
    stop: bool
    #: Unit of the indicator (empty when the model gives none).
    unit: str = ""
    doc: str = ""

    def describe(self) -> str:
        """One line: name, direction, whether it stops the run, and doc."""
        stop = ", stops the run" if self.stop else ""
        doc = f"  {self.doc.splitlines()[0]}" if self.doc else ""
        return f"{self.name} ({self.direction}{stop}){doc}"


@dataclass(frozen=True)
class Interface:
    """Everything the compiler says about a model's interface."""

    name: str
    doc: str
    states: tuple[Quantity, ...]
    n_speeds: int
    parameters: tuple[Quantity, ...]
    inputs: tuple[Quantity, ...]
    outputs: tuple[Quantity, ...]
    user_code: tuple[str, ...]
    constraints: tuple[Constraint, ...]
    dependent_coordinates: tuple[int, ...]
    linear_states: tuple[int, ...] | None
    cautions: tuple[str, ...]
    discrete: tuple[Quantity, ...] = ()
    events: tuple[Event, ...] = ()

    @staticmethod
    def from_json(text: str) -> Interface:
        """Reads the JSON the compiler writes."""
        data: dict[str, Any] = json.loads(text)

        def quantities(items: Sequence[dict[str, Any]], kind: str) -> tuple[Quantity, ...]:
            return tuple(
                Quantity(q["name"], q["unit"], float(q["default"]), q.get("doc", ""), kind) for q in items
            )

        states = tuple(Quantity(s["name"], s["unit"], 0.0, "", s["kind"]) for s in data["states"])
        constraints = tuple(
            Constraint(
                c["name"],
                c["kind"],
                c["dependent_speed"],
                c.get("dependent_coordinate"),
                c.get("doc", ""),
            )
            for c in data["constraints"]
        )
        events = tuple(
            Event(e["name"], e["direction"], bool(e["stop"]), e.get("unit", ""), e.get("doc", ""))
            for e in data.get("events", [])
        )
        linear = data.get("linear_states")
        return Interface(
            name=data["name"],
            doc=data.get("doc", ""),
            states=states,
            n_speeds=int(data["n_speeds"]),
            parameters=quantities(data["parameters"], "parameter"),
            inputs=quantities(data["inputs"], "input"),
            outputs=quantities(data["outputs"], "output"),
            user_code=tuple(data.get("user_code", [])),
            constraints=constraints,
            dependent_coordinates=tuple(data.get("dependent_coordinates", [])),
            linear_states=None if linear is None else tuple(linear),
            cautions=tuple(data.get("cautions", [])),
            discrete=quantities(data.get("discrete", []), "discrete"),
            events=events,
        )
