//! The four-bar linkage (`examples/models/four_bar.sim`, a closed loop)
//! against `tests/reference/four-bar.json`: SymPy's `KanesMethod` with
//! configuration constraints, cross-checked by Newton–Euler with pin
//! multipliers (see `tests/reference/gen/four_bar.md`).

use autosim::runtime::{Model, ModelError};
use autosim_test_support::{floats, load, tight_run};
use serde_json::Value;

autosim::model!(file = "examples/models/four_bar.sim");
use four_bar::FourBar;

/// The model with the reference's parameters.
fn model(data: &Value) -> FourBar {
    let mut m = FourBar::new();
    let values: Vec<f64> = FourBar::PARAMETER_NAMES
        .iter()
        .map(|n| {
            data["parameters"][*n]
                .as_f64()
                .expect("parameter in the reference")
        })
        .collect();
    m.set_parameter_values(&values);
    m
}

/// The state `[q1, q2, q3, u1]` of a reference sample or record.
fn state(v: &Value) -> [f64; 4] {
    let (q, u) = (floats(&v["q"]), floats(&v["u"]));
    [q[0], q[1], q[2], u[0]]
}

#[test]
fn the_state_is_every_coordinate_and_the_independent_speed() {
    assert_eq!(FourBar::STATE_NAMES, ["q1", "q2", "q3", "u1"]);
    assert_eq!(FourBar::OUTPUT_NAMES, ["energy", "loop_n2", "loop_n3"]);
    assert_eq!(FourBar::OUTPUT_UNITS, ["J", "m", "m"]);
    assert_eq!(FourBar::DEPENDENT_COORDINATES, [1, 2]);
}

#[test]
fn derivatives_match_sympy_at_every_sample() {
    let data = load("four-bar");
    let mut m = model(&data);
    for (i, s) in data["samples"].as_array().unwrap().iter().enumerate() {
        let x = state(s);
        let mut dx = [0.0; 4];
        m.derivatives(0.0, &x, &mut dx).unwrap();
        let (dq, du) = (floats(&s["dq"]), floats(&s["du"]));
        let scale = du.iter().fold(1.0f64, |a, v| a.max(v.abs()));
        // dq/dt of all three coordinates (the dependent ones through the
        // solved dependent speeds), and du1/dt.
        for k in 0..3 {
            assert!(
                (dx[k] - dq[k]).abs() < 1e-12 * (1.0 + dq[k].abs()),
                "sample {i}: dq{k} {} vs {}",
                dx[k],
                dq[k]
            );
        }
        assert!(
            (dx[3] - du[0]).abs() < 1e-10 * scale,
            "sample {i}: du1 {} vs {}",
            dx[3],
            du[0]
        );
        // The energy output is `kinetic_energy() + potential_energy()`
        // plus the spring's: against SymPy's.
        let mut y = [0.0; 3];
        m.outputs(0.0, &x, &mut y).unwrap();
        assert!(
            (y[0] - s["energy"].as_f64().unwrap()).abs() < 1e-12 * y[0].abs(),
            "energy"
        );
        assert!(
            y[1].abs() < 1e-14 && y[2].abs() < 1e-14,
            "sample {i} is assembled: {y:?}"
        );
    }
}

#[test]
fn assembly_finds_the_reference_branch() {
    let data = load("four-bar");
    let mut m = model(&data);
    let want = floats(&data["branch"]["at_q1_0"]["q"]);
    // From a rough guess on the upper branch.
    let mut x = [0.0, 1.0, 1.6, 0.0];
    m.assemble(0.0, &mut x).unwrap();
    assert!(
        (x[1] - want[1]).abs() < 1e-14 && (x[2] - want[2]).abs() < 1e-14,
        "{x:?} vs {want:?}"
    );
    assert_eq!(x[0], 0.0, "the independent coordinate is held");
    // Already assembled: nothing to do.
    assert_eq!(m.project(0.0, &mut x, 0.0), Ok(false));
}

#[test]
fn impossible_closure_and_lost_branch_are_errors() {
    let data = load("four-bar");
    let mut m = model(&data);
    // A crank longer than the rest of the loop can reach: no closure.
    let mut p = *m.parameters();
    p.L1 = 3.0;
    m.set_parameters(p);
    let mut x = [0.0, 1.0, 1.6, 0.0];
    let r = m.assemble(0.0, &mut x);
    assert!(matches!(r, Err(ModelError::NotAssembled { .. })), "{r:?}");
    assert_eq!(x, [0.0, 1.0, 1.6, 0.0], "unchanged on error");
    // The message no longer only says "start nearer": the lengths may
    // make closing impossible, and it says so.
    let text = r.unwrap_err().to_string();
    assert!(
        text.contains("or none exists (a loop cannot close when one link is longer than all the others together: check the lengths)"),
        "{text}"
    );
    // The other branch is far from this state: projection refuses to jump.
    let mut m = model(&data);
    let mut x = [0.0, -0.9, -1.0, 0.0];
    assert!(matches!(
        m.project(0.0, &mut x, 0.0),
        Err(ModelError::LostBranch { .. })
    ));
}

#[test]
fn trajectory_matches_the_reference_and_keeps_the_loop_closed() {
    let data = load("four-bar");
    let mut m = model(&data);
    let records = data["trajectory"]["records"].as_array().unwrap();
    let mut x = state(&records[0]);
    let (_, out) = tight_run(&mut m, &mut x, 10.0, 0.1);
    assert_eq!(out.len(), records.len());
    // The built-in energy (checked against SymPy's at the samples) is
    // conserved to the tolerance of the run (1e-12).
    let e0 = out[0].2[0];
    let (mut worst_q, mut worst_e, mut worst_loop) = (0.0f64, 0.0f64, 0.0f64);
    for ((t, x, y), r) in out.iter().zip(records) {
        assert!((t - r["t"].as_f64().unwrap()).abs() < 1e-12);
        let want = state(r);
        for k in 0..4 {
            worst_q = worst_q.max((x[k] - want[k]).abs());
        }
        worst_e = worst_e.max((y[0] - e0).abs() / e0.abs());
        worst_loop = worst_loop.max(y[1].abs()).max(y[2].abs());
    }
    eprintln!(
        "four-bar: state vs reference {worst_q:e}, energy drift {worst_e:e}, loop residual {worst_loop:e}"
    );
    assert!(worst_q < 1e-8, "state vs reference {worst_q:e}");
    assert!(worst_e < 1e-9, "energy drift {worst_e:e}");
    assert!(worst_loop < 1e-9, "loop residual {worst_loop:e}");
}

/// Without `dependent:`, the automatic choice keeps a declared `initial:`
/// value where another choice closes the loop (the crank declared at 1.2
/// was made dependent and moved to 1.1504); where it cannot, the generated
/// documentation says which value assembly moves.
#[test]
fn automatic_dependents_keep_declared_initial_values() {
    use autosim_core::diag::SourceFile;
    use autosim_core::pipeline::compile_source;
    let source = std::fs::read_to_string("examples/models/four_bar.sim").unwrap();
    let undeclared = source
        .replace(", dependent: q2", "")
        .replace(", dependent: q3", "");
    // Only the crank's angle declared: the coupler and rocker close the loop.
    let crank_only = undeclared
        .replace("q: [q2], u: [u2], initial: [0.2],", "q: [q2], u: [u2],")
        .replace("q: [q3], u: [u3], initial: [1.5],", "q: [q3], u: [u3],");
    let c = compile_source(&SourceFile::new("four_bar.sim", crank_only.as_str())).unwrap();
    let dependents: Vec<_> = c
        .program
        .interface
        .model
        .constraints
        .iter()
        .map(|k| k.dependent_coordinate.clone().unwrap_or_default())
        .collect();
    assert!(!dependents.contains(&"q1".to_string()), "{dependents:?}");
    assert!(
        c.program.interface.model.cautions.is_empty(),
        "{:?}",
        c.program.interface.model.cautions
    );
    // Every angle declared: two must move, and the documentation says so.
    let c = compile_source(&SourceFile::new("four_bar.sim", undeclared.as_str())).unwrap();
    let cautions = &c.program.interface.model.cautions;
    assert_eq!(cautions.len(), 2, "{cautions:?}");
    assert!(
        cautions[0].starts_with("Assembly solves `q")
            && cautions[0].contains("its declared `initial:` value is only a guess"),
        "{cautions:?}"
    );
}
