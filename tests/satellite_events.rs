//! The paper's slew with its thrusters as events, written two ways: in the
//! model language (`examples/models/satellite_events.sim`: discrete modes
//! and `event` items) and as a Rust wrapper around the user-code model
//! (`examples/common/slew_events.rs`). The switching instants are located
//! on the integrator's interpolant, so the attitude at 15 s converges as
//! Dormand–Prince's tolerance tightens (the user-code thrusters define it
//! only to about 3e-5 rad), RK4 at a fixed step agrees with it, and the
//! two formulations agree with each other.

use autosim::runtime::integrate::{DopriSettings, DormandPrince, Rk4};
use autosim::runtime::io::Recording;
use autosim::runtime::{Model, RunSettings, RunSummary, Stepper, run};

mod full {
    autosim::model!(file = "examples/models/satellite.sim");
}

mod language {
    autosim::model!(file = "examples/models/satellite_events.sim");
}

#[allow(unused_macros, dead_code)]
#[path = "../examples/common/figure8.rs"]
mod figure8;
#[macro_use]
#[path = "../examples/common/slew_events.rs"]
mod slew_events;

use language::satellite_events::SatelliteEvents;
use slew_events::{EventSlew, Modes};

slew_events_externs!(full::satellite);

/// The commanded slew (the paper's SUBROUTINE CMD), the only user code of
/// the language form.
struct Command;

impl language::satellite_events::Externs for Command {
    fn cmd(&mut self, t: f64) -> [f64; 2] {
        figure8::Figure8::new().cmd(t)
    }
}

/// Flies the language's event slew to 15 s: the attitude q4, q5, q6 at
/// the end, the run's summary and its events.
fn fly_language<S: Stepper<SatelliteEvents<Command>>>(
    stepper: &mut S,
    step: f64,
) -> ([f64; 3], RunSummary<f64>, usize) {
    let mut model = SatelliteEvents::new(Command);
    let mut x = model.initial_state();
    let settings = RunSettings::new(0.0, 15.0, step, 15.0);
    let mut recording = Recording::new();
    let summary = run(&mut model, stepper, &mut x, &settings, &mut recording).unwrap();
    let at = |name: &str| {
        let k = SatelliteEvents::<Command>::STATE_NAMES
            .iter()
            .position(|n| *n == name);
        x[k.unwrap()]
    };
    (
        [at("q4"), at("q5"), at("q6")],
        summary,
        recording.events().len(),
    )
}

#[test]
fn the_language_event_slew_converges_and_matches_the_rust_form() {
    let dopri = |tol: f64| DormandPrince::new(DopriSettings::new(tol, tol)).unwrap();
    let runs: Vec<([f64; 3], RunSummary<f64>, usize)> = TOLERANCES
        .iter()
        .map(|&tol| fly_language(&mut dopri(tol), 1e-3))
        .collect();
    println!("language form (satellite_events.sim):");
    let tightest = converged(&TOLERANCES, &runs);
    assert!(runs.iter().all(|r| r.2 > 10));
    // The Rust wrapper, an independent formulation of the same controller
    // (its modes switched by hand-written Rust), lands on the same
    // attitude with the same events.
    let mut tight = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let (wrapper, _, wrapper_events) = fly(&mut tight, 1e-3);
    let d = difference(wrapper, tightest);
    println!("Rust wrapper at 1e-12: {wrapper_events} events, {d:.1e} rad from the language form");
    assert!(d < 1e-8, "{d:e}");
    assert_eq!(wrapper_events, runs[4].2);
    let (rk4, summary, events) = fly_language(&mut Rk4::new(), 2.5e-4);
    let d = difference(rk4, tightest);
    println!(
        "RK4 h = 2.5e-4: {} evaluations, {events} events, {d:.1e} rad from Dormand-Prince at 1e-12",
        summary.evaluations
    );
    assert!(d < 1e-8, "{d:e}");
}

/// Flies the event slew to 15 s: the attitude q4, q5, q6 at the end, the
/// run's summary and its events.
fn fly<S: Stepper<EventSlew<full::satellite::Satellite<Modes>>>>(
    stepper: &mut S,
    step: f64,
) -> ([f64; 3], RunSummary<f64>, usize) {
    let mut model = EventSlew::new(full::satellite::Satellite::new(Modes::default()));
    let mut x = model.initial_state();
    let settings = RunSettings::new(0.0, 15.0, step, 15.0);
    let mut recording = Recording::new();
    let summary = run(&mut model, stepper, &mut x, &settings, &mut recording).unwrap();
    ([x[3], x[4], x[5]], summary, recording.events().len())
}

fn difference(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
}

/// Dormand–Prince's tolerances of the convergence tables.
const TOLERANCES: [f64; 5] = [1e-6, 1e-8, 1e-10, 1e-11, 1e-12];

/// Prints the table of `runs` (one per tolerance): evaluations, events,
/// attitude against the tightest run; checks that 1e-10 is within 1e-8
/// rad of 1e-12; returns the tightest attitude.
fn converged(tolerances: &[f64], runs: &[([f64; 3], RunSummary<f64>, usize)]) -> [f64; 3] {
    let tightest = runs.last().unwrap().0;
    println!(
        "| tolerance | evaluations | events | attitude at 15 s: difference from 1e-12 [rad] |"
    );
    println!("| ---: | ---: | ---: | ---: |");
    for (tol, (attitude, summary, events)) in tolerances.iter().zip(runs) {
        let d = difference(*attitude, tightest);
        println!(
            "| {tol:.0e} | {} | {events} | {d:.1e} |",
            summary.evaluations
        );
    }
    let at_1e10 = difference(runs[2].0, tightest);
    assert!(at_1e10 < 1e-8, "1e-10 against 1e-12: {at_1e10:e}");
    tightest
}

#[test]
fn the_event_slew_converges_as_the_tolerance_tightens() {
    let dopri = |tol: f64| DormandPrince::new(DopriSettings::new(tol, tol)).unwrap();
    let runs: Vec<([f64; 3], RunSummary<f64>, usize)> = TOLERANCES
        .iter()
        .map(|&tol| fly(&mut dopri(tol), 1e-3))
        .collect();
    let tightest = converged(&TOLERANCES, &runs);
    // The thrusters fire: the events are real switching, not a quiet slew.
    assert!(
        runs.iter().all(|r| r.2 > 10),
        "{:?}",
        runs.iter().map(|r| r.2).collect::<Vec<_>>()
    );
    // RK4 at fixed steps converges to the same attitude.
    for h in [1e-3, 2.5e-4] {
        let (attitude, summary, events) = fly(&mut Rk4::new(), h);
        let d = difference(attitude, tightest);
        println!(
            "RK4 h = {h}: {} evaluations, {events} events, {d:.1e} rad from Dormand-Prince at 1e-12",
            summary.evaluations
        );
    }
    let (rk4, ..) = fly(&mut Rk4::new(), 2.5e-4);
    assert!(difference(rk4, tightest) < 1e-8);
}
