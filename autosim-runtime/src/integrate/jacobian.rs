//! Where implicit methods get the Jacobian `∂f/∂x` of a model from.

use core::fmt;

use super::vector::eval;
use crate::{Float, IntegrationError, Model, ModelError};

/// A way to compute the Jacobian `J[i][j] = ∂fᵢ/∂xⱼ` of a model with an
/// `N`-state array, for implicit methods such as [`Sdirk3`](super::Sdirk3).
///
/// Use [`FiniteDifferences`] (the default) unless you have the Jacobian in
/// closed form; then wrap it in [`Analytic`], which saves `N` evaluations
/// per step and converges better on strongly nonlinear models.
pub trait JacobianSource<M: Model, const N: usize> {
    /// Writes the Jacobian at `(t, x)` into `jac`; `f0 = f(t, x)` is given.
    /// Adds the derivative evaluations it makes to `evaluations`.
    ///
    /// # Errors
    /// [`IntegrationError::Model`] if the model fails to evaluate.
    fn jacobian(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &[M::Float; N],
        f0: &[M::Float; N],
        jac: &mut [[M::Float; N]; N],
        evaluations: &mut u64,
    ) -> Result<(), IntegrationError>;
}

/// Forward-difference Jacobian: one extra model evaluation per state, with
/// increments `δⱼ = sqrt(ε·max(1e-5, |xⱼ|))` (Hairer's choice).
///
/// Use it when no analytic Jacobian is at hand; it is accurate enough for
/// Newton's method (the Jacobian only affects convergence speed, not the
/// converged result).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FiniteDifferences;

impl<F, M, const N: usize> JacobianSource<M, N> for FiniteDifferences
where
    F: Float,
    M: Model<Float = F, State = [F; N]>,
{
    fn jacobian(
        &mut self,
        model: &mut M,
        t: F,
        x: &[F; N],
        f0: &[F; N],
        jac: &mut [[F; N]; N],
        evaluations: &mut u64,
    ) -> Result<(), IntegrationError> {
        let mut xp = *x;
        let mut fp = [F::ZERO; N];
        let floor = F::from_f64(1e-5);
        for j in 0..N {
            let xj = x[j];
            let delta = (F::EPSILON * floor.max(xj.abs())).sqrt();
            // Use the increment that is exactly representable after rounding.
            xp[j] = xj + delta;
            let delta = xp[j] - xj;
            eval(model, t, &xp, &mut fp, evaluations)?;
            xp[j] = xj;
            for ((row, fpi), f0i) in jac.iter_mut().zip(fp.iter()).zip(f0.iter()) {
                row[j] = (*fpi - *f0i) / delta;
            }
        }
        Ok(())
    }
}

/// An analytic Jacobian given as a closure
/// `|model, t, x, jac| -> Result<(), ModelError>` that writes `∂fᵢ/∂xⱼ` into
/// `jac[i][j]`; the closure can read the model's parameters through `model`.
///
/// Use it when the Jacobian is known in closed form (linear models, or one
/// derived symbolically).
#[derive(Clone, Copy)]
pub struct Analytic<C>(pub C);

impl<C> fmt::Debug for Analytic<C> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Analytic(..)")
    }
}

impl<F, M, C, const N: usize> JacobianSource<M, N> for Analytic<C>
where
    F: Float,
    M: Model<Float = F, State = [F; N]>,
    C: FnMut(&M, F, &[F; N], &mut [[F; N]; N]) -> Result<(), ModelError>,
{
    fn jacobian(
        &mut self,
        model: &mut M,
        t: F,
        x: &[F; N],
        _f0: &[F; N],
        jac: &mut [[F; N]; N],
        _evaluations: &mut u64,
    ) -> Result<(), IntegrationError> {
        (self.0)(model, t, x, jac).map_err(|error| IntegrationError::Model {
            t: t.to_f64(),
            error,
        })
    }
}
