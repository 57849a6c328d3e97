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
    generate_with(file, &EmitOptions::default())
}

fn generate_with(file: &str, options: &EmitOptions) -> String {
    let text = std::fs::read_to_string(models_dir().join(file)).expect("model file");
    let src = SourceFile::new(file, text);
    let c = compile_source(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)));
    format_tokens(&model_tokens(&c.program, options))
}

/// The `FINGERPRINT` line of a generated module.
fn fingerprint_line(code: &str) -> &str {
    code.lines()
        .find(|l| l.contains("pub const FINGERPRINT: u64 ="))
        .expect("a FINGERPRINT constant")
}

/// The fingerprint does not depend on where the runtime is nor on the
/// module's name (Python's and FMUs' builds write `::autosim_runtime` and
/// their own module name), so a study of one model reads the same
/// wherever it ran; it does depend on the model.
#[test]
fn the_fingerprint_is_the_models_wherever_it_is_built() {
    let mut python = EmitOptions::with_runtime_path("::autosim_runtime").expect("a path");
    python.module_name = Some("generated".to_string());
    for file in ["pendulum.sim", "four_bar.sim"] {
        let (user, other) = (generate(file), generate_with(file, &python));
        assert_ne!(user, other);
        assert_eq!(fingerprint_line(&user), fingerprint_line(&other), "{file}");
    }
    assert_ne!(
        fingerprint_line(&generate("pendulum.sim")),
        fingerprint_line(&generate("four_bar.sim"))
    );
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

/// The Markdown documentation of a model with events lists its discrete
/// variables (initial value, unit, description) and events (indicator
/// unit, direction, actions, description), prints each indicator and new
/// value as computed, and counts their operations (the bouncing ball's
/// lines, as its file declares them).
#[test]
fn markdown_lists_discrete_variables_and_events() {
    let file = "bouncing_ball.sim";
    let text = std::fs::read_to_string(models_dir().join(file)).expect("model file");
    let src = SourceFile::new(file, text);
    let c = compile_source(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)));
    let md = markdown(&c.program, file);
    for line in [
        "## Discrete variables",
        "| `resting` | 0 | 1 (inferred) | 1 once the ball rests on the floor, 0 while it bounces. |",
        "## Events",
        "| `apex` | m/s | falling | observed | The top of each flight (observed only: no action). |",
        "### Event indicators",
        "g_bounce = h",
        "g_apex = v",
        "### Event `bounce`",
        "| event indicators | 0 | 0 | 0 | 0 |",
    ] {
        assert!(md.lines().any(|l| l == line), "no line `{line}` in:\n{md}");
    }
    let bounce = md
        .lines()
        .find(|l| l.starts_with("| `bounce` |"))
        .expect("the bounce row");
    assert!(
        bounce.starts_with(
            "| `bounce` | m | falling | set `resting`; reset `v` | The ball reaches the floor"
        ),
        "{bounce}"
    );
    let equations = md
        .split("### Event `bounce`")
        .nth(1)
        .expect("its equations");
    assert!(
        equations.contains("v⁺ = ") && equations.contains("resting⁺ = "),
        "{equations}"
    );
    assert!(
        !md.contains("### Event `apex`"),
        "an observed event has no new values"
    );
    insta::assert_snapshot!("bouncing_ball_markdown", md);
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
/// branch-free kernel, and a cosine needed alone by the branch-free lone
/// one; `f32` models call libm's `sincosf` and `cosf` for every angle
/// (the kernels compute in `f64`, in software on a single-precision FPU).
#[test]
fn branch_free_sines_in_f64_models_only() {
    let f64_code = generate("chain_planar_2.sim");
    assert!(f64_code.contains("math::sin_cos_lanes([q2, q1])"));
    assert!(f64_code.contains("math::cos_inline(q2)"));
    assert!(!f64_code.contains("math::cos(") && !f64_code.contains("math::sin("));
    let f32_code = generate("chain_planar_2_f32.sim");
    assert!(f32_code.contains("math::sin_cos(q1)"));
    assert!(f32_code.contains("math::cos(q2)"));
    for branch_free in [
        "sin_cos_lanes",
        "sin_cos_inline",
        "sin_inline",
        "cos_inline",
    ] {
        assert!(
            !f32_code.contains(branch_free),
            "{branch_free} in an f32 model"
        );
    }
}
