//! The equation program: lowering to an operation IR, the unrolled solve of
//! the mass matrix, scheduling (named intermediates, hoisted constants,
//! call order) and operation counts (the paper's Eqs. 12-23).

mod interp;
mod ir;
mod lower;
mod program;
mod schedule;
mod solve;

pub use interp::{Interpreter, SolveError};
pub use ir::{Ir, Leaf, Nid, Op};
pub use lower::{Lowering, UnboundSymbol};
pub use program::{Program, ProgramError, build};
pub use schedule::{Block, Ops, Stmt, Task};
