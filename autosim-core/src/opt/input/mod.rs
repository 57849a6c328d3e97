//! What opt is given: one owned value, built by `pipeline.rs` from the
//! resolved model and its equations. opt reads nothing else (it imports
//! nothing from `model`).

mod described;

pub use described::{ConstraintInfo, Described, EventInfo, MotionInfo, Quantity, UserCode};

use crate::expr::{Arena, ExprId, SymId};
use crate::mech::{Equations, ItemRef};

/// Everything the program of a model is built from.
#[derive(Clone, Debug)]
pub struct Input {
    /// The arena of every expression below (lowering adds the products it
    /// splits off).
    pub arena: Arena,
    /// Kane's equations.
    pub equations: Equations,
    /// What the model declares beside its equations of motion.
    pub declared: Declared,
    /// What generated code exposes of the model as declared.
    pub described: Described,
    /// What the program is asked for.
    pub options: Options,
}

/// What a model declares beside its equations of motion, as symbols and
/// expressions of the input's arena.
#[derive(Clone, Debug)]
pub struct Declared {
    /// Parameters in declaration order (`Leaf::Param` indices).
    pub parameters: Vec<SymId>,
    /// Inputs in declaration order (`Leaf::Input` indices).
    pub inputs: Vec<SymId>,
    /// The time symbol.
    pub time: SymId,
    /// The user subroutines, in declaration order.
    pub subroutines: Vec<SubroutineCall>,
    /// The outputs' expressions, in order.
    pub outputs: Vec<ExprId>,
    /// Each coordinate's item (its body), which errors of its equations
    /// name.
    pub coordinate_items: Vec<ItemRef>,
    /// Each coordinate's initial value.
    pub initial_q: Vec<ExprId>,
    /// Each speed's initial value.
    pub initial_u: Vec<ExprId>,
    /// Each extra state's initial value (the order of
    /// `Equations::states`).
    pub initial_states: Vec<ExprId>,
    /// Discrete variables in declaration order (`Leaf::Discrete` indices).
    pub discrete: Vec<SymId>,
    /// The events in declaration order.
    pub events: Vec<EventCode>,
}

/// What an event computes: its indicator and the new values of its
/// actions, all expressions of the values before the event.
#[derive(Clone, Debug)]
pub struct EventCode {
    /// The indicator.
    pub indicator: ExprId,
    /// Discrete variables set: index in `Declared::discrete`, new value.
    pub sets: Vec<(usize, ExprId)>,
    /// States reset: the symbol (a coordinate, speed or added state), new
    /// value.
    pub resets: Vec<(SymId, ExprId)>,
}

/// A user subroutine: its arguments and the symbols it sets.
#[derive(Clone, Debug)]
pub struct SubroutineCall {
    /// The argument expressions.
    pub args: Vec<ExprId>,
    /// The symbols it sets (`Leaf::SubOut`).
    pub outputs: Vec<SymId>,
}

/// What the program is asked for (the model's `settings` and the scene's
/// options).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// How a tree's accelerations are solved.
    pub formulation: Formulation,
    /// Generate the linearization.
    pub linearize: bool,
    /// Generate `derivatives_lanes` (many states per call).
    pub lanes: bool,
    /// The float type of generated code.
    pub float: FloatType,
}

/// The float type generated code computes in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FloatType {
    /// `f64` (default).
    #[default]
    F64,
    /// `f32`.
    F32,
}

/// How a tree's accelerations are solved in generated code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Formulation {
    /// Both are built; the one estimated faster per `derivatives` call
    /// (operations plus the longest chain of dependent operations, in
    /// cycles) is generated (default).
    #[default]
    Auto,
    /// The mass matrix and its unrolled LDLᵀ (O(n²) entries, O(n³) factor
    /// for a chain; the cheapest for small models).
    MassMatrix,
    /// The articulated-body recursion (O(n), the mass matrix never
    /// formed; the cheapest for long chains).
    Recursive,
}

impl Formulation {
    /// The names a model writes, in the order the documentation lists them.
    pub const NAMES: [&'static str; 3] = ["auto", "mass_matrix", "recursive"];

    /// The formulation called `name` in a model (`settings` or the macro's
    /// option).
    pub fn named(name: &str) -> Option<Formulation> {
        match name {
            "auto" => Some(Formulation::Auto),
            "mass_matrix" => Some(Formulation::MassMatrix),
            "recursive" => Some(Formulation::Recursive),
            _ => None,
        }
    }

    /// What to tell a user who wrote `name` for a formulation: the likely
    /// intended name, or what the three do.
    pub fn help_for(name: &str) -> String {
        match crate::diag::did_you_mean(name, Formulation::NAMES) {
            Some(close) => format!("did you mean `{close}`?"),
            None => "`auto` (the default) generates whichever is estimated faster; \
                     `mass_matrix` forms M and factors it, `recursive` runs the \
                     articulated-body recursion"
                .to_string(),
        }
    }
}
