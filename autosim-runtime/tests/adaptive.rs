//! Dormand–Prince 5(4): tolerance, dense output, FSAL, controller, failures.

mod common;

use autosim_runtime::integrate::{DopriSettings, DormandPrince};
use autosim_runtime::{IntegrationError, Model, RunSettings, Stepper};
use autosim_test_support::{max_diff, worst_of};
use common::{BlowUp, Oscillator, Polynomial, run_unobserved};

/// Steps the oscillator to `t_end` with DOPRI5, returning the global error
/// and the stepper.
fn oscillator_error(settings: DopriSettings<f64>, t_end: f64) -> (f64, DormandPrince<Oscillator>) {
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let mut dp = DormandPrince::new(settings).unwrap();
    let mut t = 0.0;
    let mut h: f64 = 1e-3;
    while t < t_end {
        let info = dp.step(&mut model, t, &mut x, h.min(t_end - t)).unwrap();
        t += info.h;
        h = info.h_next;
    }
    (max_diff(&x, &model.exact(t_end)), dp)
}

#[test]
fn global_error_tracks_the_tolerance() {
    for tol in [1e-4, 1e-6, 1e-8, 1e-10] {
        for beta in [0.04, 0.0] {
            let mut s = DopriSettings::new(tol, tol);
            s.beta = beta;
            let (err, dp) = oscillator_error(s, 10.0);
            println!(
                "tol {tol:e} beta {beta}: error {err:e}, {} steps, {} rejected",
                dp.accepted_steps(),
                dp.rejected_steps()
            );
            assert!(err < 10.0 * tol, "tol {tol:e}, beta {beta}: error {err:e}");
            // And the controller does not waste effort far below the tolerance.
            assert!(
                err > 1e-3 * tol,
                "tol {tol:e}: suspiciously small error {err:e}"
            );
        }
    }
}

#[test]
fn fsal_costs_six_evaluations_per_trial_step() {
    let (_, dp) = oscillator_error(DopriSettings::new(1e-7, 1e-7), 10.0);
    let trials = dp.accepted_steps() + dp.rejected_steps();
    assert!(dp.accepted_steps() > 10);
    assert_eq!(Stepper::<Oscillator>::evaluations(&dp), 1 + 6 * trials);
}

#[test]
fn dense_output_is_accurate_between_steps() {
    let tol = 1e-8;
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let mut dp = DormandPrince::new(DopriSettings::new(tol, tol)).unwrap();
    let (mut t, mut h) = (0.0, 0.1);
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    while t < 10.0 {
        // The local error of the step itself, measured from the exact start.
        let info = dp.step(&mut model, t, &mut x, h).unwrap();
        let (t0, t1) = dp.last_step().unwrap();
        assert_eq!((t0, t1), (t, t + info.h));
        for theta in [0.1, 0.25, 0.5, 0.75, 0.9] {
            let ti = t0 + theta * (t1 - t0);
            let mut xi = [0.0; 2];
            dp.interpolate(ti, &mut xi).unwrap();
            worst = worst_of(worst, max_diff(&xi, &model.exact(ti)));
            checked += 1;
        }
        t += info.h;
        h = info.h_next;
    }
    println!("dense output: worst error {worst:e} over {checked} points");
    assert!(checked > 50);
    assert!(worst < 10.0 * tol, "dense output error {worst:e}");
    // Ends of the step reproduce the step's own values.
    let mut end = [0.0; 2];
    dp.interpolate(t, &mut end).unwrap();
    assert!(max_diff(&end, &x) < 1e-15);
}

#[test]
fn dense_output_is_exact_for_quartic_solutions() {
    // A fourth-order continuous extension reproduces x = t⁴ to round-off
    // (x' = 4t³, so the step itself is exact as well).
    let mut model = Polynomial { degree: 4 };
    let mut x = model.initial_state();
    let mut dp = DormandPrince::new(DopriSettings::new(1e-3, 1e-3)).unwrap();
    let info = dp.step(&mut model, 0.0, &mut x, 1.0).unwrap();
    assert_eq!(info.h, 1.0, "the step is exact, so nothing is rejected");
    assert!((x[0] - 1.0).abs() < 1e-14);
    for ti in [0.0, 0.1, 0.3, 0.5, 0.77, 1.0] {
        let mut xi = [0.0];
        dp.interpolate(ti, &mut xi).unwrap();
        assert!(
            (xi[0] - ti.powi(4)).abs() < 1e-14,
            "t = {ti}: {} vs {}",
            xi[0],
            ti.powi(4)
        );
    }
}

#[test]
fn interpolation_outside_the_last_step_is_an_error() {
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let mut dp = DormandPrince::new(DopriSettings::default()).unwrap();
    let mut xi = [0.0; 2];
    assert!(matches!(
        dp.interpolate(0.0, &mut xi),
        Err(IntegrationError::OutsideLastStep { .. })
    ));
    let info = dp.step(&mut model, 0.0, &mut x, 0.01).unwrap();
    assert_eq!(
        dp.interpolate(0.5, &mut xi),
        Err(IntegrationError::OutsideLastStep {
            t: 0.5,
            start: 0.0,
            end: info.h
        })
    );
}

#[test]
fn step_limits_are_respected() {
    let mut s = DopriSettings::new(1e-3, 1e-3);
    s.max_step = 0.05;
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let mut dp = DormandPrince::new(s).unwrap();
    let info = dp.step(&mut model, 0.0, &mut x, 1.0).unwrap();
    assert_eq!(info.h, 0.05);
    assert!(info.h_next <= 0.05);

    // A minimum step above what the tolerance needs is a typed failure.
    let mut s = DopriSettings::new(1e-12, 1e-12);
    s.min_step = 0.5;
    let mut dp = DormandPrince::new(s).unwrap();
    let mut x = model.initial_state();
    let before = x;
    let err = dp.step(&mut model, 0.0, &mut x, 1.0).unwrap_err();
    assert!(matches!(err, IntegrationError::StepSizeUnderflow { t, h } if t == 0.0 && h < 0.5));
    assert_eq!(x, before, "a failed step leaves the state alone");
}

#[test]
fn blow_up_stops_with_step_size_underflow_near_the_singularity() {
    let mut model = BlowUp;
    let mut x = model.initial_state();
    let mut dp = DormandPrince::new(DopriSettings::new(1e-8, 1e-8)).unwrap();
    let settings = RunSettings::new(0.0, 2.0, 1e-3, 0.1);
    let err = run_unobserved(&mut model, &mut dp, &mut x, &settings).unwrap_err();
    // The closure observer cannot fail, so the run error is an integration error.
    let err = IntegrationError::from(err);
    let t = err.time().unwrap();
    assert!(
        matches!(
            err,
            IntegrationError::StepSizeUnderflow { .. } | IntegrationError::NonFinite { .. }
        ),
        "{err}"
    );
    assert!((0.99..1.01).contains(&t), "stopped at t = {t}: {err}");
    assert!(
        x[0].is_finite() && x[0] > 100.0,
        "last good state kept: {x:?}"
    );
}

#[test]
fn invalid_settings_are_rejected_by_name() {
    let bad = |f: fn(&mut DopriSettings<f64>)| {
        let mut s = DopriSettings::default();
        f(&mut s);
        match DormandPrince::<Oscillator>::new(s) {
            Err(IntegrationError::InvalidSettings { reason }) => reason,
            other => panic!("expected InvalidSettings, got {other:?}"),
        }
    };
    assert!(bad(|s| s.rtol = 0.0).contains("rtol"));
    assert!(bad(|s| s.atol = f64::NAN).contains("atol"));
    assert!(bad(|s| s.max_step = -1.0).contains("max_step"));
    assert!(bad(|s| s.safety = 1.5).contains("safety"));
    assert!(bad(|s| s.beta = 0.5).contains("beta"));
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let mut dp = DormandPrince::new(DopriSettings::default()).unwrap();
    assert!(matches!(
        dp.step(&mut model, 0.0, &mut x, -0.1),
        Err(IntegrationError::InvalidSettings { .. })
    ));
}

#[test]
fn fsal_is_not_reused_after_the_state_is_changed_by_hand() {
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let mut dp = DormandPrince::new(DopriSettings::new(1e-3, 1e-3)).unwrap();
    let a = dp.step(&mut model, 0.0, &mut x, 0.01).unwrap();
    let b = dp.step(&mut model, a.h, &mut x, 0.01).unwrap();
    assert_eq!((a.evaluations, b.evaluations), (7, 6));
    x[1] += 0.5; // an impulse applied between steps
    let c = dp.step(&mut model, a.h + b.h, &mut x, 0.01).unwrap();
    assert_eq!(c.evaluations, 7);
}
