//! The run driver: integrate from a start time to a stop time and report
//! the state and outputs at every output time.

use core::convert::Infallible;
use core::fmt;

pub(crate) mod counts;
mod driver;
#[cfg(feature = "study")]
pub(crate) use driver::{AdaptiveTrial, adaptive_trial};
mod events;
#[cfg(feature = "study")]
pub(crate) mod grid;
mod sampled;
mod times;

pub use events::EventSettings;
pub use sampled::{Controller, run_sampled, run_sampled_at};
pub use times::run_at;

use crate::integrate::Stepper;
use crate::{EventRecord, Float, IntegrationError, Model};
use driver::Driver;
use events::Flow;

/// Times and steps of a run.
///
/// Outputs are reported at `start`, `start + k·output_interval`, and `stop`.
/// Fixed-step methods take the largest step not above `step` that divides
/// each output interval into equal steps (so outputs land on steps, and a
/// step that divides the interval is used exactly). Adaptive methods use
/// `step` as their first trial step and shorten steps to land on output times.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RunSettings<F> {
    /// Start time.
    pub start: F,
    /// Stop time (≥ `start`).
    pub stop: F,
    /// Integration step (fixed-step methods), or first trial step (adaptive).
    pub step: F,
    /// Time between outputs (> 0).
    pub output_interval: F,
    /// Steps allowed before the run stops with
    /// [`IntegrationError::TooManySteps`].
    pub max_steps: u64,
    /// How far the dependent coordinates of a model with position
    /// constraints may drift (relative to `1 + |q|`) before the driver
    /// projects the state back onto the constraints after a step (see
    /// [`Model::project`]); 0 (the default) projects any drift above
    /// rounding. Steppers that carry derivatives from step to step restart
    /// after a projection, so a looser tolerance saves evaluations.
    pub projection_tolerance: F,
    /// How events are located (models with
    /// [`Model::EVENT_INDICATORS`]; ignored for others).
    pub events: EventSettings<F>,
}

impl<F: Float> RunSettings<F> {
    /// Settings with no step limit.
    pub fn new(start: F, stop: F, step: F, output_interval: F) -> Self {
        Self {
            start,
            stop,
            step,
            output_interval,
            max_steps: u64::MAX,
            projection_tolerance: F::ZERO,
            events: EventSettings::default(),
        }
    }

    /// The same settings with these event settings.
    pub fn with_events(self, events: EventSettings<F>) -> Self {
        Self { events, ..self }
    }

    /// The same settings with a step limit (a guard against adaptive runs
    /// that crawl).
    pub fn with_max_steps(self, max_steps: u64) -> Self {
        Self { max_steps, ..self }
    }

    /// The same settings with a drift tolerance for the position
    /// constraints (see [`RunSettings::projection_tolerance`]).
    pub fn with_projection_tolerance(self, projection_tolerance: F) -> Self {
        Self {
            projection_tolerance,
            ..self
        }
    }

    /// Output intervals from start to stop (the last may be shorter).
    pub(crate) fn output_count(&self) -> u64 {
        let scale = self.stop.abs().max(self.start.abs());
        counts::step_count(self.stop - self.start, self.output_interval, scale)
    }

    /// The end of output interval `k` (1 to [`output_count`](Self::output_count)):
    /// `start + k·output_interval`, and exactly `stop` for the last.
    pub(crate) fn output_time(&self, k: u64) -> F {
        if k == self.output_count() {
            self.stop
        } else {
            self.start + F::from_f64(k as f64) * self.output_interval
        }
    }

    /// Checks the settings, naming the first wrong one.
    pub fn validate(&self) -> Result<(), IntegrationError> {
        let bad = |reason| Err(IntegrationError::InvalidSettings { reason });
        if !self.start.is_finite() || !self.stop.is_finite() {
            return bad("start and stop must be finite");
        }
        let ordered = self.stop >= self.start;
        if !ordered {
            return bad("stop must not be before start");
        }
        if !(self.step > F::ZERO && self.step.is_finite()) {
            return bad("step must be positive and finite");
        }
        if !(self.output_interval > F::ZERO && self.output_interval.is_finite()) {
            return bad("output_interval must be positive and finite");
        }
        if !(self.projection_tolerance >= F::ZERO && self.projection_tolerance.is_finite()) {
            return bad("projection_tolerance must be finite and not negative");
        }
        self.events.validate()
    }
}

/// What a finished run did.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RunSummary<F> {
    /// Accepted steps.
    pub steps: u64,
    /// Trial steps rejected by error control (adaptive methods).
    pub rejected_steps: u64,
    /// Derivative evaluations made by the stepper during the run.
    pub evaluations: u64,
    /// Output times reported to the observer.
    pub outputs: u64,
    /// Time reached (the stop time).
    pub end_time: F,
    /// Smallest accepted step (zero if no step was taken).
    pub min_step: F,
    /// Largest accepted step (zero if no step was taken).
    pub max_step: F,
    /// Events that fired (each reported to the observer's
    /// [`Observer::observe_event`]).
    pub events: u64,
    /// The terminal event that stopped the run before its stop time (an
    /// index into [`Model::EVENT_INDICATORS`]), if one did.
    pub terminal_event: Option<usize>,
    /// The step an adaptive method would try next (its last suggestion:
    /// where a run continuing this one starts); `step` for fixed-step
    /// methods.
    pub next_step: F,
}

/// Receives the time, state and outputs at every output time of a
/// [`run`].
///
/// Closures `FnMut(t, &x, &y)` are observers that cannot fail; implement
/// the trait for a type that can (a file writer) and return its error to
/// stop the run.
pub trait Observer<M: Model> {
    /// Why the observer could not take the output.
    type Error;
    /// Called at every output time, in time order.
    ///
    /// # Errors
    /// Any error of the observer; the run stops and returns it.
    fn observe(&mut self, t: M::Float, x: &M::State, y: &M::Outputs) -> Result<(), Self::Error>;

    /// Called just before [`Observer::observe`] with the model's inputs at
    /// that time ([`Model::INPUT_NAMES`] order; the first
    /// [`MAX_RECORDED_INPUTS`]). The default ignores them; the CSV writer
    /// and the recording keep them as columns.
    ///
    /// # Errors
    /// Any error of the observer; the run stops and returns it.
    fn observe_inputs(&mut self, inputs: &[M::Float]) -> Result<(), Self::Error> {
        let _ = inputs;
        Ok(())
    }

    /// Called just before [`Observer::observe`] with the model's discrete
    /// variables at that time ([`Model::DISCRETE_NAMES`] order; the first
    /// [`MAX_DISCRETE`](crate::event::MAX_DISCRETE)). The default ignores
    /// them; the CSV writer and the recording keep them as columns.
    ///
    /// # Errors
    /// Any error of the observer; the run stops and returns it.
    fn observe_discrete(&mut self, values: &[M::Float]) -> Result<(), Self::Error> {
        let _ = values;
        Ok(())
    }

    /// Called at every event, in time order, with the instant and the
    /// state, discrete variables and outputs before and after its action.
    /// The default ignores it; the CSV writer writes both as rows, the
    /// recording keeps them.
    ///
    /// # Errors
    /// Any error of the observer; the run stops and returns it.
    fn observe_event(&mut self, event: &EventRecord<'_, M>) -> Result<(), Self::Error> {
        let _ = event;
        Ok(())
    }
}

/// How many inputs the run driver passes to [`Observer::observe_inputs`].
pub const MAX_RECORDED_INPUTS: usize = 64;

impl<M: Model, C: FnMut(M::Float, &M::State, &M::Outputs)> Observer<M> for C {
    type Error = Infallible;
    fn observe(&mut self, t: M::Float, x: &M::State, y: &M::Outputs) -> Result<(), Infallible> {
        self(t, x, y);
        Ok(())
    }
}

/// Why a [`run`] stopped early.
#[derive(Clone, Debug, PartialEq)]
pub enum RunError<E> {
    /// The integration failed (non-finite state, step-size underflow,
    /// failed Newton iteration, model error, bad settings, step limit).
    Integration(IntegrationError),
    /// The observer failed at output time `t`.
    Observer {
        /// The output time.
        t: f64,
        /// The observer's error.
        error: E,
    },
}

impl<E> From<IntegrationError> for RunError<E> {
    fn from(e: IntegrationError) -> Self {
        RunError::Integration(e)
    }
}

impl From<RunError<Infallible>> for IntegrationError {
    fn from(e: RunError<Infallible>) -> Self {
        match e {
            RunError::Integration(e) => e,
            RunError::Observer { error, .. } => match error {},
        }
    }
}

impl<E: fmt::Display> fmt::Display for RunError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RunError::Integration(e) => e.fmt(f),
            RunError::Observer { t, error } => write!(f, "output at t = {t} failed: {error}"),
        }
    }
}

impl<E: core::error::Error + 'static> core::error::Error for RunError<E> {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            RunError::Integration(e) => Some(e),
            RunError::Observer { error, .. } => Some(error),
        }
    }
}

/// Integrates `model` from `settings.start` to `settings.stop` with
/// `stepper`, starting from `x` (which ends holding the final state), and
/// calls `observer` with the time, state and outputs at the start, at every
/// output time, and at the stop time.
///
/// Use it for any whole simulation; own the loop with
/// [`Stepper::step`] only when something must happen between steps. The
/// driver itself never allocates.
///
/// A model with position constraints is assembled first
/// ([`Model::assemble`]: the dependent coordinates solved for the others)
/// and projected back onto its constraints after every accepted step
/// ([`Model::project`], within [`RunSettings::projection_tolerance`]); for
/// other models both do nothing. Own the loop? Call them yourself.
///
/// A model with events ([`Model::EVENT_INDICATORS`]) has its indicators
/// evaluated at the start; after every step they are scanned on the step's
/// interpolant, and at the first crossing (located as
/// [`EventSettings`] says) the step is cut there: the state moves to the
/// crossing, the event's action runs (and any event it causes at the same
/// instant), the observer's [`Observer::observe_event`] sees it, and the
/// stepper restarts from the event ([`Stepper::reset`]: no derivative
/// history crosses it). A fixed-step method then takes one shorter step
/// back onto its grid (`start + k·step`, or the equal steps of an output
/// interval), so outputs stay where they were. A terminal event ends the
/// run at its instant with one last output there
/// ([`RunSummary::terminal_event`]).
///
/// # Errors
/// [`RunError::Integration`] with the first [`IntegrationError`]
/// ([`IntegrationError::Zeno`] when events chatter; a
/// non-finite state names the time and the state, checked after every
/// step; `x` then holds the last good state; a non-finite output names the
/// time and the output, checked at every output time; a non-finite
/// derivative of a generated model is an [`IntegrationError::Model`] with
/// [`ModelError::NonFiniteDerivative`](crate::ModelError::NonFiniteDerivative)),
/// or [`RunError::Observer`] if the observer failed.
pub fn run<M, S, O>(
    model: &mut M,
    stepper: &mut S,
    x: &mut M::State,
    settings: &RunSettings<M::Float>,
    observer: &mut O,
) -> Result<RunSummary<M::Float>, RunError<O::Error>>
where
    M: Model,
    S: Stepper<M> + ?Sized,
    O: Observer<M> + ?Sized,
{
    let mut driver = Driver::begin(model, stepper, x, settings, observer)?;
    driver.emit(model, x, observer)?;
    let intervals = settings.output_count();
    for k in 1..=intervals {
        let t_out = settings.output_time(k);
        let flow = driver.advance(model, stepper, x, t_out, settings.step, observer)?;
        driver.emit(model, x, observer)?;
        if flow == Flow::Stopped {
            break;
        }
    }
    Ok(driver.finish(stepper))
}
