//! The no_std model and integrator (built with `libm`), called from a std
//! test: the undamped 3-link chain reproduces the independent reference
//! trajectory `tests/reference/chain-planar-3-trajectory.json` and
//! conserves its energy.

use autosim::runtime::Model;
use autosim_no_std_check::{ChainPlanar3, crank, swing};
use autosim_test_support::{floats, worst_of};
use serde_json::Value;

#[test]
fn no_std_rk4_reproduces_the_reference_trajectory() {
    let data = autosim_test_support::load("chain-planar-3-trajectory");
    let p = |name: &str| data["parameters"][name].as_f64().unwrap();
    let parameters: Vec<f64> = ChainPlanar3::PARAMETER_NAMES.iter().map(|n| p(n)).collect();
    assert_eq!(p("c"), 0.0);
    let records = data["records"].as_array().unwrap();
    let state = |r: &Value| -> [f64; 6] {
        let mut x = [0.0; 6];
        x[..3].copy_from_slice(&floats(&r["q"]));
        x[3..].copy_from_slice(&floats(&r["u"]));
        x
    };
    let x0 = state(&records[0]);

    // Energy (the reference's definition): ½ uᵀ M u + Σ m g z + Σ ½ k q².
    let mut model = ChainPlanar3::new();
    model.set_parameter_values(&parameters);
    let mut energy = |x: &[f64; 6]| {
        let mut m = [[0.0; 3]; 3];
        model.mass_matrix(0.0, x, &mut m);
        let mut e = 0.0;
        for i in 0..3 {
            for j in 0..3 {
                e += 0.5 * x[3 + i] * m[i][j] * x[3 + j];
            }
        }
        let (mut angle, mut joint_z) = (0.0, 0.0);
        for (i, q) in x[..3].iter().enumerate() {
            let (m_i, l_i) = (p(&format!("m{}", i + 1)), p(&format!("L{}", i + 1)));
            angle += q;
            e += m_i * p("g") * (joint_z - 0.5 * l_i * angle.cos());
            joint_z -= l_i * angle.cos();
            e += 0.5 * p("k") * q * q;
        }
        e
    };

    // RK4, h = 0.25 ms, record by record (every 0.5 s = 2000 steps; the
    // chain is autonomous, so each leg starts at t = 0 from the last state).
    let h = 2.5e-4;
    let mut worst = 0.0f64;
    let mut drift = 0.0f64;
    let e0 = energy(&x0);
    assert!((e0 - records[0]["energy"].as_f64().unwrap()).abs() < 1e-12);
    let mut x = x0;
    for record in records.iter().skip(1) {
        let result = swing(&parameters, x, h, 2000).unwrap();
        assert_eq!(result.evaluations, 4 * 2000);
        x = result.state;
        let want = state(record);
        for (g, w) in x.iter().zip(&want) {
            worst = worst_of(worst, (g - w).abs());
        }
        drift = drift.max((energy(&x) - e0).abs());
    }
    eprintln!(
        "no_std RK4 (h = 0.25 ms) vs reference trajectory: max |state error| {worst:.2e}; energy drift {drift:.2e} J of {e0:.3} J"
    );
    assert!(worst < 1e-7, "state error {worst:e}");
    assert!(drift < 1e-8, "energy drift {drift:e}");
}

#[test]
fn no_std_closed_loop_follows_the_reference() {
    let data = autosim_test_support::load("four-bar");
    let records = data["trajectory"]["records"].as_array().unwrap();
    let state = |r: &Value| -> [f64; 4] {
        let (q, u) = (floats(&r["q"]), floats(&r["u"]));
        [q[0], q[1], q[2], u[0]]
    };
    // The reference's parameters are the model's defaults.
    let x = crank(state(&records[0]), 1e-3, 1000).unwrap();
    let want = state(&records[10]);
    let err = (0..4).map(|k| (x[k] - want[k]).abs()).fold(0.0, worst_of);
    assert!(err < 1e-8, "four-bar at 1 s: {x:?} vs {want:?} ({err:e})");
}
