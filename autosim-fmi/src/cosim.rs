//! Co-Simulation: advancing an instance between communication points with
//! the runtime's integrators and run driver (events located), inputs held
//! over the step.

use crate::Export;
use crate::ffi::Status;
use crate::instance::{Fail, Instance, Outcome};
use crate::layout::Method;
use autosim_runtime::integrate::{AbmOrder, AdamsBashforthMoulton, DormandPrince, Rk4};
use autosim_runtime::{Model, RunSettings, Stepper, run};

/// Relative tolerance to which a communication point must equal the
/// instance's time.
const TIME_MATCH: f64 = 1e-9;

impl<E: Export> Instance<E> {
    /// The integrator of the `cs.method` setting.
    pub(crate) fn make_stepper(&mut self) -> Outcome {
        let s = self.settings;
        let stepper: Box<dyn Stepper<E::Model>> = match s.method {
            Method::DormandPrince => Box::new(
                DormandPrince::with_tolerances(s.tolerance, s.tolerance)
                    .map_err(|e| Fail::error(format!("cs.tolerance: {e}")))?,
            ),
            Method::Rk4 => Box::new(Rk4::new()),
            Method::Abm4 => Box::new(AdamsBashforthMoulton::new(AbmOrder::Four)),
        };
        self.stepper = Some(stepper);
        self.h_next = s.step;
        Ok(())
    }

    /// `fmi2DoStep`: integrates from `t` (which must be the instance's time)
    /// to `t + h` with the inputs held, by the runtime's run driver: the
    /// integrator restarted (Dormand–Prince from its last suggested step),
    /// the state projected onto the position constraints after every
    /// step, and the events of a model with events located inside each
    /// step and their actions run at their instants. A terminal event ends
    /// the step at its instant with `fmi2Discard` (and
    /// `fmi2GetBooleanStatus(fmi2Terminated)` true). On failure the
    /// instance keeps the state of the step's start and the error says why.
    pub fn do_step(&mut self, t: f64, h: f64) -> Outcome {
        if (t - self.t).abs() > TIME_MATCH * (1.0 + self.t.abs()) {
            return Err(Fail::error(format!(
                "fmi2DoStep from t = {t}, but the FMU is at t = {}",
                self.t
            )));
        }
        if !(h > 0.0 && h.is_finite()) {
            return Err(Fail::error(format!(
                "the communication step must be positive, not {h}"
            )));
        }
        if self.terminated {
            return Err(Fail::error(format!(
                "the model asked to end the simulation at t = {} (a terminal event)",
                self.t
            )));
        }
        self.assemble()?;
        let end = t + h;
        let mut stepper = self.stepper.take().ok_or_else(|| {
            Fail::error("fmi2DoStep before the end of initialization".to_string())
        })?;
        // Each communication step starts the integrator afresh: the inputs
        // may have changed (a first-same-as-last stage or a multistep
        // history would be stale), and a step's result depends only on
        // what an FMU state saves.
        stepper.reset();
        let result = self.advance(stepper.as_mut(), end);
        self.stepper = Some(stepper);
        self.touch();
        result
    }

    /// Runs to `end` (one output interval of the run driver): adaptive
    /// methods from their suggested step, fixed ones in equal steps of at
    /// most `cs.step`.
    fn advance(&mut self, stepper: &mut dyn Stepper<E::Model>, end: f64) -> Outcome {
        let span = end - self.t;
        let adaptive = stepper.is_adaptive();
        let first = if adaptive {
            self.h_next.min(span)
        } else {
            self.settings.step
        };
        let settings = RunSettings::new(self.t, end, first, span);
        let mut x = self.x;
        let mut ignore = |_: f64, _: &State<E>, _: &Outputs<E>| {};
        let summary = run(&mut self.model, stepper, &mut x, &settings, &mut ignore)
            .map_err(|e| Fail::error(format!("from t = {}: {e}", self.t)))?;
        self.x = x;
        if adaptive && summary.next_step > 0.0 {
            self.h_next = summary.next_step;
        }
        self.log.call(|| {
            format!(
                "fmi2DoStep: {} steps, {} events to t = {}",
                summary.steps, summary.events, summary.end_time
            )
        });
        if let Some(k) = summary.terminal_event {
            self.t = summary.end_time;
            self.terminated = true;
            let name = E::Model::EVENT_INDICATORS[k].name;
            return Err(Fail {
                status: Status::Discard,
                message: format!(
                    "terminal event {name} at t = {}: the model asks to end the simulation",
                    self.t
                ),
            });
        }
        self.t = end;
        Ok(())
    }
}

/// A model's state vector.
type State<E> = <<E as Export>::Model as Model>::State;
/// A model's output vector.
type Outputs<E> = <<E as Export>::Model as Model>::Outputs;
