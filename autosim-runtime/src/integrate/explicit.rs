//! Fixed-step explicit Runge–Kutta methods: Euler, Heun and classic RK4.
//! Each is a Butcher [`Tableau`] that one routine ([`rk_step`]) steps with,
//! and one implementation of [`Stepper`] checks the step and the result
//! around it for all three.

use core::fmt;

use super::vector::{check_step, combine_row, eval};
use super::{StepInfo, StepResult, Stepper};
use crate::{Float, IntegrationError, Model, StateArray, check_finite};

/// The Butcher tableau of an explicit Runge–Kutta method with `S` stages.
pub(crate) struct Tableau<const S: usize> {
    /// Stage times as fractions of the step; `c[0]` is 0 (stage 1 is at `t`).
    pub c: [f64; S],
    /// Row `i`: the weights `aᵢⱼ` (j < i) of the earlier stages' derivatives
    /// in stage `i`'s state (row 0 is empty).
    pub a: [&'static [f64]; S],
    /// The weights of the stages' derivatives in the new state.
    pub b: [f64; S],
}

/// Forward Euler.
pub(crate) const EULER: Tableau<1> = Tableau {
    c: [0.0],
    a: [&[]],
    b: [1.0],
};

/// Heun's method: an Euler predictor and a trapezoid corrector.
pub(crate) const HEUN: Tableau<2> = Tableau {
    c: [0.0, 1.0],
    a: [&[], &[1.0]],
    b: [0.5, 0.5],
};

/// The classic fourth-order Runge–Kutta method.
pub(crate) const RK4: Tableau<4> = Tableau {
    c: [0.0, 0.5, 0.5, 1.0],
    a: [&[], &[0.5], &[0.0, 0.5], &[0.0, 0.0, 1.0]],
    b: [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
};

/// One step of `tableau` from `(t, x)` into `out`, given the first stage's
/// derivative `k[0] = f(t, x)`: for each later stage `i`,
/// `out = x + h·Σⱼ<ᵢ aᵢⱼ·kⱼ` and `kᵢ = f(t + cᵢ·h, out)`; then
/// `out = x + h·Σᵢ bᵢ·kᵢ`.
// The arguments are the disjoint workspace borrows of the steppers.
#[allow(clippy::too_many_arguments)]
pub(crate) fn rk_step<M: Model, const S: usize>(
    model: &mut M,
    t: M::Float,
    x: &M::State,
    h: M::Float,
    tableau: &Tableau<S>,
    k: &mut [M::State; S],
    out: &mut M::State,
    evals: &mut u64,
) -> Result<(), IntegrationError> {
    for i in 1..S {
        let (earlier, rest) = k.split_at_mut(i);
        combine_row(out, x, h, tableau.a[i], earlier);
        let t_stage = t + M::Float::from_f64(tableau.c[i]) * h;
        eval(model, t_stage, out, &mut rest[0], evals)?;
    }
    combine_row(out, x, h, &tableau.b, k);
    Ok(())
}

/// Declares a fixed-step stepper for a [`Tableau`] of `S` stages: its
/// workspaces (zeroed by `new`) and evaluation counter, `Clone`, `Default`
/// and `Debug` (deriving would demand `M: Clone`), and its [`Stepper`]
/// implementation: the step checked, the new state checked before it
/// replaces `x`.
macro_rules! fixed_stepper {
    (
        $(#[$doc:meta])*
        $ty:ident: $name:literal, order $order:literal, $tableau:ident, $stages:literal stages
    ) => {
        $(#[$doc])*
        pub struct $ty<M: Model> {
            /// The stages' derivatives.
            k: [M::State; $stages],
            /// The stages' states, then the new state.
            out: M::State,
            evals: u64,
        }

        impl<M: Model> $ty<M> {
            /// A stepper with zeroed workspaces.
            pub fn new() -> Self {
                let z = M::State::zeros();
                Self { k: [z; $stages], out: z, evals: 0 }
            }
        }

        clone_and_debug!($ty { "evaluations": evals });
        impl<M: Model> Default for $ty<M> {
            fn default() -> Self {
                Self::new()
            }
        }

        impl<M: Model> Stepper<M> for $ty<M> {
            fn step(&mut self, model: &mut M, t: M::Float, x: &mut M::State, h: M::Float) -> StepResult<M> {
                check_step(h)?;
                eval(model, t, x, &mut self.k[0], &mut self.evals)?;
                rk_step(model, t, x, h, &$tableau, &mut self.k, &mut self.out, &mut self.evals)?;
                check_finite::<M>(t + h, &self.out)?;
                *x = self.out;
                Ok(StepInfo::fixed(h, $stages))
            }
            fn evaluations(&self) -> u64 {
                self.evals
            }
            fn reset(&mut self) {}
            fn name(&self) -> &'static str {
                $name
            }
            fn order(&self) -> u32 {
                $order
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
    Euler: "Euler", order 1, EULER, 1 stages
}

fixed_stepper! {
    /// Heun's method (explicit trapezoid, RK2): an Euler predictor and a
    /// trapezoid corrector. Order 2, two evaluations per step, stage times `t`
    /// and `t + h`.
    ///
    /// Use it for cheap fixed-step loops where Euler's error is too large and
    /// RK4's four evaluations are too many.
    Heun: "Heun", order 2, HEUN, 2 stages
}

fixed_stepper! {
    /// The classic fourth-order Runge–Kutta method. Order 4, four evaluations
    /// per step.
    ///
    /// The model's derivatives are called exactly four times per step, in this
    /// order: at `t`, `t + h/2`, `t + h/2`, `t + h` — user functions that keep
    /// state (AUTOSIM's controllers that count calls) may rely on it.
    /// Use it as the default fixed-step method for smooth, non-stiff models.
    Rk4: "RK4", order 4, RK4, 4 stages
}
