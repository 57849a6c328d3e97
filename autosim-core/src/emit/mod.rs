//! Emission: Rust tokens for the macro, formatted files and Markdown
//! documentation, from the program and its interface alone.

mod block;
mod copy_macros;
mod expr;
mod file;
mod lane_values;
mod markdown;
mod model;
mod pack;
mod parts;
mod placeholder;
mod sines;

pub use file::{format_tokens, header, source_hash};
pub use markdown::markdown;
pub use model::{EmitOptions, model_tokens, snake_case};
pub use placeholder::{Outline, placeholder};
