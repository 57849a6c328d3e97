//! The equation program: lowering to an operation IR, the unrolled solve of
//! the mass matrix, scheduling (named intermediates, hoisted constants,
//! call order) and operation counts (the paper's Eqs. 12-23), with the
//! interface generated code exposes, a text form and a verifier.

mod ir;
mod linearize;
mod lower;
mod program;
mod schedule;
mod solve;
mod split;

pub use ir::{Ir, Leaf, Nid, Op};
pub use lower::expr::{Lowering, UnboundSymbol};
pub use program::interface::{
    Closure, ConstraintInfo, Interface, MotionInfo, Quantity, StateLayout, StateVar, UserCode,
};
pub use program::interp::{At, Interpreter, SolveError, UserCalls};
pub use program::{BlockKind, MassLayout, Program, ProgramError, build};
pub use schedule::{Block, Guard, Ops, Stmt, Task};
pub use split::Split;
