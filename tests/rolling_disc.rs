//! The rolling disc (`examples/models/rolling_disc.sim`: a holonomic
//! contact and nonholonomic rolling) against
//! `tests/reference/rolling-disc.json`: SymPy's `KanesMethod` with
//! configuration and velocity constraints, cross-checked by Newton–Euler
//! with the contact force (see `tests/reference/gen/rolling_disc.md`).

use autosim::runtime::integrate::DormandPrince;
use autosim::runtime::{Model, RunSettings, run};
use autosim_test_support::{floats, load, tight_run};
use serde_json::Value;

autosim::model!(file = "examples/models/rolling_disc.sim");
use rolling_disc::RollingDisc;

/// The state `[x, y, z, psi, phi, theta, u4, u5, u6]` of a reference
/// sample or record (whose speeds are `[ux, uy, uz, u4, u5, u6]`).
fn state(v: &Value) -> [f64; 9] {
    let (q, u) = (floats(&v["q"]), floats(&v["u"]));
    let mut x = [0.0; 9];
    x[..6].copy_from_slice(&q);
    x[6..].copy_from_slice(&u[3..]);
    x
}

#[test]
fn the_state_holds_the_independent_speeds() {
    assert_eq!(
        RollingDisc::STATE_NAMES,
        ["x", "y", "z", "psi", "phi", "theta", "u4", "u5", "u6"]
    );
    assert_eq!(
        RollingDisc::OUTPUT_NAMES,
        ["energy", "yaw_rate", "speed", "touch"]
    );
    assert_eq!(RollingDisc::DEPENDENT_COORDINATES, [2]);
}

#[test]
fn derivatives_match_sympy_at_every_sample() {
    let data = load("rolling-disc");
    let mut m = RollingDisc::new();
    for (i, s) in data["samples"].as_array().unwrap().iter().enumerate() {
        let x = state(s);
        let mut dx = [0.0; 9];
        m.derivatives(0.0, &x, &mut dx).unwrap();
        let (dq, du) = (floats(&s["dq"]), floats(&s["du"]));
        let scale = dq.iter().chain(&du).fold(1.0f64, |a, v| a.max(v.abs()));
        for k in 0..6 {
            assert!(
                (dx[k] - dq[k]).abs() < 1e-10 * scale,
                "sample {i}: dq{k} {} vs {}",
                dx[k],
                dq[k]
            );
        }
        for k in 0..3 {
            assert!(
                (dx[6 + k] - du[3 + k]).abs() < 1e-10 * scale,
                "sample {i}: du{} {} vs {}",
                k + 4,
                dx[6 + k],
                du[3 + k]
            );
        }
        // The energy output is `kinetic_energy() + potential_energy()`:
        // against SymPy's.
        let mut y = [0.0; 4];
        m.outputs(0.0, &x, &mut y).unwrap();
        let e = s["energy"].as_f64().unwrap();
        assert!(
            (y[0] - e).abs() < 1e-12 * e.abs(),
            "sample {i}: energy {} vs {e}",
            y[0]
        );
        assert!(
            y[3].abs() < 1e-14,
            "sample {i} touches the ground: {}",
            y[3]
        );
    }
}

#[test]
fn energy_is_conserved_and_the_trajectory_matches() {
    let data = load("rolling-disc");
    let mut m = RollingDisc::new();
    let records = data["trajectory"]["records"].as_array().unwrap();
    let mut x = state(&records[0]);
    let (_, out) = tight_run(&mut m, &mut x, 5.0, 0.1);
    assert_eq!(out.len(), records.len());
    // The built-in energy is conserved to the tolerance of the run (1e-12).
    let e0 = out[0].2[0];
    let (mut worst_x, mut worst_e) = (0.0f64, 0.0f64);
    for ((_, x, y), r) in out.iter().zip(records) {
        let want = state(r);
        for k in 0..9 {
            worst_x = worst_x.max((x[k] - want[k]).abs() / (1.0 + want[k].abs()));
        }
        worst_e = worst_e.max((y[0] - e0).abs() / e0);
    }
    eprintln!("rolling disc: state vs reference {worst_x:e}, energy drift {worst_e:e}");
    assert!(worst_e < 1e-9, "energy drift {worst_e:e}");
    assert!(worst_x < 1e-8, "state vs reference {worst_x:e}");
}

#[test]
fn steady_precession_holds_the_lean() {
    let data = load("rolling-disc");
    let (r, g) = (0.5, 9.81);
    for case in data["steady_precession"]["cases"].as_array().unwrap() {
        let phi0 = case["phi0"].as_f64().unwrap();
        let omega = case["psi_dot0"].as_f64().unwrap();
        // The steady spin of a thin disc (rolling_disc.md, "Steady turning").
        let (s, c) = phi0.sin_cos();
        let w2 = (r * omega * omega * s * c / 4.0 - g * s) / (1.5 * r * omega * c);
        let mut x = [0.0, 0.0, r * c, 0.0, phi0, 0.0, 0.0, w2, omega * c];
        let mut m = RollingDisc::new();
        let mut dopri = DormandPrince::<RollingDisc>::with_tolerances(1e-12, 1e-12).unwrap();
        let settings = RunSettings::new(0.0, 5.0, 1e-3, 0.05).with_max_steps(1_000_000);
        let (mut lean, mut rate) = (0.0f64, 0.0f64);
        run(
            &mut m,
            &mut dopri,
            &mut x,
            &settings,
            &mut |_t, x: &[f64; 9], y: &[f64; 4]| {
                lean = lean.max((x[4] - phi0).abs());
                rate = rate.max((y[1] - omega).abs());
            },
        )
        .unwrap();
        eprintln!("steady precession phi0 = {phi0}: lean {lean:e}, yaw rate {rate:e}");
        assert!(lean < 1e-8, "phi0 = {phi0}: the lean moved by {lean:e}");
        assert!(rate < 1e-8, "phi0 = {phi0}: the yaw rate moved by {rate:e}");
    }
}
