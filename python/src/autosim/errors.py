"""The exceptions autosim raises (all derive from :class:`AutosimError`)."""

from __future__ import annotations


class AutosimError(Exception):
    """Base class of every autosim exception."""


class CompileError(AutosimError, ValueError):
    """The model text has errors.

    The message is the compiler's rendered diagnostics, exactly what a Rust
    user of ``autosim::build`` sees: ``file:line:column: error: ...``, the
    source line, a caret under the mistake, and a ``help:`` line with the fix.
    """

    def __init__(self, diagnostics: str) -> None:
        super().__init__(diagnostics.rstrip())
        #: The rendered diagnostics.
        self.diagnostics = diagnostics.rstrip()


class BuildError(AutosimError, RuntimeError):
    """The native module of a model could not be built (no Rust toolchain,
    a crate that could not be fetched, a compiler error in generated code).
    The message says what to install or shows cargo's output."""


class SimulationError(AutosimError, RuntimeError):
    """The model or an integrator failed at run time: a singular mass matrix
    or constraint matrix (naming the speed or constraint), a non-finite
    state (naming it and the time), a step-size underflow, failed assembly.
    """


class ZenoError(SimulationError):
    """Events chattered (Zeno behaviour): more than ``zeno_events`` events
    followed each other, each within ``zeno_interval`` of the one before,
    as a bouncing ball without a minimum rebound speed does before it
    comes to rest. Fix the model (e.g. a mode that ends the bouncing below
    a minimum rebound speed) or, if the events are real, raise
    ``zeno_events`` in :meth:`autosim.Model.simulate`."""

    def __init__(self, message: str, event: str, t: float, events: int) -> None:
        super().__init__(message)
        #: The name of the event that fired last.
        self.event = event
        #: Its time.
        self.t = t
        #: Events in the chain.
        self.events = events
