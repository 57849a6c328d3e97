//! Stability at the extremes: rotations. 1-2-3 angles through their
//! singularity, and Euler parameters (`rotate: quaternion`), which have
//! none, on a spinning body and on the satellite (see `extremes/mod.rs`).
//!
//! | case | expected behaviour |
//! | --- | --- |
//! | 1-2-3 angles through q5 → ±π/2 | passes within 1e-3 rad of the singularity, at a price: Dormand–Prince takes 6× the steps of the quaternion model (same final attitude to 1e-10), fixed-step RK4 goes through silently but keeps angular momentum only to 1.5e-5; *at* q5 = π/2 the rates are finite but meaningless (cos q5 = 6e-17), which no model can flag |
//! | Euler parameters (`rotate: quaternion`) | no singularity: the same motion in 36 steps, \|e\| = 1 and angular momentum kept to 1e-9 (RK4: 4e-15); the satellite with a quaternion bus matches the reference data after converting states (du/dt to 1e-9) |

mod extremes;

use autosim::runtime::integrate::{DormandPrince, Rk4};
use autosim::runtime::{Model, RunSettings, RunSummary, run};
use autosim_test_support::quaternion::{distance as orientation_distance, from_123, rates_123};
use autosim_test_support::{load, rel_err, satellite_samples, worst_of};
use extremes::run_to;

mod models {
    autosim::model!(file = "tests/models/extremes/spinner_123.sim");
    autosim::model!(file = "tests/models/extremes/spinner_quaternion.sim");
    autosim::model!(file = "tests/models/extremes/satellite_quaternion.sim");
}

/// A free body spun about its major axis (ω = (0.002, 1, 0.003) rad/s):
/// the spin carries the second 1-2-3 angle to within about 1e-3 rad of π/2
/// at t ≈ 1.6 s.
///
/// - Euler parameters: no singularity. Dormand–Prince at 1e-10 needs 36
///   steps for 3 s; |e| stays 1 to 1e-9 and the angular momentum in N is
///   kept to 1e-9 (RK4 at h = 1 ms: to 4e-15).
/// - 1-2-3 angles: near q2 = π/2 the rates of q1 and q3 grow like
///   1/cos q2 (the trajectory passes near the singularity, never exactly
///   through it for generic states). It passes, at a price: Dormand–Prince
///   takes 210 steps, the smallest 6e-5 s, and ends at the same orientation
///   to 1e-10 (q1 and q3 have swung by π and q2 come back below π/2: the
///   same attitude on the other branch); RK4 at h = 1 ms goes through
///   without any error but keeps the angular momentum only to 1.5e-5.
/// - Exactly at q2 = π/2 (a state set by hand) `derivatives()` returns
///   finite rates of ~10¹³ rad/s: cos(π/2) is 6e-17 in floating point, so no
///   model can tell the singularity from a near miss. Use `rotate:
///   quaternion` for bodies whose attitude is not bounded away from it.
#[test]
fn rotation_through_the_1_2_3_singularity_and_with_euler_parameters() {
    use models::spinner_quaternion::SpinnerQuaternion;
    use models::spinner123::Spinner123;
    assert_eq!(
        <SpinnerQuaternion as Model>::STATE_NAMES,
        &["q1", "q2", "q3", "u1", "u2", "u3", "B_e0"]
    );
    let h_exact = [0.002, 2.0, 0.0045]; // I ω at t = 0, body axes along N.
    let momentum_error = |y: &[f64; 3]| {
        (0..3)
            .map(|i| (y[i] - h_exact[i]).abs())
            .fold(0.0, worst_of)
    };

    // Adaptive.
    let mut angles = Spinner123::new();
    let mut quat = SpinnerQuaternion::new();
    let mut xa = angles.initial_state();
    let mut xq = quat.initial_state();
    let sa = adaptive(&mut angles, &mut xa);
    let sq = adaptive(&mut quat, &mut xq);
    assert!(sq.steps < 60, "quaternion: {} steps", sq.steps);
    assert!(
        sa.steps > 5 * sq.steps,
        "1-2-3: {} steps vs {}",
        sa.steps,
        sq.steps
    );
    let e = [xq[6], xq[0], xq[1], xq[2]];
    let norm = e.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!((norm - 1.0).abs() < 1e-9, "|e| = {norm}");
    let converted = from_123(xa[0], xa[1], xa[2]);
    let distance = orientation_distance(converted, e);
    assert!(distance < 1e-9, "orientations differ by {distance:e}");
    assert!(xa[1] < std::f64::consts::FRAC_PI_2, "q2 = {}", xa[1]);
    let (mut ya, mut yq) = ([0.0; 3], [0.0; 3]);
    angles.outputs(3.0, &xa, &mut ya).unwrap();
    quat.outputs(3.0, &xq, &mut yq).unwrap();
    assert!(momentum_error(&ya) < 1e-8, "{ya:?}");
    assert!(momentum_error(&yq) < 1e-9, "{yq:?}");

    // Fixed step; the largest q2 seen on the way, every 10 ms.
    let mut xa = angles.initial_state();
    let mut xq = quat.initial_state();
    let mut top = 0.0f64;
    let settings = RunSettings::new(0.0, 3.0, 1e-3, 0.01);
    run(
        &mut angles,
        &mut Rk4::new(),
        &mut xa,
        &settings,
        &mut |_, x: &[f64; 6], _: &[f64; 3]| {
            top = top.max(x[1]);
        },
    )
    .unwrap();
    assert!(top > 1.565, "q2 reached only {top}");
    run_to(&mut quat, &mut Rk4::new(), &mut xq, 3.0, 1e-3, 10_000).unwrap();
    angles.outputs(3.0, &xa, &mut ya).unwrap();
    quat.outputs(3.0, &xq, &mut yq).unwrap();
    let (err_a, err_q) = (momentum_error(&ya), momentum_error(&yq));
    assert!(err_a > 1e-7 && err_a < 1e-3, "1-2-3: {err_a:e}");
    assert!(err_q < 1e-14, "quaternion: {err_q:e}");

    // Exactly at the singularity.
    let mut dx = [0.0; 6];
    let at = [0.0, std::f64::consts::FRAC_PI_2, 0.0, 0.002, 1.0, 0.003];
    assert_eq!(angles.derivatives(0.0, &at, &mut dx), Ok(()));
    assert!(dx.iter().all(|v| v.is_finite()), "{dx:?}");
    assert!(dx[0].abs() > 1e12, "dq1/dt = {}", dx[0]);
}

/// 3 s of Dormand–Prince at tolerances 1e-10.
fn adaptive<M: Model<Float = f64>>(model: &mut M, x: &mut M::State) -> RunSummary<f64> {
    let mut dopri = DormandPrince::with_tolerances(1e-10, 1e-10).unwrap();
    run_to(model, &mut dopri, x, 3.0, 1e-3, 100_000).unwrap()
}

/// The user code of the satellite, replaying a reference sample's inputs.
struct Replay {
    cmd: [f64; 2],
    thrust: [f64; 3],
}

impl models::satellite_quaternion::Externs for Replay {
    fn cmd(&mut self, _t: f64) -> [f64; 2] {
        self.cmd
    }
    fn thrust(&mut self, _t: f64, axis: f64, _error: f64) -> f64 {
        self.thrust[axis as usize - 1]
    }
}

/// The satellite with its bus oriented by Euler parameters (`rotate:
/// quaternion`) has no singularity at q5 = ±π/2 and the same dynamics: at
/// every sample of the reference data (`satellite.json`, 1-2-3 angles),
/// converting the angles to Euler parameters gives the reference du/dt to
/// 1e-9, and the Euler parameters' rates equal the derivative of the
/// converted angles.
#[test]
fn satellite_with_a_quaternion_bus_matches_the_reference_by_converting_states() {
    use models::satellite_quaternion::SatelliteQuaternion;
    type Sat = SatelliteQuaternion<Replay>;
    let names = <Sat as Model>::STATE_NAMES;
    assert_eq!(names.len(), 21);
    assert_eq!((names[3], names[5], names[20]), ("q4", "q6", "B_e0"));
    let data = load("satellite");
    let samples = satellite_samples();
    assert!(!samples.is_empty());
    for s in samples {
        let (q, u) = (&s.q, &s.u);
        let mut model = Sat::new(Replay {
            cmd: s.cmd,
            thrust: s.thrust,
        });
        // The reference's parameters are the model's defaults.
        let mut values = vec![0.0; <Sat as Model>::PARAMETER_NAMES.len()];
        model.parameter_values(&mut values);
        for (name, v) in <Sat as Model>::PARAMETER_NAMES.iter().zip(&values) {
            let want = data["parameters"][*name].as_f64().unwrap();
            assert!(
                (v - want).abs() <= 1e-15 * want.abs(),
                "{name}: {v} vs {want}"
            );
        }
        let e = from_123(q[3], q[4], q[5]);
        let mut x = [0.0; 21];
        x[..10].copy_from_slice(q);
        x[3..6].copy_from_slice(&e[1..]);
        x[10..20].copy_from_slice(u);
        x[20] = e[0];
        let mut dx = [0.0; 21];
        model.derivatives(s.t, &x, &mut dx).unwrap();
        let err = rel_err(&dx[10..20], &s.du);
        assert!(err < 1e-9, "du differs by {err:e}");
        for i in (0..3).chain(6..10) {
            assert!((dx[i] - s.dq[i]).abs() < 1e-12, "dq{}", i + 1);
        }
        // de/dt = d/dt from_123(angles), by central differences along the
        // 1-2-3 rates.
        let r = rates_123([q[3], q[4], q[5]], [u[3], u[4], u[5]]);
        let h = 1e-6;
        let ep = from_123(q[3] + h * r[0], q[4] + h * r[1], q[5] + h * r[2]);
        let em = from_123(q[3] - h * r[0], q[4] - h * r[1], q[5] - h * r[2]);
        let de: Vec<f64> = (0..4).map(|k| (ep[k] - em[k]) / (2.0 * h)).collect();
        for k in 1..4 {
            assert!((dx[2 + k] - de[k]).abs() < 1e-7, "de{k}/dt");
        }
        assert!((dx[20] - de[0]).abs() < 1e-7, "de0/dt");
    }
}
