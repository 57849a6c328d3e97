//! The loop state of a run: time, step bookkeeping, output emission, and
//! advancing to a target time with a fixed-step or adaptive method
//! (shared by [`run`](super::run()) and [`run_sampled`](super::run_sampled)).

use super::counts::{rounding, step_count};
use super::events::{Events, Flow};
use super::{MAX_RECORDED_INPUTS, Observer, RunError, RunSettings, RunSummary};
use crate::error::{check_finite_outputs, check_finite_parameters};
use crate::event::MAX_DISCRETE;
use crate::integrate::{StepInfo, Stepper};
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
    /// Fixed steps of exactly `step` taken since the start: the time is in
    /// `[start + fixed_steps·step, start + (fixed_steps + 1)·step)` (at the
    /// first, or after an event inside a step) while `on_grid` holds.
    fixed_steps: u64,
    on_grid: bool,
    /// The events of a model that has them.
    events: Option<Events<M>>,
}

impl<M: Model> Driver<M> {
    /// Checks the settings and the state, assembles it, evaluates the
    /// event indicators, and starts the bookkeeping.
    pub(super) fn begin<S: Stepper<M> + ?Sized, O: Observer<M> + ?Sized>(
        model: &mut M,
        stepper: &S,
        x: &mut M::State,
        settings: &RunSettings<M::Float>,
        observer: &mut O,
    ) -> Result<Driver<M>, RunError<O::Error>> {
        settings.validate()?;
        check_finite::<M>(settings.start, x)?;
        check_finite_parameters(model, settings.start)?;
        model
            .assemble(settings.start, x)
            .map_err(|error| IntegrationError::Model {
                t: settings.start.to_f64(),
                error,
            })?;
        let events = Events::new(settings.events, settings.start, settings.stop)?;
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
                events: 0,
                terminal_event: None,
                next_step: settings.step,
            },
            t: settings.start,
            h: settings.step,
            y: M::Outputs::zeros(),
            max_steps: settings.max_steps,
            projection_tolerance: settings.projection_tolerance,
            start: settings.start,
            fixed_steps: 0,
            on_grid: true,
            events,
        };
        // Nothing fires at the start (no sign is known before it): this
        // learns the indicators' signs.
        driver.settle(model, x, observer)?;
        Ok(driver)
    }

    /// The summary at the end.
    pub(super) fn finish<S: Stepper<M> + ?Sized>(mut self, stepper: &S) -> RunSummary<M::Float> {
        let (events, extra, terminal) = self
            .events
            .as_ref()
            .map_or((0, 0, None), |e| (e.count, e.evaluations, e.terminal));
        self.summary.evaluations = stepper.evaluations() - self.evals_at_start + extra;
        self.summary.end_time = self.t;
        self.summary.events = events;
        self.summary.terminal_event = terminal;
        self.summary.next_step = self.h;
        self.summary
    }

    /// The time reached.
    pub(super) fn time(&self) -> M::Float {
        self.t
    }

    /// After the model changed discontinuously at the current time (a
    /// sample set new inputs): the stepper restarts, and the events the
    /// change causes fire now.
    pub(super) fn restart<S: Stepper<M> + ?Sized, O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &mut S,
        x: &mut M::State,
        observer: &mut O,
    ) -> Result<Flow, RunError<O::Error>> {
        stepper.reset();
        if let Some(events) = &mut self.events {
            events.restart();
        }
        self.settle(model, x, observer)
    }

    /// The events at the current time whose indicators changed sign.
    fn settle<O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        x: &mut M::State,
        observer: &mut O,
    ) -> Result<Flow, RunError<O::Error>> {
        match &mut self.events {
            Some(events) => events.settle(model, self.t, x, None, observer),
            None => Ok(Flow::Continue),
        }
    }

    /// Advances to exactly `target` with `stepper` (fixed steps of at most
    /// `step`, or adaptive steps landing on it), handling the events on the
    /// way; stops early at a terminal event.
    pub(super) fn advance<S: Stepper<M> + ?Sized, O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &mut S,
        x: &mut M::State,
        target: M::Float,
        step: M::Float,
        observer: &mut O,
    ) -> Result<Flow, RunError<O::Error>> {
        if stepper.is_adaptive() {
            self.advance_adaptive(model, stepper, x, target, observer)
        } else {
            self.advance_fixed(model, stepper, x, target, step, observer)
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
        let failed = |error| RunError::Observer {
            t: t.to_f64(),
            error,
        };
        let mut inputs = [M::Float::ZERO; MAX_RECORDED_INPUTS];
        let inputs = &mut inputs[..M::INPUT_NAMES.len().min(MAX_RECORDED_INPUTS)];
        model.input_values(inputs);
        observer.observe_inputs(inputs).map_err(failed)?;
        if !M::DISCRETE_NAMES.is_empty() {
            let mut discrete = [M::Float::ZERO; MAX_DISCRETE];
            let discrete = &mut discrete[..M::DISCRETE_NAMES.len().min(MAX_DISCRETE)];
            model.discrete_values(discrete);
            observer.observe_discrete(discrete).map_err(failed)?;
        }
        observer.observe(t, x, &self.y).map_err(failed)?;
        self.summary.outputs += 1;
        Ok(())
    }

    /// Fails if the step limit is reached (called before each step at
    /// state `x`).
    fn check_limit(&self, x: &M::State) -> Result<(), IntegrationError> {
        if self.summary.steps >= self.max_steps {
            let (index, value) =
                x.as_ref()
                    .iter()
                    .map(|v| v.to_f64())
                    .enumerate()
                    .fold((0, 0.0), |big, (k, v)| {
                        if v.abs() > f64::abs(big.1) {
                            (k, v)
                        } else {
                            big
                        }
                    });
            return Err(IntegrationError::TooManySteps {
                t: self.t.to_f64(),
                steps: self.summary.steps,
                largest: M::STATE_NAMES.get(index).copied().unwrap_or("?"),
                value,
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

    /// One step of `h` from `self.t` ending at `t_end` (after which `x`
    /// is projected and the step booked), then the step's events: `None`
    /// if there was none (the time is then `t_end`), or what the first one
    /// (located, the time and state moved to it) left.
    #[allow(clippy::too_many_arguments)]
    fn step<S: Stepper<M> + ?Sized, O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &mut S,
        x: &mut M::State,
        h: M::Float,
        t_end: M::Float,
        observer: &mut O,
    ) -> Result<Option<Flow>, RunError<O::Error>> {
        self.check_limit(x)?;
        if let Some(events) = &mut self.events {
            events.before_step(model, stepper, self.t, x)?;
        }
        let info = stepper.step(model, self.t, x, h)?;
        self.t = t_end;
        self.project(model, x)?;
        self.count_step(info.h, info.rejected);
        self.after_step(model, stepper, x, observer)
    }

    /// Fixed steps from `self.t` to `t_out`: on the grid `start + k·step`
    /// when `t_out` is on it, otherwise equal steps; after an event inside
    /// a step, one shorter step back to where the step would have ended.
    fn advance_fixed<S: Stepper<M> + ?Sized, O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &mut S,
        x: &mut M::State,
        t_out: M::Float,
        step: M::Float,
        observer: &mut O,
    ) -> Result<Flow, RunError<O::Error>> {
        let span = t_out - self.start;
        let scale = t_out.abs().max(self.start.abs());
        let last = step_count(span, step, scale);
        // When the output time is a whole number of steps from the start,
        // step exactly `step` at the times `start + k step`, as a
        // hand-written loop would: user functions that keep state see the
        // same times.
        let whole = self.on_grid
            && (M::Float::from_f64(last as f64) * step - span).abs()
                <= rounding(span.abs().max(step.abs()), step);
        if whole {
            while self.fixed_steps < last {
                let next = self.start + M::Float::from_f64((self.fixed_steps + 1) as f64) * step;
                let grid = self.start + M::Float::from_f64(self.fixed_steps as f64) * step;
                if self.t >= next {
                    // An event at the very end of the step: it is done.
                    self.fixed_steps += 1;
                    continue;
                }
                let h = if self.t == grid { step } else { next - self.t };
                match self.step(model, stepper, x, h, next, observer)? {
                    None => self.fixed_steps += 1,
                    Some(Flow::Stopped) => return Ok(Flow::Stopped),
                    Some(Flow::Continue) => {}
                }
            }
            self.t = self.start + M::Float::from_f64(last as f64) * step;
            return Ok(Flow::Continue);
        }
        self.on_grid = false;
        loop {
            let t0 = self.t;
            let interval = t_out - t0;
            let scale = t_out.abs().max(t0.abs());
            if interval <= rounding(scale, step) {
                self.t = t_out;
                return Ok(Flow::Continue);
            }
            let n = step_count(interval, step, scale).max(1);
            let h = interval / M::Float::from_f64(n as f64);
            let mut restarted = false;
            for j in 1..=n {
                let t_end = if j == n {
                    t_out
                } else {
                    t0 + M::Float::from_f64(j as f64) * h
                };
                match self.step(model, stepper, x, h, t_end, observer)? {
                    None => {}
                    Some(Flow::Stopped) => return Ok(Flow::Stopped),
                    Some(Flow::Continue) => {
                        restarted = true;
                        break;
                    }
                }
            }
            if !restarted {
                return Ok(Flow::Continue);
            }
        }
    }

    /// Steps of an adaptive method from `self.t` to exactly `t_out`.
    fn advance_adaptive<S: Stepper<M> + ?Sized, O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &mut S,
        x: &mut M::State,
        t_out: M::Float,
        observer: &mut O,
    ) -> Result<Flow, RunError<O::Error>> {
        loop {
            let Some(trial) = adaptive_trial(self.t, t_out, self.h) else {
                // Rounding only: we are there.
                self.t = t_out;
                return Ok(Flow::Continue);
            };
            let t0 = self.t;
            self.check_limit(x)?;
            if let Some(events) = &mut self.events {
                events.before_step(model, stepper, t0, x)?;
            }
            let info = stepper.step(model, t0, x, trial.h)?;
            let landed;
            (self.t, self.h, landed) = trial.accepted(t0, self.h, &info);
            self.project(model, x)?;
            self.count_step(info.h, info.rejected);
            if let Some(flow) = self.after_step(model, stepper, x, observer)? {
                if flow == Flow::Stopped {
                    return Ok(flow);
                }
                continue;
            }
            if landed {
                return Ok(Flow::Continue);
            }
        }
    }

    /// The events of the step just taken (ending at `self.t`): `None` if
    /// there was none, or what the first one (located, the time and state
    /// moved to it) left.
    fn after_step<S: Stepper<M> + ?Sized, O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &mut S,
        x: &mut M::State,
        observer: &mut O,
    ) -> Result<Option<Flow>, RunError<O::Error>> {
        let Some(events) = &mut self.events else {
            return Ok(None);
        };
        let Some(crossing) = events.after_step(model, stepper, self.t, x)? else {
            return Ok(None);
        };
        *x = *events.located_state();
        self.t = crossing.t;
        stepper.reset();
        events.restart();
        events
            .settle(model, crossing.t, x, Some(crossing.index), observer)
            .map(Some)
    }
}

/// The next trial step of an adaptive run from `t` toward the output
/// time `t_out` (what [`Driver`] does, and a study's lockstep for each of
/// its cases).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AdaptiveTrial<F> {
    /// The step to try.
    pub(crate) h: F,
    /// The output time the step lands on if the stepper takes it whole.
    t_out: F,
    lands: bool,
}

/// The trial from `t` toward `t_out` with the run's step `h`: `None` if
/// `t` is there up to rounding; otherwise `h`, or the rest of the way to
/// `t_out` when `h` stretched by up to 1 % reaches it (rather than
/// leaving a sliver for the next step).
pub(crate) fn adaptive_trial<F: Float>(t: F, t_out: F, h: F) -> Option<AdaptiveTrial<F>> {
    let remaining = t_out - t;
    if remaining <= F::from_f64(16.0) * F::EPSILON * t_out.abs().max(t.abs()) {
        return None;
    }
    let lands = h * F::from_f64(1.01) >= remaining;
    let h = if lands { remaining } else { h };
    Some(AdaptiveTrial { h, t_out, lands })
}

impl<F: Float> AdaptiveTrial<F> {
    /// After the stepper took `info` from `t0`, the run's step having been
    /// `h`: the time reached, the run's next step, and whether the step
    /// landed on the output time.
    pub(crate) fn accepted(&self, t0: F, h: F, info: &StepInfo<F>) -> (F, F, bool) {
        let landed = self.lands && info.h == self.h;
        let t = if landed { self.t_out } else { t0 + info.h };
        let h_next = if landed && info.rejected == 0 {
            // A step shortened to hit the output says nothing against
            // the longer step used before it.
            info.h_next.max(h)
        } else {
            info.h_next
        };
        (t, h_next, landed)
    }
}
