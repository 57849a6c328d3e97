//! An L-stable singly diagonally implicit Runge–Kutta method for stiff models.

use core::fmt;

use super::jacobian::{FiniteDifferences, JacobianSource};
use super::linalg::LuFactors;
use super::vector::{check_step, eval, evaluations_since};
use super::{StepInfo, Stepper};
use crate::{Float, IntegrationError, Model, check_finite};

/// Newton-iteration settings of [`Sdirk3`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SdirkSettings<F> {
    /// Convergence test: a stage has converged when the root-mean-square of
    /// `Δzᵢ / (1 + |zᵢ|)` of the last Newton update is at most this.
    pub newton_tol: F,
    /// Newton iterations allowed per stage before
    /// [`IntegrationError::NewtonFailed`].
    pub max_newton_iterations: u32,
}

impl<F: Float> Default for SdirkSettings<F> {
    /// `newton_tol = max(1e-10, 100·ε)`, 10 iterations.
    fn default() -> Self {
        Self {
            newton_tol: F::from_f64(1e-10).max(F::from_f64(100.0) * F::EPSILON),
            max_newton_iterations: 10,
        }
    }
}

// Alexander (1977), 3-stage, order 3, L-stable and stiffly accurate:
// γ is the root of γ³ − 3γ² + 3γ/2 − 1/6 = 0 in (1/6, 1/2).
const GAMMA: f64 = 0.435_866_521_508_458_999_416_019_451_193_556;
const TAU2: f64 = (1.0 + GAMMA) / 2.0;
const B1: f64 = -(6.0 * GAMMA * GAMMA - 16.0 * GAMMA + 1.0) / 4.0;
const B2: f64 = (6.0 * GAMMA * GAMMA - 20.0 * GAMMA + 5.0) / 4.0;
/// Stage times cᵢ and the strictly lower Butcher coefficients aᵢⱼ (j < i);
/// every diagonal coefficient is γ.
const C: [f64; 3] = [GAMMA, TAU2, 1.0];
const A: [[f64; 2]; 3] = [[0.0, 0.0], [TAU2 - GAMMA, 0.0], [B1, B2]];

/// Alexander's three-stage SDIRK method: order 3, L-stable, stiffly
/// accurate, fixed step. Each stage solves `zᵢ = x + h·Σⱼ<ᵢ aᵢⱼ·kⱼ + h·γ·f(t + cᵢh, zᵢ)`
/// by a simplified Newton iteration with one LU factorization of
/// `I − h·γ·J` per step (all stages share γ).
///
/// Use it for stiff models — eigenvalues of the Jacobian far out on the
/// negative real axis, where explicit methods need `h·|λ| ≲ 3` — at steps
/// chosen for accuracy rather than stability. The Jacobian comes from `J`:
/// [`FiniteDifferences`] by default (`N` extra evaluations per step), or an
/// [`Analytic`](super::Analytic) closure. Needs a model whose state is an
/// array `[F; N]` (true of all generated models).
pub struct Sdirk3<M: Model, const N: usize, J = FiniteDifferences> {
    settings: SdirkSettings<M::Float>,
    jacobian: J,
    /// The Jacobian, then (in place) the Newton matrix `I − hγJ`.
    jac: [[M::Float; N]; N],
    lu: LuFactors<M::Float, N>,
    f0: [M::Float; N],
    k: [[M::Float; N]; 3],
    z: [M::Float; N],
    s: [M::Float; N],
    r: [M::Float; N],
    evals: u64,
    newton_iterations: u64,
}

impl<F: Float, M: Model<Float = F>, const N: usize> Sdirk3<M, N, FiniteDifferences> {
    /// A stepper with a finite-difference Jacobian.
    pub fn new(settings: SdirkSettings<F>) -> Self {
        Self::with_jacobian(settings, FiniteDifferences)
    }
}

impl<F: Float, M: Model<Float = F>, const N: usize, J> Sdirk3<M, N, J> {
    /// A stepper that takes its Jacobian from `jacobian`.
    pub fn with_jacobian(settings: SdirkSettings<F>, jacobian: J) -> Self {
        let z = [F::ZERO; N];
        Self {
            settings,
            jacobian,
            jac: [z; N],
            lu: LuFactors::identity(),
            f0: z,
            k: [z; 3],
            z,
            s: z,
            r: z,
            evals: 0,
            newton_iterations: 0,
        }
    }

    /// Total Newton iterations so far (each costs one evaluation and one
    /// pair of triangular solves).
    pub fn newton_iterations(&self) -> u64 {
        self.newton_iterations
    }
}

impl<M: Model, const N: usize, J: Clone> Clone for Sdirk3<M, N, J> {
    fn clone(&self) -> Self {
        Self {
            jacobian: self.jacobian.clone(),
            ..*self
        }
    }
}

impl<M: Model, const N: usize, J: fmt::Debug> fmt::Debug for Sdirk3<M, N, J> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Sdirk3")
            .field("settings", &self.settings)
            .field("jacobian", &self.jacobian)
            .field("evaluations", &self.evals)
            .field("newton_iterations", &self.newton_iterations)
            .finish_non_exhaustive()
    }
}

impl<F, M, J, const N: usize> Sdirk3<M, N, J>
where
    F: Float,
    M: Model<Float = F, State = [F; N]>,
    J: JacobianSource<M, N>,
{
    /// Solves stage `i` for `self.z` (starting from its current value), with
    /// `self.s` the explicit part; `hg = h·γ`.
    fn newton(
        &mut self,
        model: &mut M,
        t_stage: F,
        hg: F,
        t: F,
        h: F,
    ) -> Result<(), IntegrationError> {
        let fail = |iterations| IntegrationError::NewtonFailed {
            t: t.to_f64(),
            h: h.to_f64(),
            iterations,
        };
        let mut previous = F::from_f64(f64::INFINITY);
        for iteration in 1..=self.settings.max_newton_iterations {
            self.newton_iterations += 1;
            match eval(model, t_stage, &self.z, &mut self.r, &mut self.evals) {
                Ok(()) => {}
                // The iterate overflowed: Newton diverged.
                Err(IntegrationError::NonFinite { .. }) => return Err(fail(iteration)),
                Err(e) => return Err(e),
            }
            // Residual g = z − s − hγ·f(z); Newton update Δ = −(I − hγJ)⁻¹·g.
            for ((r, z), s) in self.r.iter_mut().zip(self.z.iter()).zip(self.s.iter()) {
                *r = *s + hg * *r - *z;
            }
            self.lu.solve(&mut self.r);
            let mut sum = F::ZERO;
            for (z, d) in self.z.iter_mut().zip(self.r.iter()) {
                *z += *d;
                let w = *d / (F::ONE + z.abs());
                sum += w * w;
            }
            let norm = (sum / F::from_f64(N.max(1) as f64)).sqrt();
            let decreasing = norm < previous;
            if !norm.is_finite() || !decreasing {
                return Err(fail(iteration));
            }
            if norm <= self.settings.newton_tol {
                return Ok(());
            }
            previous = norm;
        }
        Err(fail(self.settings.max_newton_iterations))
    }
}

impl<F, M, J, const N: usize> Stepper<M> for Sdirk3<M, N, J>
where
    F: Float,
    M: Model<Float = F, State = [F; N]>,
    J: JacobianSource<M, N>,
{
    fn step(
        &mut self,
        model: &mut M,
        t: F,
        x: &mut [F; N],
        h: F,
    ) -> Result<StepInfo<F>, IntegrationError> {
        check_step(h)?;
        let evals_before = self.evals;
        let hg = h * F::from_f64(GAMMA);
        eval(model, t, x, &mut self.f0, &mut self.evals)?;
        self.jacobian
            .jacobian(model, t, x, &self.f0, &mut self.jac, &mut self.evals)?;
        // The Newton matrix I − hγJ (built in the Jacobian's storage),
        // factored once for all three stages.
        for (i, row) in self.jac.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = if i == j { F::ONE } else { F::ZERO } - hg * *v;
            }
        }
        self.lu
            .refactor(&self.jac)
            .map_err(|_| IntegrationError::SingularNewtonMatrix {
                t: t.to_f64(),
                h: h.to_f64(),
            })?;
        self.z = *x;
        for i in 0..3 {
            // Explicit part s = x + h·Σⱼ<ᵢ aᵢⱼ·kⱼ.
            self.s = *x;
            for (a, k) in A[i].iter().zip(self.k.iter()).take(i) {
                let a = F::from_f64(*a);
                for (s, kj) in self.s.iter_mut().zip(k.iter()) {
                    *s += h * a * *kj;
                }
            }
            // Start from the previous stage value (x for the first stage).
            self.newton(model, t + F::from_f64(C[i]) * h, hg, t, h)?;
            // kᵢ = (zᵢ − sᵢ)/(hγ): no extra evaluation, and no amplification
            // of the Newton residual by the stiff Jacobian.
            for ((k, z), s) in self.k[i].iter_mut().zip(self.z.iter()).zip(self.s.iter()) {
                *k = (*z - *s) / hg;
            }
        }
        // Stiffly accurate: the last stage is the new state.
        check_finite::<M>(t + h, &self.z)?;
        *x = self.z;
        Ok(StepInfo::fixed(
            h,
            evaluations_since(evals_before, self.evals),
        ))
    }
    fn evaluations(&self) -> u64 {
        self.evals
    }
    fn reset(&mut self) {}
    fn name(&self) -> &'static str {
        "SDIRK3 (Alexander)"
    }
    fn order(&self) -> u32 {
        3
    }
}
