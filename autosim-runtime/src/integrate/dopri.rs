//! Adaptive Dormand–Prince 5(4) with error control and dense output.

use core::fmt;

use super::explicit::{Tableau, rk_step};
use super::vector::{combine, combine_row, eval, evaluations_since, same, weighted_rms};
use super::{StepInfo, StepResult, Stepper};
use crate::{Float, IntegrationError, Model, StateArray, check_finite};

/// Tolerances and step-size controller of [`DormandPrince`].
///
/// The local error estimate of each component is scaled by
/// `atol + rtol·max(|x_start|, |x_end|)`; a step is accepted when the
/// root-mean-square of the scaled errors is at most 1. The new step is
/// `h·clamp(safety·err^(−(0.2 − 0.75·beta))·err_prev^beta, min_factor, max_factor)`:
/// `beta = 0.04` is Hairer's PI controller (smoother step sequences),
/// `beta = 0` the standard controller.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DopriSettings<F> {
    /// Relative tolerance (> 0).
    pub rtol: F,
    /// Absolute tolerance (> 0), in the units of the states.
    pub atol: F,
    /// Smallest step allowed; a step below it fails with
    /// [`IntegrationError::StepSizeUnderflow`]. Zero means "until the step no
    /// longer changes the time".
    pub min_step: F,
    /// Largest step allowed (> 0; infinity for no limit).
    pub max_step: F,
    /// Safety factor on the predicted step (0 < safety < 1, usually 0.9).
    pub safety: F,
    /// Smallest factor by which a step may shrink (0 < min_factor < 1).
    pub min_factor: F,
    /// Largest factor by which a step may grow (> 1).
    pub max_factor: F,
    /// Weight of the previous error in the PI controller (0 ≤ beta ≤ 0.1).
    pub beta: F,
}

impl<F: Float> DopriSettings<F> {
    /// Settings with the given tolerances and Hairer's defaults for the rest:
    /// no step limits, safety 0.9, factors 0.2 and 10, PI controller (beta 0.04).
    pub fn new(rtol: F, atol: F) -> Self {
        Self {
            rtol,
            atol,
            min_step: F::ZERO,
            max_step: F::from_f64(f64::INFINITY),
            safety: F::from_f64(0.9),
            min_factor: F::from_f64(0.2),
            max_factor: F::from_f64(10.0),
            beta: F::from_f64(0.04),
        }
    }

    /// Checks every setting, naming the first wrong one.
    pub fn validate(&self) -> Result<(), IntegrationError> {
        let zero = F::ZERO;
        let one = F::ONE;
        let bad = |reason| Err(IntegrationError::InvalidSettings { reason });
        if !(self.rtol > zero && self.rtol.is_finite()) {
            return bad("rtol must be positive and finite");
        }
        if !(self.atol > zero && self.atol.is_finite()) {
            return bad("atol must be positive and finite");
        }
        if !(self.min_step >= zero && self.min_step.is_finite()) {
            return bad("min_step must be zero or positive");
        }
        if !(self.max_step > zero && self.max_step >= self.min_step) {
            return bad("max_step must be positive and at least min_step");
        }
        if !(self.safety > zero && self.safety < one) {
            return bad("safety must be between 0 and 1");
        }
        if !(self.min_factor > zero && self.min_factor < one) {
            return bad("min_factor must be between 0 and 1");
        }
        if !(self.max_factor > one && self.max_factor.is_finite()) {
            return bad("max_factor must be finite and greater than 1");
        }
        if !(self.beta >= zero && self.beta <= F::from_f64(0.1)) {
            return bad("beta must be between 0 and 0.1");
        }
        Ok(())
    }
}

impl<F: Float> Default for DopriSettings<F> {
    /// `rtol = 1e-6`, `atol = 1e-9`.
    fn default() -> Self {
        Self::new(F::from_f64(1e-6), F::from_f64(1e-9))
    }
}

// Dormand & Prince (1980) coefficients, as in Hairer, Nørsett & Wanner,
// "Solving Ordinary Differential Equations I", DOPRI5.
/// Stages 1–6 and the fifth-order weights. The seventh stage is the new
/// state itself (first same as last): its derivative starts the next step.
pub(crate) const DOPRI5: Tableau<6> = Tableau {
    c: [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0],
    a: [
        &[],
        &[1.0 / 5.0],
        &[3.0 / 40.0, 9.0 / 40.0],
        &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
        &[
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
        ],
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
    ],
    b: [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
};
/// Error weights of the seven stages: fifth-order weights minus fourth-order
/// weights.
pub(crate) const ERROR: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Dense output (Shampine's 4th-order continuous extension): the weights of
/// the seven stages in its highest coefficient.
const DENSE: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// Adaptive Dormand–Prince 5(4) Runge–Kutta (DOPRI5): fifth-order steps
/// with an embedded fourth-order error estimate, first-same-as-last (six
/// evaluations per accepted step), and a fourth-order continuous extension
/// for output between steps ([`DormandPrince::interpolate`]).
///
/// Use it when you want a stated accuracy rather than a stated step, for
/// non-stiff models. `step(t, x, h)` tries `h` (capped at
/// [`DopriSettings::max_step`]), shrinks it until the error is within
/// tolerance, and returns the step taken and the suggested next step.
/// A trial whose stages overflow, or that the model cannot evaluate (a
/// [`ModelError`](crate::ModelError) such as a singular mass matrix far from
/// the solution), is retried smaller too; that failure is returned if the
/// step underflows. Integrates forward in time only (`h > 0`).
pub struct DormandPrince<M: Model> {
    settings: DopriSettings<M::Float>,
    k: [M::State; 7],
    x_new: M::State,
    err: M::State,
    /// Coefficients of the dense-output polynomial of the last step.
    dense: [M::State; 5],
    t_old: M::Float,
    t_new: M::Float,
    has_step: bool,
    /// `k[0]` holds f(t_new, dense state end) from the last accepted step.
    fsal: bool,
    control: Control<M::Float>,
    evals: u64,
    accepted: u64,
    rejected: u64,
}

impl<M: Model> DormandPrince<M> {
    /// A stepper with the given settings.
    ///
    /// # Errors
    /// [`IntegrationError::InvalidSettings`] naming the first bad setting.
    pub fn new(settings: DopriSettings<M::Float>) -> Result<Self, IntegrationError> {
        settings.validate()?;
        let z = M::State::zeros();
        Ok(Self {
            settings,
            k: [z; 7],
            x_new: z,
            err: z,
            dense: [z; 5],
            t_old: M::Float::ZERO,
            t_new: M::Float::ZERO,
            has_step: false,
            fsal: false,
            control: Control::new(settings),
            evals: 0,
            accepted: 0,
            rejected: 0,
        })
    }

    /// A stepper with default settings and the given tolerances.
    ///
    /// # Errors
    /// [`IntegrationError::InvalidSettings`] if a tolerance is not positive.
    pub fn with_tolerances(rtol: M::Float, atol: M::Float) -> Result<Self, IntegrationError> {
        Self::new(DopriSettings::new(rtol, atol))
    }

    /// The settings in use.
    pub fn settings(&self) -> &DopriSettings<M::Float> {
        &self.settings
    }

    /// Accepted steps so far.
    pub fn accepted_steps(&self) -> u64 {
        self.accepted
    }

    /// Rejected trial steps so far.
    pub fn rejected_steps(&self) -> u64 {
        self.rejected
    }

    /// Start and end time of the last accepted step, if any.
    pub fn last_step(&self) -> Option<(M::Float, M::Float)> {
        self.has_step.then_some((self.t_old, self.t_new))
    }

    /// Writes the solution at time `t` inside the last accepted step into
    /// `out`, from the fourth-order continuous extension (no model
    /// evaluations). Use it for output at times the steps did not land on.
    ///
    /// # Errors
    /// [`IntegrationError::OutsideLastStep`] if `t` is not within the last step.
    pub fn interpolate(&self, t: M::Float, out: &mut M::State) -> Result<(), IntegrationError> {
        let h = self.t_new - self.t_old;
        let slack = M::Float::from_f64(16.0) * M::Float::EPSILON * (self.t_new.abs() + h.abs());
        if !(self.has_step && t >= self.t_old - slack && t <= self.t_new + slack) {
            return Err(IntegrationError::OutsideLastStep {
                t: t.to_f64(),
                start: self.t_old.to_f64(),
                end: self.t_new.to_f64(),
            });
        }
        let theta = (t - self.t_old) / h;
        let theta1 = M::Float::ONE - theta;
        let [r1, r2, r3, r4, r5] = &self.dense;
        let values = r1
            .as_ref()
            .iter()
            .zip(r2.as_ref())
            .zip(r3.as_ref())
            .zip(r4.as_ref())
            .zip(r5.as_ref());
        for (o, ((((a, b), c), d), e)) in out.as_mut().iter_mut().zip(values) {
            *o = *a + theta * (*b + theta1 * (*c + theta * (*d + theta1 * *e)));
        }
        Ok(())
    }

    /// Stages 2–7 from `(t, x)` with step `h`, given `k[0] = f(t, x)`;
    /// leaves the fifth-order result in `x_new` (the stages' states are
    /// formed there too) and the error in `err`. The seventh stage is at the
    /// result itself (first same as last).
    fn stages(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
        h: M::Float,
    ) -> Result<(), IntegrationError> {
        let [first_six @ .., k7] = &mut self.k;
        let evals = &mut self.evals;
        rk_step(model, t, x, h, &DOPRI5, first_six, &mut self.x_new, evals)?;
        eval(model, t + h, &self.x_new, k7, evals)?;
        combine_row(&mut self.err, &M::State::zeros(), h, &ERROR, &self.k);
        Ok(())
    }

    /// Records the accepted step `t → t + h` from `x_old` for dense output.
    fn store_dense(&mut self, x_old: &M::State, t: M::Float, h: M::Float) {
        let one = M::Float::ONE;
        let [r1, r2, r3, r4, r5] = &mut self.dense;
        let [k1, .., k7] = &self.k;
        *r1 = *x_old;
        for ((d, a), b) in r2
            .as_mut()
            .iter_mut()
            .zip(x_old.as_ref())
            .zip(self.x_new.as_ref())
        {
            *d = *b - *a;
        }
        // r3 = h·k1 − r2; r4 = r2 − h·k7 − r3.
        combine(r3, &M::State::zeros(), h, &[(one, k1)]);
        for (d, b) in r3.as_mut().iter_mut().zip(r2.as_ref()) {
            *d -= *b;
        }
        for (((d, a), b), k) in r4
            .as_mut()
            .iter_mut()
            .zip(r2.as_ref())
            .zip(r3.as_ref())
            .zip(k7.as_ref())
        {
            *d = *a - h * *k - *b;
        }
        combine_row(r5, &M::State::zeros(), h, &DENSE, &self.k);
        self.t_old = t;
        self.t_new = t + h;
        self.has_step = true;
    }
}

clone_and_debug!(DormandPrince {
    "settings": settings,
    "evaluations": evals,
    "accepted": accepted,
    "rejected": rejected,
});

impl<M: Model> Stepper<M> for DormandPrince<M> {
    fn step(&mut self, model: &mut M, t: M::Float, x: &mut M::State, h: M::Float) -> StepResult<M> {
        check_trial_step(h)?;
        let evals_before = self.evals;
        // First same as last: k7 of the last step is f at its end point.
        let reuse = self.fsal && ends_at::<M>(t, x, self.t_new, &self.x_new);
        // Cleared first: a failed step must not leave a stale stage behind.
        self.fsal = false;
        if !reuse {
            eval(model, t, x, &mut self.k[0], &mut self.evals)?;
        }
        self.control.begin(h);
        loop {
            self.control.check_floor::<M>(t, &self.x_new)?;
            let h = self.control.h;
            match self.stages(model, t, x, h) {
                Ok(()) => self.control.stages_done(),
                Err(e @ (IntegrationError::NonFinite { .. } | IntegrationError::Model { .. })) => {
                    self.control.stage_failed(e);
                    self.rejected += 1;
                    continue;
                }
                Err(e) => return Err(e),
            }
            let Some(h_next) = self.control.judge(t, x, &self.x_new, &self.err, &self.k[6]) else {
                self.rejected += 1;
                continue;
            };
            let x_old = *x;
            self.store_dense(&x_old, t, h);
            *x = self.x_new;
            self.k[0] = self.k[6];
            self.fsal = true;
            self.accepted += 1;
            return Ok(StepInfo {
                h,
                h_next,
                rejected: self.control.rejected,
                evaluations: evaluations_since(evals_before, self.evals),
            });
        }
    }
    fn evaluations(&self) -> u64 {
        self.evals
    }
    fn reset(&mut self) {
        self.fsal = false;
        self.has_step = false;
        self.control.reset();
    }
    fn is_adaptive(&self) -> bool {
        true
    }
    fn has_dense_output(&self) -> bool {
        true
    }
    fn dense_output(&self, t: M::Float, out: &mut M::State) -> Result<(), IntegrationError> {
        self.interpolate(t, out)
    }
    fn name(&self) -> &'static str {
        "Dormand-Prince 5(4)"
    }
    fn order(&self) -> u32 {
        5
    }
}

/// Rejects a trial step that is not positive and finite.
pub(crate) fn check_trial_step<F: Float>(h: F) -> Result<(), IntegrationError> {
    if h > F::ZERO && h.is_finite() {
        Ok(())
    } else {
        Err(IntegrationError::InvalidSettings {
            reason: "the trial step of Dormand-Prince must be positive and finite",
        })
    }
}

/// Whether a step from `(t, x)` starts where the last accepted step ended
/// (`(end, x_end)`), so that its last stage is this step's first (first
/// same as last).
pub(crate) fn ends_at<M: Model>(
    t: M::Float,
    x: &M::State,
    end: M::Float,
    x_end: &M::State,
) -> bool {
    let tol_t = M::Float::from_f64(16.0) * M::Float::EPSILON * t.abs().max(end.abs());
    (t - end).abs() <= tol_t && same(x, x_end)
}

/// The step-size control of [`DormandPrince`]: the error of the last
/// accepted step (its PI controller's memory) and the trials of the step
/// in progress. A study's lockstep keeps one per case and drives it as
/// the stepper does, trial by trial.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Control<F> {
    settings: DopriSettings<F>,
    err_old: F,
    /// The step being tried.
    pub(crate) h: F,
    /// Trials of this step rejected so far.
    pub(crate) rejected: u32,
    /// The end of the last trial, if it was rejected for values that were
    /// not finite.
    last_trial_t: Option<F>,
    /// Why the model could not evaluate a stage of the last trial.
    stage_failure: Option<IntegrationError>,
}

impl<F: Float> Control<F> {
    /// No step taken yet.
    pub(crate) fn new(settings: DopriSettings<F>) -> Self {
        Control {
            settings,
            err_old: F::from_f64(1e-4),
            h: F::ZERO,
            rejected: 0,
            last_trial_t: None,
            stage_failure: None,
        }
    }

    /// Forgets the last step's error.
    pub(crate) fn reset(&mut self) {
        self.err_old = F::from_f64(1e-4);
    }

    /// Starts a step whose first trial is `h` (at most the largest step).
    pub(crate) fn begin(&mut self, h: F) {
        self.h = h.min(self.settings.max_step);
        self.rejected = 0;
        self.last_trial_t = None;
        self.stage_failure = None;
    }

    /// Whether the trial from `t` is below the smallest step (or no
    /// longer changes the time).
    pub(crate) fn underflows(&self, t: F) -> bool {
        let floor = self
            .settings
            .min_step
            .max(F::from_f64(4.0) * F::EPSILON * t.abs());
        self.h < floor || t + self.h == t
    }

    /// Before a trial from `t`: the error the step fails with if the
    /// trial underflows (the stage that could not be evaluated, the state
    /// `x_new` of the last trial if it was not finite, or the step size).
    pub(crate) fn check_floor<M: Model<Float = F>>(
        &self,
        t: F,
        x_new: &M::State,
    ) -> Result<(), IntegrationError> {
        if !self.underflows(t) {
            return Ok(());
        }
        if let Some(e) = self.stage_failure {
            return Err(e);
        }
        if let Some(t_bad) = self.last_trial_t {
            // The step shrank because the values were not finite: name
            // the state, it says more than the step size.
            check_finite::<M>(t_bad, x_new)?;
        }
        Err(IntegrationError::StepSizeUnderflow {
            t: t.to_f64(),
            h: self.h.to_f64(),
        })
    }

    /// The trial's stages were all evaluated.
    pub(crate) fn stages_done(&mut self) {
        self.stage_failure = None;
    }

    /// The model could not evaluate a stage of the trial (it overflowed,
    /// or left the states where the model is valid, e.g. a singular mass
    /// matrix far from the solution): the next trial is much smaller, as
    /// for a non-finite result; `e` is reported if the step underflows.
    pub(crate) fn stage_failed(&mut self, e: IntegrationError) {
        self.stage_failure = Some(e);
        self.last_trial_t = None;
        self.h *= self.settings.min_factor;
        self.rejected += 1;
    }

    /// Judges the trial from `(t, x)` to `x_new` with the error estimate
    /// `err` and the last stage `k7`: the next step suggested if it is
    /// accepted (`self.h` is then the step taken), `None` if it is rejected
    /// (`self.h` is then the next trial).
    pub(crate) fn judge<S: StateArray<F>>(
        &mut self,
        t: F,
        x: &S,
        x_new: &S,
        err: &S,
        k7: &S,
    ) -> Option<F> {
        let (s, one) = (&self.settings, F::ONE);
        let expo = F::from_f64(0.2) - s.beta * F::from_f64(0.75);
        let err = weighted_rms(err, x, x_new, s.rtol, s.atol);
        let finite = err.is_finite()
            && x_new.as_ref().iter().all(|v| v.is_finite())
            && k7.as_ref().iter().all(|v| v.is_finite());
        if !finite {
            // Overflow or a model blowing up: retry much smaller.
            self.last_trial_t = Some(t + self.h);
            self.h *= s.min_factor;
            self.rejected += 1;
            return None;
        }
        let fac11 = err.powf(expo);
        if err <= one {
            let fac = (fac11 / self.err_old.powf(s.beta) / s.safety)
                .max(one / s.max_factor)
                .min(one / s.min_factor);
            let mut h_next = (self.h / fac).min(s.max_step);
            if self.rejected > 0 {
                h_next = h_next.min(self.h);
            }
            self.err_old = err.max(F::from_f64(1e-4));
            return Some(h_next);
        }
        self.last_trial_t = None;
        let shrink = (fac11 / s.safety).min(one / s.min_factor);
        self.h /= shrink;
        self.rejected += 1;
        None
    }
}
