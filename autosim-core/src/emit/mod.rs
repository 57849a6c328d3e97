//! Emission: Rust tokens for the macro, formatted files and Markdown
//! documentation for build scripts.

mod block;
pub mod build;
mod expr;
mod file;
mod markdown;
mod model;

pub use file::{format_tokens, header, source_hash};
pub use markdown::markdown;
pub use model::{EmitOptions, model_tokens, ops_summary, snake_case};
