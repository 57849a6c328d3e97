//! The multibody system: frames, basis-free vectors, bodies, kinematics and
//! Kane's equations.

mod body;
mod body_check;
mod body_order;
mod constraint;
mod declare;
mod energy;
mod error;
mod event;
mod frames;
mod framevec;
mod joint;
mod kane;
mod kinematics;
mod system;
mod vector;
mod vector_ops;

pub use body_order::{ParentOrder, order_parents_first};
pub use constraint::{Constraint, ConstraintKind, ConstraintLoad, Motion};
pub use error::{BodyField, ItemRef, LocatedError, ModelError};
pub use event::{Event, EventDirection};
pub use frames::{Frame, FrameId, Frames, Uv, UvId};
pub use framevec::{Fv, Mat3};
pub use joint::{Axis, Direction, DofKind, FixedTurn, Joint, Rotation, UnitMotion};
pub use kane::{
    BodyKinetics, ConstraintEquations, ConstraintRow, Equations, JointReaction, Prescribed,
    TreeKinetics,
};
pub use system::{
    Body, BodyId, BodySpec, Coordinate, ExtraState, Force, Load, Moment, Output, Point, PointId,
    Subroutine, System,
};
pub use vector::{Dyadic, Vector};
