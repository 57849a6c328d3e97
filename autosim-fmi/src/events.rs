//! Events in an FMU, from the model's generic event interface (the
//! `Model` trait's `EVENT_INDICATORS`, `event_indicators`, `event` and
//! discrete variables, see `autosim_runtime::event`):
//!
//! - Model Exchange: `fmi2GetEventIndicators` gives the indicators; the
//!   importer locates their zero crossings (FMI's indicators have no
//!   direction) and calls `fmi2NewDiscreteStates`, which fires every
//!   indicator whose sign changed in its direction since the last event
//!   mode, one at a time in index order with the indicators evaluated
//!   again after each action ([`Instance::settle_events`], the run
//!   driver's event iteration);
//! - Co-Simulation: `fmi2DoStep` runs the runtime's run driver, which
//!   locates the crossings inside each integrator step (`cosim`);
//! - what the description declares ([`EventInterface`]): the number of
//!   indicators and the discrete variables, read by `autosim-fmu` from the
//!   built library (the exported `autosim_fmi_event_interface`), so that
//!   any model implementing the trait's event items gets them.

use crate::Export;
use crate::instance::{Fail, Instance, Outcome};
use autosim_runtime::event::{MAX_EVENT_INDICATORS, indicator_rates, returning};
use autosim_runtime::{Direction, EventOutcome, Model};

/// Most events at one instant (one `fmi2NewDiscreteStates`): more means
/// the actions keep causing each other (a Zeno chain), an error.
pub const MAX_EVENTS_AT_AN_INSTANT: usize = 100;

/// What `fmi2NewDiscreteStates` reports.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Settled {
    /// An action reset continuous states (`valuesOfContinuousStatesChanged`).
    pub states_changed: bool,
    /// A terminal event fired (`terminateSimulation`).
    pub terminate: bool,
}

/// The sign of an indicator value: -1, +1, or 0 for zero (and NaN).
fn sign(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

/// The side of an indicator value `v` whose last known side was `known`:
/// its sign, and for exactly zero the side opposite `known` (0 while
/// unknown). The importer stops at a zero crossing it located, and CVode's
/// root finding can land on the root itself (an indicator linear in time
/// does): the crossing is there, and after the importer restarts it
/// masks an indicator that starts at zero, so no later stop would report
/// it. (The run driver, which locates crossings itself, waits for the far
/// side instead.)
fn side(v: f64, known: i8) -> i8 {
    match sign(v) {
        0 => -known,
        s => s,
    }
}

/// The sign an indicator has after it fires in `direction`, coming from
/// `before`.
fn side_after(direction: Direction, before: i8) -> i8 {
    match direction {
        Direction::Rising => 1,
        Direction::Falling => -1,
        Direction::Either => -before,
    }
}

impl<E: Export> Instance<E> {
    /// Number of event indicators.
    pub fn event_count(&self) -> usize {
        E::Model::EVENT_INDICATORS.len()
    }

    /// The event indicators at the current time and state into `out`.
    pub fn event_indicators(&mut self, out: &mut [f64]) -> Outcome {
        let n = self.event_count();
        if out.len() != n {
            return Err(Fail::error(format!(
                "the FMU has {n} event indicators, not {}",
                out.len()
            )));
        }
        if n == 0 {
            return Ok(());
        }
        self.assemble()?;
        self.model.event_indicators(self.t, &self.x, out)?;
        Ok(())
    }

    /// The events at the current instant: every indicator whose sign
    /// changed in its direction since it was last known fires (an
    /// indicator exactly zero counts as crossed: the importer stopped there), one at a
    /// time in index order, the indicators evaluated again after each
    /// action (an action may cause another crossing); then every sign is
    /// known anew. An indicator an action left at zero heading back to
    /// the side it crossed from (a bounce: the reset reversed its rate)
    /// is on that side at once, so its next crossing fires even if the
    /// importer, which masks an indicator that starts at zero, reports it
    /// only when it is back at zero. At the first call (the end of
    /// initialization) no sign is known, so nothing fires: the signs are
    /// learned.
    pub fn settle_events(&mut self) -> Outcome<Settled> {
        let n = self.event_count();
        let mut settled = Settled::default();
        if n == 0 {
            return Ok(settled);
        }
        let mut g = vec![0.0; n];
        // The indicator just fired, the side it came from and what counts
        // as zero for it; the indicators left at zero heading back.
        let mut fired: Option<(usize, i8, f64)> = None;
        let mut back = vec![false; n];
        for round in 0..=MAX_EVENTS_AT_AN_INSTANT {
            self.event_indicators(&mut g)?;
            if let Some((k, old_side, at_crossing)) = fired {
                if sign(g[k]) != 0 {
                    self.signs[k] = sign(g[k]);
                }
                if self.heading_back(g[k], (k, old_side), at_crossing)? {
                    self.signs[k] = old_side;
                    back[k] = true;
                }
            }
            let indicators = E::Model::EVENT_INDICATORS;
            let sides = self.sides(&g)?;
            let quiet = |k: usize| back[k] || fired.is_some_and(|f| f.0 == k);
            let next = (0..n)
                .find(|&k| !quiet(k) && indicators[k].direction.fires(self.signs[k], sides[k]));
            let Some(k) = next else {
                for (k, v) in g.iter().enumerate() {
                    let just_fired = fired.is_some_and(|f| f.0 == k);
                    if !back[k] && (!just_fired || sign(*v) != 0) && sides[k] != 0 {
                        self.signs[k] = sides[k];
                    }
                }
                return Ok(settled);
            };
            // The first event of the instant may be a crossing the importer
            // located: if it is at zero there, its value there counts as
            // zero after the action.
            let at_crossing = if round == 0 {
                self.at_zero(g[k], k)?
            } else {
                0.0
            };
            let before = self.x;
            let outcome = self.model.event(k, self.t, &mut self.x)?;
            self.touch();
            if self.x.as_ref() != before.as_ref() {
                settled.states_changed = true;
                // A reset: the dependent coordinates solved again.
                self.touch_state();
                self.assemble()?;
            }
            self.log.call(|| {
                format!(
                    "event {} at t = {}{}",
                    indicators[k].name,
                    self.t,
                    if settled.states_changed {
                        " (states reset)"
                    } else {
                        ""
                    }
                )
            });
            let old_side = self.signs[k];
            self.signs[k] = side_after(indicators[k].direction, old_side);
            back[k] = false;
            fired = Some((k, old_side, at_crossing));
            if outcome == EventOutcome::Stop {
                settled.terminate = true;
                self.terminated = true;
                return Ok(settled);
            }
        }
        Err(Fail::error(format!(
            "more than {MAX_EVENTS_AT_AN_INSTANT} events at t = {}: the event actions keep causing each other (Zeno)",
            self.t
        )))
    }
}

impl<E: Export> Instance<E> {
    /// The rate of indicator `k` at the current time and state (0 past
    /// the runtime's [`MAX_EVENT_INDICATORS`]).
    fn rate(&mut self, k: usize) -> Outcome<f64> {
        if k >= MAX_EVENT_INDICATORS {
            return Ok(0.0);
        }
        let mut rates = [0.0; MAX_EVENT_INDICATORS];
        self.assemble()?;
        indicator_rates(&mut self.model, self.t, &self.x, &mut rates[..=k])?;
        Ok(rates[k])
    }

    /// The side of each indicator, now `g`: its sign; exactly zero (the
    /// importer stopped on the crossing), the sign of its rate, the side
    /// it is going to (the opposite of the side last known if the rate is
    /// zero too).
    fn sides(&mut self, g: &[f64]) -> Outcome<Vec<i8>> {
        let mut rates = [0.0; MAX_EVENT_INDICATORS];
        let zero = g.iter().take(MAX_EVENT_INDICATORS).any(|v| *v == 0.0);
        if zero {
            let n = g.len().min(MAX_EVENT_INDICATORS);
            self.assemble()?;
            indicator_rates(&mut self.model, self.t, &self.x, &mut rates[..n])?;
        }
        Ok(g.iter()
            .enumerate()
            .map(|(k, v)| match (sign(*v), rates.get(k).map(|r| sign(*r))) {
                (0, Some(s)) if s != 0 => s,
                _ => side(*v, self.signs[k]),
            })
            .collect())
    }

    /// What counts as zero for indicator `k`, now `g`: `|g|` if its rate
    /// reaches zero from there within the resolution of a located
    /// crossing (`RESOLUTION`·max(1, |t|) seconds), else 0.
    fn at_zero(&mut self, g: f64, k: usize) -> Outcome<f64> {
        let rate = self.rate(k)?;
        let within = g.abs() <= rate.abs() * RESOLUTION * self.t.abs().max(1.0);
        Ok(if within { g.abs() } else { 0.0 })
    }

    /// Whether indicator `k`, now `g` after its action, is at zero (no
    /// farther from it than `at_crossing`, or than its rate covers in the
    /// resolution) heading back to `old_side`
    /// (`autosim_runtime::event::returning`).
    fn heading_back(
        &mut self,
        g: f64,
        (k, old_side): (usize, i8),
        at_crossing: f64,
    ) -> Outcome<bool> {
        if old_side == 0 {
            return Ok(false);
        }
        let rate = self.rate(k)?;
        let reach = at_crossing.max(rate.abs() * RESOLUTION * self.t.abs().max(1.0));
        Ok(returning(g, rate, old_side, reach))
    }
}

/// The relative time resolution of a crossing the importer located, for
/// [`Instance::heading_back`] (a root finder's tolerance is a few hundred
/// roundings of the time at most).
const RESOLUTION: f64 = 1e-12;

/// What `modelDescription.xml` says about a model's events: its event
/// indicators and its discrete variables with their units and start
/// values. Carried from the library to the description as text, one item
/// per line, fields separated by tabs: `indicator NAME DIRECTION` and
/// `discrete NAME UNIT START`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EventInterface {
    /// Indicator names with their directions (`rising`, `falling`,
    /// `either`).
    pub indicators: Vec<(String, String)>,
    /// Discrete variables: name, unit, start value.
    pub discrete: Vec<(String, String, f64)>,
}

impl EventInterface {
    /// The interface of an exported model (start values from a new model).
    pub fn of<E: Export>() -> EventInterface {
        let model = E::new();
        let names = E::Model::DISCRETE_NAMES;
        let mut start = vec![0.0; names.len()];
        model.discrete_values(&mut start);
        let units = E::Model::DISCRETE_UNITS;
        EventInterface {
            indicators: E::Model::EVENT_INDICATORS
                .iter()
                .map(|e| (e.name.to_string(), direction_name(e.direction).into()))
                .collect(),
            discrete: names
                .iter()
                .zip(start)
                .enumerate()
                .map(|(k, (n, v))| {
                    let unit = units.get(k).copied().unwrap_or_default();
                    (n.to_string(), unit.to_string(), v)
                })
                .collect(),
        }
    }

    /// Whether the model has neither indicators nor discrete variables.
    pub fn is_empty(&self) -> bool {
        self.indicators.is_empty() && self.discrete.is_empty()
    }

    /// The text form.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        for (name, direction) in &self.indicators {
            out += &format!("indicator\t{name}\t{direction}\n");
        }
        for (name, unit, start) in &self.discrete {
            out += &format!("discrete\t{name}\t{unit}\t{start:?}\n");
        }
        out
    }

    /// The interface from its text form, or the line that is not one.
    pub fn from_text(text: &str) -> Result<EventInterface, String> {
        let mut out = EventInterface::default();
        for line in text.lines().filter(|l| !l.is_empty()) {
            let fields: Vec<&str> = line.split('\t').collect();
            match fields.as_slice() {
                ["indicator", name, direction] => out
                    .indicators
                    .push((name.to_string(), direction.to_string())),
                ["discrete", name, unit, start] => {
                    let start = start
                        .parse()
                        .map_err(|_| format!("not a start value in {line:?}"))?;
                    out.discrete
                        .push((name.to_string(), unit.to_string(), start));
                }
                _ => return Err(format!("not an event interface line: {line:?}")),
            }
        }
        Ok(out)
    }
}

/// The name of a direction in the event interface's text.
fn direction_name(d: Direction) -> &'static str {
    match d {
        Direction::Rising => "rising",
        Direction::Falling => "falling",
        Direction::Either => "either",
    }
}

/// The body of the exported `autosim_fmi_event_interface(buffer, length)`:
/// writes the interface's text (what fits) and returns its full length in
/// bytes.
///
/// # Safety
/// `buffer` points to `length` writable bytes (or `length` is 0).
pub unsafe fn write_event_interface<E: Export>(buffer: *mut u8, length: usize) -> usize {
    let text = std::panic::catch_unwind(|| EventInterface::of::<E>().to_text());
    let Ok(text) = text else { return 0 };
    // SAFETY: as this function's.
    unsafe { write_text(&text, buffer, length) }
}

/// The body of the exported `autosim_fmi_guid(buffer, length)`: the GUID
/// the library's `fmi2Instantiate` accepts, written as
/// [`write_event_interface`] writes its text (`autosim-fmu` checks it
/// against the description it packages the library with).
///
/// # Safety
/// `buffer` points to `length` writable bytes (or `length` is 0).
pub unsafe fn write_guid<E: Export>(buffer: *mut u8, length: usize) -> usize {
    // SAFETY: as this function's.
    unsafe { write_text(E::GUID, buffer, length) }
}

/// Writes what fits of `text` into `buffer`; returns its full length.
///
/// # Safety
/// `buffer` points to `length` writable bytes (or `length` is 0).
unsafe fn write_text(text: &str, buffer: *mut u8, length: usize) -> usize {
    let n = text.len().min(length);
    if n > 0 && !buffer.is_null() {
        // SAFETY: the caller passes `length` writable bytes.
        unsafe { std::ptr::copy_nonoverlapping(text.as_ptr(), buffer, n) };
    }
    text.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_interface_survives_its_text_and_bad_text_is_refused() {
        let interface = EventInterface {
            indicators: vec![("bounce".into(), "falling".into())],
            discrete: vec![("bounces".into(), "1".into(), 0.5)],
        };
        let text = interface.to_text();
        assert_eq!(EventInterface::from_text(&text), Ok(interface));
        assert!(EventInterface::from_text("indicator\tonly a name").is_err());
        assert!(EventInterface::from_text("discrete\ta\t1\tnot a number").is_err());
        assert_eq!(EventInterface::from_text(""), Ok(EventInterface::default()));
    }

    #[test]
    fn signs_and_sides_follow_the_run_driver() {
        assert_eq!(
            (sign(2.0), sign(-1.0), sign(0.0), sign(f64::NAN)),
            (1, -1, 0, 0)
        );
        assert_eq!(side_after(Direction::Falling, 1), -1);
        assert_eq!(side_after(Direction::Rising, -1), 1);
        assert_eq!(side_after(Direction::Either, -1), 1);
        assert_eq!((side(0.0, -1), side(0.0, 1), side(0.0, 0)), (1, -1, 0));
        assert_eq!((side(-3.0, 1), side(3.0, 1)), (-1, 1));
    }
}
