//! Runs reporting at given times (any increasing list), as SciPy's
//! `solve_ivp(t_eval=...)` does, where [`run`](super::run()) reports at a
//! fixed interval.

use super::driver::Driver;
use super::events::Flow;
use super::{Observer, RunError, RunSettings, RunSummary};
use crate::integrate::Stepper;
use crate::{Float, IntegrationError, Model};

/// Integrates `model` from `settings.start` to `settings.stop` like
/// [`run`](super::run()), but calls `observer` exactly at each of `times`
/// (which must be non-decreasing and within `[start, stop]`; a time equal
/// to `start` is reported from the initial state) instead of at
/// `settings.output_interval`, which is ignored. The integration ends at
/// `settings.stop`, after the last output time if that is earlier.
///
/// Fixed-step methods take the largest step not above `settings.step`
/// that divides each gap between output times into equal steps; adaptive
/// methods keep their step size from gap to gap and shorten a step only
/// to land on an output time.
///
/// # Errors
/// As [`run`](super::run()); [`IntegrationError::InvalidSettings`] when
/// `times` is not ordered or leaves `[start, stop]`.
pub fn run_at<M, S, O>(
    model: &mut M,
    stepper: &mut S,
    x: &mut M::State,
    settings: &RunSettings<M::Float>,
    times: &[M::Float],
    observer: &mut O,
) -> Result<RunSummary<M::Float>, RunError<O::Error>>
where
    M: Model,
    S: Stepper<M> + ?Sized,
    O: Observer<M> + ?Sized,
{
    check_times(settings, times)?;
    let mut driver = Driver::begin(model, stepper, x, settings, observer)?;
    for &t_out in times {
        if t_out > driver.time() {
            let flow = driver.advance(model, stepper, x, t_out, settings.step, observer)?;
            if flow == Flow::Stopped {
                // A terminal event: one last output at its instant.
                driver.emit(model, x, observer)?;
                return Ok(driver.finish(stepper));
            }
        }
        driver.emit(model, x, observer)?;
    }
    if settings.stop > driver.time() {
        driver.advance(model, stepper, x, settings.stop, settings.step, observer)?;
    }
    Ok(driver.finish(stepper))
}

/// `times` as output times of a run with `settings`: non-decreasing and
/// within `[start, stop]`, else [`IntegrationError::InvalidSettings`].
pub(super) fn check_times<F: Float, E>(
    settings: &RunSettings<F>,
    times: &[F],
) -> Result<(), RunError<E>> {
    let ordered = times.windows(2).all(|w| w[0] <= w[1]);
    let inside = times
        .iter()
        .all(|&t| t >= settings.start && t <= settings.stop);
    if ordered && inside {
        return Ok(());
    }
    Err(RunError::Integration(IntegrationError::InvalidSettings {
        reason: "output times must be non-decreasing and within [start, stop]",
    }))
}
