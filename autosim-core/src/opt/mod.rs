//! The equation program: lowering to an operation IR, the unrolled solve of
//! the mass matrix, scheduling (named intermediates, hoisted constants,
//! call order) and operation counts (the paper's Eqs. 12-23), with the
//! interface generated code exposes, a text form and a verifier. Its one
//! input is [`Input`], built by `pipeline.rs`.

pub mod dependencies;
mod error;
mod input;
mod interface;
mod ir;
mod linearize;
mod lower;
mod program;
mod schedule;
mod solve;
mod split;

pub use error::ProgramError;
pub use input::{
    ConstraintInfo, Declared, Described, EventCode, EventInfo, FloatType, Formulation, Input,
    MotionInfo, Options, Quantity, SubroutineCall, UserCode,
};
pub use interface::{Closure, Interface, StateLayout, StateVar};
pub use ir::{Ir, Leaf, Nid, Op};
pub use program::interp::{At, Interpreter, SolveError, UserCalls};
pub use program::{Assigned, BlockKind, MassLayout, Program, build};
pub use schedule::{Block, Guard, Ops, Stmt, Task};
pub use split::Split;
