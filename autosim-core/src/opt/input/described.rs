//! What generated code exposes of a model as the model declares it (names,
//! units, defaults, docs, spans), handed to opt with its input; opt adds
//! the state vector and what it solves for (`Interface`).

use crate::diag::Span;
use crate::mech::{ConstraintKind, EventDirection};

/// What generated code exposes of a model as the model declares it:
/// names, units, defaults, docs and spans (opt adds the state vector and
/// what it solves for).
#[derive(Clone, Debug)]
pub struct Described {
    /// The model's name (the generated type).
    pub name: String,
    /// The model's doc comments.
    pub docs: Vec<String>,
    /// Parameters in declaration order.
    pub parameters: Vec<Quantity>,
    /// Inputs in declaration order.
    pub inputs: Vec<Quantity>,
    /// The outputs: the model's, then the residual of each position
    /// constraint and the force of each motion.
    pub outputs: Vec<Quantity>,
    /// User functions, by `UserFnId` index.
    pub extern_fns: Vec<UserCode>,
    /// User subroutines in declaration order.
    pub subroutines: Vec<UserCode>,
    /// Constraints in declaration order.
    pub constraints: Vec<ConstraintInfo>,
    /// Prescribed motions in declaration order.
    pub motions: Vec<MotionInfo>,
    /// Discrete variables in declaration order (`default`: the initial
    /// value).
    pub discrete: Vec<Quantity>,
    /// Events in declaration order.
    pub events: Vec<EventInfo>,
    /// Cautions for the user, printed in the model's documentation.
    pub cautions: Vec<String>,
    /// The units the unit check inferred for states declared without one
    /// (by name): shown in the documentation only.
    pub inferred_state_units: std::collections::BTreeMap<String, String>,
}

/// A named value of the interface: a parameter (a field of `Parameters`),
/// an input (of `Inputs`) or an output.
#[derive(Clone, Debug)]
pub struct Quantity {
    /// Name.
    pub name: String,
    /// Unit text (empty when none).
    pub unit: String,
    /// The unit the unit check inferred, when none is declared (empty
    /// otherwise): shown in the documentation only.
    pub inferred_unit: String,
    /// Default value (0 for outputs).
    pub default: f64,
    /// The model's doc comments; `None` for a parameter the compiler
    /// declared (a body's default mass or inertia).
    pub docs: Option<Vec<String>>,
    /// Where it is declared (the body, for a default mass property).
    pub span: Span,
}

/// User code the model calls: an `extern fn` (one value) or an `extern
/// sub` (an array of values), a method of the `Externs` trait.
#[derive(Clone, Debug)]
pub struct UserCode {
    /// Name.
    pub name: String,
    /// Formal argument names.
    pub params: Vec<String>,
    /// Names of the values a subroutine returns (empty for a function).
    pub outputs: Vec<String>,
    /// The declared unit of each argument (empty where none, and for a
    /// subroutine, whose arguments are expressions).
    pub param_units: Vec<String>,
    /// The declared unit of a function's result, or of each output of a
    /// subroutine (empty where none).
    pub result_units: Vec<String>,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
}

/// A constraint, as generated code and its documentation name it.
#[derive(Clone, Debug)]
pub struct ConstraintInfo {
    /// Name.
    pub name: String,
    /// Position or speed.
    pub kind: ConstraintKind,
    /// The speed it determines.
    pub dependent_speed: String,
    /// The coordinate it determines (position constraints).
    pub dependent_coordinate: Option<String>,
    /// Unit of its expression (empty when not given).
    pub unit: String,
    /// The unit the unit check inferred, when none is declared (empty
    /// otherwise): shown in the documentation only.
    pub inferred_unit: String,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
}

/// A prescribed motion.
#[derive(Clone, Debug)]
pub struct MotionInfo {
    /// Name (also the output of the generalized force that enforces it).
    pub name: String,
    /// The coordinate it drives.
    pub coordinate: String,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
}

/// An event, as generated code and its documentation name it.
#[derive(Clone, Debug)]
pub struct EventInfo {
    /// Name (the runtime's `EventIndicator::name`).
    pub name: String,
    /// Which sign changes fire it.
    pub direction: EventDirection,
    /// The run ends at the event.
    pub stop: bool,
    /// The unit of its indicator (empty when not given).
    pub unit: String,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
}
