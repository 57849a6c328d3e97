//! The implicit method on stiff problems, and explicit failure reported as
//! a typed error.

mod common;

use autosim_runtime::integrate::{Analytic, Rk4, Sdirk3, SdirkSettings};
use autosim_runtime::{IntegrationError, Model, ModelError, RunError, RunSettings, Stepper};
use autosim_test_support::max_diff;
use common::{StiffLinear, VanDerPol, run_from_start, run_unobserved};

/// Runs `stepper` on the stiff linear system over [0, 1] with step `h`.
fn stiff_run<S: Stepper<StiffLinear>>(
    stepper: &mut S,
    h: f64,
) -> Result<[f64; 3], RunError<core::convert::Infallible>> {
    let mut model = StiffLinear::default();
    let mut x = model.initial_state();
    let settings = RunSettings::new(0.0, 1.0, h, 0.1);
    run_unobserved(&mut model, stepper, &mut x, &settings)?;
    Ok(x)
}

#[test]
fn sdirk_is_stable_and_accurate_where_rk4_blows_up() {
    for h in [0.1, 0.01, 0.001] {
        let mut sdirk = Sdirk3::new(SdirkSettings::default());
        let x = stiff_run(&mut sdirk, h).unwrap();
        let err = max_diff(&x, &StiffLinear::exact(1.0));
        println!(
            "SDIRK3 h = {h}: error {err:e}, {} evaluations",
            sdirk.evaluations()
        );
        // h·|λ| is 1e3 .. 1e5: an explicit method is unstable by orders of magnitude.
        assert!(err < 1e-6, "h = {h}: error {err:e}");
    }
}

#[test]
fn rk4_at_a_huge_step_stops_with_a_named_non_finite_state() {
    let mut rk4 = Rk4::new();
    let err = stiff_run(&mut rk4, 0.01).unwrap_err();
    match err {
        RunError::Integration(IntegrationError::NonFinite { t, index, name }) => {
            assert!(t > 0.0 && t <= 1.0, "t = {t}");
            assert_eq!(name, StiffLinear::STATE_NAMES[index]);
            let text = err.to_string();
            assert!(text.contains(name) && text.contains("non-finite"), "{text}");
        }
        other => panic!("expected NonFinite, got {other:?}"),
    }
}

#[test]
fn rk4_failure_leaves_the_last_finite_state() {
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.01);
    let (result, outputs, x) =
        run_from_start(&mut StiffLinear::default(), &mut Rk4::new(), &settings);
    let err = result.unwrap_err();
    assert!(matches!(
        err,
        RunError::Integration(IntegrationError::NonFinite { .. })
    ));
    assert!(
        x.iter().all(|v| v.is_finite()),
        "state after the error: {x:?}"
    );
    let (_, last_output, _) = outputs.last().unwrap();
    assert!(last_output.iter().all(|v| v.is_finite()));
}

/// The exact Jacobian of the stiff system is its matrix A.
#[test]
fn analytic_jacobian_matches_finite_differences_with_fewer_evaluations() {
    let jac = Analytic(
        |m: &StiffLinear, _t: f64, _x: &[f64; 3], j: &mut [[f64; 3]; 3]| {
            *j = m.a;
            Ok(())
        },
    );
    let mut analytic = Sdirk3::with_jacobian(SdirkSettings::default(), jac);
    let mut fd = Sdirk3::new(SdirkSettings::default());
    let xa = stiff_run(&mut analytic, 0.01).unwrap();
    let xf = stiff_run(&mut fd, 0.01).unwrap();
    assert!(max_diff(&xa, &xf) < 1e-9, "{xa:?} vs {xf:?}");
    // 100 steps; finite differences cost N = 3 more evaluations per step.
    assert_eq!(
        fd.evaluations() - analytic.evaluations(),
        300 + fd.newton_iterations() - analytic.newton_iterations()
    );
    // With the exact Jacobian of a linear model, Newton converges at once:
    // one iteration to solve and one to confirm, per stage.
    assert_eq!(analytic.newton_iterations(), 100 * 3 * 2);
}

#[test]
fn sdirk_handles_stiff_van_der_pol() {
    // μ = 1000: the relaxation oscillation is stiff (a fast eigenvalue near
    // −μ(x² − 1) ≈ −3000), and from x = 2 the solution follows the slow manifold.
    let mut model = VanDerPol::with_mu(1000.0);
    let mut x = model.initial_state();
    let mut sdirk = Sdirk3::new(SdirkSettings::default());
    let settings = RunSettings::new(0.0, 100.0, 0.05, 10.0);
    let summary = run_unobserved(&mut model, &mut sdirk, &mut x, &settings).unwrap();
    assert_eq!(summary.steps, 2000);
    // On the slow manifold dx/dt = x / (μ (1 − x²)) (to O(1/μ²)), whose
    // solution from x = 2 satisfies ln x − x²/2 = ln 2 − 2 + t/μ (g decreases
    // for x > 1).
    let g = |x: f64| x.ln() - x * x / 2.0;
    let target = 2.0f64.ln() - 2.0 + 100.0 / 1000.0;
    let mut lo = 1.0;
    let mut hi = 2.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) > target { lo = mid } else { hi = mid }
    }
    println!("VdP x(100) = {}, slow-manifold estimate {lo}", x[0]);
    assert!((x[0] - lo).abs() < 1e-5, "x(100) = {} vs {lo}", x[0]);
}

/// dx/dt = −1000·sign(x): the finite-difference Jacobian is zero, so the
/// "Newton" iteration is a fixed-point iteration with factor hγ·1000 ≫ 1.
struct SignSwitch;

impl Model for SignSwitch {
    autosim_test_support::model_header!(f64, "SignSwitch", states: ["x" in "1"], outputs: 0);
    fn derivatives(&mut self, _t: f64, x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
        dx[0] = -1000.0 * x[0].signum();
        Ok(())
    }
    fn initial_state(&self) -> [f64; 1] {
        [1.0]
    }
}

#[test]
fn newton_failure_is_a_typed_error_with_the_time() {
    let mut model = SignSwitch;
    let mut x = [1.0];
    let mut sdirk = Sdirk3::new(SdirkSettings::default());
    let settings = RunSettings::new(0.5, 2.0, 1.0, 1.0);
    let err = run_unobserved(&mut model, &mut sdirk, &mut x, &settings).unwrap_err();
    match err {
        RunError::Integration(IntegrationError::NewtonFailed { t, h, iterations }) => {
            assert_eq!(t, 0.5);
            assert_eq!(h, 1.0);
            assert!(iterations >= 1);
        }
        other => panic!("expected NewtonFailed, got {other:?}"),
    }
    assert_eq!(x, [1.0], "state left at the start of the failed step");
}

#[test]
fn singular_newton_matrix_is_a_typed_error() {
    // J = I/(hγ) makes I − hγJ exactly zero.
    let h = 0.5;
    let gamma = 0.435_866_521_508_459;
    let jac = Analytic(
        move |_: &StiffLinear, _t: f64, _x: &[f64; 3], j: &mut [[f64; 3]; 3]| {
            *j = [[0.0; 3]; 3];
            for (i, row) in j.iter_mut().enumerate() {
                row[i] = 1.0 / (h * gamma);
            }
            Ok(())
        },
    );
    let mut sdirk = Sdirk3::with_jacobian(SdirkSettings::default(), jac);
    let mut model = StiffLinear::default();
    let mut x = model.initial_state();
    let err = sdirk.step(&mut model, 0.0, &mut x, h).unwrap_err();
    assert_eq!(err, IntegrationError::SingularNewtonMatrix { t: 0.0, h });
}
