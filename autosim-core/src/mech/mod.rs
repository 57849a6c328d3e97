//! The multibody system: frames, basis-free vectors, bodies, kinematics and
//! Kane's equations.

mod body;
mod error;
mod frames;
mod framevec;
mod kane;
mod kinematics;
mod system;
mod vector;
mod vector_ops;

pub use error::{ItemRef, LocatedError, ModelError};
pub use frames::{Frame, FrameId, Frames, Uv, UvId};
pub use framevec::{Fv, Mat3};
pub use kane::Equations;
pub use system::{
    Body, BodyId, BodySpec, Coordinate, Direction, DofKind, ExtraState, Force, Moment, Output,
    Point, PointId, Subroutine, System,
};
pub use vector::{Dyadic, Vector};
