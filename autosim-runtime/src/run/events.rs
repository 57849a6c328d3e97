//! Events inside the run driver: each step's indicators scanned on the
//! step's interpolant, the first crossing located by root-finding, the
//! actions called at the instant (with the crossings they cause in turn),
//! and chattering stopped as [`IntegrationError::Zeno`].

use super::{MAX_RECORDED_INPUTS, Observer, RunError};
use crate::event::{
    EventRecord, MAX_DISCRETE, MAX_EVENT_INDICATORS, indicator_rates, returning, sign,
};
use crate::integrate::Stepper;
use crate::{EventOutcome, Float, IntegrationError, Model, StateArray, check_finite};

/// How the run driver finds events (see [`RunSettings::events`](super::RunSettings::events)).
///
/// What is guaranteed: after every step the indicators are evaluated on the
/// step's interpolant — Dormand–Prince's own continuous extension, or for
/// the other steppers the Hermite cubic through the step's end states and
/// their derivatives — at `interior_samples` equally spaced interior points
/// and at the end. A sign change (in the indicator's direction) between two
/// consecutive points is always found and located to `time_tolerance`;
/// the earliest crossing of all indicators in the step is the event. What
/// is not: an indicator that leaves its side and comes back between two
/// consecutive points (a grazing crossing), and a crossing that the
/// interpolant misses because the step's own error is larger than the
/// excursion. Raise `interior_samples`, tighten the tolerance or shorten
/// the step when such crossings matter. Except the return after a bounce:
/// an indicator its own action left at zero with its rate pointing back
/// to its old side is on that side at once, and a return within the next
/// step's first sampling interval is looked for at halving distances from
/// the event, down to the located instant's resolution; a bounce smaller
/// than that is [`IntegrationError::Zeno`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EventSettings<F> {
    /// The width of the time bracket a crossing is located to (s). 0, the
    /// default: to the rounding of the time (`4·ε·(|t| + h)`), which costs
    /// only indicator evaluations on the interpolant (no derivatives), so
    /// the instant is as accurate as the step itself: its error is the
    /// interpolant's error in the indicator divided by the indicator's rate
    /// of change.
    pub time_tolerance: F,
    /// Points inside each step (equally spaced) where the indicators are
    /// evaluated on the interpolant besides the step's end (default 4).
    pub interior_samples: u32,
    /// The longest chain of events, each within `zeno_interval` of the one
    /// before, that a run accepts; one more is
    /// [`IntegrationError::Zeno`] (default 100).
    pub zeno_events: u32,
    /// Two events closer than this (s) belong to one chain; 0, the default:
    /// a thousandth of the run (`(stop − start)/1000`).
    pub zeno_interval: F,
}

impl<F: Float> Default for EventSettings<F> {
    fn default() -> Self {
        Self {
            time_tolerance: F::ZERO,
            interior_samples: 4,
            zeno_events: 100,
            zeno_interval: F::ZERO,
        }
    }
}

impl<F: Float> EventSettings<F> {
    /// Checks the settings, naming the first wrong one.
    pub fn validate(&self) -> Result<(), IntegrationError> {
        let bad = |reason| Err(IntegrationError::InvalidSettings { reason });
        if !(self.time_tolerance >= F::ZERO && self.time_tolerance.is_finite()) {
            return bad("events.time_tolerance must be finite and not negative");
        }
        if !(self.zeno_interval >= F::ZERO && self.zeno_interval.is_finite()) {
            return bad("events.zeno_interval must be finite and not negative");
        }
        if self.zeno_events == 0 {
            return bad("events.zeno_events must be at least 1");
        }
        if self.interior_samples > 1000 {
            return bad("events.interior_samples must be at most 1000");
        }
        Ok(())
    }
}

/// Whether a run goes on after an instant's events.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Flow {
    Continue,
    /// A terminal event stopped the run.
    Stopped,
}

/// Two instants with the indicator's values there, on either side of a
/// crossing.
type Bracket<F> = [(F, F); 2];

/// How many times the located instant's resolution an indicator may be
/// from zero after its action and still count as left at zero (the
/// located instant is within the resolution past the crossing, and a
/// reset that scales the rate by a restitution down to 1/64 moves the
/// indicator back to zero within this).
const RETURNING_MARGIN: f64 = 64.0;

/// Most root-finding iterations for one crossing (each halves the bracket
/// at worst every other iteration: far more than 2·53 are never needed).
const MAX_ITERATIONS: u32 = 400;

/// The event state of one run of a model with events.
pub(super) struct Events<M: Model> {
    n: usize,
    settings: EventSettings<M::Float>,
    zeno_interval: M::Float,
    /// The last known sign of every indicator (0: not known yet).
    signs: [i8; MAX_EVENT_INDICATORS],
    /// Indicators (bit `k`) that fired and were left at zero heading
    /// back to the side they came from (a bounce): their sign is that
    /// side already, and until a point on it is seen, a crossing in the
    /// first part of a step is looked for by [`Events::dip`].
    returning: u64,
    /// The width of the last step scanned (for the resolution of
    /// located instants).
    last_step: M::Float,
    /// The indicators at the start of the step.
    g_start: [M::Float; MAX_EVENT_INDICATORS],
    /// Scratch: the indicators at a point.
    g: [M::Float; MAX_EVENT_INDICATORS],
    /// The step's start (for the Hermite interpolant).
    t_start: M::Float,
    x_start: M::State,
    /// f(t_start, x_start), if computed since the last restart.
    f_start: Option<M::State>,
    f_end: M::State,
    /// Scratch: a state on the interpolant (the located state after a scan).
    point: M::State,
    /// Events in the current chain and the time of the last one.
    chain: u32,
    last_event: Option<M::Float>,
    /// Events so far.
    pub(super) count: u64,
    /// Derivative evaluations for the Hermite interpolant.
    pub(super) evaluations: u64,
    /// The event that stopped the run.
    pub(super) terminal: Option<usize>,
}

/// A crossing found inside a step: the indicator and the instant (the
/// state there is `Events::point`).
pub(super) struct Crossing<F> {
    pub(super) index: usize,
    pub(super) t: F,
}

impl<M: Model> Events<M> {
    /// The event state of a run from `start` to `stop`, or `None` for a
    /// model without events (which then costs nothing).
    pub(super) fn new(
        settings: EventSettings<M::Float>,
        start: M::Float,
        stop: M::Float,
    ) -> Result<Option<Self>, IntegrationError> {
        settings.validate()?;
        let n = M::EVENT_INDICATORS.len();
        if n == 0 {
            return Ok(None);
        }
        if n > MAX_EVENT_INDICATORS {
            return Err(IntegrationError::InvalidSettings {
                reason: "the model has more event indicators than the run driver handles (MAX_EVENT_INDICATORS)",
            });
        }
        let zeno_interval = if settings.zeno_interval > M::Float::ZERO {
            settings.zeno_interval
        } else {
            (stop - start) * M::Float::from_f64(1e-3)
        };
        let z = M::State::zeros();
        Ok(Some(Self {
            n,
            settings,
            zeno_interval,
            signs: [0; MAX_EVENT_INDICATORS],
            returning: 0,
            last_step: M::Float::ZERO,
            g_start: [M::Float::ZERO; MAX_EVENT_INDICATORS],
            g: [M::Float::ZERO; MAX_EVENT_INDICATORS],
            t_start: start,
            x_start: z,
            f_start: None,
            f_end: z,
            point: z,
            chain: 0,
            last_event: None,
            count: 0,
            evaluations: 0,
            terminal: None,
        }))
    }

    /// The located state after [`Events::after_step`] found a crossing.
    pub(super) fn located_state(&self) -> &M::State {
        &self.point
    }

    /// Forgets the derivative carried to the next step (the model or the
    /// state changed discontinuously).
    pub(super) fn restart(&mut self) {
        self.f_start = None;
    }

    /// Remembers the step's start; for a stepper without dense output,
    /// makes sure the derivative there is known.
    pub(super) fn before_step<S: Stepper<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &S,
        t: M::Float,
        x: &M::State,
    ) -> Result<(), IntegrationError> {
        self.t_start = t;
        self.x_start = *x;
        if !stepper.has_dense_output() && self.f_start.is_none() {
            let mut f = M::State::zeros();
            self.derivatives(model, t, x, &mut f)?;
            self.f_start = Some(f);
        }
        Ok(())
    }

    fn derivatives(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
        f: &mut M::State,
    ) -> Result<(), IntegrationError> {
        self.evaluations += 1;
        model
            .derivatives(t, x, f)
            .map_err(|error| IntegrationError::Model {
                t: t.to_f64(),
                error,
            })
    }

    /// The indicators at `(t, x)` into `self.g`.
    fn indicators(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
    ) -> Result<(), IntegrationError> {
        model
            .event_indicators(t, x, &mut self.g[..self.n])
            .map_err(|error| IntegrationError::Model {
                t: t.to_f64(),
                error,
            })
    }

    /// The state at `t` inside the step `[t_start, t_end]` into `self.point`.
    fn interpolate<S: Stepper<M> + ?Sized>(
        &mut self,
        stepper: &S,
        t: M::Float,
        t_end: M::Float,
        x_end: &M::State,
    ) -> Result<(), IntegrationError> {
        if stepper.has_dense_output() {
            return stepper.dense_output(t, &mut self.point);
        }
        let h = t_end - self.t_start;
        let th = (t - self.t_start) / h;
        let one = M::Float::ONE;
        let two = M::Float::from_f64(2.0);
        let three = M::Float::from_f64(3.0);
        // The cubic Hermite basis on θ ∈ [0, 1].
        let h00 = (one + two * th) * (one - th) * (one - th);
        let h10 = th * (one - th) * (one - th);
        let h01 = th * th * (three - two * th);
        let h11 = th * th * (th - one);
        let f0 = self.f_start.as_ref().unwrap_or(&self.f_end);
        let values = self
            .x_start
            .as_ref()
            .iter()
            .zip(f0.as_ref())
            .zip(x_end.as_ref().iter().zip(self.f_end.as_ref()));
        for (p, ((x0, d0), (x1, d1))) in self.point.as_mut().iter_mut().zip(values) {
            *p = h00 * *x0 + h * (h10 * *d0 + h11 * *d1) + h01 * *x1;
        }
        Ok(())
    }

    /// Scans the step just taken, `[t_start, t_end]` ending at `x_end`: the
    /// earliest crossing, located, with its state in `self.point`; or
    /// `None`, the signs and values then carried to the next step.
    pub(super) fn after_step<S: Stepper<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &S,
        t_end: M::Float,
        x_end: &M::State,
    ) -> Result<Option<Crossing<M::Float>>, IntegrationError> {
        if !stepper.has_dense_output() {
            let mut f = M::State::zeros();
            self.derivatives(model, t_end, x_end, &mut f)?;
            self.f_end = f;
        }
        let n = self.n;
        let h = t_end - self.t_start;
        self.last_step = h;
        let parts = self.settings.interior_samples + 1;
        let mut current = self.signs;
        let mut g_prev = self.g_start;
        let mut t_prev = self.t_start;
        for j in 1..=parts {
            let t_j = if j == parts {
                self.indicators(model, t_end, x_end)?;
                t_end
            } else {
                let t_j = self.t_start + h * M::Float::from_f64(f64::from(j) / f64::from(parts));
                self.interpolate(stepper, t_j, t_end, x_end)?;
                let point = self.point;
                self.indicators(model, t_j, &point)?;
                t_j
            };
            let g_j = self.g;
            let mut first: Option<Crossing<M::Float>> = None;
            for (k, indicator) in M::EVENT_INDICATORS.iter().enumerate().take(n) {
                let back = self.returning & (1 << k) != 0;
                if back && sign(g_j[k]) == current[k] {
                    self.returning &= !(1 << k);
                }
                if indicator.direction.fires(current[k], sign(g_j[k])) {
                    let mut bracket = [(t_prev, g_prev[k]), (t_j, g_j[k])];
                    if back {
                        self.returning &= !(1 << k);
                        bracket = self.dip(model, stepper, k, bracket, t_end, x_end)?;
                    }
                    let t = self.locate(model, stepper, k, bracket, t_end, x_end)?;
                    if back {
                        self.check_return(model, stepper, (k, t), sign(g_j[k]), (t_end, x_end))?;
                    }
                    if first.as_ref().is_none_or(|c| t < c.t) {
                        first = Some(Crossing { index: k, t });
                    }
                }
            }
            if let Some(crossing) = first {
                self.signs = current;
                self.interpolate_or_end(stepper, crossing.t, t_end, x_end)?;
                return Ok(Some(crossing));
            }
            for (c, v) in current.iter_mut().zip(&g_j).take(n) {
                let s = sign(*v);
                if s != 0 {
                    *c = s;
                }
            }
            g_prev = g_j;
            t_prev = t_j;
        }
        self.signs = current;
        self.g_start = g_prev;
        self.f_start = Some(self.f_end);
        Ok(None)
    }

    /// The bracket of the crossing of indicator `k`, which fired at the
    /// step's start and was left there at zero heading back to its old
    /// side, and is on its new side again at the end of `bracket`: a
    /// point on the old side is looked for at halving distances from the
    /// start (a bounce smaller than the sampling), and the crossing is
    /// between it and the point after it. None down to the time
    /// resolution: the bounces have become too small to resolve, the
    /// events accumulate (Zeno).
    fn dip<S: Stepper<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &S,
        k: usize,
        bracket: Bracket<M::Float>,
        t_end: M::Float,
        x_end: &M::State,
    ) -> Result<Bracket<M::Float>, IntegrationError> {
        let [(a, _), mut after] = bracket;
        let old_side = -sign(after.1);
        let resolution = self.rounding(a);
        let half = M::Float::from_f64(0.5);
        let mut width = after.0 - a;
        while width > resolution {
            width *= half;
            let t = a + width;
            self.interpolate_or_end(stepper, t, t_end, x_end)?;
            let point = self.point;
            self.indicators(model, t, &point)?;
            let g = self.g[k];
            if sign(g) == old_side {
                return Ok([(t, g), after]);
            }
            after = (t, g);
        }
        Err(self.unresolved(a, k))
    }

    /// A bounce's return located at `t` for indicator `k` must head to
    /// `new_side` there; heading back, the crossing is in the rounding of
    /// the indicator (a bounce too small to resolve: its reset would send
    /// the state the wrong way).
    fn check_return<S: Stepper<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &S,
        (k, t): (usize, M::Float),
        new_side: i8,
        (t_end, x_end): (M::Float, &M::State),
    ) -> Result<(), IntegrationError> {
        self.interpolate_or_end(stepper, t, t_end, x_end)?;
        let point = self.point;
        if sign(self.rate(model, t, &point, k)?) == new_side {
            Ok(())
        } else {
            Err(self.unresolved(t, k))
        }
    }

    /// The rate of indicator `k` at `(t, x)` ([`indicator_rates`]: one
    /// derivative evaluation, counted).
    fn rate(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
        k: usize,
    ) -> Result<M::Float, IntegrationError> {
        let mut rates = [M::Float::ZERO; MAX_EVENT_INDICATORS];
        self.evaluations += 1;
        indicator_rates(model, t, x, &mut rates[..=k]).map_err(|error| {
            IntegrationError::Model {
                t: t.to_f64(),
                error,
            }
        })?;
        Ok(rates[k])
    }

    /// The Zeno error of a bounce of indicator `k` at `t` too small to
    /// resolve.
    fn unresolved(&self, t: M::Float, k: usize) -> IntegrationError {
        IntegrationError::Zeno {
            t: t.to_f64(),
            name: M::EVENT_INDICATORS[k].name,
            events: self.chain.saturating_add(1),
            unresolved: true,
        }
    }

    /// The rounding of the time at `t`, after the last step: the width
    /// [`Events::locate`] closes a bracket to by default.
    fn rounding(&self, t: M::Float) -> M::Float {
        M::Float::from_f64(4.0) * M::Float::EPSILON * (t.abs() + self.last_step.abs())
    }

    /// The state at `t` into `self.point`: `x_end` itself at the step's end.
    fn interpolate_or_end<S: Stepper<M> + ?Sized>(
        &mut self,
        stepper: &S,
        t: M::Float,
        t_end: M::Float,
        x_end: &M::State,
    ) -> Result<(), IntegrationError> {
        if t >= t_end {
            self.point = *x_end;
            Ok(())
        } else {
            self.interpolate(stepper, t, t_end, x_end)
        }
    }

    /// The crossing of indicator `k` inside `bracket` (its old sign at the
    /// first end, its new sign at the second), by the Illinois variant of
    /// regula falsi on the interpolant: the first time found on the new
    /// side, within the time tolerance of the last time on the old side.
    fn locate<S: Stepper<M> + ?Sized>(
        &mut self,
        model: &mut M,
        stepper: &S,
        k: usize,
        bracket: [(M::Float, M::Float); 2],
        t_end: M::Float,
        x_end: &M::State,
    ) -> Result<M::Float, IntegrationError> {
        let [(mut a, mut ga), (mut b, mut gb)] = bracket;
        let new_side = sign(gb);
        let h = t_end - self.t_start;
        let eps = M::Float::from_f64(4.0) * M::Float::EPSILON * (t_end.abs() + h.abs());
        let tol = self.settings.time_tolerance.max(eps);
        let half = M::Float::from_f64(0.5);
        // Which end the last iteration kept (Illinois halves its value when
        // the same end is kept twice, so the bracket closes from both sides).
        let mut kept = 0i8;
        for _ in 0..MAX_ITERATIONS {
            let width = b - a;
            if width <= tol {
                break;
            }
            let secant = b - gb * width / (gb - ga);
            let margin = tol * half;
            let c = if secant.is_finite() {
                secant.max(a + margin).min(b - margin)
            } else {
                a + width * half
            };
            self.interpolate_or_end(stepper, c, t_end, x_end)?;
            let point = self.point;
            self.indicators(model, c, &point)?;
            let gc = self.g[k];
            if sign(gc) == new_side {
                b = c;
                gb = gc;
                if kept == 1 {
                    ga *= half;
                }
                kept = 1;
            } else {
                a = c;
                ga = gc;
                if kept == -1 {
                    gb *= half;
                }
                kept = -1;
            }
        }
        Ok(b)
    }

    /// The events at the instant `t`: `forced` (a located crossing) first,
    /// then every indicator whose sign at `(t, x)` changed in its direction
    /// since it was last known, one at a time in index order, each action
    /// followed by the indicators again (an action may cause another
    /// crossing: event iteration). Each event is given to the observer.
    pub(super) fn settle<O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &mut M::State,
        forced: Option<usize>,
        observer: &mut O,
    ) -> Result<Flow, RunError<O::Error>> {
        let n = self.n;
        let mut forced = forced;
        // The indicator just fired and the side it came from: its sign
        // after the action is its new one, whatever it is (an action may
        // move it far, as a wrap-around), unless the action left it at
        // zero heading back (`returning`).
        let mut fired: Option<(usize, i8, M::Float)> = None;
        loop {
            self.indicators(model, t, x)?;
            if let Some((k, old_side, located)) = fired {
                self.after_action(model, t, x, (k, old_side), located)?;
            }
            let quiet =
                |k: usize| self.returning & (1 << k) != 0 || fired.is_some_and(|f| f.0 == k);
            let located = forced.is_some();
            let next = forced.take().or_else(|| {
                (0..n).find(|&k| {
                    !quiet(k)
                        && M::EVENT_INDICATORS[k]
                            .direction
                            .fires(self.signs[k], sign(self.g[k]))
                })
            });
            let Some(k) = next else {
                for (k, (s, v)) in self.signs.iter_mut().zip(&self.g).enumerate().take(n) {
                    let v = sign(*v);
                    if v != 0 && self.returning & (1 << k) == 0 {
                        *s = v;
                    }
                }
                self.g_start = self.g;
                return Ok(Flow::Continue);
            };
            self.count_in_chain(t, k)?;
            // A located crossing's value: what counts as zero after the
            // action (none for a crossing an action caused).
            let at_crossing = if located {
                self.g[k].abs()
            } else {
                M::Float::ZERO
            };
            let outcome = self.fire(model, t, x, k, observer)?;
            let old_side = self.signs[k];
            self.signs[k] = M::EVENT_INDICATORS[k].direction.side_after(old_side);
            self.returning &= !(1 << k);
            fired = Some((k, old_side, at_crossing));
            if outcome == EventOutcome::Stop {
                self.terminal = Some(k);
                return Ok(Flow::Stopped);
            }
        }
    }

    /// The sign of indicator `k` (now in `self.g`) after its action at
    /// `(t, x)`: its new one; but left at zero (no farther from it than
    /// `at_crossing`, its value at the located crossing, or than its rate
    /// covers in the located instant's resolution) and heading back to
    /// `old_side` (a bounce), `old_side`, and marked `returning`.
    fn after_action(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &M::State,
        (k, old_side): (usize, i8),
        at_crossing: M::Float,
    ) -> Result<(), IntegrationError> {
        let g = self.g[k];
        if sign(g) != 0 {
            self.signs[k] = sign(g);
        }
        if old_side == 0 {
            return Ok(());
        }
        let rate = self.rate(model, t, x, k)?;
        // A crossing located to a coarser time tolerance is not at zero:
        // its value there does not count.
        let rounding = self.rounding(t);
        let located_to_rounding = self.settings.time_tolerance <= rounding;
        let at_crossing = if located_to_rounding {
            at_crossing
        } else {
            M::Float::ZERO
        };
        let reach = at_crossing.max(rate.abs() * rounding * M::Float::from_f64(RETURNING_MARGIN));
        if returning(g, rate, old_side, reach) {
            self.signs[k] = old_side;
            self.returning |= 1 << k;
        }
        Ok(())
    }

    /// Adds an event at `t` to the chain of close events; too long a chain
    /// is Zeno.
    fn count_in_chain(&mut self, t: M::Float, k: usize) -> Result<(), IntegrationError> {
        let close = self
            .last_event
            .is_some_and(|last| t - last <= self.zeno_interval);
        self.chain = if close {
            self.chain.saturating_add(1)
        } else {
            1
        };
        self.last_event = Some(t);
        if self.chain > self.settings.zeno_events {
            return Err(IntegrationError::Zeno {
                t: t.to_f64(),
                name: M::EVENT_INDICATORS[k].name,
                events: self.chain,
                unresolved: false,
            });
        }
        Ok(())
    }

    /// Calls the action of event `k` at `(t, x)` and reports it.
    fn fire<O: Observer<M> + ?Sized>(
        &mut self,
        model: &mut M,
        t: M::Float,
        x: &mut M::State,
        k: usize,
        observer: &mut O,
    ) -> Result<EventOutcome, RunError<O::Error>> {
        let model_error = |error| IntegrationError::Model {
            t: t.to_f64(),
            error,
        };
        let n_discrete = M::DISCRETE_NAMES.len().min(MAX_DISCRETE);
        let n_inputs = M::INPUT_NAMES.len().min(MAX_RECORDED_INPUTS);
        let mut discrete_before = [M::Float::ZERO; MAX_DISCRETE];
        let mut discrete_after = [M::Float::ZERO; MAX_DISCRETE];
        let mut inputs = [M::Float::ZERO; MAX_RECORDED_INPUTS];
        let mut outputs_before = M::Outputs::zeros();
        let mut outputs_after = M::Outputs::zeros();
        let before = *x;
        model.discrete_values(&mut discrete_before[..n_discrete]);
        model.input_values(&mut inputs[..n_inputs]);
        model
            .outputs(t, x, &mut outputs_before)
            .map_err(model_error)?;
        let outcome = model.event(k, t, x).map_err(model_error)?;
        check_finite::<M>(t, x)?;
        if x.as_ref() != before.as_ref() {
            // A reset: the position constraints solved again for the
            // dependent coordinates (nothing to do without constraints).
            model.assemble(t, x).map_err(model_error)?;
        }
        model.discrete_values(&mut discrete_after[..n_discrete]);
        model
            .outputs(t, x, &mut outputs_after)
            .map_err(model_error)?;
        self.count += 1;
        let record = EventRecord {
            t,
            index: k,
            name: M::EVENT_INDICATORS[k].name,
            before: &before,
            after: x,
            discrete_before: &discrete_before[..n_discrete],
            discrete_after: &discrete_after[..n_discrete],
            outputs_before: &outputs_before,
            outputs_after: &outputs_after,
            inputs: &inputs[..n_inputs],
        };
        observer
            .observe_event(&record)
            .map_err(|error| RunError::Observer {
                t: t.to_f64(),
                error,
            })?;
        Ok(outcome)
    }
}
