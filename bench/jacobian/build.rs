//! Compiles every model `run.sh` put into `models/` with `linearize = true`
//! (the chains also with `outputs = []`: their `linearize()` is then the
//! state Jacobian A alone, what CasADi's side computes), and writes
//! `registry.rs` into `OUT_DIR`: the `include_model!` lines and `dispatch`,
//! which runs `src/main.rs`'s generic `run` on the model of a given name.

use autosim_core::model::Scene;
use std::fmt::Write;
use std::path::PathBuf;

fn main() {
    let mut models: Vec<PathBuf> = std::fs::read_dir("models")
        .map(|dir| dir.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    models.retain(|p| p.extension().is_some_and(|x| x == "sim"));
    models.sort();
    println!("cargo::rerun-if-changed=models");
    let mut registry = String::new();
    let mut arms = String::new();
    let mut names = Vec::new();
    for path in &models {
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        let chain = stem.starts_with("chain_");
        let scene = Scene {
            linearize: Some(true),
            outputs: chain.then(Vec::new),
            ..Scene::default()
        };
        let compiled = match autosim::build::Config::new().scene(scene).compile(&[path]) {
            Ok(mut c) => c.remove(0),
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(1);
            }
        };
        let _ = writeln!(registry, "autosim::include_model!({});", compiled.module);
        let _ = writeln!(
            arms,
            "        \"{stem}\" => run({ty}::new(), {ty}::LINEARIZE_OPS.total(), |m: &mut {ty}, x| {{ let _ = black_box(m.linearize(0.0, x)); }}, name, mode),",
            ty = format!("{}::{}", compiled.module, compiled.model)
        );
        names.push(format!("\"{stem}\""));
    }
    let _ = writeln!(
        registry,
        "/// The models compiled, by file name.\npub const MODELS: &[&str] = &[{}];",
        names.join(", ")
    );
    let _ = writeln!(
        registry,
        "/// Runs `mode` on the model named `name` (false: no such model).\nfn dispatch(name: &str, mode: &Mode) -> bool {{\n    match name {{\n{arms}        _ => return false,\n    }}\n    true\n}}"
    );
    let out = PathBuf::from(std::env::var_os("OUT_DIR").unwrap()).join("registry.rs");
    std::fs::write(out, registry).unwrap();
}
