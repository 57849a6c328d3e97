//! The times of a fixed-step run without events, as a list of ticks
//! (an output, a step): what [`run`](super::run()) does with a fixed-step
//! method and a model without events, for drivers that step many states
//! together (a study's lockstep groups) and must land on the same times
//! and steps, bit for bit.

use super::RunSettings;
use super::counts::{rounding, step_count};
use crate::Float;

/// One thing the run does, in order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Tick<F> {
    /// Report the state at this time (the start, each output time, the
    /// stop).
    Output(F),
    /// Step from `t` by `h`; the time is then `t_end`.
    Step {
        /// The step's start (the time the stepper is given).
        t: F,
        /// The step.
        h: F,
        /// The time after the step.
        t_end: F,
    },
}

/// Calls `visit` with every tick of a fixed-step run of `settings` (a
/// model without events), stopping at the first error `visit` returns.
///
/// The same arithmetic as the driver's `advance_fixed` without events:
/// steps of exactly `step` on the grid `start + k·step` while every output
/// time is a whole number of steps from the start, equal steps that divide
/// each output interval after the first one that is not (the run driver's
/// test `fixed_grid_ticks_are_the_drivers` holds them equal).
pub(crate) fn fixed_ticks<F: Float, E>(
    settings: &RunSettings<F>,
    mut visit: impl FnMut(Tick<F>) -> Result<(), E>,
) -> Result<(), E> {
    let (start, step) = (settings.start, settings.step);
    let mut t = start;
    let mut fixed_steps = 0;
    let mut on_grid = true;
    visit(Tick::Output(t))?;
    for k in 1..=settings.output_count() {
        let t_out = settings.output_time(k);
        let span = t_out - start;
        let last = step_count(span, step, t_out.abs().max(start.abs()));
        let whole = on_grid
            && (F::from_f64(last as f64) * step - span).abs()
                <= rounding(span.abs().max(step.abs()), step);
        if whole {
            while fixed_steps < last {
                let next = start + F::from_f64((fixed_steps + 1) as f64) * step;
                let grid = start + F::from_f64(fixed_steps as f64) * step;
                if t >= next {
                    fixed_steps += 1;
                    continue;
                }
                let h = if t == grid { step } else { next - t };
                visit(Tick::Step { t, h, t_end: next })?;
                t = next;
                fixed_steps += 1;
            }
            t = start + F::from_f64(last as f64) * step;
        } else {
            on_grid = false;
            t = equal_steps(t, t_out, step, &mut visit)?;
        }
        visit(Tick::Output(t))?;
    }
    Ok(())
}

/// Equal steps of at most `step` from `t0` to `t_out` (none when they
/// are a rounding apart); returns `t_out`.
fn equal_steps<F: Float, E>(
    t0: F,
    t_out: F,
    step: F,
    visit: &mut impl FnMut(Tick<F>) -> Result<(), E>,
) -> Result<F, E> {
    let interval = t_out - t0;
    let scale = t_out.abs().max(t0.abs());
    if interval <= rounding(scale, step) {
        return Ok(t_out);
    }
    let n = step_count(interval, step, scale).max(1);
    let h = interval / F::from_f64(n as f64);
    let mut t = t0;
    for j in 1..=n {
        let t_end = if j == n {
            t_out
        } else {
            t0 + F::from_f64(j as f64) * h
        };
        visit(Tick::Step { t, h, t_end })?;
        t = t_end;
    }
    Ok(t_out)
}

#[cfg(test)]
mod tests {
    use core::cell::RefCell;
    use std::vec::Vec;

    use super::{Tick, fixed_ticks};
    use crate::integrate::{StepInfo, StepResult, Stepper};
    use crate::{Model, ModelError, RunSettings, run};

    struct Still;
    impl Model for Still {
        type Float = f64;
        type State = [f64; 1];
        type Outputs = [f64; 0];
        const NAME: &'static str = "Still";
        const STATE_NAMES: &'static [&'static str] = &["x"];
        const STATE_UNITS: &'static [&'static str] = &["1"];
        fn derivatives(
            &mut self,
            _: f64,
            _: &[f64; 1],
            dx: &mut [f64; 1],
        ) -> Result<(), ModelError> {
            dx[0] = 0.0;
            Ok(())
        }
    }

    /// The log of a run: `(t, h)` for a step, `(t, NaN)` for an output.
    type Log = RefCell<Vec<(f64, f64)>>;

    /// A fixed-step stepper that only logs what the driver asks.
    struct Logging<'a>(&'a Log);
    impl Stepper<Still> for Logging<'_> {
        fn step(&mut self, _: &mut Still, t: f64, _: &mut [f64; 1], h: f64) -> StepResult<Still> {
            self.0.borrow_mut().push((t, h));
            Ok(StepInfo::fixed(h, 0))
        }
        fn evaluations(&self) -> u64 {
            0
        }
        fn reset(&mut self) {}
        fn name(&self) -> &'static str {
            "logging"
        }
        fn order(&self) -> u32 {
            1
        }
    }

    fn bits(log: &[(f64, f64)]) -> Vec<(u64, u64)> {
        log.iter()
            .map(|(t, h)| (t.to_bits(), h.to_bits()))
            .collect()
    }

    #[test]
    fn fixed_grid_ticks_are_the_drivers() {
        let cases = [
            RunSettings::new(0.0, 1.0, 0.01, 0.1),
            RunSettings::new(0.0, 1.0, 0.03, 0.1),
            RunSettings::new(0.3, 2.05, 0.25, 0.5),
            RunSettings::new(-1.0, 1.0, 0.1, 0.7),
            RunSettings::new(0.0, 0.0, 0.1, 0.1),
            RunSettings::new(1e6, 1e6 + 1.0, 1e-3, 0.25),
        ];
        for settings in &cases {
            let log = Log::default();
            let mut observe =
                |t: f64, _: &[f64; 1], _: &[f64; 0]| log.borrow_mut().push((t, f64::NAN));
            run(
                &mut Still,
                &mut Logging(&log),
                &mut [0.0],
                settings,
                &mut observe,
            )
            .unwrap();
            let mut ticks = Vec::new();
            fixed_ticks::<f64, ()>(settings, |tick| {
                ticks.push(tick);
                Ok(())
            })
            .unwrap();
            let time = |tick: &Tick<f64>| match *tick {
                Tick::Output(t) | Tick::Step { t, .. } => t,
            };
            let ours: Vec<(f64, f64)> = ticks
                .iter()
                .map(|tick| match *tick {
                    Tick::Output(t) => (t, f64::NAN),
                    Tick::Step { t, h, .. } => (t, h),
                })
                .collect();
            assert_eq!(bits(&ours), bits(&log.borrow()), "{settings:?}");
            // Each step ends where the next tick is.
            for pair in ticks.windows(2) {
                if let Tick::Step { t_end, .. } = pair[0] {
                    assert_eq!(t_end.to_bits(), time(&pair[1]).to_bits(), "{settings:?}");
                }
            }
        }
    }
}
