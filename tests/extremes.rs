//! Stability at the extremes. Each case below states its expected behaviour
//! and asserts it: the run passes (with a stated accuracy), or it stops with
//! a typed error that names the cause. Never a silent NaN, a hang or a
//! panic. The models are small files in `tests/models/extremes/` so every
//! case runs in well under a second in a debug build (the 10⁶-step runs use
//! a one-degree-of-freedom oscillator).
//!
//! | case | expected behaviour |
//! | --- | --- |
//! | stiff springs (k × 10⁶), explicit methods at h = 1 ms | `IntegrationError::NonFinite` naming a state, within 0.05 s; the state is left at its last finite value |
//! | stiff springs, Dormand–Prince | passes, at steps held below the stability limit (≈ 3.3/ω_max, 6e-5 s); energy within 0.1 % |
//! | stiff springs, SDIRK3 at h = 1 ms | passes; L-stable: the energy never grows, the unresolved vibration is damped out to the static equilibrium |
//! | mass and inertia ratios 1e-6 … 1e6 | passes with Dormand–Prince at 1e-10: energy within 1e-7, no spurious singular-matrix error |
//! | zero mass and zero inertia on a free degree of freedom | compile-time error naming the speed and the body |
//! | zero masses set at run time (inertia kept) | `ModelError::SingularMassMatrix` naming the cart's speed `vy`; the run stops at t = 0 with `IntegrationError::Model`, state untouched |
//! | zero mass with non-zero inertia on a rotation | passes (the inertia carries the rotation) |
//! | singular only at some states (spherical pendulum at its pole) | `SingularMassMatrix` naming `azimuth_rate` at the pole, nothing elsewhere |
//! | singular with a non-zero diagonal (two parallel translations) | not detectable from the diagonal, so it compiles; `SingularMassMatrix` naming `v1` at run time |
//! | 1-2-3 angles through q5 → ±π/2 | passes within 1e-3 rad of the singularity, at a price: Dormand–Prince takes 6× the steps of the quaternion model (same final attitude to 1e-10), fixed-step RK4 goes through silently but keeps angular momentum only to 1.5e-5; *at* q5 = π/2 the rates are finite but meaningless (cos q5 = 6e-17), which no model can flag |
//! | Euler parameters (`rotate: quaternion`) | no singularity: the same motion in 36 steps, \|e\| = 1 and angular momentum kept to 1e-9 (RK4: 4e-15); the satellite with a quaternion bus matches the reference data after converting states (du/dt to 1e-9) |
//! | 10⁶ steps, energy drift per integrator | the drift each method's stability function predicts for ωh = 0.01 (table in `energy_drift_over_a_million_steps`) |
//! | very large speeds | 10³ rad/s: passes (Dormand–Prince), energy within 1e-7; 10⁸ rad/s: `TooManySteps` at the step limit (never a hang); 10¹⁶⁰ rad/s (u² overflows): `NonFinite` naming a state |
//! | a step far beyond the stability limit | explicit: `NonFinite`; Dormand–Prince: passes (the step is only a first trial); SDIRK3: `NewtonFailed` at t = 0, state untouched |

use autosim::runtime::integrate::{
    AbmOrder, AdamsBashforthMoulton, DormandPrince, Euler, Heun, Rk4, Sdirk3, SdirkSettings,
};
use autosim::runtime::{
    IntegrationError, Model, ModelError, RunSettings, RunSummary, Stepper, run,
};
use autosim_test_support::quaternion::{distance as orientation_distance, from_123, rates_123};
use autosim_test_support::{floats, load, rel_err};

mod models {
    autosim::model!(file = "tests/models/extremes/two_link.sim");
    autosim::model!(file = "tests/models/extremes/oscillator.sim");
    autosim::model!(file = "tests/models/extremes/cart_pendulum.sim");
    autosim::model!(file = "tests/models/extremes/spherical_pendulum.sim");
    autosim::model!(file = "tests/models/extremes/double_slider.sim");
    autosim::model!(file = "tests/models/extremes/spinner_123.sim");
    autosim::model!(file = "tests/models/extremes/spinner_quaternion.sim");
    autosim::model!(file = "tests/models/extremes/satellite_quaternion.sim");
}

use models::two_link::{self, TwoLink};

/// Runs from 0 to `stop` (one output at each end) and returns the summary
/// or the integration error; `x` ends at the last good state.
fn run_to<M, S>(
    model: &mut M,
    stepper: &mut S,
    x: &mut M::State,
    stop: f64,
    step: f64,
    max_steps: u64,
) -> Result<RunSummary<f64>, IntegrationError>
where
    M: Model<Float = f64>,
    S: Stepper<M> + ?Sized,
{
    let settings = RunSettings::new(0.0, stop, step, stop).with_max_steps(max_steps);
    run(model, stepper, x, &settings, &mut |_, _: &_, _: &_| {}).map_err(IntegrationError::from)
}

/// Kinetic (½ uᵀ M u with the generated mass matrix) plus potential energy
/// (the model's output) of the two-link model.
fn energy(m: &mut TwoLink, x: &[f64; 4]) -> f64 {
    let mut mm = [[0.0; 2]; 2];
    m.mass_matrix(0.0, x, &mut mm);
    let u = [x[2], x[3]];
    let mut kinetic = 0.0;
    for i in 0..2 {
        for j in 0..2 {
            kinetic += 0.5 * u[i] * mm[i][j] * u[j];
        }
    }
    let mut y = [0.0];
    m.outputs(0.0, x, &mut y).expect("outputs");
    kinetic + y[0]
}

/// The two-link model with its joint stiffness multiplied by 10⁶
/// (k = 2·10⁶ N m/rad), released from small deflections.
fn stiff() -> (TwoLink, [f64; 4]) {
    let mut p = two_link::Parameters::default();
    p.k *= 1e6;
    (TwoLink::with_parameters(p), [0.01, -0.01, 0.0, 0.0])
}

fn explicit_steppers<M: Model + 'static>() -> Vec<(&'static str, Box<dyn Stepper<M>>)> {
    vec![
        ("Euler", Box::new(Euler::new())),
        ("Heun", Box::new(Heun::new())),
        ("RK4", Box::new(Rk4::new())),
        ("ABM2", Box::new(AdamsBashforthMoulton::new(AbmOrder::Two))),
        ("ABM4", Box::new(AdamsBashforthMoulton::new(AbmOrder::Four))),
    ]
}

/// Expects a `NonFinite` error before `t_max`, naming a state of `M`, with
/// the state left finite.
fn assert_non_finite<M: Model<Float = f64>>(
    what: &str,
    result: Result<RunSummary<f64>, IntegrationError>,
    x: &M::State,
    t_max: f64,
) {
    match result {
        Err(IntegrationError::NonFinite { t, index, name }) => {
            assert!(t >= 0.0 && t <= t_max, "{what}: stopped at t = {t}");
            assert_eq!(M::STATE_NAMES[index], name, "{what}");
        }
        other => panic!("{what}: expected a non-finite state, got {other:?}"),
    }
    assert!(
        x.as_ref().iter().all(|v| v.is_finite()),
        "{what}: the state left behind is not finite"
    );
}

// ------------------------------------------------------------------ stiff

/// Stiff springs (10⁶ × nominal): every explicit method at h = 1 ms is far
/// beyond its stability limit (ω_max h ≈ 60) and stops with
/// `IntegrationError::NonFinite` naming the first state that overflowed,
/// within 0.05 s, leaving the last finite state behind. (Before the
/// runtime checked stage states, RK4 reported this blow-up as a singular
/// mass matrix: the overflowed stage gave the generated solve a NaN pivot.)
#[test]
fn stiff_springs_stop_explicit_methods_with_a_named_non_finite_state() {
    for (name, mut stepper) in explicit_steppers::<TwoLink>() {
        let (mut model, mut x) = stiff();
        let result = run_to(&mut model, &mut *stepper, &mut x, 1.0, 1e-3, 10_000);
        assert_non_finite::<TwoLink>(name, result, &x, 0.05);
    }
}

/// Stiff springs: Dormand–Prince passes, its steps held below the
/// stability limit whatever the tolerance asks (≈ 3.3/ω_max = 6e-5 s), and
/// keeps the energy to 0.1 %. SDIRK3 at h = 1 ms passes too: L-stable, it
/// never lets the energy grow, and it damps the unresolved vibration (ωh ≈
/// 60) out entirely: the links end at rest at the static equilibrium. Stable
/// is not accurate: resolve the vibration, or accept that it is removed.
#[test]
fn stiff_springs_pass_with_dormand_prince_and_sdirk3() {
    let (mut model, mut x) = stiff();
    let e0 = energy(&mut model, &x);
    let mut dopri = DormandPrince::with_tolerances(1e-6, 1e-9).unwrap();
    let s = run_to(&mut model, &mut dopri, &mut x, 0.2, 1e-3, 100_000).unwrap();
    assert!(s.max_step < 7e-5, "largest step {}", s.max_step);
    let e1 = energy(&mut model, &x);
    assert!(((e1 - e0) / e0).abs() < 1e-3, "energy {e0} -> {e1}");

    let (mut model, mut x) = stiff();
    let mut sdirk = Sdirk3::<TwoLink, 4>::new(SdirkSettings::default());
    let mut energies = Vec::new();
    let settings = RunSettings::new(0.0, 1.0, 1e-3, 0.01);
    run(
        &mut model,
        &mut sdirk,
        &mut x,
        &settings,
        &mut |_, x: &[f64; 4], y: &[f64; 1]| {
            energies.push((*x, y[0]));
        },
    )
    .unwrap();
    let mut m = stiff().0;
    let e: Vec<f64> = energies.iter().map(|(x, _)| energy(&mut m, x)).collect();
    for w in e.windows(2) {
        assert!(
            w[1] <= w[0] + 1e-9 * w[0].abs(),
            "energy grew: {} -> {}",
            w[0],
            w[1]
        );
    }
    // At rest in the static equilibrium: only gravity's small deflection.
    assert!(x.iter().all(|v| v.abs() < 1e-6), "{x:?}");
    let equilibrium = e[e.len() - 1];
    assert!(equilibrium < e[0], "{equilibrium} vs {}", e[0]);
}

// ------------------------------------------------------------------ mass ratios

/// Link 2's mass and inertia scaled by 1e-6 … 1e6 relative to link 1:
/// every ratio passes with Dormand–Prince at 1e-10 (the light link simply
/// needs shorter steps), keeps the energy (no damping) to 1e-7, and never
/// reports a singular mass matrix.
#[test]
fn mass_and_inertia_ratios_from_1e_minus_6_to_1e6() {
    for ratio in [1e-6, 1e-3, 1.0, 1e3, 1e6] {
        let mut p = two_link::Parameters::default();
        p.m2 *= ratio;
        p.Ixx2 *= ratio;
        p.Iyy2 *= ratio;
        p.Izz2 *= ratio;
        let mut model = TwoLink::with_parameters(p);
        let mut x = model.initial_state();
        let e0 = energy(&mut model, &x);
        let mut dopri = DormandPrince::with_tolerances(1e-10, 1e-10).unwrap();
        let s = run_to(&mut model, &mut dopri, &mut x, 0.1, 1e-3, 1_000_000)
            .unwrap_or_else(|e| panic!("ratio {ratio:e}: {e}"));
        let e1 = energy(&mut model, &x);
        let drift = ((e1 - e0) / e0).abs();
        assert!(
            drift < 1e-7,
            "ratio {ratio:e}: energy {e0} -> {e1} ({drift:e})"
        );
        assert!(s.steps > 0);
    }
}

// ------------------------------------------------------------------ singular mass matrices

/// A body without mass or inertia that a degree of freedom moves alone is
/// singular whatever the state: the compiler says so, naming the speed and
/// the body, and suggests a fix.
#[test]
fn zero_mass_and_inertia_on_a_free_degree_of_freedom_is_a_compile_time_error() {
    use autosim_core::diag::SourceFile;
    use autosim_core::pipeline::compile_source;
    let cases = [
        (
            "model MasslessTip;\n\
             body Arm { rotate: 3, mass: 1, cm: [1, 0, 0], inertia: 0 }\n\
             body Tip { parent: Arm, joint: [1, 0, 0], rotate: 1, mass: 0, inertia: 0 }\n",
            "u2",
            "Tip",
        ),
        (
            // Zero mass everywhere, inertia only on the pendulum: nothing
            // resists the cart's translation.
            "model MasslessCart;\n\
             body Cart { translate: 2, mass: 0, inertia: 0 }\n\
             body Pend { parent: Cart, rotate: 1, mass: 0, cm: [0, 0, -1], inertia: diag(1, 1, 1) }\n",
            "u1",
            "Cart",
        ),
    ];
    for (text, speed, body) in cases {
        let file = SourceFile::new("singular.sim", text);
        let diagnostics = match compile_source(&file) {
            Ok(_) => panic!("compiled a singular model:\n{text}"),
            Err(d) => d.render(&file),
        };
        assert!(
            diagnostics.contains(&format!(
                "the mass matrix is singular: nothing resists the acceleration of `{speed}` (a degree of freedom of body `{body}`)"
            )),
            "{diagnostics}"
        );
        assert!(diagnostics.contains("help: give"), "{diagnostics}");
    }
}

/// Masses that are parameters can only be checked at run time: with the
/// cart's and the pendulum's masses set to zero (the pendulum keeping its
/// inertia) `derivatives()` returns `ModelError::SingularMassMatrix` naming
/// the cart's speed `vy`, and a run stops at t = 0 with
/// `IntegrationError::Model`, the state untouched.
#[test]
fn zero_masses_set_at_run_time_name_the_speed() {
    use models::cart_pendulum::{CartPendulum, Parameters};
    let singular = Parameters {
        mc: 0.0,
        mp: 0.0,
        ..Parameters::default()
    };
    let mut model = CartPendulum::with_parameters(singular);
    let x0 = model.initial_state();
    let mut dx = [0.0; 4];
    let expected = ModelError::SingularMassMatrix {
        speed: 0,
        name: "vy",
    };
    assert_eq!(model.derivatives(0.0, &x0, &mut dx), Err(expected));
    let mut x = x0;
    let err = run_to(&mut model, &mut Rk4::new(), &mut x, 1.0, 1e-3, 10_000).unwrap_err();
    assert_eq!(
        err,
        IntegrationError::Model {
            t: 0.0,
            error: expected
        }
    );
    assert_eq!(x, x0);
    assert!(err.to_string().contains("pivot of speed vy"), "{err}");
}

/// Zero mass with non-zero inertia on a rotation is not singular: the
/// inertia resists the rotation. With the pendulum's mass zero the run
/// passes and, with nothing driving it, the pendulum keeps its angle.
#[test]
fn zero_mass_with_inertia_on_a_rotation_passes() {
    use models::cart_pendulum::{CartPendulum, Parameters};
    let mut model = CartPendulum::with_parameters(Parameters {
        mp: 0.0,
        ..Parameters::default()
    });
    let mut x = model.initial_state();
    let x0 = x;
    run_to(&mut model, &mut Rk4::new(), &mut x, 1.0, 1e-3, 10_000).unwrap();
    assert_eq!(x, x0);
}

/// Singular at some states only: the spherical pendulum's azimuth has no
/// inertia at the pole (M = diag(m l² sin²θ, m l²)). The compiler cannot
/// know; `derivatives()` reports `SingularMassMatrix` naming
/// `azimuth_rate` at the pole and works everywhere else.
#[test]
fn a_singularity_at_some_states_is_reported_where_it_happens() {
    let mut model = models::spherical_pendulum::SphericalPendulum::new();
    let mut dx = [0.0; 4];
    assert_eq!(
        model.derivatives(0.0, &[0.3, 0.0, 0.1, 0.0], &mut dx),
        Err(ModelError::SingularMassMatrix {
            speed: 0,
            name: "azimuth_rate"
        })
    );
    let x = model.initial_state();
    assert_eq!(model.derivatives(0.0, &x, &mut dx), Ok(()));
    assert!(dx.iter().all(|v| v.is_finite()));
}

/// Singular with a non-zero diagonal: a block given two translations
/// along the same direction has M = [[m, m], [m, m]]. The compile-time
/// check looks at the diagonal and lets it through; the generated LDLᵀ
/// solve finds the zero pivot. Its elimination runs from the last speed to
/// the first, so the pivot that vanishes, and the speed named, is `v1`.
#[test]
fn a_singular_matrix_with_a_non_zero_diagonal_is_found_at_run_time() {
    use autosim_core::diag::SourceFile;
    use autosim_core::pipeline::compile_source;
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/models/extremes/double_slider.sim"
    );
    let text = std::fs::read_to_string(path).unwrap();
    assert!(compile_source(&SourceFile::new(path, text)).is_ok());

    use models::double_slider::{DoubleSlider, Parameters};
    for m in [1.0, 0.3, 7.0] {
        let mut model = DoubleSlider::with_parameters(Parameters { m, k: 10.0 });
        let mut dx = [0.0; 4];
        assert_eq!(
            model.derivatives(0.0, &model.initial_state(), &mut dx),
            Err(ModelError::SingularMassMatrix {
                speed: 0,
                name: "v1"
            }),
            "m = {m}"
        );
    }
}

// ------------------------------------------------------------------ rotations

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
            .fold(0.0, f64::max)
    };

    // Adaptive.
    let mut angles = Spinner123::new();
    let mut quat = SpinnerQuaternion::new();
    let mut xa = angles.initial_state();
    let mut xq = quat.initial_state();
    let sa = run_to(
        &mut angles,
        &mut DormandPrince::with_tolerances(1e-10, 1e-10).unwrap(),
        &mut xa,
        3.0,
        1e-3,
        100_000,
    )
    .unwrap();
    let sq = run_to(
        &mut quat,
        &mut DormandPrince::with_tolerances(1e-10, 1e-10).unwrap(),
        &mut xq,
        3.0,
        1e-3,
        100_000,
    )
    .unwrap();
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
    let samples = data["samples"].as_array().unwrap();
    assert!(!samples.is_empty());
    for s in samples {
        let q = floats(&s["q"]);
        let u = floats(&s["u"]);
        let inputs = &s["inputs"];
        let input = |name: &str| inputs[name].as_f64().unwrap();
        let mut model = Sat::new(Replay {
            cmd: [input("clkcmd"), input("camcmd")],
            thrust: [input("thr1"), input("thr2"), input("thr3")],
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
        x[..10].copy_from_slice(&q);
        x[3..6].copy_from_slice(&e[1..]);
        x[10..20].copy_from_slice(&u);
        x[20] = e[0];
        let mut dx = [0.0; 21];
        model
            .derivatives(s["t"].as_f64().unwrap(), &x, &mut dx)
            .unwrap();
        let err = rel_err(&dx[10..20], &floats(&s["du"]));
        assert!(err < 1e-9, "du differs by {err:e}");
        let dq = floats(&s["dq"]);
        for i in (0..3).chain(6..10) {
            assert!((dx[i] - dq[i]).abs() < 1e-12, "dq{}", i + 1);
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

// ------------------------------------------------------------------ 10⁶ steps

/// A million steps of h = 0.01 s (ωh = 0.01, 1592 periods) of the
/// undamped oscillator, per integrator. For x'' = -ω²x the energy after n
/// steps is |R(iωh)|²ⁿ E₀, with R the method's stability function (for
/// the multistep pairs, the principal root of the PECE recurrence), so
/// each method's drift is known in advance:
///
/// | method | predicted ln(E/E₀) after 10⁶ steps | meaning | measured − predicted |
/// | --- | --- | --- | --- |
/// | Euler | +99.995 | grows ×10⁴³: unusable for long undamped runs | 3e-13 |
/// | Heun | +2.5000e-3 | grows 0.25 % | −3e-14 |
/// | RK4 | −1.3889e-8 | decays 1.4e-8 | 1.4e-13 |
/// | ABM2 (PECE) | −4.9995e-3 | decays 0.5 % | 5e-9 (RK4 start-up) |
/// | ABM4 (PECE) | +3.2286e-7 | grows 3e-7 | −1e-12 |
/// | Dormand–Prince (steps capped at h) | −5.555e-10 | decays 6e-10 | 2e-13 |
/// | SDIRK3 | −5.1792e-4 | decays 0.05 % (L-stable: always decays) | 3e-14 |
///
/// Each measured drift is asserted to match its prediction to about ten
/// times the difference above: bounded, of the sign and size the method
/// implies, never a random walk or a blow-up. (The Dormand–Prince and
/// SDIRK3 runs are the slowest cases here, a few seconds in a debug build.)
fn drift(name: &str, stepper: &mut dyn Stepper<models::oscillator::Oscillator>) -> f64 {
    let mut model = models::oscillator::Oscillator::new();
    let mut x = model.initial_state();
    let (mut y0, mut y1) = ([0.0], [0.0]);
    model.outputs(0.0, &x, &mut y0).unwrap();
    let s = run_to(&mut model, stepper, &mut x, 1e4, 0.01, 2_000_000)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(
        (999_990..=1_000_010).contains(&s.steps),
        "{name}: {} steps",
        s.steps
    );
    model.outputs(1e4, &x, &mut y1).unwrap();
    (y1[0] / y0[0]).ln()
}

macro_rules! drift_test {
    ($test:ident, $stepper:expr, $theory:expr, $tolerance:expr) => {
        #[test]
        fn $test() {
            let mut stepper = $stepper;
            let measured = drift(stringify!($test), &mut stepper);
            let theory: f64 = $theory;
            assert!(
                (measured - theory).abs() <= $tolerance,
                "ln(E/E0) = {measured:e}, predicted {theory:e}"
            );
        }
    };
}

drift_test!(energy_drift_euler, Euler::new(), 99.995_000_333_308, 1e-9);
drift_test!(energy_drift_heun, Heun::new(), 2.499_999_996_875e-3, 1e-12);
drift_test!(energy_drift_rk4, Rk4::new(), -1.388_871_527_8e-8, 2e-12);
drift_test!(
    energy_drift_abm2,
    AdamsBashforthMoulton::new(AbmOrder::Two),
    -4.999_500_084_36e-3,
    5e-8
);
drift_test!(
    energy_drift_abm4,
    AdamsBashforthMoulton::new(AbmOrder::Four),
    3.228_610_438_5e-7,
    1e-11
);
drift_test!(
    energy_drift_dormand_prince,
    {
        let mut settings = autosim::runtime::integrate::DopriSettings::new(1e-3, 1e-3);
        settings.max_step = 0.01;
        DormandPrince::new(settings).unwrap()
    },
    -5.554_930_562_5e-10,
    5e-12
);
drift_test!(
    energy_drift_sdirk3,
    // The Jacobian in closed form (the model is linear): two evaluations a
    // step fewer than finite differences, so the run stays short in debug.
    Sdirk3::<models::oscillator::Oscillator, 2, _>::with_jacobian(
        SdirkSettings::default(),
        autosim::runtime::integrate::Analytic(
            |m: &models::oscillator::Oscillator, _t: f64, _x: &[f64; 2], j: &mut [[f64; 2]; 2]| {
                let p = m.parameters();
                *j = [[0.0, 1.0], [-p.k / p.m, 0.0]];
                Ok(())
            }
        )
    ),
    -5.179_190_311_6e-4,
    1e-12
);

// ------------------------------------------------------------------ large speeds

/// Very large speeds on the two-link model:
///
/// - 10³ rad/s at both joints: Dormand–Prince at 1e-8 passes (steps shrink
///   to ~3e-5 s) and keeps the energy to 1e-7. RK4 at h = 1 ms (a radian per
///   step) also ends finite, but its energy is off by more than 1 %: a fixed
///   step cannot know it is too long; only an adaptive method or a smaller
///   step can.
/// - 10⁸ rad/s: Dormand–Prince would need ~10⁹ steps; the run stops at its
///   step limit with `TooManySteps` (never a hang). RK4 at 1 ms overflows:
///   `NonFinite`.
/// - 10¹⁶⁰ rad/s (u² overflows to infinity): every method stops with
///   `NonFinite` naming a state, at once.
#[test]
fn very_large_speeds() {
    let start = |u: f64| {
        let model = TwoLink::new();
        let mut x = model.initial_state();
        x[2] = u;
        x[3] = -u;
        (model, x)
    };
    let (mut model, mut x) = start(1e3);
    let e0 = energy(&mut model, &x);
    let mut dopri = DormandPrince::with_tolerances(1e-8, 1e-8).unwrap();
    let s = run_to(&mut model, &mut dopri, &mut x, 0.01, 1e-3, 100_000).unwrap();
    assert!(s.min_step < 1e-4, "smallest step {}", s.min_step);
    let e1 = energy(&mut model, &x);
    assert!(((e1 - e0) / e0).abs() < 1e-7, "{e0} -> {e1}");

    let (mut model, mut x) = start(1e3);
    run_to(&mut model, &mut Rk4::new(), &mut x, 0.01, 1e-3, 100_000).unwrap();
    assert!(x.iter().all(|v| v.is_finite()));
    let e1 = energy(&mut model, &x);
    assert!(((e1 - e0) / e0).abs() > 1e-2, "{e0} -> {e1}");

    let (mut model, mut x) = start(1e8);
    let mut dopri = DormandPrince::with_tolerances(1e-8, 1e-8).unwrap();
    match run_to(&mut model, &mut dopri, &mut x, 1.0, 1e-3, 20_000) {
        Err(IntegrationError::TooManySteps { t, steps }) => {
            assert_eq!(steps, 20_000);
            assert!(t > 0.0 && t < 1e-3, "t = {t}");
        }
        other => panic!("expected the step limit, got {other:?}"),
    }
    assert!(x.iter().all(|v| v.is_finite()));
    let (mut model, mut x) = start(1e8);
    let result = run_to(&mut model, &mut Rk4::new(), &mut x, 1.0, 1e-3, 20_000);
    assert_non_finite::<TwoLink>("RK4 at 1e8 rad/s", result, &x, 1.0);

    let (mut model, mut x) = start(1e160);
    let result = run_to(&mut model, &mut Rk4::new(), &mut x, 1.0, 1e-3, 20_000);
    assert_non_finite::<TwoLink>("RK4 at 1e160 rad/s", result, &x, 1e-3);
    let (mut model, mut x) = start(1e160);
    let mut dopri = DormandPrince::with_tolerances(1e-8, 1e-8).unwrap();
    let result = run_to(&mut model, &mut dopri, &mut x, 1.0, 1e-3, 20_000);
    assert_non_finite::<TwoLink>("Dormand-Prince at 1e160 rad/s", result, &x, 1e-3);
    assert_eq!(x[2], 1e160);
}

// ------------------------------------------------------------------ huge steps

/// A step far beyond the stability limit (h = 1 s and 100 s; the two-link
/// model's fastest mode has ω ≈ 25 rad/s):
///
/// - explicit methods overflow within a few steps: `NonFinite` naming the
///   state, the last finite state left behind;
/// - Dormand–Prince takes the step as a first trial, rejects it and
///   passes, landing within 1e-6 of the run started at h = 10 ms;
/// - SDIRK3 (stable for any step on linear problems) cannot solve its
///   stage equations at these steps on this nonlinear model: `NewtonFailed`
///   at t = 0 after 10 iterations, the state untouched. At h = 10 ms it
///   passes.
#[test]
fn a_step_far_beyond_the_stability_limit() {
    for h in [1.0, 100.0] {
        for (name, mut stepper) in explicit_steppers::<TwoLink>() {
            let mut model = TwoLink::new();
            let mut x = model.initial_state();
            let result = run_to(&mut model, &mut *stepper, &mut x, 1000.0, h, 100_000);
            assert_non_finite::<TwoLink>(&format!("{name}, h = {h}"), result, &x, 1000.0);
        }
    }

    let mut model = TwoLink::new();
    let mut reference = model.initial_state();
    let mut dopri = DormandPrince::with_tolerances(1e-8, 1e-8).unwrap();
    run_to(&mut model, &mut dopri, &mut reference, 10.0, 0.01, 100_000).unwrap();
    for h in [1.0, 100.0] {
        let mut x = model.initial_state();
        let mut dopri = DormandPrince::with_tolerances(1e-8, 1e-8).unwrap();
        run_to(&mut model, &mut dopri, &mut x, 10.0, h, 100_000).unwrap();
        let d = (0..4)
            .map(|i| (x[i] - reference[i]).abs())
            .fold(0.0, f64::max);
        assert!(d < 1e-6, "h = {h}: {d:e}");
    }

    for h in [1.0, 100.0] {
        let mut x = model.initial_state();
        let x0 = x;
        let mut sdirk = Sdirk3::<TwoLink, 4>::new(SdirkSettings::default());
        match run_to(&mut model, &mut sdirk, &mut x, 1000.0, h, 100_000) {
            Err(IntegrationError::NewtonFailed {
                t,
                h: step,
                iterations,
            }) => {
                assert_eq!((t, step, iterations), (0.0, h, 10));
            }
            other => panic!("SDIRK3 at h = {h}: expected NewtonFailed, got {other:?}"),
        }
        assert_eq!(x, x0);
    }
    let mut x = model.initial_state();
    let mut sdirk = Sdirk3::<TwoLink, 4>::new(SdirkSettings::default());
    run_to(&mut model, &mut sdirk, &mut x, 10.0, 0.01, 100_000).unwrap();
    let d = (0..2)
        .map(|i| (x[i] - reference[i]).abs())
        .fold(0.0, f64::max);
    assert!(d < 0.1, "SDIRK3 at 10 ms: {d:e}");
}
