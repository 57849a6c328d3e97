//! The `model!` procedural macro of autosim: a shell around
//! [`autosim_core::expand::expand_model`], which does all the work (tokens
//! or a `.sim` file in, the generated module out, errors with spans).

use std::path::PathBuf;

/// Compiles a model into a Rust module.
///
/// Inline: `autosim::model! { model Pendulum; ... }`. From a file relative to
/// the crate root: `autosim::model!(file = "models/pendulum.sim");` (the crate
/// is rebuilt when the file changes), optionally with scene options that
/// tailor the model to one use: `name = RigidBoom`, `float = f32`,
/// `threshold = 3`, `outputs = [roll, yaw]`, `small = [B, q9]`,
/// `lock = [q9, q10]` (bodies or coordinates). Either way the macro expands to
/// `pub mod <model_name_in_snake_case> { ... }` holding the model type, its
/// `Parameters`, `Inputs` and (if it calls user code) `Externs` trait.
#[proc_macro]
pub fn model(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    let crate_root = std::env::var("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_default();
    autosim_core::expand::expand_model(input.into(), &crate_root).into()
}
