//! Events: what a model declares about its switching (indicator functions
//! with a direction, discrete variables, actions) and what the run driver
//! reports when one happens.
//!
//! A model with events implements [`Model::EVENT_INDICATORS`],
//! [`Model::event_indicators`] and [`Model::event`] (and, if its equations
//! read modes, [`Model::DISCRETE_NAMES`] with [`Model::discrete_values`] and
//! [`Model::set_discrete_values`]). The [`run`](crate::run()) driver locates
//! every crossing of an indicator inside each step on the step's
//! interpolant, moves the state to the crossing, calls the action and
//! restarts the stepper there (see [`EventSettings`](crate::run::EventSettings)
//! for what is guaranteed). Models without events (every hand-written model
//! that does not implement these items) are unchanged.

use crate::Model;

/// How many event indicators the run driver handles (its workspaces are
/// fixed arrays of this length; a model with more is an
/// [`IntegrationError::InvalidSettings`](crate::IntegrationError::InvalidSettings)).
pub const MAX_EVENT_INDICATORS: usize = 64;

/// How many discrete variables the run driver passes to observers.
pub const MAX_DISCRETE: usize = 64;

/// Which sign changes of an indicator are events.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Direction {
    /// From negative to positive.
    Rising,
    /// From positive to negative.
    Falling,
    /// Either way.
    Either,
}

impl Direction {
    /// `true` if a change from sign `before` to sign `after` (each -1 or +1)
    /// is an event in this direction.
    pub fn fires(self, before: i8, after: i8) -> bool {
        match self {
            Direction::Rising => before < 0 && after > 0,
            Direction::Falling => before > 0 && after < 0,
            Direction::Either => before != 0 && after != 0 && before != after,
        }
    }

    /// The sign an indicator has after it fires, coming from `before`.
    pub(crate) fn side_after(self, before: i8) -> i8 {
        match self {
            Direction::Rising => 1,
            Direction::Falling => -1,
            Direction::Either => -before,
        }
    }
}

/// One event indicator of a model: the function `g(t, x, discrete)` whose
/// sign change (in `direction`) is the event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EventIndicator {
    /// The event's name (reports, CSV files, errors).
    pub name: &'static str,
    /// Which sign changes fire it.
    pub direction: Direction,
}

impl EventIndicator {
    /// An event when the indicator rises from negative to positive.
    pub const fn rising(name: &'static str) -> Self {
        Self {
            name,
            direction: Direction::Rising,
        }
    }

    /// An event when the indicator falls from positive to negative.
    pub const fn falling(name: &'static str) -> Self {
        Self {
            name,
            direction: Direction::Falling,
        }
    }

    /// An event when the indicator changes sign either way.
    pub const fn either(name: &'static str) -> Self {
        Self {
            name,
            direction: Direction::Either,
        }
    }
}

/// What the run does after an event's action.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum EventOutcome {
    /// Go on integrating from the event (the stepper restarts there).
    #[default]
    Continue,
    /// Stop the run at the event (a terminal event).
    Stop,
}

/// What an observer sees of one event: the instant, which indicator fired,
/// and the state, discrete variables and outputs just before and just
/// after its action.
#[derive(Debug)]
pub struct EventRecord<'a, M: Model> {
    /// The located instant.
    pub t: M::Float,
    /// Index of the indicator in [`Model::EVENT_INDICATORS`].
    pub index: usize,
    /// Its name.
    pub name: &'static str,
    /// The state at the crossing, before the action.
    pub before: &'a M::State,
    /// The state after the action (a reset changes it; a mode switch not).
    pub after: &'a M::State,
    /// The discrete variables before the action ([`Model::DISCRETE_NAMES`]
    /// order, the first [`MAX_DISCRETE`]).
    pub discrete_before: &'a [M::Float],
    /// The discrete variables after the action.
    pub discrete_after: &'a [M::Float],
    /// The outputs before the action.
    pub outputs_before: &'a M::Outputs,
    /// The outputs after the action (in the new mode).
    pub outputs_after: &'a M::Outputs,
    /// The inputs at the instant ([`Model::INPUT_NAMES`] order).
    pub inputs: &'a [M::Float],
}

/// The rates of change `dg/dt` of the first `rates.len()` event
/// indicators at `(t, x)` along the motion: a central difference of the
/// indicators along `(1, dx/dt)` over `±√ε·max(1, |t|)` seconds (one
/// derivative evaluation, two of the indicators).
///
/// # Errors
/// The model's error from its derivatives or indicators.
pub fn indicator_rates<M: Model>(
    model: &mut M,
    t: M::Float,
    x: &M::State,
    rates: &mut [M::Float],
) -> Result<(), crate::ModelError> {
    use crate::{Float, StateArray};
    let n = rates
        .len()
        .min(M::EVENT_INDICATORS.len())
        .min(MAX_EVENT_INDICATORS);
    if n == 0 {
        return Ok(());
    }
    let mut f = M::State::zeros();
    model.derivatives(t, x, &mut f)?;
    let delta = M::Float::EPSILON.sqrt() * M::Float::ONE.max(t.abs());
    let along = |sign: M::Float| {
        let mut moved = *x;
        for (m, d) in moved.as_mut().iter_mut().zip(f.as_ref()) {
            *m += sign * delta * *d;
        }
        moved
    };
    let (ahead, behind) = (along(M::Float::ONE), along(-M::Float::ONE));
    let mut g_ahead = [M::Float::ZERO; MAX_EVENT_INDICATORS];
    let mut g_behind = [M::Float::ZERO; MAX_EVENT_INDICATORS];
    let all = M::EVENT_INDICATORS.len().min(MAX_EVENT_INDICATORS);
    model.event_indicators(t + delta, &ahead, &mut g_ahead[..all])?;
    model.event_indicators(t - delta, &behind, &mut g_behind[..all])?;
    let two_delta = delta + delta;
    for (k, rate) in rates.iter_mut().enumerate().take(n) {
        *rate = (g_ahead[k] - g_behind[k]) / two_delta;
    }
    Ok(())
}

/// Whether an indicator that just fired, now `g` and changing at `rate`
/// after its event's action, is at zero (`|g| ≤ reach`) and heading back
/// to `old_side`, the side it crossed from. So a bounce leaves it: the
/// stop's indicator is zero at the impact, to the precision the crossing
/// was located to, and the reset reverses its rate. Such an indicator is
/// on its old side already for the next crossing, which may come within
/// the next step (a small bounce). `reach` is what counts as zero: the
/// indicator's value at the located crossing, or what its rate covers in
/// the time the crossing was located to.
pub fn returning<F: crate::Float>(g: F, rate: F, old_side: i8, reach: F) -> bool {
    let heading_back = match old_side {
        -1 => rate < F::ZERO,
        1 => rate > F::ZERO,
        _ => false,
    };
    heading_back && g.abs() <= reach
}

/// The sign of an indicator value: -1, +1, or 0 for zero (and NaN).
pub(crate) fn sign<F: crate::Float>(v: F) -> i8 {
    if v > F::ZERO {
        1
    } else if v < F::ZERO {
        -1
    } else {
        0
    }
}
