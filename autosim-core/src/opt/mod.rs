//! The equation program: lowering to an operation IR, the unrolled solve of
//! the mass matrix, scheduling (named intermediates, hoisted constants,
//! call order) and operation counts (the paper's Eqs. 12-23), with the
//! interface generated code exposes, a text form and a verifier.

mod articulated;
mod axis_rotation;
mod common;
mod constrained;
mod cost;
pub mod dependencies;
mod elim;
mod interface;
mod interleave;
mod interp;
mod ir;
mod linearize;
mod lower;
mod lowered;
mod naming;
mod program;
mod schedule;
mod solve;
mod split;
mod tangent;
mod text;
mod tree;
mod verify;

pub use interface::{
    Closure, ConstraintInfo, Interface, MotionInfo, Quantity, StateLayout, StateVar, UserCode,
};
pub use interp::{At, Interpreter, SolveError, UserCalls};
pub use ir::{Ir, Leaf, Nid, Op};
pub use lower::{Lowering, UnboundSymbol};
pub use program::{BlockKind, MassLayout, Program, ProgramError, build};
pub use schedule::{Block, Guard, Ops, Stmt, Task};
pub use split::Split;
