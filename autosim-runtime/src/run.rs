//! The run driver: integrate from a start time to a stop time and report
//! the state and outputs at every output time.

use core::convert::Infallible;
use core::fmt;

use crate::integrate::Stepper;
use crate::{Float, IntegrationError, Model, StateArray, check_finite};

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
        }
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
        Ok(())
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
/// # Errors
/// [`RunError::Integration`] with the first [`IntegrationError`] (a
/// non-finite state names the time and the state; `x` then holds the last
/// good state), or [`RunError::Observer`] if the observer failed.
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
    settings.validate()?;
    check_finite::<M>(settings.start, x)?;
    model
        .assemble(settings.start, x)
        .map_err(|error| IntegrationError::Model {
            t: settings.start.to_f64(),
            error,
        })?;
    let mut driver = Driver {
        evals_at_start: stepper.evaluations(),
        summary: RunSummary {
            steps: 0,
            rejected_steps: 0,
            evaluations: 0,
            outputs: 0,
            end_time: settings.start,
            min_step: M::Float::ZERO,
            max_step: M::Float::ZERO,
        },
        t: settings.start,
        h: settings.step,
        y: M::Outputs::zeros(),
        max_steps: settings.max_steps,
        projection_tolerance: settings.projection_tolerance,
        start: settings.start,
        fixed_steps: 0,
    };
    driver.emit(model, x, observer)?;
    let span = settings.stop - settings.start;
    let intervals = ceil_count((span / settings.output_interval).to_f64());
    for k in 1..=intervals {
        let t_out = if k == intervals {
            settings.stop
        } else {
            settings.start + M::Float::from_f64(k as f64) * settings.output_interval
        };
        if stepper.is_adaptive() {
            driver.advance_adaptive(model, stepper, x, t_out)?;
        } else {
            driver.advance_fixed(model, stepper, x, t_out, settings.step)?;
        }
        driver.emit(model, x, observer)?;
    }
    driver.summary.evaluations = stepper.evaluations() - driver.evals_at_start;
    driver.summary.end_time = driver.t;
    Ok(driver.summary)
}

/// The loop state of one run.
struct Driver<M: Model> {
    evals_at_start: u64,
    summary: RunSummary<M::Float>,
    t: M::Float,
    /// Next trial step of an adaptive method.
    h: M::Float,
    y: M::Outputs,
    max_steps: u64,
    /// Drift allowed before projecting onto the position constraints.
    projection_tolerance: M::Float,
    /// Start time of the run.
    start: M::Float,
    /// Fixed steps of exactly `step` taken since the start.
    fixed_steps: u64,
}

impl<M: Model> Driver<M> {
    fn emit<O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        x: &M::State,
        observer: &mut O,
    ) -> Result<(), RunError<O::Error>> {
        let t = self.t;
        model
            .outputs(t, x, &mut self.y)
            .map_err(|error| IntegrationError::Model {
                t: t.to_f64(),
                error,
            })?;
        let mut inputs = [M::Float::ZERO; MAX_RECORDED_INPUTS];
        let inputs = &mut inputs[..M::INPUT_NAMES.len().min(MAX_RECORDED_INPUTS)];
        model.input_values(inputs);
        let failed = |error| RunError::Observer {
            t: t.to_f64(),
            error,
        };
        observer.observe_inputs(inputs).map_err(failed)?;
        observer
            .observe(t, x, &self.y)
            .map_err(|error| RunError::Observer {
                t: t.to_f64(),
                error,
            })?;
        self.summary.outputs += 1;
        Ok(())
    }

    /// Fails if the step limit is reached (called before each step).
    fn check_limit(&self) -> Result<(), IntegrationError> {
        if self.summary.steps >= self.max_steps {
            return Err(IntegrationError::TooManySteps {
                t: self.t.to_f64(),
                steps: self.summary.steps,
            });
        }
        Ok(())
    }

    /// Projects `x` onto the position constraints after a step at `self.t`.
    fn project(&self, model: &mut M, x: &mut M::State) -> Result<(), IntegrationError> {
        model
            .project(self.t, x, self.projection_tolerance)
            .map(|_| ())
            .map_err(|error| IntegrationError::Model {
                t: self.t.to_f64(),
                error,
            })
    }

    /// Books an accepted step of length `h`.
    fn count_step(&mut self, h: M::Float, rejected: u32) {
        let s = &mut self.summary;
        if s.steps == 0 {
            s.min_step = h;
            s.max_step = h;
        } else {
            s.min_step = s.min_step.min(h);
            s.max_step = s.max_step.max(h);
        }
        s.steps += 1;
        s.rejected_steps += u64::from(rejected);
    }

    /// Equal fixed steps from `self.t` to `t_out`.
    fn advance_fixed<S: Stepper<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &mut S,
        x: &mut M::State,
        t_out: M::Float,
        step: M::Float,
    ) -> Result<(), IntegrationError> {
        let t0 = self.t;
        let interval = t_out - t0;
        let n = ceil_count((interval / step).to_f64()).max(1);
        // When the output interval holds a whole number of steps, step
        // exactly `step` at the times `start + k step` (k counted from the
        // start), as a hand-written loop would: user functions that keep
        // state see the same times.
        let whole = ((M::Float::from_f64(n as f64) * step - interval).abs()
            <= M::Float::from_f64(64.0) * M::Float::EPSILON * interval.abs().max(step.abs()))
            && self.t == self.start + M::Float::from_f64(self.fixed_steps as f64) * step;
        if whole {
            for _ in 0..n {
                self.check_limit()?;
                stepper.step(model, self.t, x, step)?;
                self.fixed_steps += 1;
                self.t = self.start + M::Float::from_f64(self.fixed_steps as f64) * step;
                self.project(model, x)?;
                self.count_step(step, 0);
            }
            return Ok(());
        }
        let h = interval / M::Float::from_f64(n as f64);
        for j in 1..=n {
            self.check_limit()?;
            stepper.step(model, self.t, x, h)?;
            self.t = if j == n {
                t_out
            } else {
                t0 + M::Float::from_f64(j as f64) * h
            };
            self.project(model, x)?;
            self.count_step(h, 0);
        }
        Ok(())
    }

    /// Steps of an adaptive method from `self.t` to exactly `t_out`.
    fn advance_adaptive<S: Stepper<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &mut S,
        x: &mut M::State,
        t_out: M::Float,
    ) -> Result<(), IntegrationError> {
        let sixteen_eps = M::Float::from_f64(16.0) * M::Float::EPSILON;
        loop {
            let remaining = t_out - self.t;
            if remaining <= sixteen_eps * t_out.abs().max(self.t.abs()) {
                // Rounding only: we are there.
                self.t = t_out;
                return Ok(());
            }
            // Land on the output time, stretching the step by up to 1 % rather
            // than leaving a sliver for the next step.
            let stretch = M::Float::from_f64(1.01);
            let lands = self.h * stretch >= remaining;
            let h_try = if lands { remaining } else { self.h };
            self.check_limit()?;
            let info = stepper.step(model, self.t, x, h_try)?;
            let landed = lands && info.h == h_try;
            self.t = if landed { t_out } else { self.t + info.h };
            self.h = if landed && info.rejected == 0 {
                // A step shortened to hit the output says nothing against
                // the longer step used before it.
                info.h_next.max(self.h)
            } else {
                info.h_next
            };
            self.project(model, x)?;
            self.count_step(info.h, info.rejected);
            if landed {
                return Ok(());
            }
        }
    }
}

/// ⌈v⌉ as a count, treating values within 1e-9 (relative) above an integer
/// as that integer (so 1.0000000000002 intervals are 1, not 2). Zero for
/// non-positive or NaN values; saturates for huge ones.
fn ceil_count(v: f64) -> u64 {
    if v.is_nan() || v <= 0.0 {
        return 0;
    }
    let v = v - 1e-9 * v.max(1.0);
    if v.is_nan() || v <= 0.0 {
        return 0;
    }
    // `as` saturates; the comparison rounds up a fractional part.
    let i = v as u64;
    if (i as f64) < v {
        i.saturating_add(1)
    } else {
        i
    }
}

#[cfg(test)]
mod tests {
    use super::ceil_count;

    #[test]
    fn ceil_count_rounds_up_but_forgives_rounding_noise() {
        assert_eq!(ceil_count(0.0), 0);
        assert_eq!(ceil_count(-3.0), 0);
        assert_eq!(ceil_count(f64::NAN), 0);
        assert_eq!(ceil_count(1.0), 1);
        assert_eq!(ceil_count(1.0 + 1e-13), 1);
        assert_eq!(ceil_count(1.01), 2);
        assert_eq!(ceil_count(10.0 / 0.1), 100);
        assert_eq!(ceil_count(2.5), 3);
        assert_eq!(ceil_count(1e300), u64::MAX);
    }
}
