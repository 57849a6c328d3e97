//! Fixed-step explicit Runge–Kutta methods: Euler, Heun and classic RK4.

use core::fmt;

use super::vector::{check_step, combine, eval};
use super::{StepInfo, Stepper};
use crate::{Float, IntegrationError, Model, StateArray, check_finite};

/// Implements `Clone`, `Default` and `Debug` for a stepper whose fields are
/// state arrays and counters (deriving would demand `M: Clone`).
macro_rules! workspace_impls {
    ($ty:ident { $($field:ident),* }) => {
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
    };
}

/// Explicit (forward) Euler: `x += h·f(t, x)`. Order 1, one evaluation per
/// step.
///
/// Use it only where the step is tiny anyway (a fast control loop) or to
/// show what a better method buys; [`Heun`] costs one more evaluation and is
/// an order more accurate.
pub struct Euler<M: Model> {
    k: M::State,
    x_new: M::State,
    evals: u64,
}

impl<M: Model> Euler<M> {
    /// A stepper with zeroed workspaces.
    pub fn new() -> Self {
        Self {
            k: M::State::zeros(),
            x_new: M::State::zeros(),
            evals: 0,
        }
    }
}

workspace_impls!(Euler { k, x_new });

impl<M: Model> Stepper<M> for Euler<M> {
    fn step(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &mut M::State,
        h: M::Float,
    ) -> Result<StepInfo<M::Float>, IntegrationError> {
        check_step(h)?;
        eval(model, t, x, &mut self.k, &mut self.evals)?;
        combine(&mut self.x_new, x, h, &[(M::Float::ONE, &self.k)]);
        check_finite::<M>(t + h, &self.x_new)?;
        *x = self.x_new;
        Ok(fixed_info(h, 1))
    }
    fn evaluations(&self) -> u64 {
        self.evals
    }
    fn reset(&mut self) {}
    fn name(&self) -> &'static str {
        "Euler"
    }
    fn order(&self) -> u32 {
        1
    }
}

/// Heun's method (explicit trapezoid, RK2): an Euler predictor and a
/// trapezoid corrector. Order 2, two evaluations per step, stage times `t`
/// and `t + h`.
///
/// Use it for cheap fixed-step loops where Euler's error is too large and
/// RK4's four evaluations are too many.
pub struct Heun<M: Model> {
    k1: M::State,
    k2: M::State,
    stage: M::State,
    evals: u64,
}

impl<M: Model> Heun<M> {
    /// A stepper with zeroed workspaces.
    pub fn new() -> Self {
        Self {
            k1: M::State::zeros(),
            k2: M::State::zeros(),
            stage: M::State::zeros(),
            evals: 0,
        }
    }
}

workspace_impls!(Heun { k1, k2, stage });

impl<M: Model> Stepper<M> for Heun<M> {
    fn step(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &mut M::State,
        h: M::Float,
    ) -> Result<StepInfo<M::Float>, IntegrationError> {
        check_step(h)?;
        let one = M::Float::ONE;
        let half = M::Float::from_f64(0.5);
        eval(model, t, x, &mut self.k1, &mut self.evals)?;
        combine(&mut self.stage, x, h, &[(one, &self.k1)]);
        eval(model, t + h, &self.stage, &mut self.k2, &mut self.evals)?;
        combine(&mut self.stage, x, h, &[(half, &self.k1), (half, &self.k2)]);
        check_finite::<M>(t + h, &self.stage)?;
        *x = self.stage;
        Ok(fixed_info(h, 2))
    }
    fn evaluations(&self) -> u64 {
        self.evals
    }
    fn reset(&mut self) {}
    fn name(&self) -> &'static str {
        "Heun"
    }
    fn order(&self) -> u32 {
        2
    }
}

/// The classic fourth-order Runge–Kutta method. Order 4, four evaluations
/// per step.
///
/// The model's derivatives are called exactly four times per step, in this
/// order: at `t`, `t + h/2`, `t + h/2`, `t + h` — user functions that keep
/// state (AUTOSIM's controllers that count calls) may rely on it.
/// Use it as the default fixed-step method for smooth, non-stiff models.
pub struct Rk4<M: Model> {
    k1: M::State,
    k2: M::State,
    k3: M::State,
    k4: M::State,
    stage: M::State,
    evals: u64,
}

impl<M: Model> Rk4<M> {
    /// A stepper with zeroed workspaces.
    pub fn new() -> Self {
        Self {
            k1: M::State::zeros(),
            k2: M::State::zeros(),
            k3: M::State::zeros(),
            k4: M::State::zeros(),
            stage: M::State::zeros(),
            evals: 0,
        }
    }
}

workspace_impls!(Rk4 {
    k1,
    k2,
    k3,
    k4,
    stage
});

impl<M: Model> Stepper<M> for Rk4<M> {
    fn step(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &mut M::State,
        h: M::Float,
    ) -> Result<StepInfo<M::Float>, IntegrationError> {
        check_step(h)?;
        rk4_step(
            model,
            t,
            x,
            h,
            [&mut self.k1, &mut self.k2, &mut self.k3, &mut self.k4],
            &mut self.stage,
            &mut self.evals,
        )?;
        check_finite::<M>(t + h, &self.stage)?;
        *x = self.stage;
        Ok(fixed_info(h, 4))
    }
    fn evaluations(&self) -> u64 {
        self.evals
    }
    fn reset(&mut self) {}
    fn name(&self) -> &'static str {
        "RK4"
    }
    fn order(&self) -> u32 {
        4
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
