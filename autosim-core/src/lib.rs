//! autosim-core: the compiler behind autosim.
//!
//! The pipeline, one module per phase, data flowing forward only:
//! `syntax` (model text → AST with spans) → `model` (resolve names, build
//! the multibody system) → `mech` (kinematics and Kane's equations) →
//! `opt` (the equation program: constants hoisted, common subexpressions
//! named once) → `emit` (Rust tokens, formatted files, Markdown). The
//! symbolic algebra every phase uses lives in `expr`; diagnostics in `diag`.
#![deny(missing_docs)]
// Index loops over 3×3 components read like the mathematics they implement.
#![allow(clippy::needless_range_loop)]

pub mod build_script;
pub mod diag;
pub mod emit;
pub mod expand;
pub mod expr;
mod ids;
pub mod limits;
pub mod mech;
pub mod model;
pub mod opt;
pub mod pipeline;
pub mod syntax;
