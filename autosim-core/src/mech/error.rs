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
    /// A mistake in one option of a body's specification.
    Body {
        /// Body name.
        body: String,
        /// The option at fault.
        field: BodyField,
        /// What is wrong.
        message: String,
        /// How to fix it, if there is more to say than the message.
        help: Option<String>,
    },
    /// A mistake in one option of a constraint or motion.
    Option {
        /// The item's name.
        item: String,
        /// The option at fault, as written (`position`, `dependent`, ...).
        key: &'static str,
        /// What is wrong.
        message: String,
        /// How to fix it.
        help: String,
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
    /// The body `N` cannot be redefined or given options.
    InertialFrame(String),
    /// Something else about an expression.
    Expr(ExprError),
    /// A body, point or force refers to something invalid.
    Invalid(String),
}

/// The option of a body's specification a problem is in, so that a front
/// end can point at its text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BodyField {
    /// The whole list of translations.
    Translations,
    /// One translation (by position).
    Translation(usize),
    /// The rotation.
    Rotation,
    /// The reference direction of a rotation about a direction.
    Reference,
    /// A constant rotation (by position).
    FixedRotation(usize),
    /// The joint point.
    JointPoint,
    /// The mass center.
    Cm,
    /// The mass.
    Mass,
    /// The inertia matrix.
    Inertia,
    /// The small-variable flags.
    Small,
    /// The lock flags.
    Lock,
    /// The coordinate names.
    CoordinateNames,
    /// The speed names.
    SpeedNames,
    /// The initial coordinates.
    InitialCoordinates,
    /// The initial speeds.
    InitialSpeeds,
}

impl ModelError {
    /// A mistake in option `field` of body `body`.
    pub fn body(body: &str, field: BodyField, message: String) -> ModelError {
        ModelError::Body {
            body: body.to_string(),
            field,
            message,
            help: None,
        }
    }

    /// The same error with a fix to suggest.
    pub fn with_help(mut self, text: &str) -> ModelError {
        if let ModelError::Body { help, .. } = &mut self {
            *help = Some(text.to_string());
        }
        self
    }

    /// The message as said where the option is shown (without naming the
    /// body again).
    pub fn local_message(&self) -> String {
        match self {
            ModelError::Body { message, .. } => message.clone(),
            other => other.to_string(),
        }
    }

    /// The fix to suggest, where the message does not say it.
    pub fn help(&self) -> Option<&str> {
        match self {
            ModelError::Body { help, .. } => help.as_deref(),
            ModelError::Option { help, .. } => Some(help),
            _ => None,
        }
    }
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
            ModelError::Body { body, message, .. } => {
                if message.contains(&format!("`{body}`")) {
                    write!(f, "{message}")
                } else {
                    write!(f, "body `{body}`: {message}")
                }
            }
            ModelError::Option { message, .. } => write!(f, "{message}"),
            ModelError::NotConstant { what } => write!(
                f,
                "the {what} must be constant (parameters and numbers only)"
            ),
            ModelError::TypeMismatch {
                context,
                expected,
                found,
            } => write!(f, "{context} needs a {expected}, but this is a {found}"),
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
    /// A constraint, by index in [`System::constraints`](super::System::constraints).
    Constraint(usize),
    /// A prescribed motion, by index in [`System::motions`](super::System::motions).
    Motion(usize),
    /// An event, by index in [`System::events`](super::System::events).
    Event(usize),
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
