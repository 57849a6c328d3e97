//! Models written in the language, compiled to programs, match the
//! reference data; the optimized program matches the unoptimized equations.

use autosim_core::diag::SourceFile;
use autosim_core::opt::{At, Interpreter, UserCalls};
use autosim_core::pipeline::{Compiled, compile_source};
use autosim_test_support::*;
use std::path::PathBuf;

fn models_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/models")
}

fn compile_file(name: &str) -> Compiled {
    let path = models_dir().join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let file = SourceFile::new(name, text);
    match compile_source(&file) {
        Ok(c) => c,
        Err(d) => panic!("{}", d.render(&file)),
    }
}

fn params_from(c: &Compiled, data: &serde_json::Value) -> Vec<f64> {
    c.program
        .interface
        .model
        .parameters
        .iter()
        .map(|p| {
            let n = &p.name;
            data["parameters"][n]
                .as_f64()
                .unwrap_or_else(|| panic!("no parameter {n}"))
        })
        .collect()
}

#[test]
fn satellite_program_matches_reference() {
    let c = compile_file("satellite.sim");
    let data = load("satellite");
    let params = params_from(&c, &data);
    let it = Interpreter::new(&c.program, &params);
    let n = c.program.n();
    let mut worst: f64 = 0.0;
    for s in data["samples"].as_array().unwrap() {
        let mut x = floats(&s["q"]);
        x.extend(floats(&s["u"]));
        let inp = &s["inputs"];
        let thr = [
            inp["thr1"].as_f64().unwrap(),
            inp["thr2"].as_f64().unwrap(),
            inp["thr3"].as_f64().unwrap(),
        ];
        let cmd = vec![
            inp["clkcmd"].as_f64().unwrap(),
            inp["camcmd"].as_f64().unwrap(),
        ];
        let mut function = |_f: usize, args: &[f64]| thr[args[1] as usize - 1];
        let mut subroutine = |_s: usize, _a: &[f64]| cmd.clone();
        let mut user = UserCalls {
            function: &mut function,
            subroutine: &mut subroutine,
        };
        let at = At {
            t: s["t"].as_f64().unwrap(),
            x: &x,
            inputs: &[],
            discrete: &[],
        };
        let dx = it.derivatives(at, &mut user).unwrap();
        let e_dq = rel_err(&dx[..n], &floats(&s["dq"]));
        let e_du = rel_err(&dx[n..], &floats(&s["du"]));
        worst = worst_of(worst_of(worst, e_dq), e_du);
        assert!(e_dq < 1e-9 && e_du < 1e-9, "dq {e_dq:e} du {e_du:e}");
    }
    eprintln!("satellite.sim program: worst relative error {worst:.2e}");
    eprintln!(
        "derivatives: {}",
        c.program
            .block(autosim_core::opt::BlockKind::Derivatives)
            .ops
    );
}

/// Scene options: locking the boom at the use site.
#[test]
fn scene_lock_boom() {
    use autosim_core::model::Scene;
    use autosim_core::pipeline::compile_source_scene;
    let path = models_dir().join("satellite.sim");
    let file = SourceFile::new("satellite.sim", std::fs::read_to_string(path).unwrap());
    let scene = Scene {
        lock: vec![Scene::name("q9"), Scene::name("q10")],
        ..Scene::default()
    };
    let c = match compile_source_scene(&file, &scene) {
        Ok(c) => c,
        Err(d) => panic!("{}", d.render(&file)),
    };
    assert_eq!(c.program.n(), 8);
}
