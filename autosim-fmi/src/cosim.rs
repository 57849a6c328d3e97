//! Co-Simulation: advancing an instance between communication points with
//! the runtime's integrators, inputs held over the step.

use crate::Export;
use crate::instance::{Fail, Instance, Outcome};
use crate::layout::Method;
use autosim_runtime::integrate::{AbmOrder, AdamsBashforthMoulton, DormandPrince, Rk4};
use autosim_runtime::{Model as _, Stepper};

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
    /// to `t + h` with the inputs held, the integrator restarted (Dormand–
    /// Prince from its last suggested step), projecting onto the position
    /// constraints after every step. On failure the state is left where
    /// the last good step ended and the error says why.
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

    /// Steps to `end`: adaptive methods from their suggested step, fixed
    /// ones in equal steps of at most `cs.step`.
    fn advance(&mut self, stepper: &mut dyn Stepper<E::Model>, end: f64) -> Outcome {
        let span = end - self.t;
        let fixed =
            (!stepper.is_adaptive()).then(|| span / (span / self.settings.step).ceil().max(1.0));
        let mut taken = 0u64;
        while self.t < end {
            let remaining = end - self.t;
            if remaining <= TIME_MATCH * (1.0 + end.abs()) {
                break;
            }
            let h = match fixed {
                Some(h) => h.min(remaining),
                None => self.h_next.min(remaining),
            };
            let mut x = self.x;
            let info = stepper
                .step(&mut self.model, self.t, &mut x, h)
                .map_err(|e| Fail::error(format!("at t = {}: {e}", self.t)))?;
            self.model
                .project(self.t + info.h, &mut x, 0.0)
                .map_err(Fail::from)?;
            self.x = x;
            self.t += info.h;
            if stepper.is_adaptive() && info.h_next > 0.0 {
                self.h_next = info.h_next;
            }
            taken += 1;
        }
        self.t = end;
        self.log
            .call(|| format!("fmi2DoStep: {taken} steps to t = {end}"));
        Ok(())
    }
}
