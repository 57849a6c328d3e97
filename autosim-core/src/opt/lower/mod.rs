//! From the equations to IR nodes: expressions (`expr.rs`), what lowering
//! hands to scheduling (`equations.rs`), and the two lowerings of a model
//! (`tree_model.rs`, `constrained.rs`).

pub(super) mod constrained;
pub(super) mod equations;
pub(super) mod expr;
pub(super) mod tree_model;
