//! Why a program could not be built (below every lowering, which reports
//! it).

use crate::mech::ItemRef;

/// Why a program could not be built.
#[derive(Clone, Debug, PartialEq)]
pub enum ProgramError {
    /// An expression of `item` uses a symbol that has no value at run time.
    Unbound {
        /// The symbol's name.
        name: String,
        /// The item whose expression uses it.
        item: ItemRef,
    },
    /// An event resets a coordinate or speed that is not a state of the
    /// generated model (a dependent one, solved from the constraints, or
    /// one a motion prescribes).
    EventReset {
        /// The coordinate's or speed's name.
        name: String,
        /// The event.
        item: ItemRef,
    },
    /// An event's indicator or action reads a dependent speed, which only
    /// `derivatives` solves.
    EventReads {
        /// The speed's name.
        name: String,
        /// The event.
        item: ItemRef,
    },
}

impl ProgramError {
    /// The item whose expression caused the error.
    pub fn item(&self) -> ItemRef {
        match self {
            ProgramError::Unbound { item, .. }
            | ProgramError::EventReset { item, .. }
            | ProgramError::EventReads { item, .. } => *item,
        }
    }

    /// How to fix it, where there is a fix to suggest.
    pub fn help(&self) -> Option<&'static str> {
        match self {
            ProgramError::Unbound { .. } => None,
            ProgramError::EventReset { .. } => Some(
                "reset the independent coordinates and speeds only: after the event the run solves the dependent coordinates again (assembly), and the dependent speeds follow from the independent ones; name the ones you want to reset independent with the constraint's `dependent:`",
            ),
            ProgramError::EventReads { .. } => Some(
                "write the indicator or value with the independent speeds (the state), or name this speed independent with another constraint's `dependent:`",
            ),
        }
    }
}

impl std::fmt::Display for ProgramError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ProgramError::Unbound { name, .. } => {
                write!(f, "`{name}` has no value in the generated program")
            }
            ProgramError::EventReset { name, .. } => write!(
                f,
                "an event cannot reset `{name}`: it is not a state of the generated model (a dependent coordinate or speed of a constraint, or prescribed by a motion)"
            ),
            ProgramError::EventReads { name, .. } => write!(
                f,
                "an event cannot read `{name}`: it is a dependent speed, solved from the constraints only in `derivatives`"
            ),
        }
    }
}
