//! Why an integration step or a run stopped.

use crate::ModelError;

/// Why a step (or a run of steps) could not continue.
///
/// Every integrator and the [`run`](crate::run()) driver report failures with
/// this type; times and steps are converted to `f64` so the error reads the
/// same for `f32` and `f64` models. When a stepper returns an error it leaves
/// the state it was given unchanged (the start-of-step value), so the caller
/// can inspect or save it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum IntegrationError {
    /// A state became NaN or infinite. `index` and `name` identify the first
    /// such state (in [`Model::STATE_NAMES`](crate::Model::STATE_NAMES)
    /// order); `t` is the time the step would have reached, or the time of
    /// the stage whose state overflowed (the model cannot evaluate a
    /// non-finite state; a generated model would report a singular mass
    /// matrix, which is not the cause).
    NonFinite {
        /// Time at the end of the step (or of the stage) that produced the value.
        t: f64,
        /// Index of the first non-finite state.
        index: usize,
        /// Name of that state (`"?"` if the model lists fewer names than states).
        name: &'static str,
    },
    /// An output became NaN or infinite at a finite state (the run driver
    /// checks the outputs at every output time). `index` and `name`
    /// identify the first such output (in
    /// [`Model::OUTPUT_NAMES`](crate::Model::OUTPUT_NAMES) order).
    NonFiniteOutput {
        /// Time of the output.
        t: f64,
        /// Index of the first non-finite output.
        index: usize,
        /// Name of that output (`"?"` if the model lists fewer names).
        name: &'static str,
    },
    /// A parameter or an input is NaN or infinite at the start of a run
    /// (the run driver checks them before the first step: a NaN mass would
    /// otherwise be reported as a singular mass matrix).
    NonFiniteParameter {
        /// Time of the start.
        t: f64,
        /// Name of the first such parameter or input.
        name: &'static str,
        /// `true` for an input, `false` for a parameter.
        input: bool,
    },
    /// An adaptive integrator needed a step smaller than its minimum step to
    /// meet its tolerances (or to get finite values): the solution is
    /// probably singular near `t`, or the tolerances are too tight for the
    /// float type.
    StepSizeUnderflow {
        /// Time of the step start.
        t: f64,
        /// The step that would have been needed.
        h: f64,
    },
    /// The Newton iteration of an implicit method did not converge (it
    /// diverged, produced non-finite values, or ran out of iterations).
    /// A smaller step usually helps.
    NewtonFailed {
        /// Time of the step start.
        t: f64,
        /// The step being taken.
        h: f64,
        /// Newton iterations done for the stage that failed.
        iterations: u32,
    },
    /// The Newton matrix `I - h·γ·J` of an implicit method is singular (to
    /// working precision) or its Jacobian contains non-finite values.
    SingularNewtonMatrix {
        /// Time of the step start.
        t: f64,
        /// The step being taken.
        h: f64,
    },
    /// The model could not evaluate its derivatives or outputs.
    Model {
        /// Time of the evaluation that failed.
        t: f64,
        /// What the model reported.
        error: ModelError,
    },
    /// A run or a stepper was configured with settings that cannot work
    /// (a non-positive step or tolerance, a stop time before the start, ...).
    InvalidSettings {
        /// What is wrong, naming the setting.
        reason: &'static str,
    },
    /// Dense output was asked for a time outside the last accepted step
    /// (or before any step was taken).
    OutsideLastStep {
        /// The requested time.
        t: f64,
        /// Start of the last step.
        start: f64,
        /// End of the last step.
        end: f64,
    },
    /// Events chattered (Zeno behaviour): more than
    /// [`EventSettings::zeno_events`](crate::run::EventSettings::zeno_events)
    /// events followed each other, each within
    /// [`EventSettings::zeno_interval`](crate::run::EventSettings::zeno_interval)
    /// of the one before, as a bouncing ball without a minimum rebound speed
    /// does before it comes to rest; or (`unresolved`) a bounce became too
    /// small to resolve in time before that. Fix the model (e.g. stop the
    /// bounces below a minimum speed: a second event, or a condition in the
    /// action) or, if the events are real and resolved, raise the limits.
    Zeno {
        /// Time of the last event.
        t: f64,
        /// The event that fired last.
        name: &'static str,
        /// Events in the chain.
        events: u32,
        /// The chain ended in a bounce too small to resolve (its return
        /// within the rounding of the time, or its crossing in the
        /// rounding of the indicator), not at the limit of its length.
        unresolved: bool,
    },
    /// The run reached its step limit before the stop time.
    TooManySteps {
        /// Time reached.
        t: f64,
        /// Steps taken.
        steps: u64,
        /// The state of largest magnitude then: a diverging motion (a
        /// controller that destabilizes, an unbounded spin) shows here.
        largest: &'static str,
        /// Its value.
        value: f64,
    },
}

impl IntegrationError {
    /// The time at which the failure happened, if it has one.
    pub fn time(&self) -> Option<f64> {
        match *self {
            IntegrationError::NonFinite { t, .. }
            | IntegrationError::NonFiniteOutput { t, .. }
            | IntegrationError::NonFiniteParameter { t, .. }
            | IntegrationError::StepSizeUnderflow { t, .. }
            | IntegrationError::NewtonFailed { t, .. }
            | IntegrationError::SingularNewtonMatrix { t, .. }
            | IntegrationError::Model { t, .. }
            | IntegrationError::OutsideLastStep { t, .. }
            | IntegrationError::Zeno { t, .. }
            | IntegrationError::TooManySteps { t, .. } => Some(t),
            IntegrationError::InvalidSettings { .. } => None,
        }
    }
}

impl core::fmt::Display for IntegrationError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            IntegrationError::NonFinite { t, index, name } => write!(
                f,
                "state {name} (#{index}) became non-finite at t = {t}; try a smaller step or check the model"
            ),
            IntegrationError::NonFiniteOutput { t, index, name } => write!(
                f,
                "output {name} (#{index}) is not finite at t = {t} although the state is: the output divides by zero or calls a function outside its domain there"
            ),
            IntegrationError::NonFiniteParameter { t, name, input } => write!(
                f,
                "{} {name} is not finite at t = {t}: set it to a finite value",
                if *input { "input" } else { "parameter" }
            ),
            IntegrationError::StepSizeUnderflow { t, h } => write!(
                f,
                "step size underflow at t = {t}: step {h:e} is below the minimum step; the solution may be singular there, or the tolerances too tight"
            ),
            IntegrationError::NewtonFailed { t, h, iterations } => write!(
                f,
                "Newton iteration failed at t = {t} with step {h:e} after {iterations} iterations; try a smaller step"
            ),
            IntegrationError::SingularNewtonMatrix { t, h } => write!(
                f,
                "Newton matrix is singular or not finite at t = {t} with step {h:e}"
            ),
            IntegrationError::Model { t, error } => write!(f, "at t = {t}: {error}"),
            IntegrationError::InvalidSettings { reason } => {
                write!(f, "invalid integration settings: {reason}")
            }
            IntegrationError::OutsideLastStep { t, start, end } => write!(
                f,
                "cannot interpolate at t = {t}: outside the last step [{start}, {end}]"
            ),
            IntegrationError::Zeno {
                t,
                name,
                events,
                unresolved: true,
            } => write!(
                f,
                "events chatter at t = {t}: after {events} close events the next {name} is too small to resolve (its return within the rounding of the time or of the indicator); stop the chattering in the model (e.g. a minimum rebound speed)"
            ),
            IntegrationError::Zeno {
                t, name, events, ..
            } => write!(
                f,
                "events chatter at t = {t}: {events} events each within the Zeno interval of the one before, the last one {name}; stop the chattering in the model (e.g. a minimum rebound speed) or raise the limit (`zeno_events`)"
            ),
            IntegrationError::TooManySteps {
                t,
                steps,
                largest,
                value,
            } => write!(
                f,
                "stopped at t = {t} after {steps} steps (the step limit), the largest state {largest} = {value:e}; raise the limit or loosen the tolerances, or, if the motion diverges, end it sooner (a terminal event, `stop: true`, or a smaller step limit)"
            ),
        }
    }
}

impl core::error::Error for IntegrationError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        // `ModelError` implements `Error` only with `std`.
        #[cfg(feature = "std")]
        if let IntegrationError::Model { error, .. } = self {
            return Some(error);
        }
        None
    }
}

/// How many parameters and inputs the run driver checks at the start of a
/// run (the first ones, in name order; a stack buffer of this size).
pub const MAX_CHECKED_VALUES: usize = 128;

/// The first non-finite parameter, then input, of `model` as an
/// [`IntegrationError::NonFiniteParameter`] at time `t` (the run driver
/// checks them before the first step).
pub fn check_finite_parameters<M: crate::Model>(
    model: &M,
    t: M::Float,
) -> Result<(), IntegrationError> {
    use crate::Float;
    let mut buffer = [M::Float::ZERO; MAX_CHECKED_VALUES];
    let lists = [(M::PARAMETER_NAMES, false), (M::INPUT_NAMES, true)];
    for (names, input) in lists {
        let values = &mut buffer[..names.len().min(MAX_CHECKED_VALUES)];
        match input {
            false => model.parameter_values(values),
            true => model.input_values(values),
        }
        if let Some(k) = first_non_finite(values) {
            return Err(IntegrationError::NonFiniteParameter {
                t: t.to_f64(),
                name: names[k],
                input,
            });
        }
    }
    Ok(())
}

/// Returns the first non-finite output of `y` as an
/// [`IntegrationError::NonFiniteOutput`] at time `t` (the run driver checks
/// the outputs it reports).
pub fn check_finite_outputs<M: crate::Model>(
    t: M::Float,
    y: &M::Outputs,
) -> Result<(), IntegrationError> {
    use crate::Float;
    let Some(index) = first_non_finite(y.as_ref()) else {
        return Ok(());
    };
    Err(IntegrationError::NonFiniteOutput {
        t: t.to_f64(),
        index,
        name: M::OUTPUT_NAMES.get(index).copied().unwrap_or("?"),
    })
}

/// Returns the first non-finite state of `x` as an
/// [`IntegrationError::NonFinite`] at time `t`.
///
/// Steppers call this on every new state; call it yourself when you change a
/// state outside a stepper.
pub fn check_finite<M: crate::Model>(t: M::Float, x: &M::State) -> Result<(), IntegrationError> {
    use crate::Float;
    let Some(index) = first_non_finite(x.as_ref()) else {
        return Ok(());
    };
    Err(IntegrationError::NonFinite {
        t: t.to_f64(),
        index,
        name: M::STATE_NAMES.get(index).copied().unwrap_or("?"),
    })
}

/// The index of the first NaN or infinite value.
#[inline]
pub(crate) fn first_non_finite<F: crate::Float>(values: &[F]) -> Option<usize> {
    values.iter().position(|v| !v.is_finite())
}
