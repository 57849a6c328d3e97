//! The run driver and the calling pattern of the steppers.

mod common;

use std::convert::Infallible;

use autosim_runtime::integrate::{DopriSettings, DormandPrince, Euler, Heun, Rk4};
use autosim_runtime::{
    IntegrationError, Model, ModelError, Observer, RunError, RunSettings, Stepper, run,
};
use autosim_test_support::max_diff;
use common::{Decay, Oscillator, run_from_start, run_unobserved};

/// Records every call of `derivatives`: (t, x).
#[derive(Default)]
struct CallLog {
    calls: Vec<(f64, f64)>,
    fail_above: Option<f64>,
}

impl Model for CallLog {
    autosim_test_support::model_header!(f64, "CallLog", states: ["x" in "m"], outputs: 1);
    const OUTPUT_NAMES: &'static [&'static str] = &["twice_x"];
    const OUTPUT_UNITS: &'static [&'static str] = &["m"];
    fn derivatives(&mut self, t: f64, x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
        self.calls.push((t, x[0]));
        if self.fail_above.is_some_and(|limit| x[0] > limit) {
            return Err(ModelError::SingularMassMatrix {
                speed: 0,
                name: "x",
            });
        }
        dx[0] = 1.0;
        Ok(())
    }
    fn outputs(&mut self, _t: f64, x: &[f64; 1], y: &mut [f64; 1]) -> Result<(), ModelError> {
        y[0] = 2.0 * x[0];
        Ok(())
    }
    fn initial_state(&self) -> [f64; 1] {
        [0.0]
    }
}

#[test]
fn rk4_calls_derivatives_at_t_half_half_full_in_order() {
    let mut model = CallLog::default();
    let mut x = [3.0];
    let mut rk4 = Rk4::new();
    let info = rk4.step(&mut model, 1.0, &mut x, 0.5).unwrap();
    // x' = 1: stages at x, x + h/2·1, x + h/2·1, x + h·1.
    assert_eq!(
        model.calls,
        [(1.0, 3.0), (1.25, 3.25), (1.25, 3.25), (1.5, 3.5)]
    );
    assert_eq!(info.evaluations, 4);
    assert_eq!(x, [3.5]);
    // And again for the next step: exactly four more, in the same pattern.
    rk4.step(&mut model, 1.5, &mut x, 0.5).unwrap();
    let times: Vec<f64> = model.calls[4..].iter().map(|c| c.0).collect();
    assert_eq!(times, [1.5, 1.75, 1.75, 2.0]);
    assert_eq!(rk4.evaluations(), 8);
}

#[test]
fn euler_and_heun_call_at_their_stage_times() {
    let mut model = CallLog::default();
    let mut x = [0.0];
    Euler::new().step(&mut model, 2.0, &mut x, 0.1).unwrap();
    assert_eq!(model.calls, [(2.0, 0.0)]);
    model.calls.clear();
    Heun::new().step(&mut model, 2.0, &mut x, 0.1).unwrap();
    assert_eq!(model.calls.len(), 2);
    assert_eq!(model.calls[0].0, 2.0);
    assert!((model.calls[1].0 - 2.1).abs() < 1e-15);
}

#[test]
fn outputs_land_on_output_times_with_exact_step_counts() {
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.1);
    let (summary, seen, _) = run_from_start(&mut Oscillator::default(), &mut Rk4::new(), &settings);
    let summary = summary.unwrap();
    assert_eq!(summary.steps, 100);
    assert_eq!(summary.evaluations, 400);
    assert_eq!(summary.outputs, 11);
    assert_eq!(summary.end_time, 1.0);
    assert_eq!(summary.rejected_steps, 0);
    let exact = Oscillator::default();
    for (k, (t, x, [energy])) in seen.iter().enumerate() {
        assert!((t - 0.1 * k as f64).abs() < 1e-15, "output {k} at {t}");
        assert!(max_diff(x, &exact.exact(*t)) < 1e-9);
        // Energy ½·m·v² + ½·m·ω²·x² of x = cos t with m = 2: exactly 1.
        assert!((energy - 1.0).abs() < 1e-9);
    }
    assert_eq!(seen.last().unwrap().0, 1.0);
}

#[test]
fn steps_divide_output_intervals_and_the_last_interval_is_short() {
    // 0.1 / 0.03 → 4 steps of 0.025 per interval; the last interval [0.2, 0.25]
    // takes 2 steps of 0.025.
    let settings = RunSettings::new(0.0, 0.25, 0.03, 0.1);
    let (summary, seen, x) = run_from_start(&mut Decay { k: 1.0 }, &mut Rk4::new(), &settings);
    let summary = summary.unwrap();
    let times: Vec<f64> = seen.iter().map(|output| output.0).collect();
    assert_eq!(times, [0.0, 0.1, 0.2, 0.25]);
    assert_eq!(summary.steps, 10);
    assert!((summary.max_step - 0.025).abs() < 1e-15);
    assert!((x[0] - (-0.25f64).exp()).abs() < 1e-9);
}

#[test]
fn adaptive_runs_land_on_output_times() {
    let mut dp = DormandPrince::new(DopriSettings::new(1e-9, 1e-9)).unwrap();
    let settings = RunSettings::new(0.0, 10.0, 0.01, 0.25);
    let (summary, seen, _) = run_from_start(&mut Oscillator::default(), &mut dp, &settings);
    let summary = summary.unwrap();
    assert_eq!(seen.len(), 41);
    let exact = Oscillator::default();
    for (k, (t, x, _)) in seen.iter().enumerate() {
        assert_eq!(*t, if k == 40 { 10.0 } else { 0.25 * k as f64 });
        assert!(max_diff(x, &exact.exact(*t)) < 1e-8, "t = {t}");
    }
    assert_eq!(summary.evaluations, dp.evaluations());
    assert!(summary.steps >= 40);
}

#[test]
fn a_model_error_is_wrapped_with_its_time() {
    let mut model = CallLog {
        fail_above: Some(0.5),
        ..CallLog::default()
    };
    let mut x = [0.0];
    let settings = RunSettings::new(0.0, 1.0, 0.1, 0.1);
    let err = run_unobserved(&mut model, &mut Euler::new(), &mut x, &settings).unwrap_err();
    match err {
        RunError::Integration(IntegrationError::Model { t, error }) => {
            // x = t; the call at x ≈ 0.6 fails.
            assert!((t - 0.6).abs() < 1e-12, "t = {t}");
            assert_eq!(
                error,
                ModelError::SingularMassMatrix {
                    speed: 0,
                    name: "x"
                }
            );
        }
        other => panic!("expected a model error, got {other:?}"),
    }
}

/// An observer that fails at a chosen time.
struct FailAt(f64);

#[derive(Debug, PartialEq)]
struct Full;

impl Observer<Decay> for FailAt {
    type Error = Full;
    fn observe(&mut self, t: f64, _x: &[f64; 1], _y: &[f64; 0]) -> Result<(), Full> {
        if t >= self.0 { Err(Full) } else { Ok(()) }
    }
}

#[test]
fn an_observer_error_stops_the_run() {
    let mut model = Decay { k: 1.0 };
    let mut x = model.initial_state();
    let settings = RunSettings::new(0.0, 1.0, 0.1, 0.1);
    let err = run(
        &mut model,
        &mut Rk4::new(),
        &mut x,
        &settings,
        &mut FailAt(0.5),
    )
    .unwrap_err();
    assert_eq!(
        err,
        RunError::Observer {
            t: 0.5,
            error: Full
        }
    );
    assert!(
        (x[0] - (-0.5f64).exp()).abs() < 1e-6,
        "stopped where it failed"
    );
}

#[test]
fn step_limit_is_a_typed_error() {
    let mut model = Decay { k: 1.0 };
    let mut x = model.initial_state();
    let settings = RunSettings::new(0.0, 1.0, 0.1, 0.5).with_max_steps(7);
    let err: IntegrationError = run_unobserved(&mut model, &mut Rk4::new(), &mut x, &settings)
        .unwrap_err()
        .into();
    assert!(
        matches!(err, IntegrationError::TooManySteps { steps: 7, t, .. } if (t - 0.7).abs() < 1e-12),
        "{err:?}"
    );
    // Exactly enough steps is fine.
    let settings = settings.with_max_steps(10);
    let mut x = model.initial_state();
    let summary = run_unobserved(&mut model, &mut Rk4::new(), &mut x, &settings).unwrap();
    assert_eq!(summary.steps, 10);
}

#[test]
fn bad_settings_and_bad_initial_states_are_typed_errors() {
    let mut model = Decay { k: 1.0 };
    let mut obs = |_: f64, _: &[f64; 1], _: &[f64; 0]| {};
    let cases = [
        (RunSettings::new(0.0, -1.0, 0.1, 0.1), "stop"),
        (RunSettings::new(0.0, 1.0, 0.0, 0.1), "step"),
        (RunSettings::new(0.0, 1.0, 0.1, -0.1), "output_interval"),
        (RunSettings::new(f64::NAN, 1.0, 0.1, 0.1), "start"),
    ];
    for (settings, word) in cases {
        let mut x = [1.0];
        match run(&mut model, &mut Rk4::new(), &mut x, &settings, &mut obs) {
            Err(RunError::Integration(IntegrationError::InvalidSettings { reason })) => {
                assert!(reason.contains(word), "{reason}")
            }
            other => panic!("expected InvalidSettings, got {other:?}"),
        }
    }
    let mut x = [f64::NAN];
    let err = run(
        &mut model,
        &mut Rk4::new(),
        &mut x,
        &RunSettings::new(0.0, 1.0, 0.1, 0.1),
        &mut obs,
    )
    .unwrap_err();
    assert_eq!(
        err,
        RunError::<Infallible>::Integration(IntegrationError::NonFinite {
            t: 0.0,
            index: 0,
            name: "x"
        })
    );
}

#[test]
fn a_zero_length_run_reports_the_initial_state_once() {
    let mut model = Decay { k: 1.0 };
    let mut x = [1.0];
    let mut n = 0;
    let summary = run(
        &mut model,
        &mut Rk4::new(),
        &mut x,
        &RunSettings::new(2.0, 2.0, 0.1, 0.1),
        &mut |t, _: &[f64; 1], _: &[f64; 0]| {
            assert_eq!(t, 2.0);
            n += 1;
        },
    )
    .unwrap();
    assert_eq!((n, summary.steps, summary.outputs), (1, 0, 1));
}

#[test]
fn f32_models_run_too() {
    struct DecayF32;
    impl Model for DecayF32 {
        autosim_test_support::model_header!(f32, "DecayF32", states: ["x" in "1"], outputs: 0);
        fn derivatives(
            &mut self,
            _t: f32,
            x: &[f32; 1],
            dx: &mut [f32; 1],
        ) -> Result<(), ModelError> {
            dx[0] = -x[0];
            Ok(())
        }
        fn initial_state(&self) -> [f32; 1] {
            [1.0]
        }
    }
    let mut x = [1.0f32];
    let mut dp = DormandPrince::new(DopriSettings::new(1e-5f32, 1e-6)).unwrap();
    let settings = RunSettings::new(0.0f32, 5.0, 0.1, 0.5);
    run_unobserved(&mut DecayF32, &mut dp, &mut x, &settings).unwrap();
    assert!((x[0] - (-5.0f32).exp()).abs() < 1e-5, "{}", x[0]);
}

/// `run_at` reports exactly at uneven times (the oscillator's exact
/// solution there), ends at the stop time, equals `run` on an even grid,
/// and refuses times out of order or outside the run.
#[test]
fn run_at_reports_at_the_given_times() {
    use autosim_runtime::run_at;
    let times = [0.0, 0.013, 0.25, 0.25, 0.9, 1.7];
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-11, 1e-13)).unwrap();
    let mut seen: Vec<(f64, [f64; 2])> = Vec::new();
    let settings = RunSettings::new(0.0, 2.0, 1e-3, 1.0);
    let summary = run_at(
        &mut model,
        &mut dopri,
        &mut x,
        &settings,
        &times,
        &mut |t, x: &[f64; 2], _: &[f64; 1]| {
            seen.push((t, *x));
        },
    )
    .unwrap();
    assert_eq!(summary.end_time, 2.0);
    assert_eq!(seen.iter().map(|s| s.0).collect::<Vec<_>>(), times);
    for (t, x) in &seen {
        assert!(max_diff(x, &model.exact(*t)) < 1e-9, "t = {t}: {x:?}");
    }
    assert!(max_diff(&x, &model.exact(2.0)) < 1e-9);

    // On an even grid with a fixed-step method: the same bits as `run`.
    let grid: Vec<f64> = (0..=10).map(|k| k as f64 * 0.1).collect();
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.1);
    let (mut at, mut even) = (Vec::new(), Vec::new());
    let mut x = model.initial_state();
    run_at(
        &mut model,
        &mut Rk4::new(),
        &mut x,
        &settings,
        &grid,
        &mut |_t, x: &[f64; 2], _: &[f64; 1]| at.push(*x),
    )
    .unwrap();
    let mut x = model.initial_state();
    run(
        &mut model,
        &mut Rk4::new(),
        &mut x,
        &settings,
        &mut |_t, x: &[f64; 2], _: &[f64; 1]| even.push(*x),
    )
    .unwrap();
    assert_eq!(at, even);

    for bad in [&[0.5, 0.4][..], &[-0.1][..], &[1.5][..]] {
        let mut x = model.initial_state();
        let err = run_at(
            &mut model,
            &mut Rk4::new(),
            &mut x,
            &settings,
            bad,
            &mut |_t, _: &[f64; 2], _: &[f64; 1]| {},
        )
        .unwrap_err();
        assert!(
            matches!(
                err,
                RunError::Integration(IntegrationError::InvalidSettings { .. })
            ),
            "{bad:?}: {err:?}"
        );
    }
}
