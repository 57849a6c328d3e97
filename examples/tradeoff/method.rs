//! The integrators under study and one integration run: a method at a step
//! (or, for Dormand–Prince, a tolerance) from an initial state to the end
//! time, what it cost and how it ended, and the tight reference runs.

use autosim::runtime::integrate::{
    AbmOrder, AdamsBashforthMoulton, DormandPrince, Euler, Heun, Rk4, Sdirk3, SdirkSettings,
};
use autosim::runtime::{Float, IntegrationError, Model, RunSettings, Stepper, run};

/// An integrator of the runtime, as the tables and plots name it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Method {
    Euler,
    Heun,
    Rk4,
    Abm2,
    Abm4,
    Dopri,
    Sdirk3,
}

impl Method {
    pub(crate) const ALL: [Method; 7] = [
        Method::Euler,
        Method::Heun,
        Method::Rk4,
        Method::Abm2,
        Method::Abm4,
        Method::Dopri,
        Method::Sdirk3,
    ];

    pub(crate) fn name(self) -> &'static str {
        match self {
            Method::Euler => "Euler",
            Method::Heun => "Heun",
            Method::Rk4 => "RK4",
            Method::Abm2 => "ABM2",
            Method::Abm4 => "ABM4",
            Method::Dopri => "DOPRI5",
            Method::Sdirk3 => "SDIRK3",
        }
    }

    /// Palette index of the method's lines (distinct, legible colours).
    pub(crate) fn color(self) -> usize {
        match self {
            Method::Euler => 0,
            Method::Heun => 1,
            Method::Rk4 => 3,
            Method::Abm2 => 4,
            Method::Abm4 => 5,
            Method::Dopri => 10,
            Method::Sdirk3 => 7,
        }
    }

    /// Evaluations per step, roughly (to skip runs over the budget).
    pub(crate) fn evaluations_per_step(self, states: usize) -> f64 {
        match self {
            Method::Euler => 1.0,
            Method::Heun | Method::Abm2 | Method::Abm4 => 2.0,
            Method::Rk4 => 4.0,
            Method::Dopri => 6.0,
            Method::Sdirk3 => 1.0 + states as f64 + 6.0,
        }
    }
}

/// The end of one run.
pub(crate) struct Outcome {
    pub(crate) x: Vec<f64>,
    pub(crate) steps: u64,
    pub(crate) rejected: u64,
    pub(crate) evaluations: u64,
    pub(crate) failure: Option<IntegrationError>,
}

/// Runs `stepper` from `x0` over [0, t_end] with one output at each end.
fn go<M, S, const N: usize>(
    model: &mut M,
    stepper: &mut S,
    x0: [M::Float; N],
    t_end: f64,
    step: f64,
) -> Outcome
where
    M: Model<State = [<M as Model>::Float; N]>,
    S: Stepper<M>,
{
    let f = <M::Float as Float>::from_f64;
    let settings = RunSettings::new(f(0.0), f(t_end), f(step), f(t_end)).with_max_steps(20_000_000);
    let mut x = x0;
    let result = run(model, stepper, &mut x, &settings, &mut |_, _: &_, _: &_| {});
    // The run's evaluations include those the driver makes for events (the
    // end-point derivatives of a fixed step's interpolant).
    let (steps, rejected, evaluations, failure) = match result {
        Ok(s) => (s.steps, s.rejected_steps, s.evaluations, None),
        Err(e) => (0, 0, stepper.evaluations(), Some(IntegrationError::from(e))),
    };
    Outcome {
        x: x.iter().map(|v| v.to_f64()).collect(),
        steps,
        rejected,
        evaluations,
        failure,
    }
}

/// One run of `method` at `setting` (a step or a tolerance).
pub(crate) fn integrate<M, const N: usize>(
    model: &mut M,
    method: Method,
    setting: f64,
    x0: [M::Float; N],
    t_end: f64,
) -> Outcome
where
    M: Model<State = [<M as Model>::Float; N]>,
{
    let f = <M::Float as Float>::from_f64;
    let abm = AdamsBashforthMoulton::new;
    match method {
        Method::Euler => go(model, &mut Euler::new(), x0, t_end, setting),
        Method::Heun => go(model, &mut Heun::new(), x0, t_end, setting),
        Method::Rk4 => go(model, &mut Rk4::new(), x0, t_end, setting),
        Method::Abm2 => go(model, &mut abm(AbmOrder::Two), x0, t_end, setting),
        Method::Abm4 => go(model, &mut abm(AbmOrder::Four), x0, t_end, setting),
        Method::Dopri => match DormandPrince::with_tolerances(f(setting), f(setting)) {
            Ok(mut dopri) => go(model, &mut dopri, x0, t_end, 1e-3),
            Err(e) => Outcome {
                x: Vec::new(),
                steps: 0,
                rejected: 0,
                evaluations: 0,
                failure: Some(e),
            },
        },
        Method::Sdirk3 => {
            let mut sdirk = Sdirk3::<M, N>::new(SdirkSettings::default());
            go(model, &mut sdirk, x0, t_end, setting)
        }
    }
}

/// A tight reference: Dormand–Prince at `tol` in f64.
pub(crate) fn reference<M, const N: usize>(
    mut model: M,
    x0: [f64; N],
    t_end: f64,
    tol: f64,
) -> Vec<f64>
where
    M: Model<Float = f64, State = [f64; N]>,
{
    let out = integrate(&mut model, Method::Dopri, tol, x0, t_end);
    if let Some(e) = out.failure {
        panic!("reference run of {} failed: {e}", M::NAME);
    }
    out.x
}

/// A failure in a few words.
pub(crate) fn short(e: &IntegrationError) -> String {
    match *e {
        IntegrationError::NonFinite { t, name, .. } => format!("non-finite {name} at t={t:.3}"),
        IntegrationError::StepSizeUnderflow { t, .. } => format!("step underflow at t={t:.3}"),
        IntegrationError::NewtonFailed { t, .. } => format!("Newton failed at t={t:.3}"),
        IntegrationError::SingularNewtonMatrix { t, .. } => {
            format!("singular Newton matrix at t={t:.3}")
        }
        IntegrationError::TooManySteps { t, .. } => format!("step limit at t={t:.3}"),
        IntegrationError::Model { t, error } => format!("model error at t={t:.3}: {error}"),
        ref other => other.to_string(),
    }
}
