//! Fixed-step explicit Runge–Kutta methods: Euler, Heun and classic RK4.
//! Each is a [`FixedStep`]: it computes the new state into a workspace, and
//! one implementation of [`Stepper`] checks the step and the result around
//! it for all three.

use core::fmt;

use super::vector::{check_step, combine, eval};
use super::{StepInfo, StepResult, Stepper};
use crate::{Float, IntegrationError, Model, StateArray, check_finite};

/// A fixed-step method that carries nothing from one step to the next.
trait FixedStep<M: Model> {
    /// The method's name.
    const NAME: &'static str;
    /// Its order of accuracy.
    const ORDER: u32;
    /// Derivative evaluations per step.
    const STAGES: u32;

    /// Computes the state at `t + h` from `x` (returned; `x` unchanged).
    fn advance(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
        h: M::Float,
    ) -> Result<&M::State, IntegrationError>;
}

/// A [`FixedStep`] as a [`Stepper`]: the step checked, the new state
/// checked before it replaces `x`.
fn fixed_step<M: Model, S: FixedStep<M>>(
    s: &mut S,
    model: &mut M,
    t: M::Float,
    x: &mut M::State,
    h: M::Float,
) -> Result<StepInfo<M::Float>, IntegrationError> {
    check_step(h)?;
    let new = *s.advance(model, t, x, h)?;
    check_finite::<M>(t + h, &new)?;
    *x = new;
    Ok(fixed_info(h, S::STAGES))
}

/// Declares a stepper whose fields are state arrays (zeroed by `new`) and
/// an evaluation counter, with `Clone`, `Default` and `Debug` (deriving
/// would demand `M: Clone`), and its [`Stepper`] implementation through
/// [`FixedStep`].
macro_rules! fixed_stepper {
    ($(#[$doc:meta])* $ty:ident { $($field:ident),* }) => {
        $(#[$doc])*
        pub struct $ty<M: Model> {
            $($field: M::State,)*
            evals: u64,
        }

        impl<M: Model> $ty<M> {
            /// A stepper with zeroed workspaces.
            pub fn new() -> Self {
                Self { $($field: M::State::zeros(),)* evals: 0 }
            }
        }

        impl<M: Model> Clone for $ty<M> {
            fn clone(&self) -> Self {
                Self { $($field: self.$field,)* evals: self.evals }
            }
        }
        impl<M: Model> Default for $ty<M> {
            fn default() -> Self {
                Self::new()
            }
        }
        impl<M: Model> fmt::Debug for $ty<M> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.debug_struct(stringify!($ty))
                    .field("evaluations", &self.evals)
                    .finish_non_exhaustive()
            }
        }

        impl<M: Model> Stepper<M> for $ty<M> {
            fn step(&mut self, model: &mut M, t: M::Float, x: &mut M::State, h: M::Float) -> StepResult<M> {
                fixed_step(self, model, t, x, h)
            }
            fn evaluations(&self) -> u64 {
                self.evals
            }
            fn reset(&mut self) {}
            fn name(&self) -> &'static str {
                <Self as FixedStep<M>>::NAME
            }
            fn order(&self) -> u32 {
                <Self as FixedStep<M>>::ORDER
            }
        }
    };
}

fixed_stepper! {
    /// Explicit (forward) Euler: `x += h·f(t, x)`. Order 1, one evaluation per
    /// step.
    ///
    /// Use it only where the step is tiny anyway (a fast control loop) or to
    /// show what a better method buys; [`Heun`] costs one more evaluation and is
    /// an order more accurate.
    Euler { k, x_new }
}

impl<M: Model> FixedStep<M> for Euler<M> {
    const NAME: &'static str = "Euler";
    const ORDER: u32 = 1;
    const STAGES: u32 = 1;
    fn advance(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
        h: M::Float,
    ) -> Result<&M::State, IntegrationError> {
        eval(model, t, x, &mut self.k, &mut self.evals)?;
        combine(&mut self.x_new, x, h, &[(M::Float::ONE, &self.k)]);
        Ok(&self.x_new)
    }
}

fixed_stepper! {
    /// Heun's method (explicit trapezoid, RK2): an Euler predictor and a
    /// trapezoid corrector. Order 2, two evaluations per step, stage times `t`
    /// and `t + h`.
    ///
    /// Use it for cheap fixed-step loops where Euler's error is too large and
    /// RK4's four evaluations are too many.
    Heun { k1, k2, stage }
}

impl<M: Model> FixedStep<M> for Heun<M> {
    const NAME: &'static str = "Heun";
    const ORDER: u32 = 2;
    const STAGES: u32 = 2;
    fn advance(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
        h: M::Float,
    ) -> Result<&M::State, IntegrationError> {
        let one = M::Float::ONE;
        let half = M::Float::from_f64(0.5);
        eval(model, t, x, &mut self.k1, &mut self.evals)?;
        combine(&mut self.stage, x, h, &[(one, &self.k1)]);
        eval(model, t + h, &self.stage, &mut self.k2, &mut self.evals)?;
        combine(&mut self.stage, x, h, &[(half, &self.k1), (half, &self.k2)]);
        Ok(&self.stage)
    }
}

fixed_stepper! {
    /// The classic fourth-order Runge–Kutta method. Order 4, four evaluations
    /// per step.
    ///
    /// The model's derivatives are called exactly four times per step, in this
    /// order: at `t`, `t + h/2`, `t + h/2`, `t + h` — user functions that keep
    /// state (AUTOSIM's controllers that count calls) may rely on it.
    /// Use it as the default fixed-step method for smooth, non-stiff models.
    Rk4 { k1, k2, k3, k4, stage }
}

impl<M: Model> FixedStep<M> for Rk4<M> {
    const NAME: &'static str = "RK4";
    const ORDER: u32 = 4;
    const STAGES: u32 = 4;
    fn advance(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
        h: M::Float,
    ) -> Result<&M::State, IntegrationError> {
        rk4_step(
            model,
            t,
            x,
            h,
            [&mut self.k1, &mut self.k2, &mut self.k3, &mut self.k4],
            &mut self.stage,
            &mut self.evals,
        )?;
        Ok(&self.stage)
    }
}

/// One classic RK4 step from `(t, x)` into `out`, using `k` as workspace.
/// Shared with the Adams–Bashforth–Moulton start-up.
pub(crate) fn rk4_step<M: Model>(
    model: &mut M,
    t: M::Float,
    x: &M::State,
    h: M::Float,
    k: [&mut M::State; 4],
    out: &mut M::State,
    evals: &mut u64,
) -> Result<(), IntegrationError> {
    let [k1, k2, k3, k4] = k;
    eval(model, t, x, k1, evals)?;
    rk4_tail(model, t, x, h, k1, [k2, k3, k4], out, evals)
}

/// RK4 stages 2–4 and the update, given `k1 = f(t, x)`.
// The arguments are the disjoint workspace borrows of two steppers.
#[allow(clippy::too_many_arguments)]
pub(crate) fn rk4_tail<M: Model>(
    model: &mut M,
    t: M::Float,
    x: &M::State,
    h: M::Float,
    k1: &M::State,
    k: [&mut M::State; 3],
    out: &mut M::State,
    evals: &mut u64,
) -> Result<(), IntegrationError> {
    let [k2, k3, k4] = k;
    let one = M::Float::ONE;
    let half = M::Float::from_f64(0.5);
    let sixth = M::Float::from_f64(1.0 / 6.0);
    let third = M::Float::from_f64(1.0 / 3.0);
    let t_half = t + half * h;
    combine(out, x, h, &[(half, k1)]);
    eval(model, t_half, out, k2, evals)?;
    combine(out, x, h, &[(half, &*k2)]);
    eval(model, t_half, out, k3, evals)?;
    combine(out, x, h, &[(one, &*k3)]);
    eval(model, t + h, out, k4, evals)?;
    combine(
        out,
        x,
        h,
        &[(sixth, k1), (third, &*k2), (third, &*k3), (sixth, &*k4)],
    );
    Ok(())
}

pub(crate) fn fixed_info<F: Float>(h: F, evaluations: u32) -> StepInfo<F> {
    StepInfo {
        h,
        h_next: h,
        rejected: 0,
        evaluations,
    }
}
