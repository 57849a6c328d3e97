//! The integrator of a simulation study, chosen by value ([`Method`]) so
//! a study can be described (and sent from Python) as data.

use crate::integrate::{
    AbmOrder, AdamsBashforthMoulton, DopriSettings, DormandPrince, Euler, Heun, Rk4, StepResult,
};
use crate::{Float, IntegrationError, Model, Stepper};

/// The integration method of a [`Simulate`](super::Simulate) task (see
/// [`integrate`](crate::integrate) for what each is for). Stiff models
/// (SDIRK3, whose workspace size is a constant of the model) run through a
/// [`Custom`](super::Custom) task.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Forward Euler (fixed step).
    Euler,
    /// Heun's method (fixed step).
    Heun,
    /// Classic Runge–Kutta 4 (fixed step).
    Rk4,
    /// Adams–Bashforth–Moulton of order 2 or 4 (fixed step).
    AdamsBashforthMoulton(AbmOrder),
    /// Dormand–Prince 5(4) with these tolerances (adaptive; the run's step
    /// is the first trial step).
    DormandPrince {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance.
        atol: f64,
    },
}

impl Method {
    /// Checks the method's settings.
    ///
    /// # Errors
    /// [`IntegrationError::InvalidSettings`] naming the bad tolerance.
    pub fn validate(&self) -> Result<(), IntegrationError> {
        match *self {
            Method::DormandPrince { rtol, atol } => DopriSettings::new(rtol, atol).validate(),
            _ => Ok(()),
        }
    }

    /// A new stepper of this method for `M` (zeroed workspaces, no
    /// allocation).
    ///
    /// # Errors
    /// As [`Method::validate`].
    pub fn stepper<M: Model>(&self) -> Result<MethodStepper<M>, IntegrationError> {
        Ok(match *self {
            Method::Euler => MethodStepper::Euler(Euler::new()),
            Method::Heun => MethodStepper::Heun(Heun::new()),
            Method::Rk4 => MethodStepper::Rk4(Rk4::new()),
            Method::AdamsBashforthMoulton(order) => {
                MethodStepper::Abm(AdamsBashforthMoulton::new(order))
            }
            Method::DormandPrince { rtol, atol } => {
                let f = M::Float::from_f64;
                MethodStepper::DormandPrince(DormandPrince::with_tolerances(f(rtol), f(atol))?)
            }
        })
    }
}

/// A stepper of any [`Method`]: one type for the run driver whatever the
/// method (a `match` per call, static dispatch, no allocation).
#[allow(clippy::large_enum_variant)] // lives on a worker's stack, once
pub enum MethodStepper<M: Model> {
    /// [`Method::Euler`].
    Euler(Euler<M>),
    /// [`Method::Heun`].
    Heun(Heun<M>),
    /// [`Method::Rk4`].
    Rk4(Rk4<M>),
    /// [`Method::AdamsBashforthMoulton`].
    Abm(AdamsBashforthMoulton<M>),
    /// [`Method::DormandPrince`].
    DormandPrince(DormandPrince<M>),
}

/// `$body` with `$s` bound to the stepper inside, whatever the method.
macro_rules! each_method {
    ($stepper:expr, $s:ident => $body:expr) => {
        match $stepper {
            MethodStepper::Euler($s) => $body,
            MethodStepper::Heun($s) => $body,
            MethodStepper::Rk4($s) => $body,
            MethodStepper::Abm($s) => $body,
            MethodStepper::DormandPrince($s) => $body,
        }
    };
}

impl<M: Model> Stepper<M> for MethodStepper<M> {
    fn step(&mut self, model: &mut M, t: M::Float, x: &mut M::State, h: M::Float) -> StepResult<M> {
        each_method!(self, s => s.step(model, t, x, h))
    }
    fn evaluations(&self) -> u64 {
        each_method!(self, s => s.evaluations())
    }
    fn reset(&mut self) {
        each_method!(self, s => s.reset())
    }
    fn is_adaptive(&self) -> bool {
        each_method!(self, s => s.is_adaptive())
    }
    fn has_dense_output(&self) -> bool {
        each_method!(self, s => s.has_dense_output())
    }
    fn dense_output(&self, t: M::Float, out: &mut M::State) -> Result<(), IntegrationError> {
        each_method!(self, s => s.dense_output(t, out))
    }
    fn name(&self) -> &'static str {
        each_method!(self, s => s.name())
    }
    fn order(&self) -> u32 {
        each_method!(self, s => s.order())
    }
}
