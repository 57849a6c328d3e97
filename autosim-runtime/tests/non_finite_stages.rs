//! A model that cannot evaluate a non-finite state (as generated models,
//! whose LDLᵀ solve sees a NaN pivot and reports a singular mass matrix):
//! an overflow inside a step is reported as the non-finite state it is,
//! and Dormand–Prince retries a trial step smaller, instead of giving up,
//! when the model cannot evaluate one of its stages.

mod common;

use autosim_runtime::integrate::{
    AbmOrder, AdamsBashforthMoulton, DormandPrince, Euler, Heun, Rk4, Sdirk3, SdirkSettings,
};
use autosim_runtime::{IntegrationError, Model, ModelError, RunSettings, Stepper};
use common::run_unobserved;

/// `x'' = -ω² x` with ω = 1000, failing like a generated model on a
/// non-finite state.
struct Guarded;

impl Model for Guarded {
    autosim_test_support::model_header!(f64, "Guarded", states: ["x" in "m", "v" in "m/s"], outputs: 0);
    fn derivatives(&mut self, _t: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        // The "pivot" is NaN when the state is not finite, as a generated
        // model's would be.
        let pivot = 1.0 + 0.0 * x[0] * x[1];
        if pivot.is_nan() || pivot <= 0.0 {
            return Err(ModelError::SingularMassMatrix {
                speed: 0,
                name: "v",
            });
        }
        dx[0] = x[1];
        dx[1] = -1e6 * x[0];
        Ok(())
    }
    fn initial_state(&self) -> [f64; 2] {
        [1.0, 0.0]
    }
}

fn go<S: Stepper<Guarded> + ?Sized>(
    stepper: &mut S,
    step: f64,
    stop: f64,
) -> (Result<(), IntegrationError>, [f64; 2]) {
    let mut x = Guarded.initial_state();
    let settings = RunSettings::new(0.0, stop, step, stop).with_max_steps(100_000);
    let r = run_unobserved(&mut Guarded, stepper, &mut x, &settings)
        .map(|_| ())
        .map_err(IntegrationError::from);
    (r, x)
}

#[test]
fn explicit_methods_name_the_state_that_overflowed() {
    // h·ω = 1000, far beyond every explicit method's stability limit.
    let steppers: [(&str, &mut dyn Stepper<Guarded>); 5] = [
        ("Euler", &mut Euler::new()),
        ("Heun", &mut Heun::new()),
        ("RK4", &mut Rk4::new()),
        ("ABM2", &mut AdamsBashforthMoulton::new(AbmOrder::Two)),
        ("ABM4", &mut AdamsBashforthMoulton::new(AbmOrder::Four)),
    ];
    for (name, stepper) in steppers {
        let (r, x) = go(stepper, 1.0, 1000.0);
        match r {
            Err(IntegrationError::NonFinite { t, name: state, .. }) => {
                assert!(t > 0.0 && t < 1000.0, "{name}: t = {t}");
                assert!(state == "x" || state == "v", "{name}: {state}");
            }
            other => panic!("{name}: expected a non-finite state, got {other:?}"),
        }
        assert!(x.iter().all(|v| v.is_finite()), "{name}: {x:?}");
    }
}

#[test]
fn dormand_prince_shrinks_a_step_whose_stages_overflow() {
    let mut dopri = DormandPrince::<Guarded>::with_tolerances(1e-6, 1e-9).unwrap();
    let mut x = Guarded.initial_state();
    // A trial step of 1e300 s overflows in the stages: the model cannot
    // evaluate them, and the step is retried smaller until it succeeds.
    let info = dopri.step(&mut Guarded, 0.0, &mut x, 1e300).unwrap();
    assert!(info.h > 0.0 && info.h < 1e-2, "h = {}", info.h);
    assert!(info.rejected > 0);
    assert!(x.iter().all(|v| v.is_finite()), "{x:?}");
    // And a whole run from a huge first trial step lands on the solution.
    let (r, x) = go(&mut dopri, 1e6, 10.0);
    assert_eq!(r, Ok(()));
    let exact = (1000.0f64 * 10.0).cos();
    assert!((x[0] - exact).abs() < 1e-2, "{} vs {exact}", x[0]);
}

#[test]
fn sdirk_passes_at_a_step_where_explicit_methods_overflow() {
    // L-stable: no overflow at any step on this linear model.
    let mut sdirk = Sdirk3::<Guarded, 2>::new(SdirkSettings::default());
    let (r, x) = go(&mut sdirk, 1.0, 10.0);
    assert_eq!(r, Ok(()));
    assert!(x.iter().all(|v| v.is_finite()));
}

/// `x'' = -x` for |x| ≤ 2, or drifting `x' = 1` (`drift`); the model cannot
/// evaluate |x| > 2 (like a small-angle model whose mass matrix stops being
/// positive definite far from the states it was made for).
struct Fenced {
    drift: bool,
}

impl Model for Fenced {
    autosim_test_support::model_header!(f64, "Fenced", states: ["x" in "m", "v" in "m/s"], outputs: 0);
    fn derivatives(&mut self, _t: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        if x[0].abs() > 2.0 {
            return Err(ModelError::SingularMassMatrix {
                speed: 0,
                name: "v",
            });
        }
        if self.drift {
            *dx = [1.0, 0.0];
        } else {
            *dx = [x[1], -x[0]];
        }
        Ok(())
    }
    fn initial_state(&self) -> [f64; 2] {
        [if self.drift { 0.0 } else { 1.0 }, 0.0]
    }
}

#[test]
fn dormand_prince_retries_a_trial_the_model_cannot_evaluate() {
    let mut model = Fenced { drift: false };
    let mut dopri = DormandPrince::<Fenced>::with_tolerances(1e-8, 1e-8).unwrap();
    let mut x = model.initial_state();
    // Stages of a 100 s trial leave |x| <= 2: retried smaller.
    let settings = RunSettings::new(0.0, 10.0, 100.0, 10.0);
    run_unobserved(&mut model, &mut dopri, &mut x, &settings).unwrap();
    assert!((x[0] - 10.0f64.cos()).abs() < 1e-6, "{x:?}");

    // A solution that leaves the model's domain is still reported, naming
    // the model's error, where it leaves.
    let mut model = Fenced { drift: true };
    let mut dopri = DormandPrince::<Fenced>::with_tolerances(1e-8, 1e-8).unwrap();
    let mut x = model.initial_state();
    let settings = RunSettings::new(0.0, 5.0, 0.1, 5.0);
    let err = run_unobserved(&mut model, &mut dopri, &mut x, &settings)
        .map_err(IntegrationError::from)
        .unwrap_err();
    match err {
        IntegrationError::Model { t, error } => {
            assert!((t - 2.0).abs() < 1e-6, "t = {t}");
            assert_eq!(
                error,
                ModelError::SingularMassMatrix {
                    speed: 0,
                    name: "v"
                }
            );
        }
        other => panic!("expected the model's error, got {other:?}"),
    }
    assert!(x[0] <= 2.0 && (x[0] - 2.0).abs() < 1e-6, "{x:?}");
}
