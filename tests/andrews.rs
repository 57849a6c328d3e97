//! Andrews' squeezing mechanism (`examples/models/andrews.sim`: seven
//! bodies, three loops through one joint) against the published values of
//! the CWI/Bari IVP test set, and against an independent converged solution
//! (`tests/reference/andrews.json`, `tests/reference/gen/andrews.md`).

// The test set publishes more digits than an f64 holds; they are kept as published.
#![allow(clippy::excessive_precision)]

use autosim::runtime::integrate::DormandPrince;
use autosim::runtime::{Model, RunSettings, run};
use autosim_test_support::{floats, load, worst_of};

autosim::model!(file = "examples/models/andrews.sim");
use andrews::Andrews;

/// The test set's names of the angles, in its order.
const NAMES: [&str; 7] = ["beta", "Theta", "gamma", "Phi", "delta", "Omega", "epsilon"];

/// Position of the test set's angle `k` in our state (parents come before
/// their children there: K5 before K4, K7 before K6).
fn slot(k: usize) -> usize {
    Andrews::STATE_NAMES
        .iter()
        .position(|n| *n == NAMES[k])
        .unwrap()
}

/// Our state at the test set's consistent initial state (its angles in its
/// order, at rest; the crank's speed last).
fn initial_state() -> [f64; 8] {
    let mut x = [0.0; 8];
    for (k, q) in floats(&load("andrews")["initial"]["q"]).iter().enumerate() {
        x[slot(k)] = *q;
    }
    x
}

#[test]
fn the_crank_is_the_one_degree_of_freedom() {
    assert_eq!(Andrews::STATE_NAMES[7], "beta_d");
    assert_eq!(Andrews::STATE_NAMES.len(), 8);
}

#[test]
fn initial_accelerations_match_the_test_set() {
    let mut m = Andrews::new();
    let x = initial_state();
    let mut y = [0.0; 8];
    m.outputs(0.0, &x, &mut y).unwrap();
    // The test set's published β'' and Θ'' at t = 0.
    let (beta_dd, theta_dd) = (
        14222.4439199541138705911625887,
        -10666.8329399655854029433719415,
    );
    let (eb, et) = (
        (y[0] - beta_dd).abs() / beta_dd,
        (y[1] - theta_dd).abs() / theta_dd.abs(),
    );
    eprintln!("andrews t = 0: beta'' {:e}, Theta'' {:e} relative", eb, et);
    assert!(eb < 1e-10 && et < 1e-10, "{} {}", y[0], y[1]);
    // The published state closes the loops.
    assert!(
        y[2..].iter().all(|r| r.abs() < 1e-15),
        "residuals {:?}",
        &y[2..]
    );
}

#[test]
fn the_state_at_30_ms_matches_the_test_set() {
    let mut m = Andrews::new();
    let mut x = initial_state();
    let mut dopri = DormandPrince::<Andrews>::with_tolerances(1e-13, 1e-13).unwrap();
    let settings = RunSettings::new(0.0, 0.03, 1e-6, 0.03).with_max_steps(1_000_000);
    run(
        &mut m,
        &mut dopri,
        &mut x,
        &settings,
        &mut |_, _: &[f64; 8], _: &[f64; 8]| {},
    )
    .unwrap();
    // Published (PSIDE, rtol 1e-14, index 3).
    let (beta, theta) = (15.81077119629904, -15.75637105984298);
    let (eb, et) = (
        (x[0] - beta).abs() / beta,
        (x[1] - theta).abs() / theta.abs(),
    );
    // Converged (independent: SciPy DOP853 and Radau, and an 8th-order
    // Runge–Kutta in long double, agree to 4e-12).
    let data = load("andrews");
    let converged: Vec<f64> = data["t0.03_longdouble_rk8"]["q"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap().parse().unwrap())
        .collect();
    let worst = (0..7)
        .map(|k| (x[slot(k)] - converged[k]).abs() / (1.0 + converged[k].abs()))
        .fold(0.0f64, worst_of);
    eprintln!("andrews t = 0.03: vs test set beta {eb:e}, Theta {et:e}; vs converged {worst:e}");
    assert!(eb < 1e-6 && et < 1e-6, "beta {} Theta {}", x[0], x[1]);
    assert!(worst < 1e-9, "vs converged {worst:e}");
}
