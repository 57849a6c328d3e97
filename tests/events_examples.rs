//! Two of the events issue's examples written in the model language and
//! checked against independent references: the quarter car hitting its
//! bump stop (`examples/models/quarter_car_bump_stop.sim`: the stop's
//! spring switched by events setting a discrete mode, against the exact
//! solution of each linear mode with the switches bisected in 40 digits,
//! `tests/reference/gen/quarter_car_bump_stop.py`) and the nonlinear
//! pendulum striking an end stop (`examples/models/pendulum_end_stop.sim`:
//! a restitution reset, against the closed form in elliptic integrals,
//! `tests/reference/gen/pendulum_end_stop.py`).

use autosim::runtime::integrate::{DopriSettings, DormandPrince, Rk4};
use autosim::runtime::io::Recording;
use autosim::runtime::{Model, RunSettings, Stepper, run};
use autosim_test_support::{floats, load, sample_error};
use serde_json::Value;

autosim::model!(file = "examples/models/quarter_car_bump_stop.sim");
autosim::model!(file = "examples/models/pendulum_end_stop.sim");

use pendulum_end_stop::PendulumEndStop;
use quarter_car_bump_stop::QuarterCarBumpStop;

/// A number of the reference file's `parameters`.
fn parameter(reference: &Value, name: &str) -> f64 {
    reference["parameters"][name].as_f64().unwrap()
}

/// The largest differences of the quarter car's switch times, of its state
/// at the switches and of its sampled states from the reference.
fn quarter_car_errors<S: Stepper<QuarterCarBumpStop>>(stepper: &mut S, step: f64) -> [f64; 3] {
    let reference = load("quarter-car-bump-stop");
    let mut car = QuarterCarBumpStop::new();
    let mut x = car.initial_state();
    let settings = RunSettings::new(0.0, 1.5, step, 0.1);
    let mut recording = Recording::new();
    run(&mut car, stepper, &mut x, &settings, &mut recording).unwrap();
    let switches = reference["switches"].as_array().unwrap();
    let events = recording.events();
    assert_eq!(events.len(), switches.len(), "{events:?}");
    let (mut times, mut at_switches): (f64, f64) = (0.0, 0.0);
    for (event, switch) in events.iter().zip(switches) {
        assert_eq!(event.name, switch["event"].as_str().unwrap());
        times = times.max((event.t - switch["t"].as_f64().unwrap()).abs());
        for (got, expected) in event.before.iter().zip(floats(&switch["state"])) {
            at_switches = at_switches.max((got - expected).abs());
        }
    }
    let samples = sample_error(&reference["samples"], recording.time(), |i, k| {
        recording.columns()[i].values[k]
    });
    [times, at_switches, samples]
}

#[test]
fn the_quarter_car_model_is_the_reference_scripts() {
    let reference = load("quarter-car-bump-stop");
    let p = quarter_car_bump_stop::Parameters::default();
    let ours = [
        ("ms", p.ms),
        ("mu", p.mu),
        ("ks", p.ks),
        ("cs", p.cs),
        ("kt", p.kt),
        ("Ls", p.Ls),
        ("Lt", p.Lt),
        ("g", p.g),
        ("kb", p.kb),
        ("gap", p.gap),
    ];
    for (name, value) in ours {
        assert_eq!(value, parameter(&reference, name), "{name}");
    }
    let car = QuarterCarBumpStop::new();
    assert_eq!(
        car.initial_state().to_vec(),
        floats(&reference["initial_state"])
    );
    assert_eq!(QuarterCarBumpStop::STATE_NAMES, ["zu", "zs", "vu", "vs"]);
    assert_eq!(QuarterCarBumpStop::DISCRETE_NAMES, ["contact"]);
}

#[test]
fn the_bump_stop_switches_where_the_exact_solution_does() {
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let [times, at_switches, samples] = quarter_car_errors(&mut dopri, 1e-3);
    println!(
        "Dormand-Prince 1e-12: switch times within {times:.1e} s, states at the switches \
         within {at_switches:.1e}, sampled states within {samples:.1e}"
    );
    assert!(
        times < 1e-11 && at_switches < 1e-10 && samples < 1e-10,
        "{times:e} {at_switches:e} {samples:e}"
    );
    // RK4 converges at its order through the switches: each halving of the
    // step divides the errors by about 16 (more than 10 asserted).
    let mut last: Option<[f64; 3]> = None;
    for h in [4e-4, 2e-4, 1e-4] {
        let errors = quarter_car_errors(&mut Rk4::new(), h);
        let [times, at_switches, samples] = errors;
        println!(
            "RK4 h = {h}: switch times within {times:.1e} s, states at the switches \
             within {at_switches:.1e}, sampled states within {samples:.1e}"
        );
        if let Some(previous) = last {
            for (a, b) in previous.iter().zip(errors) {
                assert!(a / b > 10.0, "h = {h}: {previous:?} then {errors:?}");
            }
        }
        last = Some(errors);
    }
    // At h = 1e-4 the errors are near 1e-11: the accuracy that step allows.
    assert!(last.unwrap().iter().all(|&e| e < 1e-10), "{last:?}");
}

/// The largest differences of the pendulum's first ten strike times and
/// strike rates from the closed form; checks the reset on the way.
fn pendulum_errors<S: Stepper<PendulumEndStop>>(stepper: &mut S, step: f64) -> (f64, f64) {
    let reference = load("pendulum-end-stop");
    let strikes = reference["strikes"].as_array().unwrap();
    let last = strikes.last().unwrap()["t"].as_f64().unwrap();
    let mut pendulum = PendulumEndStop::new();
    let mut x = pendulum.initial_state();
    let settings = RunSettings::new(0.0, last + 0.1, step, 0.1);
    let mut recording = Recording::new();
    run(&mut pendulum, stepper, &mut x, &settings, &mut recording).unwrap();
    let events = recording.events();
    assert_eq!(events.len(), strikes.len(), "{events:?}");
    let e = parameter(&reference, "e");
    let (mut times, mut rates): (f64, f64) = (0.0, 0.0);
    for (event, strike) in events.iter().zip(strikes) {
        assert_eq!(event.name, "strike");
        // The reset is the language's `u: -e*u`, exactly.
        assert_eq!(event.after[1], -e * event.before[1]);
        times = times.max((event.t - strike["t"].as_f64().unwrap()).abs());
        let before = strike["rate_before"].as_f64().unwrap();
        rates = rates.max((event.before[1] - before).abs());
    }
    (times, rates)
}

#[test]
fn the_pendulum_strikes_its_end_stop_at_the_closed_forms_times() {
    let reference = load("pendulum-end-stop");
    let p = pendulum_end_stop::Parameters::default();
    for (name, value) in [("m", p.m), ("L", p.L), ("g", p.g), ("s", p.s), ("e", p.e)] {
        assert_eq!(value, parameter(&reference, name), "{name}");
    }
    let pendulum = PendulumEndStop::new();
    assert_eq!(
        pendulum.initial_state().to_vec(),
        floats(&reference["initial_state"])
    );
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let (times, rates) = pendulum_errors(&mut dopri, 1e-3);
    println!(
        "Dormand-Prince 1e-12: 10 strike times within {times:.1e} s, rates within {rates:.1e} rad/s"
    );
    assert!(times < 1e-10 && rates < 1e-10, "{times:e} {rates:e}");
    // RK4 at fixed steps: fourth order (about 16x per halving).
    let mut last: Option<(f64, f64)> = None;
    for h in [4e-3, 2e-3, 1e-3] {
        let (times, rates) = pendulum_errors(&mut Rk4::new(), h);
        println!("RK4 h = {h}: strike times within {times:.1e} s, rates within {rates:.1e} rad/s");
        if let Some((t0, r0)) = last {
            assert!(t0 / times > 10.0 && r0 / rates > 10.0, "h = {h}");
        }
        last = Some((times, rates));
    }
    let (times, rates) = last.unwrap();
    // At h = 1e-3 the errors are near 1e-11: the accuracy that step allows.
    assert!(times < 1e-10 && rates < 1e-10, "{times:e} {rates:e}");
}
