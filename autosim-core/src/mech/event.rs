//! Discrete variables and events of a system: a discrete variable is a
//! symbol that is constant between events; an event is a sign change of an
//! indicator expression, in a direction, with the actions taken at the
//! located instant (discrete variables set, states reset, the run
//! stopped). The equations of motion read discrete variables like
//! parameters; the program lowers the indicators and actions into the
//! generated `event_indicators` and `event`.

use super::error::ModelError;
use super::system::System;
use crate::expr::{ExprId, SymId, SymbolKind};

/// Which sign changes of an indicator fire an event (the runtime's
/// `Direction`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventDirection {
    /// From negative to positive.
    Rising,
    /// From positive to negative.
    Falling,
    /// Either way.
    Either,
}

impl EventDirection {
    /// The spellings a model writes, in documentation order.
    pub const NAMES: [&'static str; 3] = ["rising", "falling", "either"];

    /// The direction spelled `name`.
    pub fn named(name: &str) -> Option<EventDirection> {
        match name {
            "rising" => Some(EventDirection::Rising),
            "falling" => Some(EventDirection::Falling),
            "either" => Some(EventDirection::Either),
            _ => None,
        }
    }
}

/// An event: an indicator, its direction and its actions. Every value of
/// the actions is an expression of the time, state, inputs, parameters and
/// discrete variables just before the event (the assignments are
/// simultaneous).
#[derive(Clone, Debug)]
pub struct Event {
    /// Name (reports, CSV files, errors).
    pub name: String,
    /// The indicator `g`: the event is a sign change of `g`.
    pub indicator: ExprId,
    /// Which sign changes fire it.
    pub direction: EventDirection,
    /// Discrete variables given new values.
    pub sets: Vec<(SymId, ExprId)>,
    /// Coordinates, speeds or added states given new values.
    pub resets: Vec<(SymId, ExprId)>,
    /// The run ends at the event.
    pub stop: bool,
    /// The indicator's declared unit.
    pub unit: Option<String>,
}

impl System {
    /// Declares a discrete variable with its initial value and unit.
    pub fn add_discrete(
        &mut self,
        name: &str,
        default: f64,
        unit: Option<&str>,
    ) -> Result<SymId, ModelError> {
        let s = self.add_run_time_value(name, SymbolKind::Discrete { default }, unit)?;
        let zero = self.arena.zero();
        self.arena.set_dxdt(s, zero);
        self.discrete.push(s);
        Ok(s)
    }

    /// Adds an event (its targets checked: discrete variables are set,
    /// coordinates, speeds and added states reset).
    pub fn add_event(&mut self, event: Event) -> Result<(), ModelError> {
        if self.events.iter().any(|e| e.name == event.name) {
            return Err(ModelError::DuplicateName(event.name));
        }
        for (s, _) in &event.sets {
            if !self.discrete.contains(s) {
                return Err(ModelError::Invalid(format!(
                    "`{}` is not a discrete variable",
                    self.arena.symbol(*s).name
                )));
            }
        }
        for (s, _) in &event.resets {
            let kind = &self.arena.symbol(*s).kind;
            if !matches!(
                kind,
                SymbolKind::Coordinate { .. } | SymbolKind::Speed { .. } | SymbolKind::State { .. }
            ) {
                return Err(ModelError::Invalid(format!(
                    "`{}` is not a state",
                    self.arena.symbol(*s).name
                )));
            }
        }
        self.events.push(event);
        Ok(())
    }

    /// Discrete variables in declaration order.
    pub fn discrete(&self) -> &[SymId] {
        &self.discrete
    }

    /// Events in declaration order.
    pub fn events(&self) -> &[Event] {
        &self.events
    }
}
