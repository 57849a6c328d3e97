//! Errors of the multibody API: each says what is wrong and how to fix it.

use super::system::BodyId;
use crate::expr::{ExprError, SymId};
use std::fmt;

/// A mistake in a model built through the API.
#[derive(Clone, Debug, PartialEq)]
pub enum ModelError {
    /// A body name that does not exist.
    UnknownBody(String),
    /// A point name that does not exist.
    UnknownPoint(String),
    /// A name used twice.
    DuplicateName(String),
    /// Bodies whose parents form a cycle (names in cycle order).
    ParentCycle(Vec<String>),
    /// A rotation or translation axis outside 1..=3.
    AxisOutOfRange {
        /// Body name.
        body: String,
        /// The axis given.
        axis: i64,
    },
    /// A body with 2 or more than 3 rotations.
    RotationCount {
        /// Body name.
        body: String,
        /// Number of rotations given.
        count: usize,
    },
    /// More than three translations.
    TranslationCount {
        /// Body name.
        body: String,
        /// Number of translations given.
        count: usize,
    },
    /// A translation direction that is the zero vector.
    ZeroDirection {
        /// Body name.
        body: String,
    },
    /// A quantity that must be constant (parameters and numbers only) is not.
    NotConstant {
        /// What it is, e.g. "joint coordinates of body B".
        what: String,
    },
    /// A value of the wrong kind (scalar, vector, dyadic).
    TypeMismatch {
        /// Where it was used.
        context: String,
        /// The kind needed.
        expected: &'static str,
        /// The kind given.
        found: &'static str,
    },
    /// A wrong number of coordinate or speed names.
    NameCount {
        /// Body name.
        body: String,
        /// What was named ("coordinates" or "speeds").
        what: &'static str,
        /// Number of degrees of freedom.
        expected: usize,
        /// Number of names given.
        got: usize,
    },
    /// The body `N` cannot be redefined or given options.
    InertialFrame(String),
    /// Something else about an expression.
    Expr(ExprError),
    /// A body, point or force refers to something invalid.
    Invalid(String),
}

impl From<ExprError> for ModelError {
    fn from(e: ExprError) -> Self {
        ModelError::Expr(e)
    }
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ModelError::UnknownBody(n) => {
                write!(
                    f,
                    "unknown body `{n}`: declare it with `body {n} {{ ... }}`, or use `N` for the inertial frame"
                )
            }
            ModelError::UnknownPoint(n) => write!(
                f,
                "unknown point `{n}`: declare it with `point {n} in <body> at [x, y, z];`"
            ),
            ModelError::DuplicateName(n) => {
                write!(f, "the name `{n}` is defined twice: rename one of them")
            }
            ModelError::ParentCycle(names) => write!(
                f,
                "the parents of bodies {} form a cycle: every chain of parents must end at `N`",
                names
                    .iter()
                    .map(|n| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(" -> ")
            ),
            ModelError::AxisOutOfRange { body, axis } => write!(
                f,
                "axis {axis} of body `{body}` is out of range: axes are 1, 2 or 3"
            ),
            ModelError::RotationCount { body, count } => write!(
                f,
                "body `{body}` has {count} rotations: a body rotates 0, 1 or 3 times (e.g. `rotate: 3` or `rotate: [1, 2, 3]`)"
            ),
            ModelError::TranslationCount { body, count } => write!(
                f,
                "body `{body}` has {count} translations: at most 3 are allowed"
            ),
            ModelError::ZeroDirection { body } => write!(
                f,
                "a translation direction of body `{body}` is the zero vector"
            ),
            ModelError::NotConstant { what } => write!(
                f,
                "the {what} must be constant (parameters and numbers only)"
            ),
            ModelError::TypeMismatch {
                context,
                expected,
                found,
            } => write!(f, "{context} needs a {expected}, but this is a {found}"),
            ModelError::NameCount {
                body,
                what,
                expected,
                got,
            } => write!(
                f,
                "body `{body}` has {expected} degrees of freedom but {got} {what} names were given"
            ),
            ModelError::InertialFrame(msg) => write!(f, "{msg}"),
            ModelError::Expr(e) => write!(f, "{e}"),
            ModelError::Invalid(msg) => write!(f, "{msg}"),
        }
    }
}

impl std::error::Error for ModelError {}

/// The item of a system a problem is about, so that a front end can point
/// at the text that declared it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ItemRef {
    /// The model as a whole.
    Model,
    /// A body (its degrees of freedom, frames, mass properties).
    Body(BodyId),
    /// A force, by index in [`System::forces`](super::System::forces).
    Force(usize),
    /// A moment, by index in [`System::moments`](super::System::moments).
    Moment(usize),
    /// An added state variable.
    State(SymId),
    /// An output, by index.
    Output(usize),
    /// A user subroutine, by index.
    Subroutine(usize),
}

/// An error of an analysis of the system, with the item that caused it.
#[derive(Clone, Debug, PartialEq)]
pub struct LocatedError {
    /// The item.
    pub item: ItemRef,
    /// The error.
    pub error: ModelError,
}

impl LocatedError {
    /// `error`, caused by `item`.
    pub fn new(item: ItemRef, error: impl Into<ModelError>) -> LocatedError {
        LocatedError {
            item,
            error: error.into(),
        }
    }
}

impl fmt::Display for LocatedError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.error.fmt(f)
    }
}

impl std::error::Error for LocatedError {}
