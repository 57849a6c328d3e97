//! A stop that the motion keeps pressing against: a cart on a spring whose
//! rest point lies beyond an end stop bounces off it with restitution `e`,
//! each bounce smaller and shorter, infinitely many before a finite
//! instant. Between impacts the motion is harmonic, so the impact times
//! are known in closed form; the run must follow them and then end in
//! the typed Zeno error, never pass through the stop. (The bounces soon
//! last less than a step's first sampling interval, so the crossing after
//! each impact lies inside the first part of a step: the run driver finds
//! it there from the indicator's rate after the reset.)

use autosim::runtime::integrate::{DopriSettings, DormandPrince, Rk4};
use autosim::runtime::io::Recording;
use autosim::runtime::{IntegrationError, Model, RunError, RunSettings, Stepper, run};

autosim::model! {
    /// A cart on a spring that pulls it towards `x_rest`, beyond a stop at
    /// `x_stop`, from rest at `x = 0`.
    model PressedCart;
    parameters {
        M = 1 [kg], k = 4 [N/m], x_rest = 1 [m], x_stop = 0.5 [m], e = 0.5 [1],
    }
    body C { translate: 1, q: [x], u: [v], mass: M, inertia: 0 }
    force spring { on: C, along: n1, magnitude: -k*(x - x_rest) }
    event stop [m] { indicator: x - x_stop, direction: rising, reset: { v: -e*v } }
}

use pressed_cart::{Parameters, PressedCart};

/// The impact instants in closed form (M = 1, ω = 2): released from
/// rest at `D = x_rest` from the rest point, the cart reaches the stop
/// (`d = x_rest - x_stop` from it) after `acos(d/D)/ω` at speed
/// `ω √(D² - d²)`; leaving it at speed `s` it returns after
/// `(2/ω) atan(s/(ω d))` at the same speed, and leaves at `e` times it.
fn impact_times(p: &Parameters, count: usize) -> (Vec<f64>, f64) {
    let w = (p.k / p.M).sqrt();
    let (big_d, d) = (p.x_rest, p.x_rest - p.x_stop);
    let mut t = (d / big_d).acos() / w;
    let mut speed = p.e * w * (big_d * big_d - d * d).sqrt();
    let mut times = vec![t];
    let mut limit = t;
    for n in 0..2000 {
        let gap = 2.0 / w * (speed / (w * d)).atan();
        limit += gap;
        if n + 1 < count {
            t += gap;
            times.push(t);
        }
        speed *= p.e;
    }
    (times, limit)
}

/// Runs the cart to `stop` with `stepper`: the impacts recorded, or the
/// error that ended the run.
fn press<S: Stepper<PressedCart>>(
    stepper: &mut S,
    step: f64,
    stop: f64,
) -> (
    Recording<PressedCart>,
    Result<(), RunError<std::convert::Infallible>>,
) {
    let mut cart = PressedCart::new();
    let mut x = cart.initial_state();
    let settings = RunSettings::new(0.0, stop, step, 0.01);
    let mut recording = Recording::new();
    let result = run(&mut cart, stepper, &mut x, &settings, &mut recording).map(|_| ());
    (recording, result)
}

fn check<S: Stepper<PressedCart>>(what: &str, stepper: &mut S, step: f64, within: f64) {
    let p = Parameters::default();
    let (expected, limit) = impact_times(&p, 12);
    let (recording, result) = press(stepper, step, 3.0);
    let impacts: Vec<f64> = recording.events().iter().map(|e| e.t).collect();
    let worst = expected
        .iter()
        .zip(&impacts)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let past_stop = recording.columns()[0]
        .values
        .iter()
        .fold(f64::NEG_INFINITY, |m, &x| m.max(x - p.x_stop));
    println!(
        "{what}: {} impacts, the first 12 within {worst:.1e} s of the closed form; furthest past the stop {past_stop:.1e} m; {result:?} (the limit {limit:.6} s)",
        impacts.len()
    );
    assert!(impacts.len() >= 12, "{impacts:?}");
    assert!(worst < within, "{what}: {worst:e}");
    assert!(
        past_stop < 1e-9,
        "{what}: the cart went {past_stop} m through the stop"
    );
    match result {
        Err(RunError::Integration(IntegrationError::Zeno { t, name, .. })) => {
            assert_eq!(name, "stop");
            assert!(
                (t - limit).abs() < 1e-6,
                "{what}: Zeno at {t}, the limit is {limit}"
            );
        }
        other => panic!("{what}: expected the Zeno error, got {other:?}"),
    }
}

#[test]
fn a_pressed_stop_follows_the_closed_form_then_ends_in_zeno() {
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-10, 1e-12)).unwrap();
    check("Dormand-Prince 1e-10", &mut dopri, 1e-3, 1e-8);
    check("RK4 h = 1 ms", &mut Rk4::new(), 1e-3, 1e-8);
    check("RK4 h = 10 ms", &mut Rk4::new(), 1e-2, 1e-5);
}
