//! The `model!` procedural macro of autosim: a shell around
//! [`autosim_core::expand::expand_model`], which does all the work (tokens
//! or a `.sim` file in, the generated module out, errors with spans).

use std::path::PathBuf;

/// Compiles a model into a Rust module.
///
/// Inline: `autosim::model! { model Pendulum; ... }`. From a file relative to
/// the crate root: `autosim::model!(file = "models/pendulum.sim");` (the crate
/// is rebuilt when the file changes), optionally followed by scene options
/// `key = value` that tailor the model to one use (they override the file's
/// `settings` and add to its bodies' options; every mistake among them is
/// reported at once):
///
/// - `name = RigidBoom`: a new name for the model and its module.
/// - `float = f32`: the float type of generated code (`f64` or `f32`).
/// - `threshold = 3`: the small-term threshold (an integer from 1 to 20).
/// - `outputs = [roll, yaw]`: generate only these outputs.
/// - `small = [B, q9]`: bodies (all their degrees of freedom) or
///   coordinates made small.
/// - `lock = [q9, q10]`: bodies or coordinates locked (each becomes a
///   parameter).
/// - `linearize = true`: also generate `linearize` (A, B, C, D).
/// - `formulation = recursive`: how a tree's accelerations are solved
///   (`auto`, `mass_matrix` or `recursive`).
/// - `lanes = true`: also generate `derivatives_lanes` (several states
///   per call, which `Model::derivatives_batch` then uses; `f64` models).
///
/// Either way the macro expands to `pub mod <model_name_in_snake_case> {
/// ... }` holding the model type, its `Parameters`, `Inputs` and (if it
/// calls user code) `Externs` trait.
#[proc_macro]
pub fn model(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    let crate_root = std::env::var("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_default();
    autosim_core::expand::expand_model(input.into(), &crate_root).into()
}

#[cfg(test)]
mod tests {
    use autosim_core::syntax::ast::{OptionKey, SceneKey};

    /// The options the docs of `model!` list, in order (`/// - `key = ...`).
    fn documented() -> Vec<String> {
        include_str!("lib.rs")
            .lines()
            .filter_map(|l| l.trim().strip_prefix("/// - `"))
            .filter_map(|l| l.split_once(" = ").map(|(key, _)| key.to_string()))
            .collect()
    }

    /// Every scene option is documented, in the order of the key table, and
    /// nothing else is.
    #[test]
    fn the_docs_list_every_scene_option() {
        let keys: Vec<&str> = SceneKey::ALL.iter().map(|(text, _)| *text).collect();
        assert_eq!(documented(), keys);
    }
}
