//! Lowering the events: each indicator, and the new values of each
//! event's actions, under the environment of the state alone (an event
//! reads no solved value; it may call user functions, whose calls keep
//! the model's order). Lowered after everything else, so a model without
//! events numbers its IR as before.

use super::Lowering;
use super::context::UnboundSymbol;
use crate::expr::{ExprId, SymId};
use crate::mech::ItemRef;
use crate::opt::error::ProgramError;
use crate::opt::ir::Nid;

/// What an action assigns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Assigned {
    /// The state at this slot of the state vector.
    State(usize),
    /// The discrete variable of this index.
    Discrete(usize),
}

/// The events as IR nodes.
#[derive(Clone, Debug, Default)]
pub(crate) struct LoweredEvents {
    /// Each event's indicator.
    pub indicators: Vec<Nid>,
    /// The new values of each event's actions.
    pub actions: Vec<Vec<Nid>>,
    /// For each event, what each of its values (a slot of its `actions`)
    /// assigns.
    pub assignments: Vec<Vec<(Assigned, usize)>>,
    /// Every user-function call in the order the model makes them (the
    /// events' calls among them).
    pub call_order: Vec<Nid>,
}

/// Lowers every event (`None` without events).
pub(crate) fn lower(lw: &mut Lowering<'_>) -> Result<Option<LoweredEvents>, ProgramError> {
    let given = lw.given;
    if given.declared.events.is_empty() {
        return Ok(None);
    }
    lw.bind_state();
    let mut out = LoweredEvents::default();
    for (k, event) in given.declared.events.iter().enumerate() {
        out.indicators.push(reading(lw, event.indicator, k)?);
        let (mut assignments, mut actions) = (Vec::new(), Vec::new());
        for &(d, value) in &event.sets {
            assignments.push((Assigned::Discrete(d), actions.len()));
            actions.push(reading(lw, value, k)?);
        }
        for &(s, value) in &event.resets {
            let slot = resettable_slot(lw, s).ok_or_else(|| ProgramError::EventReset {
                name: lw.name(s).to_string(),
                item: ItemRef::Event(k),
            })?;
            assignments.push((Assigned::State(slot), actions.len()));
            actions.push(reading(lw, value, k)?);
        }
        out.actions.push(actions);
        out.assignments.push(assignments);
    }
    out.call_order = lw.call_order();
    Ok(Some(out))
}

/// `e`, a value event `k` reads, lowered; a symbol without a value here
/// is a dependent speed.
fn reading(lw: &mut Lowering<'_>, e: ExprId, k: usize) -> Result<Nid, ProgramError> {
    lw.lower(e)
        .map_err(|UnboundSymbol(name)| ProgramError::EventReads {
            name,
            item: ItemRef::Event(k),
        })
}

/// The state slot of `s` if an event may reset it: an independent
/// coordinate or speed, or an added state (a dependent coordinate would
/// be solved again by assembly, a dependent speed is no state, a
/// prescribed one follows its motion).
fn resettable_slot(lw: &Lowering<'_>, s: SymId) -> Option<usize> {
    let (eqs, split) = (lw.given.eqs, lw.given.split);
    let dependent = &eqs.constraints.dependent_coordinates;
    if let Some(slot) = split
        .coordinates
        .iter()
        .position(|&j| eqs.coordinates[j] == s)
    {
        let j = split.coordinates[slot];
        return (!dependent.contains(&j)).then_some(slot);
    }
    let nq = split.coordinates.len();
    if let Some(k) = split.free.iter().position(|&j| eqs.speeds[j] == s) {
        return Some(nq + k);
    }
    let n = split.free.len();
    eqs.states.iter().position(|&x| x == s).map(|k| nq + n + k)
}
