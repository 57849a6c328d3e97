//! Adams–Bashforth–Moulton predictor–corrector (PECE), the multistep pair
//! AUTOSIM's generated Fortran programs used.

use core::fmt;

use super::explicit::{RK4, rk_step};
use super::vector::{check_step, combine, eval, evaluations_since, same};
use super::{StepInfo, StepResult, Stepper};
use crate::{Float, IntegrationError, Model, StateArray, check_finite};

/// The order of an [`AdamsBashforthMoulton`] pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum AbmOrder {
    /// Two-step Adams–Bashforth predictor with the trapezoid (two-point
    /// Adams–Moulton) corrector: global error O(h²).
    #[default]
    Two,
    /// Four-step Adams–Bashforth predictor with the three-step Adams–Moulton
    /// corrector: global error O(h⁴).
    Four,
}

impl AbmOrder {
    /// Derivatives at past points the predictor needs (including the current one).
    fn history(self) -> usize {
        match self {
            AbmOrder::Two => 2,
            AbmOrder::Four => 4,
        }
    }
}

/// Adams–Bashforth–Moulton predictor–corrector in PECE form: predict with
/// Adams–Bashforth, evaluate, correct with Adams–Moulton, evaluate. Two
/// derivative evaluations per step once started.
///
/// * [`AbmOrder::Two`]: `xᵖ = xₙ + h(3fₙ − fₙ₋₁)/2`, `xₙ₊₁ = xₙ + h(f(xᵖ) + fₙ)/2`
///   — order 2.
/// * [`AbmOrder::Four`]: `xᵖ = xₙ + h(55fₙ − 59fₙ₋₁ + 37fₙ₋₂ − 9fₙ₋₃)/24`,
///   `xₙ₊₁ = xₙ + h(9f(xᵖ) + 19fₙ − 5fₙ₋₁ + fₙ₋₂)/24` — order 4.
///
/// The history needs a constant step: the first steps, and every step after
/// the step size, the time or the state changed outside the stepper (or
/// after [`Stepper::reset`]), are classic RK4 steps (order 4, four
/// evaluations plus one for the history). Use it for smooth models run at a
/// constant step where evaluations are expensive; prefer [`Rk4`](super::Rk4)
/// when the model has discontinuities (each one needs a reset).
pub struct AdamsBashforthMoulton<M: Model> {
    order: AbmOrder,
    history: AbmHistory<M>,
    /// The RK4 stages' derivatives of a start-up step.
    k: [M::State; 4],
    predicted: M::State,
    f_predicted: M::State,
    corrected: M::State,
    evals: u64,
    startup_steps: u64,
}

/// What an Adams–Bashforth–Moulton method carries from one step to the
/// next: the derivatives at the last points and where the last step
/// ended (a study's lockstep keeps one per case, [`AdamsBashforthMoulton`]
/// one).
pub(crate) struct AbmHistory<M: Model> {
    /// Ring buffer of past derivatives: `f[head]` is fₙ, `f[head - 1]` fₙ₋₁, ...
    f: [M::State; 4],
    head: usize,
    count: usize,
    t_end: M::Float,
    h_last: M::Float,
    x_end: M::State,
}

impl<M: Model> Clone for AbmHistory<M> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M: Model> Copy for AbmHistory<M> {}

impl<M: Model> AbmHistory<M> {
    /// No derivative known yet.
    pub(crate) fn new() -> Self {
        let z = M::State::zeros();
        AbmHistory {
            f: [z; 4],
            head: 0,
            count: 0,
            t_end: M::Float::ZERO,
            h_last: M::Float::ZERO,
            x_end: z,
        }
    }

    /// Keeps only what is still valid for a step from `(t, x)` with `h`:
    /// nothing if the time or the state is not where the last step ended,
    /// the newest derivative only if the step size changed.
    pub(crate) fn validate(&mut self, t: M::Float, x: &M::State, h: M::Float) {
        if self.count == 0 {
            return;
        }
        let tol_t = M::Float::from_f64(1e-6) * h.abs()
            + M::Float::from_f64(16.0) * M::Float::EPSILON * t.abs().max(self.t_end.abs());
        if (t - self.t_end).abs() > tol_t || !same(x, &self.x_end) {
            self.count = 0;
        } else if (h - self.h_last).abs() > M::Float::from_f64(1e-9) * h.abs() {
            self.count = 1;
        }
    }

    /// `true` if not even the derivative at the current point is known.
    pub(crate) fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// `true` if the step must be a start-up (RK4) step: fewer past
    /// derivatives than `order`'s predictor needs.
    pub(crate) fn starts_up(&self, order: AbmOrder) -> bool {
        self.count < order.history()
    }

    /// Records `f`, the derivative at the current point, as the newest.
    pub(crate) fn begin(&mut self, f: &M::State) {
        self.push_slot();
        self.f[self.head] = *f;
    }

    /// fₙ, the derivative at the current point.
    pub(crate) fn newest(&self) -> &M::State {
        &self.f[self.head]
    }

    /// Forgets everything (after a failed step).
    pub(crate) fn forget(&mut self) {
        self.count = 0;
    }

    /// The step from `t` by `h` ended at `x` with derivative `f`.
    pub(crate) fn accept(&mut self, t: M::Float, h: M::Float, x: &M::State, f: &M::State) {
        self.push_slot();
        self.f[self.head] = *f;
        self.t_end = t + h;
        self.h_last = h;
        self.x_end = *x;
    }

    /// Makes the next ring slot the newest.
    fn push_slot(&mut self) {
        self.head = (self.head + 1) % 4;
        self.count = (self.count + 1).min(4);
    }

    /// fₙ₋ⱼ.
    fn past(&self, j: usize) -> &M::State {
        &self.f[(self.head + 4 - j % 4) % 4]
    }

    /// The Adams–Bashforth predictor of a step from `x` by `h`.
    pub(crate) fn predict(
        &self,
        order: AbmOrder,
        predicted: &mut M::State,
        x: &M::State,
        h: M::Float,
    ) {
        let c = |v: f64| M::Float::from_f64(v);
        let (f0, f1, f2, f3) = (self.past(0), self.past(1), self.past(2), self.past(3));
        match order {
            AbmOrder::Two => combine(predicted, x, h, &[(c(1.5), f0), (c(-0.5), f1)]),
            AbmOrder::Four => combine(
                predicted,
                x,
                h,
                &[
                    (c(55.0 / 24.0), f0),
                    (c(-59.0 / 24.0), f1),
                    (c(37.0 / 24.0), f2),
                    (c(-9.0 / 24.0), f3),
                ],
            ),
        }
    }

    /// The Adams–Moulton corrector of a step from `x` by `h`, given the
    /// derivative `fp` at the predicted state.
    pub(crate) fn correct(
        &self,
        order: AbmOrder,
        corrected: &mut M::State,
        x: &M::State,
        h: M::Float,
        fp: &M::State,
    ) {
        let c = |v: f64| M::Float::from_f64(v);
        let (f0, f1, f2) = (self.past(0), self.past(1), self.past(2));
        match order {
            AbmOrder::Two => combine(corrected, x, h, &[(c(0.5), fp), (c(0.5), f0)]),
            AbmOrder::Four => combine(
                corrected,
                x,
                h,
                &[
                    (c(9.0 / 24.0), fp),
                    (c(19.0 / 24.0), f0),
                    (c(-5.0 / 24.0), f1),
                    (c(1.0 / 24.0), f2),
                ],
            ),
        }
    }
}

impl<M: Model> AdamsBashforthMoulton<M> {
    /// A stepper of the given order with an empty history.
    pub fn new(order: AbmOrder) -> Self {
        let z = M::State::zeros();
        Self {
            order,
            history: AbmHistory::new(),
            k: [z; 4],
            predicted: z,
            f_predicted: z,
            corrected: z,
            evals: 0,
            startup_steps: 0,
        }
    }

    /// The order chosen at construction.
    pub fn abm_order(&self) -> AbmOrder {
        self.order
    }

    /// Steps taken with RK4 because the history was not (yet) usable.
    pub fn startup_steps(&self) -> u64 {
        self.startup_steps
    }
}

clone_and_debug!(AdamsBashforthMoulton {
    "order": order,
    "history": history,
    "evaluations": evals,
    "startup_steps": startup_steps,
});

impl<M: Model> fmt::Debug for AbmHistory<M> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // How many past derivatives are usable: what a reader debugs.
        fmt::Debug::fmt(&self.count, f)
    }
}

impl<M: Model> Stepper<M> for AdamsBashforthMoulton<M> {
    fn step(&mut self, model: &mut M, t: M::Float, x: &mut M::State, h: M::Float) -> StepResult<M> {
        check_step(h)?;
        let evals_before = self.evals;
        let result = self.step_from(model, t, x, h);
        if let Err(e) = result {
            self.history.forget();
            return Err(e);
        }
        *x = self.corrected;
        Ok(StepInfo::fixed(
            h,
            evaluations_since(evals_before, self.evals),
        ))
    }
    fn evaluations(&self) -> u64 {
        self.evals
    }
    fn reset(&mut self) {
        self.history.forget();
    }
    fn name(&self) -> &'static str {
        match self.order {
            AbmOrder::Two => "ABM2",
            AbmOrder::Four => "ABM4",
        }
    }
    fn order(&self) -> u32 {
        match self.order {
            AbmOrder::Two => 2,
            AbmOrder::Four => 4,
        }
    }
}

impl<M: Model> AdamsBashforthMoulton<M> {
    /// A step from `(t, x)` by `h` into `self.corrected`, the history
    /// advanced (left as it is if the step fails).
    fn step_from(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
        h: M::Float,
    ) -> Result<(), IntegrationError> {
        let history = &mut self.history;
        history.validate(t, x, h);
        if history.is_empty() {
            eval(model, t, x, &mut self.k[0], &mut self.evals)?;
            history.begin(&self.k[0]);
        }
        if history.starts_up(self.order) {
            self.startup_steps += 1;
            self.k[0] = *history.newest();
            rk_step(
                model,
                t,
                x,
                h,
                &RK4,
                &mut self.k,
                &mut self.corrected,
                &mut self.evals,
            )?;
        } else {
            // P, E and C of PECE.
            history.predict(self.order, &mut self.predicted, x, h);
            eval(
                model,
                t + h,
                &self.predicted,
                &mut self.f_predicted,
                &mut self.evals,
            )?;
            history.correct(self.order, &mut self.corrected, x, h, &self.f_predicted);
        }
        check_finite::<M>(t + h, &self.corrected)?;
        // The final E of PECE: the derivative at the new point, for the history.
        eval(
            model,
            t + h,
            &self.corrected,
            &mut self.f_predicted,
            &mut self.evals,
        )?;
        history.accept(t, h, &self.corrected, &self.f_predicted);
        Ok(())
    }
}
