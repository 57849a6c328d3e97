//! autosim: a symbolic multibody compiler.
pub use autosim_macros::model;
pub use autosim_runtime as runtime;
