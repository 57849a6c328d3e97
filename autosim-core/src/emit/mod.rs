//! Emission: Rust tokens for the macro, a formatted file for build scripts,
//! and Markdown documentation.

mod block;
mod expr;
mod file;
mod model;

pub use file::{format_tokens, header, source_hash};
pub use model::{EmitOptions, model_tokens, ops_summary, snake_case};
