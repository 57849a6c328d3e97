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
}

impl ProgramError {
    /// The item whose expression caused the error.
    pub fn item(&self) -> ItemRef {
        match self {
            ProgramError::Unbound { item, .. } => *item,
        }
    }
}

impl std::fmt::Display for ProgramError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ProgramError::Unbound { name, .. } => {
                write!(f, "`{name}` has no value in the generated program")
            }
        }
    }
}
