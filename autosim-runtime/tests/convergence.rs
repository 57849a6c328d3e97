//! Orders of convergence of the fixed-step integrators, measured on the
//! harmonic oscillator against its exact solution.

mod common;

use autosim_runtime::integrate::{
    AbmOrder, AdamsBashforthMoulton, Euler, Heun, Rk4, Sdirk3, SdirkSettings,
};
use autosim_runtime::{Model, Stepper};
use autosim_test_support::max_diff;
use common::{Oscillator, convergence_slope};

const T_END: f64 = 4.0;

/// Global error at `T_END` for `n` equal steps.
fn global_error<S: Stepper<Oscillator>>(stepper: &mut S, n: u32) -> f64 {
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let h = T_END / f64::from(n);
    for i in 0..n {
        stepper
            .step(&mut model, f64::from(i) * h, &mut x, h)
            .unwrap();
    }
    max_diff(&x, &model.exact(T_END))
}

/// Measures the slope over five step sizes (halving) and checks it against
/// the method's theoretical order within ±0.2.
fn check_order<S: Stepper<Oscillator>>(make: impl Fn() -> S, n0: u32, expected: f64) -> f64 {
    let points: Vec<(f64, f64)> = (0..5)
        .map(|i| {
            let n = n0 << i;
            (T_END / f64::from(n), global_error(&mut make(), n))
        })
        .collect();
    let slope = convergence_slope(&points);
    println!("{}: slope {slope:.3}, errors {points:?}", make().name());
    assert!(
        (slope - expected).abs() <= 0.2,
        "{}: measured order {slope}, expected {expected}; (h, error) = {points:?}",
        make().name()
    );
    assert_eq!(f64::from(make().order()), expected);
    slope
}

#[test]
fn euler_is_first_order() {
    check_order(Euler::new, 400, 1.0);
}

#[test]
fn heun_is_second_order() {
    check_order(Heun::new, 40, 2.0);
}

#[test]
fn rk4_is_fourth_order() {
    check_order(Rk4::new, 20, 4.0);
}

#[test]
fn abm2_is_second_order() {
    check_order(|| AdamsBashforthMoulton::new(AbmOrder::Two), 40, 2.0);
}

#[test]
fn abm4_is_fourth_order() {
    check_order(|| AdamsBashforthMoulton::new(AbmOrder::Four), 40, 4.0);
}

#[test]
fn sdirk3_is_third_order() {
    check_order(|| Sdirk3::new(SdirkSettings::default()), 20, 3.0);
}

#[test]
fn abm4_evaluation_count_matches_start_up_then_pece() {
    // Start-up: f(t0) + 3 RK4 stages + f at the new point for the first
    // step, 3 + 1 for the next two, then 2 per PECE step.
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let mut abm = AdamsBashforthMoulton::new(AbmOrder::Four);
    let h = 0.01;
    let mut counts = Vec::new();
    for i in 0..10 {
        let info = abm.step(&mut model, f64::from(i) * h, &mut x, h).unwrap();
        counts.push(info.evaluations);
    }
    assert_eq!(counts, [5, 4, 4, 2, 2, 2, 2, 2, 2, 2]);
    assert_eq!(abm.evaluations(), 13 + 2 * 7);
    assert_eq!(abm.startup_steps(), 3);
}

#[test]
fn abm_restarts_when_the_step_changes() {
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let mut abm = AdamsBashforthMoulton::new(AbmOrder::Two);
    let mut t = 0.0;
    for h in [0.01, 0.01, 0.01, 0.02, 0.02] {
        abm.step(&mut model, t, &mut x, h).unwrap();
        t += h;
    }
    // RK4 for the first step and again for the first step of size 0.02.
    assert_eq!(abm.startup_steps(), 2);
    assert!(max_diff(&x, &model.exact(t)) < 1e-5);
}
