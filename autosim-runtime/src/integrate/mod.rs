//! Integrators: stepper objects that advance a [`Model`] by one step without
//! allocating.
//!
//! Every integrator implements [`Stepper`]; pick one by what the model needs:
//!
//! | stepper | order | evaluations per step | use it for |
//! | --- | --- | --- | --- |
//! | [`Euler`] | 1 | 1 | teaching, cheap real-time loops with tiny steps |
//! | [`Heun`] | 2 | 2 | cheap real-time loops where Euler drifts |
//! | [`Rk4`] | 4 | 4 | the default fixed-step method for smooth models |
//! | [`AdamsBashforthMoulton`] | 2 or 4 | 2 (after start-up) | AUTOSIM-style runs: smooth models, constant step, few evaluations |
//! | [`DormandPrince`] | 5(4) | 6 (FSAL), adaptive | accuracy-controlled runs and dense output |
//! | [`Sdirk3`] | 3 | 3 Newton solves + Jacobian | stiff models (stiff springs, fast dampers) |
//!
//! A stepper owns fixed-size workspaces (arrays of the model's state type),
//! counts the model's derivative evaluations ([`Stepper::evaluations`]),
//! checks every new state for NaN and infinity, and leaves the state
//! unchanged when it returns an error. The [`run`](crate::run()) driver is the
//! usual way to call one; call [`Stepper::step`] yourself when you own the
//! loop (a controller on a microcontroller, a co-simulation).

/// `Clone` (a copy of every field) and `Debug` (the fields named) for a
/// stepper generic over the model alone, whose derives would require the
/// model itself to be `Clone` and `Debug`.
macro_rules! clone_and_debug {
    ($ty:ident { $($label:literal: $field:ident),+ $(,)? }) => {
        impl<M: Model> Clone for $ty<M> {
            fn clone(&self) -> Self {
                Self { ..*self }
            }
        }
        impl<M: Model> fmt::Debug for $ty<M> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.debug_struct(stringify!($ty))
                    $(.field($label, &self.$field))+
                    .finish_non_exhaustive()
            }
        }
    };
}

mod abm;
mod dopri;
mod explicit;
mod jacobian;
mod linalg;
mod sdirk;
mod vector;

#[cfg(feature = "study")]
pub(crate) use abm::AbmHistory;
pub use abm::{AbmOrder, AdamsBashforthMoulton};
#[cfg(feature = "study")]
pub(crate) use dopri::{Control, DOPRI5, ERROR, check_trial_step, ends_at};
pub use dopri::{DopriSettings, DormandPrince};
#[cfg(feature = "study")]
pub(crate) use explicit::{EULER, HEUN, RK4, Tableau};
pub use explicit::{Euler, Heun, Rk4};
pub use jacobian::{Analytic, FiniteDifferences, JacobianSource};
pub use linalg::{LuFactors, SingularMatrix};
pub use sdirk::{Sdirk3, SdirkSettings};
#[cfg(feature = "study")]
pub(crate) use vector::{check_step, combine_lane, evaluation_error};

pub use crate::error::check_finite;
use crate::{IntegrationError, Model};

/// What one call of [`Stepper::step`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StepInfo<F> {
    /// The step actually taken: the requested step for fixed-step methods,
    /// at most the requested step for adaptive ones.
    pub h: F,
    /// The step the method suggests next (the step taken for fixed-step
    /// methods).
    pub h_next: F,
    /// Trial steps rejected by error control before this step was accepted.
    pub rejected: u32,
    /// Derivative evaluations spent on this step (including rejected trials
    /// and Jacobian columns).
    pub evaluations: u32,
}

impl<F: Copy> StepInfo<F> {
    /// A step of a fixed-step method: `h` taken and suggested next, nothing
    /// rejected.
    pub(crate) fn fixed(h: F, evaluations: u32) -> Self {
        Self {
            h,
            h_next: h,
            rejected: 0,
            evaluations,
        }
    }
}

/// What [`Stepper::step`] returns for a model `M`.
pub type StepResult<M> = Result<StepInfo<<M as Model>::Float>, IntegrationError>;

/// A one-step (or multistep) integrator for a [`Model`].
///
/// Implement it to plug your own method into the [`run`](crate::run())
/// driver. Contract: `step` advances `x` from `t` to `t + info.h`, never
/// allocates, and on error leaves `x` unchanged.
pub trait Stepper<M: Model> {
    /// Advances `x` from time `t` by the step `h` (adaptive methods: by at
    /// most `h`, see [`StepInfo::h`]).
    ///
    /// # Errors
    /// Any [`IntegrationError`] the method can detect; `x` is left unchanged.
    fn step(&mut self, model: &mut M, t: M::Float, x: &mut M::State, h: M::Float) -> StepResult<M>;

    /// Total derivative evaluations since the stepper was created.
    fn evaluations(&self) -> u64;

    /// Forgets anything carried from step to step (derivative history,
    /// first-same-as-last stage). Call it after changing the model's
    /// parameters or inputs discontinuously, or the state by hand. Steppers
    /// also notice a changed state or time on their own.
    fn reset(&mut self);

    /// `true` if the method chooses its own step size (the driver then
    /// treats the run's step as the first trial step).
    fn is_adaptive(&self) -> bool {
        false
    }

    /// `true` if the method has its own continuous extension of the last
    /// step ([`Stepper::dense_output`]); the run driver then locates events
    /// on it. Without one (the default) the driver interpolates the step
    /// with a Hermite cubic from the derivatives at its ends.
    fn has_dense_output(&self) -> bool {
        false
    }

    /// Writes the solution at `t` inside the last accepted step into `out`
    /// from the method's continuous extension.
    ///
    /// # Errors
    /// [`IntegrationError::OutsideLastStep`] if `t` is not inside the last
    /// step, or the method has no dense output (the default).
    fn dense_output(&self, t: M::Float, out: &mut M::State) -> Result<(), IntegrationError> {
        let _ = out;
        let t = crate::Float::to_f64(t);
        Err(IntegrationError::OutsideLastStep {
            t,
            start: f64::NAN,
            end: f64::NAN,
        })
    }

    /// The method's name, for reports.
    fn name(&self) -> &'static str;

    /// The method's order of accuracy (global error ∝ hᵒʳᵈᵉʳ).
    fn order(&self) -> u32;
}

impl<M: Model, S: Stepper<M> + ?Sized> Stepper<M> for &mut S {
    fn step(&mut self, model: &mut M, t: M::Float, x: &mut M::State, h: M::Float) -> StepResult<M> {
        (**self).step(model, t, x, h)
    }
    fn evaluations(&self) -> u64 {
        (**self).evaluations()
    }
    fn reset(&mut self) {
        (**self).reset()
    }
    fn is_adaptive(&self) -> bool {
        (**self).is_adaptive()
    }
    fn has_dense_output(&self) -> bool {
        (**self).has_dense_output()
    }
    fn dense_output(&self, t: M::Float, out: &mut M::State) -> Result<(), IntegrationError> {
        (**self).dense_output(t, out)
    }
    fn name(&self) -> &'static str {
        (**self).name()
    }
    fn order(&self) -> u32 {
        (**self).order()
    }
}
