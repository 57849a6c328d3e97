//! Linear models about an operating point: `dx/dt ≈ A δx + B δw`,
//! `y ≈ C δx + D δw`, as generated models' `linearize` returns them, and
//! the trait generic analysis code (trim, modes, export) uses.

use crate::{Float, Model, ModelError};

/// The matrices of a linear model with `NX` states, `NU` inputs and `NY`
/// outputs (fixed-size, no allocation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Linear<F, const NX: usize, const NU: usize, const NY: usize> {
    /// `∂(dx/dt)/∂x`.
    pub a: [[F; NX]; NX],
    /// `∂(dx/dt)/∂w`.
    pub b: [[F; NU]; NX],
    /// `∂y/∂x`.
    pub c: [[F; NX]; NY],
    /// `∂y/∂w`.
    pub d: [[F; NU]; NY],
}

impl<F: Float, const NX: usize, const NU: usize, const NY: usize> Linear<F, NX, NU, NY> {
    /// All matrices zero.
    pub fn zeros() -> Self {
        Linear {
            a: [[F::ZERO; NX]; NX],
            b: [[F::ZERO; NU]; NX],
            c: [[F::ZERO; NX]; NY],
            d: [[F::ZERO; NU]; NY],
        }
    }
}

/// A model that can linearize itself (generated with `linearize: true`).
///
/// The linear model is in the *linear states*: every state of the model
/// but the dependent coordinates of position constraints (they follow the
/// independent ones). Its inputs are the model's inputs, its outputs the
/// model's outputs.
pub trait Linearize: Model {
    /// Positions in the state vector of the linear model's states.
    const LINEAR_STATES: &'static [usize];

    /// Writes `A`, `B`, `C`, `D` row-major at `(t, x)` with the model's
    /// current inputs: `a` has `LINEAR_STATES.len()²` entries, `b`
    /// `LINEAR_STATES.len() × INPUT_NAMES.len()`, `c`
    /// `OUTPUT_NAMES.len() × LINEAR_STATES.len()`, `d` `OUTPUT_NAMES.len()
    /// × INPUT_NAMES.len()` (shorter slices get what fits).
    ///
    /// # Errors
    /// The model's errors at this state (a singular mass matrix or
    /// constraint matrix).
    fn linearize_into(
        &mut self,
        t: Self::Float,
        x: &Self::State,
        a: &mut [Self::Float],
        b: &mut [Self::Float],
        c: &mut [Self::Float],
        d: &mut [Self::Float],
    ) -> Result<(), ModelError>;
}

/// Copies a fixed-size matrix into a row-major slice (what fits).
pub fn copy_rows<F: Float, const C: usize>(rows: &[[F; C]], out: &mut [F]) {
    for (o, v) in out.iter_mut().zip(rows.iter().flatten()) {
        *o = *v;
    }
}
