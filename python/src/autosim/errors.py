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
