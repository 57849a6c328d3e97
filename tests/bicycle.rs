//! The Whipple bicycle (`examples/models/bicycle.sim`: rolling wheels, a
//! ground contact and a tilted steer axis) against
//! `tests/reference/bicycle.json`: SymPy's `KanesMethod` with the same
//! constraints, whose linearization reproduces Meijaard et al. (2007) to
//! 1.5e-14 (see `tests/reference/gen/bicycle.md`).

use autosim::runtime::Model;
use autosim_test_support::{kinetic_energy, load, tight_run, worst_of};
use serde_json::Value;

autosim::model!(file = "examples/models/bicycle.sim");
use bicycle::Bicycle;

const PHI: usize = 3;
const THETA: usize = 4;
const DELTA: usize = 6;
const U_THETA_R: usize = 9;

fn number(v: &Value) -> f64 {
    match v {
        Value::String(s) => s.parse().unwrap(),
        other => other.as_f64().unwrap(),
    }
}

/// Upright, straight running at `speed` with a roll perturbation.
fn perturbed(speed: f64, roll: f64) -> [f64; 11] {
    let mut x = [0.0; 11];
    x[PHI] = roll;
    x[U_THETA_R] = speed / 0.3;
    x
}

/// Kinetic energy `½ uᵀ M u` over the independent speeds (the constraints
/// are scleronomic, so the reduced mass matrix gives it), plus gravity's
/// (the model's output, `potential_energy()`: a body left out would break
/// the conservation checked below).
fn energy(m: &mut Bicycle, x: &[f64; 11], potential: f64) -> f64 {
    let mut mass = [[0.0; 3]; 3];
    m.mass_matrix(0.0, x, &mut mass);
    kinetic_energy(&mass, &x[8..]) + potential
}

#[test]
fn the_ground_contact_sets_the_pitch() {
    let data = load("bicycle");
    let mut m = Bicycle::new();
    for s in data["pitch_samples"].as_array().unwrap() {
        let mut x = [0.0; 11];
        x[PHI] = number(&s["roll"]);
        x[DELTA] = number(&s["steer"]);
        m.assemble(0.0, &mut x).unwrap();
        let want = number(&s["pitch"]);
        assert!(
            (x[THETA] - want).abs() < 1e-14,
            "pitch {} vs {want}",
            x[THETA]
        );
    }
}

/// Runs `case` of the reference for `stop` seconds and compares the roll
/// at its records; returns the final state and the energy drift.
fn run_case(case: &Value, stop: f64, tolerance: f64) -> ([f64; 11], f64) {
    let mut m = Bicycle::new();
    let v = number(&case["v"]);
    let mut x = perturbed(v, number(&case["roll0"]));
    let (_, out) = tight_run(&mut m, &mut x, stop, 0.25);
    let out: Vec<(f64, [f64; 11], f64)> = out.into_iter().map(|(t, x, y)| (t, x, y[1])).collect();
    let e0 = energy(&mut m, &out[0].1, out[0].2);
    let drift = out
        .iter()
        .map(|(_, x, p)| (energy(&mut m, x, *p) - e0).abs() / e0)
        .fold(0.0, worst_of);
    let times: Vec<f64> = case["t"].as_array().unwrap().iter().map(number).collect();
    let rolls: Vec<f64> = case["roll"]
        .as_array()
        .unwrap()
        .iter()
        .map(number)
        .collect();
    let mut worst = 0.0f64;
    for (t, roll) in times.iter().zip(&rolls).filter(|(t, _)| **t <= stop + 1e-9) {
        let (_, x, _) = out
            .iter()
            .find(|o| (o.0 - t).abs() < 1e-9)
            .expect("output at the record");
        worst = worst_of(worst, (x[PHI] - roll).abs());
    }
    eprintln!("bicycle at {v} m/s: roll vs reference {worst:e}, energy drift {drift:e}");
    assert!(worst < tolerance, "roll vs reference {worst:e}");
    (x, drift)
}

#[test]
fn at_5_m_s_it_is_self_stable() {
    let data = load("bicycle");
    let (x, drift) = run_case(&data["nonlinear"]["v5"], 10.0, 1e-8);
    assert!(drift < 1e-9, "energy drift {drift:e}");
    assert!(x[PHI].abs() < 0.005, "back upright: roll {}", x[PHI]);
}

#[test]
fn at_3_m_s_it_weaves_and_falls() {
    let data = load("bicycle");
    let (x, drift) = run_case(&data["nonlinear"]["v3"], 1.5, 1e-8);
    assert!(drift < 1e-9, "energy drift {drift:e}");
    assert!(x[PHI].abs() > 0.2, "the weave grows: roll {}", x[PHI]);
}
