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
use std::convert::Infallible;

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

/// Runs `model` from its initial state to `stop` with `stepper` at
/// `step`: the recording, and the error that ended the run if one did.
fn run_recorded<M: Model<Float = f64>, S: Stepper<M>>(
    mut model: M,
    stepper: &mut S,
    step: f64,
    stop: f64,
) -> (Recording<M>, Result<(), RunError<Infallible>>) {
    let mut x = model.initial_state();
    let settings = RunSettings::new(0.0, stop, step, 0.01);
    let mut recording = Recording::new();
    let result = run(&mut model, stepper, &mut x, &settings, &mut recording).map(|_| ());
    (recording, result)
}

/// The recorded events' instants and their largest difference from the
/// first of them `expected`.
fn instants<M: Model>(recording: &Recording<M>, expected: &[f64]) -> (Vec<f64>, f64) {
    let instants: Vec<f64> = recording.events().iter().map(|e| e.t).collect();
    let worst = expected
        .iter()
        .zip(&instants)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    (instants, worst)
}

fn check<S: Stepper<PressedCart>>(what: &str, stepper: &mut S, step: f64, within: f64) {
    let p = Parameters::default();
    let (expected, limit) = impact_times(&p, 12);
    let (recording, result) = run_recorded(PressedCart::new(), stepper, step, 3.0);
    let (impacts, worst) = instants(&recording, &expected);
    let past_stop = recording
        .column("x")
        .unwrap()
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

mod table {
    autosim::model! {
        /// A ball bouncing on a table driven as `A sin(w t)`: its impacts
        /// pile up where the table overtakes the ever lower bounces.
        model TableBall;
        parameters { g = 9.81 [m/s^2], e = 0.7, A = 0.05 [m], w = 6 [rad/s], m = 0.2 [kg] }
        body Ball { translate: 3, q: [h], u: [v], mass: m, inertia: 0, initial: [1] }
        gravity = -g*n3;
        let table = A*sin(w*t);
        let table_speed = A*w*cos(w*t);
        event impact [m] {
            indicator: h - table,
            direction: falling,
            reset: { v: table_speed - e*(v - table_speed) },
        }
        output gap [m] = h - table;
    }
}

/// The ball on the moving table: impact instants by bisection on the
/// exact flight (a parabola) against the exact table, after each the
/// relative speed reversed and scaled.
fn table_impacts(count: usize) -> Vec<f64> {
    let (g, e, a, w) = (9.81, 0.7, 0.05, 6.0);
    let table = |t: f64| a * (w * t).sin();
    let table_speed = |t: f64| a * w * (w * t).cos();
    let (mut t0, mut h0, mut v0) = (0.0, 1.0, 0.0);
    let mut times = Vec::new();
    while times.len() < count {
        let gap = |t: f64| {
            let s = t - t0;
            h0 + v0 * s - 0.5 * g * s * s - table(t)
        };
        // The first sign change after t0, by small steps, then bisection.
        let mut a_t = t0 + 1e-9;
        let step = 1e-4;
        while gap(a_t + step) > 0.0 {
            a_t += step;
        }
        let mut b_t = a_t + step;
        for _ in 0..200 {
            let mid = 0.5 * (a_t + b_t);
            if gap(mid) > 0.0 { a_t = mid } else { b_t = mid }
        }
        let t = b_t;
        let v = v0 - g * (t - t0);
        times.push(t);
        (t0, h0, v0) = (t, table(t), table_speed(t) - e * (v - table_speed(t)));
    }
    times
}

#[test]
fn a_ball_on_a_moving_table_ends_in_zeno_never_below_it() {
    use table::table_ball::TableBall;
    let expected = table_impacts(8);
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    for (what, (recording, result)) in [
        (
            "Dormand-Prince 1e-12",
            run_recorded(TableBall::new(), &mut dopri, 1e-3, 3.0),
        ),
        (
            "RK4 h = 1 ms",
            run_recorded(TableBall::new(), &mut Rk4::new(), 1e-3, 3.0),
        ),
    ] {
        let (impacts, worst) = instants(&recording, &expected);
        let lowest = recording
            .column("gap")
            .unwrap()
            .values
            .iter()
            .fold(f64::INFINITY, |m, &x| m.min(x));
        println!(
            "{what}: {} impacts, the first 8 within {worst:.1e} s; lowest gap {lowest:.1e} m; {result:?}",
            impacts.len()
        );
        assert!(worst < 1e-7, "{what}: {worst:e}");
        assert!(
            lowest > -1e-9,
            "{what}: the ball went {lowest} m into the table"
        );
        assert!(
            matches!(
                result,
                Err(RunError::Integration(IntegrationError::Zeno { .. }))
            ),
            "{what}: {result:?}"
        );
    }
}
