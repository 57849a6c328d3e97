//! Sampled control: a discrete-time controller that runs at a fixed sample
//! period beside any integrator, reads the time, state and outputs at each
//! sample instant, and sets the model's inputs, which hold until the next
//! sample (a zero-order hold), as a real controller's outputs do.
//!
//! Why: user code called from the equations (`extern fn`, `extern sub`)
//! runs at every evaluation — every Runge–Kutta stage, every rejected
//! trial step of an adaptive method, every finite-difference column — so
//! state it keeps between calls (a thruster's on-time, a filter) advances
//! at times the integrator chooses, and the result depends on the
//! integrator. A controller run here is called exactly once per sample
//! instant whatever the integrator: between samples the model is a smooth
//! function of time and state, and any integrator converges to the same
//! answer.

use super::counts::rounding;
use super::driver::Driver;
use super::events::Flow;
use super::times::check_times;
use super::{MAX_RECORDED_INPUTS, Observer, RunError, RunSettings, RunSummary};
use crate::integrate::Stepper;
use crate::{Float, IntegrationError, Model};

/// A discrete-time controller for [`run_sampled`].
///
/// Closures `FnMut(t, &x, &y, &mut inputs)` are controllers.
pub trait Controller<M: Model> {
    /// At a sample instant `t` with state `x` and outputs `y`: write the
    /// inputs to hold until the next sample into `inputs`
    /// ([`Model::INPUT_NAMES`] order; it holds the current inputs, so
    /// leave alone what the controller does not set).
    fn sample(&mut self, t: M::Float, x: &M::State, y: &M::Outputs, inputs: &mut [M::Float]);
}

impl<M, C> Controller<M> for C
where
    M: Model,
    C: FnMut(M::Float, &M::State, &M::Outputs, &mut [M::Float]),
{
    fn sample(&mut self, t: M::Float, x: &M::State, y: &M::Outputs, inputs: &mut [M::Float]) {
        self(t, x, y, inputs)
    }
}

/// Like [`run`](super::run()), with `controller` sampled every `period`
/// from the start: steps land on every sample instant and on every output
/// time, the controller runs first at a sample instant (the outputs
/// reported there already use its new inputs), and the stepper is reset
/// after each sample (the inputs jump). Never allocates.
///
/// # Errors
/// As [`run`](super::run()); a `period` that is not positive and finite is
/// [`IntegrationError::InvalidSettings`].
pub fn run_sampled<M, S, C, O>(
    model: &mut M,
    stepper: &mut S,
    x: &mut M::State,
    settings: &RunSettings<M::Float>,
    period: M::Float,
    controller: &mut C,
    observer: &mut O,
) -> Result<RunSummary<M::Float>, RunError<O::Error>>
where
    M: Model,
    S: Stepper<M> + ?Sized,
    C: Controller<M> + ?Sized,
    O: Observer<M> + ?Sized,
{
    let every = (0..=settings.output_count()).map(|k| match k {
        0 => settings.start,
        k => settings.output_time(k),
    });
    sampled(
        model, stepper, x, settings, every, period, controller, observer,
    )
}

/// Like [`run_sampled`], reporting at `times` (non-decreasing, within
/// `[start, stop]`) as [`run_at`](super::run_at()) does instead of at
/// `settings.output_interval`: the controller still runs every `period`
/// to `settings.stop`. Never allocates.
///
/// # Errors
/// As [`run_sampled`]; [`IntegrationError::InvalidSettings`] when `times`
/// is not ordered or leaves `[start, stop]`.
#[allow(clippy::too_many_arguments)]
pub fn run_sampled_at<M, S, C, O>(
    model: &mut M,
    stepper: &mut S,
    x: &mut M::State,
    settings: &RunSettings<M::Float>,
    times: &[M::Float],
    period: M::Float,
    controller: &mut C,
    observer: &mut O,
) -> Result<RunSummary<M::Float>, RunError<O::Error>>
where
    M: Model,
    S: Stepper<M> + ?Sized,
    C: Controller<M> + ?Sized,
    O: Observer<M> + ?Sized,
{
    check_times(settings, times)?;
    let times = times.iter().copied();
    sampled(
        model, stepper, x, settings, times, period, controller, observer,
    )
}

/// The loop both entries share: samples at the start and every `period`,
/// reports at each of `outputs` (in order; one at or before the current
/// time at once), and ends at the stop time or at a terminal event (one
/// last output at its instant).
#[allow(clippy::too_many_arguments)]
fn sampled<M, S, C, O>(
    model: &mut M,
    stepper: &mut S,
    x: &mut M::State,
    settings: &RunSettings<M::Float>,
    outputs: impl Iterator<Item = M::Float>,
    period: M::Float,
    controller: &mut C,
    observer: &mut O,
) -> Result<RunSummary<M::Float>, RunError<O::Error>>
where
    M: Model,
    S: Stepper<M> + ?Sized,
    C: Controller<M> + ?Sized,
    O: Observer<M> + ?Sized,
{
    if !(period > M::Float::ZERO && period.is_finite()) {
        let reason = "the sample period must be positive and finite";
        return Err(IntegrationError::InvalidSettings { reason }.into());
    }
    let mut driver = Driver::begin(model, stepper, x, settings, observer)?;
    let mut flow = sample(&mut driver, model, stepper, x, controller, observer)?;
    let mut outputs = outputs.peekable();
    let (mut j, mut at_stop) = (1u64, false);
    loop {
        if flow == Flow::Stopped {
            // A terminal event: one last output at its instant.
            driver.emit(model, x, observer)?;
            break;
        }
        let next = outputs.peek().copied();
        let until = match next {
            Some(t_out) => t_out,
            None if at_stop => break,
            None => settings.stop,
        };
        // A sample instant a rounding from the next output time is that
        // time (in `f32`, `j · period` of the last sample can round past
        // the stop).
        let t_sample = match settings.start + M::Float::from_f64(j as f64) * period {
            t if (t - until).abs() <= rounding(until.abs().max(t.abs()), period) => until,
            t => t,
        };
        let target = if t_sample < until { t_sample } else { until };
        if target > driver.time() {
            flow = driver.advance(model, stepper, x, target, settings.step, observer)?;
            if flow == Flow::Stopped {
                continue;
            }
        }
        if t_sample <= until {
            flow = sample(&mut driver, model, stepper, x, controller, observer)?;
            j += 1;
        }
        // At `until`: its output (after a terminal event at the sample,
        // the loop's first line reports it, once), or the stop.
        if until <= t_sample {
            if next.is_none() {
                at_stop = true;
            } else if outputs.next().is_some() && flow == Flow::Continue {
                driver.emit(model, x, observer)?;
            }
        }
    }
    Ok(driver.finish(stepper))
}

/// Runs the controller at the driver's time, sets the inputs it chose and
/// restarts the stepper (with the events the new inputs cause).
fn sample<M, S, C, O>(
    driver: &mut Driver<M>,
    model: &mut M,
    stepper: &mut S,
    x: &mut M::State,
    controller: &mut C,
    observer: &mut O,
) -> Result<Flow, RunError<O::Error>>
where
    M: Model,
    S: Stepper<M> + ?Sized,
    C: Controller<M> + ?Sized,
    O: Observer<M> + ?Sized,
{
    let t = driver.time();
    let mut inputs = [M::Float::ZERO; MAX_RECORDED_INPUTS];
    let inputs = &mut inputs[..M::INPUT_NAMES.len().min(MAX_RECORDED_INPUTS)];
    model.input_values(inputs);
    let y = *driver.outputs(model, x)?;
    controller.sample(t, x, &y, inputs);
    model.set_input_values(inputs);
    driver.restart(model, stepper, x, observer)
}
