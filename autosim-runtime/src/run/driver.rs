//! The loop state of a run: time, step bookkeeping, output emission, and
//! advancing to a target time with a fixed-step or adaptive method
//! (shared by [`run`](super::run()) and [`run_sampled`](super::run_sampled)).

use super::MAX_RECORDED_INPUTS;

use super::{Observer, RunError, RunSettings, RunSummary};
use crate::error::{check_finite_outputs, check_finite_parameters};
use crate::integrate::Stepper;
use crate::{Float, IntegrationError, Model, StateArray, check_finite};

/// The loop state of one run.
pub(super) struct Driver<M: Model> {
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
    /// Checks the settings and the state, assembles it, and starts the
    /// bookkeeping.
    pub(super) fn begin<S: Stepper<M> + ?Sized>(
        model: &mut M,
        stepper: &S,
        x: &mut M::State,
        settings: &RunSettings<M::Float>,
    ) -> Result<Driver<M>, IntegrationError> {
        settings.validate()?;
        check_finite::<M>(settings.start, x)?;
        check_finite_parameters(model, settings.start)?;
        model
            .assemble(settings.start, x)
            .map_err(|error| IntegrationError::Model {
                t: settings.start.to_f64(),
                error,
            })?;
        Ok(Driver {
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
        })
    }

    /// The summary at the end.
    pub(super) fn finish<S: Stepper<M> + ?Sized>(mut self, stepper: &S) -> RunSummary<M::Float> {
        self.summary.evaluations = stepper.evaluations() - self.evals_at_start;
        self.summary.end_time = self.t;
        self.summary
    }

    /// The time reached.
    pub(super) fn time(&self) -> M::Float {
        self.t
    }

    /// Advances to exactly `target` with `stepper` (fixed steps of at most
    /// `step`, or adaptive steps landing on it).
    pub(super) fn advance<S: Stepper<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &mut S,
        x: &mut M::State,
        target: M::Float,
        step: M::Float,
    ) -> Result<(), IntegrationError> {
        if stepper.is_adaptive() {
            self.advance_adaptive(model, stepper, x, target)
        } else {
            self.advance_fixed(model, stepper, x, target, step)
        }
    }

    /// The outputs at the current time (kept for the next emission).
    pub(super) fn outputs(
        &mut self,
        model: &mut M,
        x: &M::State,
    ) -> Result<&M::Outputs, IntegrationError> {
        let t = self.t;
        model
            .outputs(t, x, &mut self.y)
            .map_err(|error| IntegrationError::Model {
                t: t.to_f64(),
                error,
            })?;
        check_finite_outputs::<M>(t, &self.y)?;
        Ok(&self.y)
    }

    pub(super) fn emit<O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        x: &M::State,
        observer: &mut O,
    ) -> Result<(), RunError<O::Error>> {
        let t = self.t;
        self.outputs(model, x)?;
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
pub(super) fn ceil_count(v: f64) -> u64 {
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
