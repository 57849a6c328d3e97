"""Linear models about an operating point, as :meth:`Model.linearize`
returns them."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True)
class LinearModel:
    """``dx/dt ≈ A δx + B δu``, ``y ≈ C δx + D δu`` with names."""

    #: ``∂(dx/dt)/∂x`` (linear states × linear states).
    A: np.ndarray
    #: ``∂(dx/dt)/∂u`` (linear states × inputs).
    B: np.ndarray
    #: ``∂y/∂x`` (outputs × linear states).
    C: np.ndarray
    #: ``∂y/∂u`` (outputs × inputs).
    D: np.ndarray
    #: The linear states (all states but dependent coordinates).
    state_names: tuple[str, ...]
    #: Their units.
    state_units: tuple[str, ...]
    #: The inputs.
    input_names: tuple[str, ...]
    #: The outputs.
    output_names: tuple[str, ...]

    def __iter__(self) -> Any:
        """Unpacks as ``A, B, C, D = model.linearize(...)``."""
        return iter((self.A, self.B, self.C, self.D))

    def modes(self) -> tuple[np.ndarray, np.ndarray]:
        """Eigenvalues of ``A`` (sorted by real part, then imaginary) and
        the eigenvectors as columns, rows in :attr:`state_names` order."""
        values, vectors = np.linalg.eig(self.A)
        order = np.lexsort((values.imag, values.real))
        return values[order], vectors[:, order]

    def to_control(self) -> Any:
        """A python-control ``StateSpace`` with the state, input and output
        names (needs the ``control`` package: LQR, pole placement and
        discretization are then a line away)."""
        try:
            import control
        except ImportError:
            raise ImportError("to_control needs python-control: pip install control") from None
        return control.ss(
            self.A,
            self.B,
            self.C,
            self.D,
            states=list(self.state_names),
            inputs=list(self.input_names),
            outputs=list(self.output_names),
        )
