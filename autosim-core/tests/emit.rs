//! Generated code: snapshots of small models (reviewed by eye when they
//! change), and determinism (the same model gives byte-identical output).

use autosim_core::diag::SourceFile;
use autosim_core::emit::{EmitOptions, format_tokens, markdown, model_tokens};
use autosim_core::pipeline::compile_source;
use std::path::PathBuf;

fn models_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/models")
}

fn generate(file: &str) -> String {
    let text = std::fs::read_to_string(models_dir().join(file)).expect("model file");
    let src = SourceFile::new(file, text);
    let c = compile_source(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)));
    format_tokens(&model_tokens(&c.program, &EmitOptions::default()))
}

#[test]
fn snapshot_chain_planar_2() {
    insta::assert_snapshot!("chain_planar_2", generate("chain_planar_2.sim"));
}

#[test]
fn snapshot_every_feature() {
    insta::assert_snapshot!("features", generate("features.sim"));
}

#[test]
fn snapshot_markdown() {
    let text =
        std::fs::read_to_string(models_dir().join("chain_planar_2.sim")).expect("model file");
    let src = SourceFile::new("chain_planar_2.sim", text);
    let c = compile_source(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)));
    insta::assert_snapshot!(
        "chain_planar_2_markdown",
        markdown(&c.program, "chain_planar_2.sim")
    );
}

/// Every example model, generated twice in one process, is byte-identical.
#[test]
fn generation_is_deterministic() {
    let mut files: Vec<String> = std::fs::read_dir(models_dir())
        .expect("examples/models")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| n.ends_with(".sim"))
        .collect();
    files.sort();
    assert!(
        files.len() >= 10,
        "expected the example models, found {files:?}"
    );
    for f in &files {
        let a = generate(f);
        let b = generate(f);
        assert!(a == b, "{f}: two generations differ");
    }
}

/// `f64` models take the sines of the angles they read in pairs by the
/// branch-free kernel; `f32` models call libm's `sincosf` for every angle
/// (the kernel computes in `f64`, in software on a single-precision FPU).
#[test]
fn sines_in_pairs_in_f64_models_only() {
    let f64_code = generate("chain_planar_2.sim");
    assert!(f64_code.contains("math::sin_cos_lanes([q2, q1])"));
    let f32_code = generate("chain_planar_2_f32.sim");
    assert!(f32_code.contains("math::sin_cos(q1)"));
    assert!(!f32_code.contains("sin_cos_lanes") && !f32_code.contains("sin_cos_inline"));
}
