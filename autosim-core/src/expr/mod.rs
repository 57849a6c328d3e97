//! Scalar expressions: a hash-consed arena with simplifying constructors,
//! calculus, evaluation and a text form.

mod angle_sum;
mod arena;
mod calculus;
mod construct;
mod count;
mod eval;
mod funcs;
mod number;
mod ops;
mod text;
mod trigpoly;

pub use arena::{
    Arena, ExprError, ExprId, Func, Meta, Node, SymId, Symbol, SymbolKind, UserFn, UserFnId,
};
pub use count::OpCount;
pub use eval::{Bindings, NoUserFunctions, UserFunctions};
pub use number::Number;
pub(crate) use text::Prec;

#[cfg(test)]
mod tests;
