//! A model's interface as JSON, the form the Python package (and a model's
//! native module, which embeds it) reads: names, units, defaults and docs
//! of parameters, inputs, states and outputs; the state layout; user code;
//! constraints, motions and what assembly solves; the linear states; the
//! discrete variables and events.

use autosim_core::mech::{ConstraintKind, EventDirection};
use autosim_core::opt::{Interface, Quantity, StateVar};
use serde_json::{Value, json};

/// The interface as a JSON object (see the module docs; read by
/// `autosim._interface.Interface`).
pub fn to_json(interface: &Interface) -> String {
    let layout = &interface.states;
    let states: Vec<Value> = layout
        .coordinates
        .iter()
        .map(|s| state(s, "coordinate"))
        .chain(layout.speeds.iter().map(|s| state(s, "speed")))
        .chain(layout.extra.iter().map(|s| state(s, "extra")))
        .collect();
    let user_code: Vec<&str> = interface
        .model
        .extern_fns
        .iter()
        .chain(&interface.model.subroutines)
        .map(|u| u.name.as_str())
        .collect();
    let constraints: Vec<Value> = interface
        .model
        .constraints
        .iter()
        .map(|c| {
            json!({
                "name": c.name,
                "kind": match c.kind {
                    ConstraintKind::Position => "position",
                    ConstraintKind::Speed => "speed",
                },
                "dependent_speed": c.dependent_speed,
                "dependent_coordinate": c.dependent_coordinate,
                "unit": c.unit,
                "doc": docs(&c.docs),
            })
        })
        .collect();
    let motions: Vec<Value> = interface
        .model
        .motions
        .iter()
        .map(|m| json!({"name": m.name, "coordinate": m.coordinate, "doc": docs(&m.docs)}))
        .collect();
    let events: Vec<Value> = interface
        .model
        .events
        .iter()
        .map(|e| {
            json!({
                "name": e.name,
                "direction": match e.direction {
                    EventDirection::Rising => "rising",
                    EventDirection::Falling => "falling",
                    EventDirection::Either => "either",
                },
                "stop": e.stop,
                "unit": e.unit,
                "doc": docs(&e.docs),
            })
        })
        .collect();
    let value = json!({
        "name": interface.model.name,
        "doc": docs(&interface.model.docs),
        "parameters": quantities(&interface.model.parameters),
        "inputs": quantities(&interface.model.inputs),
        "states": states,
        "n_speeds": layout.n_speeds(),
        "outputs": quantities(&interface.model.outputs),
        "user_code": user_code,
        "constraints": constraints,
        "motions": motions,
        "dependent_coordinates": interface.closures.iter().map(|c| c.slot).collect::<Vec<_>>(),
        "linear_states": interface.linear_states,
        "discrete": quantities(&interface.model.discrete),
        "events": events,
        "cautions": interface.model.cautions,
    });
    value.to_string()
}

fn state(s: &StateVar, kind: &str) -> Value {
    json!({"name": s.name, "unit": s.unit, "kind": kind})
}

fn quantities(list: &[Quantity]) -> Vec<Value> {
    list.iter()
        .map(|q| {
            json!({
                "name": q.name,
                "unit": q.unit,
                "default": q.default,
                "doc": q.docs.as_deref().map(docs).unwrap_or_default(),
            })
        })
        .collect()
}

/// Doc comment lines as one text (each line's leading space removed).
fn docs(lines: &[String]) -> String {
    lines
        .iter()
        .map(|l| l.strip_prefix(' ').unwrap_or(l))
        .collect::<Vec<_>>()
        .join("\n")
        .trim()
        .to_string()
}
