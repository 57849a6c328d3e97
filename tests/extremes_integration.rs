//! Stability at the extremes of integration, on the two-link model: stiff
//! springs, mass and inertia ratios, very large speeds, and steps far
//! beyond the stability limit. Each case ends in a result or a typed error
//! that names the cause (see `extremes/mod.rs`).
//!
//! | case | expected behaviour |
//! | --- | --- |
//! | stiff springs (k × 10⁶), explicit methods at h = 1 ms | `IntegrationError::NonFinite` naming a state (or the model's `NonFiniteDerivative`, when a derivative overflows before a state does), within 0.05 s; the state is left at its last finite value |
//! | stiff springs, Dormand–Prince | passes, at steps held below the stability limit (≈ 3.3/ω_max, 6e-5 s); energy within 0.1 % |
//! | stiff springs, SDIRK3 at h = 1 ms | passes; L-stable: the energy never grows, the unresolved vibration is damped out to the static equilibrium |
//! | mass and inertia ratios 1e-6 … 1e6 | passes with Dormand–Prince at 1e-10: energy within 1e-7, no spurious singular-matrix error |
//! | very large speeds | 10³ rad/s: passes (Dormand–Prince), energy within 1e-7; 10⁸ rad/s: `TooManySteps` at the step limit (never a hang); 10¹⁶⁰ rad/s (u² overflows): `NonFinite` naming a state |
//! | a step far beyond the stability limit | explicit: `NonFinite`; Dormand–Prince: passes (the step is only a first trial); SDIRK3: `NewtonFailed` at t = 0, state untouched |

mod extremes;

use autosim::runtime::integrate::{
    AbmOrder, AdamsBashforthMoulton, DormandPrince, Euler, Heun, Rk4, Sdirk3, SdirkSettings,
};
use autosim::runtime::{
    IntegrationError, Model, ModelError, RunSettings, RunSummary, Stepper, run,
};
use autosim_test_support::worst_of;
use extremes::run_to;

mod models {
    autosim::model!(file = "tests/models/extremes/two_link.sim");
}

use models::two_link::{self, TwoLink};

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
/// Runs Dormand–Prince at tolerances `(relative, absolute)` from `x` to
/// `t_end` (1 ms first step); its summary and the relative change of the
/// energy.
fn dopri_energy_drift(
    model: &mut TwoLink,
    x: &mut [f64; 4],
    (relative, absolute): (f64, f64),
    t_end: f64,
) -> (RunSummary<f64>, f64) {
    let e0 = energy(model, x);
    let mut dopri = DormandPrince::with_tolerances(relative, absolute).unwrap();
    let s = run_to(model, &mut dopri, x, t_end, 1e-3, 100_000).unwrap();
    let e1 = energy(model, x);
    (s, ((e1 - e0) / e0).abs())
}

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
/// the state left finite; or, when a huge but finite state makes a
/// derivative overflow first, the model's `NonFiniteDerivative` naming that
/// state (the generated model checks its derivatives).
fn assert_non_finite<M: Model<Float = f64>>(
    what: &str,
    result: Result<RunSummary<f64>, IntegrationError>,
    x: &M::State,
    t_max: f64,
) {
    match result {
        Err(
            IntegrationError::NonFinite { t, index, name }
            | IntegrationError::Model {
                t,
                error: ModelError::NonFiniteDerivative { index, name },
            },
        ) => {
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
    let (s, drift) = dopri_energy_drift(&mut model, &mut x, (1e-6, 1e-9), 0.2);
    assert!(s.max_step < 7e-5, "largest step {}", s.max_step);
    assert!(drift < 1e-3, "energy changed by {drift:e}");

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
    let (s, drift) = dopri_energy_drift(&mut model, &mut x, (1e-8, 1e-8), 0.01);
    assert!(s.min_step < 1e-4, "smallest step {}", s.min_step);
    assert!(drift < 1e-7, "energy changed by {drift:e}");

    let (mut model, mut x) = start(1e3);
    let e0 = energy(&mut model, &x);
    run_to(&mut model, &mut Rk4::new(), &mut x, 0.01, 1e-3, 100_000).unwrap();
    assert!(x.iter().all(|v| v.is_finite()));
    let e1 = energy(&mut model, &x);
    assert!(((e1 - e0) / e0).abs() > 1e-2, "{e0} -> {e1}");

    let (mut model, mut x) = start(1e8);
    let mut dopri = DormandPrince::with_tolerances(1e-8, 1e-8).unwrap();
    match run_to(&mut model, &mut dopri, &mut x, 1.0, 1e-3, 20_000) {
        Err(IntegrationError::TooManySteps {
            t,
            steps,
            largest,
            value,
        }) => {
            assert_eq!(steps, 20_000);
            assert!(t > 0.0 && t < 1e-3, "t = {t}");
            // The error names the state that shows the size of the motion:
            // a speed of 1e8 rad/s (the angles are still below 1e5 rad).
            let speeds = &<TwoLink as Model>::STATE_NAMES[2..];
            assert!(speeds.contains(&largest), "{largest}");
            assert!(value.abs() > 0.5e8, "{largest} = {value}");
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
            .fold(0.0, worst_of);
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
        .fold(0.0, worst_of);
    assert!(d < 0.1, "SDIRK3 at 10 ms: {d:e}");
}
