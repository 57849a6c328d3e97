//! From the equations to IR nodes: one lowering context (`context.rs`:
//! arena, IR, environment, user calls, errors naming their item, and the
//! pieces both lowerings share) over the expression lowering (`expr.rs`),
//! the two lowerings of a model (`tree_model.rs`, `constrained.rs`), the
//! events (`events.rs`), and what they hand to scheduling
//! (`equations.rs`).

pub(crate) mod constrained;
mod context;
pub(crate) mod equations;
pub(crate) mod events;
mod expr;
pub(crate) mod tree_model;

pub(crate) use context::Lowering;

use crate::mech::Equations;
use crate::opt::input::Declared;
use crate::opt::split::Split;

/// What a lowering reads: the equations, what the model declares beside
/// them, and which speeds are states.
#[derive(Clone, Copy)]
pub(crate) struct Given<'a> {
    /// Kane's equations.
    pub eqs: &'a Equations,
    /// What the model declares.
    pub declared: &'a Declared,
    /// Which speeds are states.
    pub split: &'a Split,
}
