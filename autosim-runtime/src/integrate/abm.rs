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
    /// Ring buffer of past derivatives: `f[head]` is fₙ, `f[head - 1]` fₙ₋₁, ...
    f: [M::State; 4],
    head: usize,
    count: usize,
    t_end: M::Float,
    h_last: M::Float,
    x_end: M::State,
    /// The RK4 stages' derivatives of a start-up step.
    k: [M::State; 4],
    predicted: M::State,
    f_predicted: M::State,
    corrected: M::State,
    evals: u64,
    startup_steps: u64,
}

impl<M: Model> AdamsBashforthMoulton<M> {
    /// A stepper of the given order with an empty history.
    pub fn new(order: AbmOrder) -> Self {
        let z = M::State::zeros();
        Self {
            order,
            f: [z; 4],
            head: 0,
            count: 0,
            t_end: M::Float::ZERO,
            h_last: M::Float::ZERO,
            x_end: z,
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

    /// Makes the next ring slot the newest and returns it.
    fn push_slot(&mut self) -> usize {
        self.head = (self.head + 1) % 4;
        self.count = (self.count + 1).min(4);
        self.head
    }

    /// Keeps only what is still valid for a step from `(t, x)` with `h`.
    fn validate_history(&mut self, t: M::Float, x: &M::State, h: M::Float) {
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
}

clone_and_debug!(AdamsBashforthMoulton {
    "order": order,
    "history": count,
    "evaluations": evals,
    "startup_steps": startup_steps,
});

impl<M: Model> Stepper<M> for AdamsBashforthMoulton<M> {
    fn step(&mut self, model: &mut M, t: M::Float, x: &mut M::State, h: M::Float) -> StepResult<M> {
        check_step(h)?;
        let evals_before = self.evals;
        self.validate_history(t, x, h);
        if self.count == 0 {
            let slot = self.push_slot();
            if let Err(e) = eval(model, t, x, &mut self.f[slot], &mut self.evals) {
                self.count = 0;
                return Err(e);
            }
        }
        let result = if self.count < self.order.history() {
            self.startup_steps += 1;
            self.k[0] = self.f[self.head];
            rk_step(
                model,
                t,
                x,
                h,
                &RK4,
                &mut self.k,
                &mut self.corrected,
                &mut self.evals,
            )
        } else {
            self.predict_correct(model, t, x, h)
        };
        let result = result
            .and_then(|()| check_finite::<M>(t + h, &self.corrected))
            .and_then(|()| {
                // The final E of PECE: the derivative at the new point, for the history.
                let slot = (self.head + 1) % 4;
                eval(
                    model,
                    t + h,
                    &self.corrected,
                    &mut self.f[slot],
                    &mut self.evals,
                )
            });
        if let Err(e) = result {
            self.count = 0;
            return Err(e);
        }
        self.push_slot();
        self.t_end = t + h;
        self.h_last = h;
        self.x_end = self.corrected;
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
        self.count = 0;
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
    /// P, E and C of PECE into `self.corrected`.
    fn predict_correct(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
        h: M::Float,
    ) -> Result<(), IntegrationError> {
        let c = |v: f64| M::Float::from_f64(v);
        let (f0, f1, f2, f3) = (
            past(&self.f, self.head, 0),
            past(&self.f, self.head, 1),
            past(&self.f, self.head, 2),
            past(&self.f, self.head, 3),
        );
        match self.order {
            AbmOrder::Two => combine(&mut self.predicted, x, h, &[(c(1.5), f0), (c(-0.5), f1)]),
            AbmOrder::Four => combine(
                &mut self.predicted,
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
        eval(
            model,
            t + h,
            &self.predicted,
            &mut self.f_predicted,
            &mut self.evals,
        )?;
        let fp = &self.f_predicted;
        let (f0, f1, f2) = (
            past(&self.f, self.head, 0),
            past(&self.f, self.head, 1),
            past(&self.f, self.head, 2),
        );
        match self.order {
            AbmOrder::Two => combine(&mut self.corrected, x, h, &[(c(0.5), fp), (c(0.5), f0)]),
            AbmOrder::Four => combine(
                &mut self.corrected,
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
        Ok(())
    }
}

/// fₙ₋ⱼ from the ring buffer whose newest entry is `f[head]`.
fn past<S>(f: &[S; 4], head: usize, j: usize) -> &S {
    &f[(head + 4 - j % 4) % 4]
}
