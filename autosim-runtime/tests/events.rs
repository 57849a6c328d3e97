//! Events located by the run driver, on hand-written models with known
//! answers: a bouncing ball (analytic bounce times and apex heights), a
//! crossing hidden between a step's end points, several events in one
//! step, a terminal event, a thermostat with a dead band, and Zeno.

mod common;

use autosim_runtime::integrate::{
    AbmOrder, AdamsBashforthMoulton, DopriSettings, DormandPrince, Euler, Heun, Rk4, Sdirk3,
    SdirkSettings,
};
use autosim_runtime::io::{CsvWriter, Recording};
use autosim_runtime::{
    EventIndicator, EventOutcome, EventSettings, IntegrationError, Model, ModelError, RunError,
    RunSettings, Stepper, run, run_at, run_sampled,
};
use common::{Ball, Oscillator};

/// Runs `model` from its initial state over `[0, stop]` keeping everything.
fn record<M: Model<Float = f64>, S: Stepper<M> + ?Sized>(
    model: &mut M,
    stepper: &mut S,
    settings: &RunSettings<f64>,
) -> (
    Result<autosim_runtime::RunSummary<f64>, RunError<std::convert::Infallible>>,
    Recording<M>,
) {
    let mut recording = Recording::new();
    let mut x = model.initial_state();
    let result = run(model, stepper, &mut x, settings, &mut recording);
    (result, recording)
}

/// The bounce times and the apex heights a run recorded.
fn bounces_and_apexes(recording: &Recording<Ball>) -> (Vec<f64>, Vec<f64>) {
    let bounces = recording.events().iter().filter(|e| e.name == "bounce");
    let apexes = recording.events().iter().filter(|e| e.name == "apex");
    (
        bounces.map(|e| e.t).collect(),
        apexes.map(|e| e.before[0]).collect(),
    )
}

/// The largest difference of the first ten bounce times and apex heights
/// from the analytic ones.
fn ball_error<S: Stepper<Ball>>(stepper: &mut S, step: f64) -> f64 {
    let mut ball = Ball::new(0.8, 0.0);
    let settings = RunSettings::new(0.0, 3.8, step, 0.1);
    let (result, recording) = record(&mut ball, stepper, &settings);
    let summary = result.unwrap();
    let (bounces, apexes) = bounces_and_apexes(&recording);
    assert!(bounces.len() >= 10 && apexes.len() >= 10, "{bounces:?}");
    assert_eq!(summary.events as usize, recording.events().len());
    let mut worst: f64 = 0.0;
    for n in 1..=10u32 {
        let (t, h) = ball.exact_bounce(n);
        let i = n as usize - 1;
        worst = worst.max((bounces[i] - t).abs()).max((apexes[i] - h).abs());
    }
    worst
}

#[test]
fn bouncing_ball_with_dormand_prince_matches_the_analytic_bounces() {
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let worst = ball_error(&mut dopri, 1e-3);
    println!("Dormand-Prince 1e-12: first 10 bounce times and apex heights within {worst:.1e}");
    assert!(worst < 1e-10, "{worst:e}");
}

#[test]
fn bouncing_ball_with_rk4_at_a_fixed_step_matches_the_analytic_bounces() {
    // Free fall is a quadratic in time: RK4 and the Hermite cubic the
    // driver locates on are exact for it, so at any step the bounces are
    // as accurate as rounding allows (the location's own tolerance).
    for step in [0.1, 0.01, 0.001] {
        let worst = ball_error(&mut Rk4::new(), step);
        println!("RK4 h = {step}: first 10 bounce times and apex heights within {worst:.1e}");
        assert!(worst < 1e-10, "h = {step}: {worst:e}");
    }
}

#[test]
fn every_stepper_locates_the_bounces_to_its_own_accuracy() {
    // Every method of order two or more is exact for the ball's quadratic
    // motion, so locates its bounces to rounding; Euler (order one) is
    // off by about h·g per second of flight and drifts (5e-2 at h = 1 ms).
    let h = 1e-3;
    let abm = |order| AdamsBashforthMoulton::new(order);
    let sdirk = || Sdirk3::<Ball, 2, _>::new(SdirkSettings::default());
    let cases = [
        ("Euler", 0.1, ball_error(&mut Euler::new(), h)),
        ("Heun", 1e-10, ball_error(&mut Heun::new(), h)),
        ("ABM4", 1e-10, ball_error(&mut abm(AbmOrder::Four), h)),
        ("ABM2", 1e-10, ball_error(&mut abm(AbmOrder::Two), h)),
        ("SDIRK3", 1e-10, ball_error(&mut sdirk(), h)),
    ];
    for (name, bound, worst) in cases {
        println!("{name} h = {h}: bounces within {worst:.1e}");
        assert!(worst < bound, "{name}: {worst:e}");
    }
}

/// x = cos t with the event `near_peak` when x rises through 0.99.
struct NearPeak(Oscillator);

impl Model for NearPeak {
    autosim_test_support::model_header!(f64, "NearPeak", states: ["x" in "m", "v" in "m/s"], outputs: 0);
    const EVENT_INDICATORS: &'static [EventIndicator] = &[EventIndicator::rising("near_peak")];
    fn derivatives(&mut self, t: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        self.0.derivatives(t, x, dx)
    }
    fn event_indicators(&mut self, _t: f64, x: &[f64; 2], g: &mut [f64]) -> Result<(), ModelError> {
        g[0] = x[0] - THRESHOLD;
        Ok(())
    }
    fn initial_state(&self) -> [f64; 2] {
        [1.0, 0.0]
    }
}

const THRESHOLD: f64 = 0.99;

/// The times of the event a run found, with `samples` interior points.
fn near_peak_times<S: Stepper<NearPeak>>(stepper: &mut S, step: f64, samples: u32) -> Vec<f64> {
    let mut model = NearPeak(Oscillator::default());
    let events = EventSettings {
        interior_samples: samples,
        ..EventSettings::default()
    };
    let settings = RunSettings::new(0.0, 7.0, step, 7.0).with_events(events);
    let (result, recording) = record(&mut model, stepper, &settings);
    result.unwrap();
    recording.events().iter().map(|e| e.t).collect()
}

#[test]
fn a_crossing_between_the_end_points_of_a_step_is_found_on_the_interpolant() {
    // cos t rises through 0.99 at 2π − acos(0.99) ≈ 6.1417 and falls back
    // at 2π + acos(0.99) ≈ 6.4248: both inside the RK4 step [6.0, 6.5],
    // whose end points (0.960, 0.977) are below the threshold.
    let exact = 2.0 * std::f64::consts::PI - THRESHOLD.acos();
    assert!(near_peak_times(&mut Rk4::new(), 0.5, 0).is_empty());
    let found = near_peak_times(&mut Rk4::new(), 0.5, 4);
    assert_eq!(found.len(), 1, "{found:?}");
    // As accurate as RK4 at h = 0.5 is: its own error in x by t = 6 is
    // about 2e-3, which at the crossing's slope (sin 0.14 = 0.14) moves
    // the instant by about 1.5e-2.
    assert!((found[0] - exact).abs() < 3e-2, "{found:?} against {exact}");
    // Dormand–Prince at tolerance 1e-5 takes steps of about 0.5 s here
    // (its own continuous extension): hidden at the end points, found at
    // the samples, the instant as accurate as the tolerance allows where
    // the indicator's slope is 0.14 (1e-5/0.14 ≈ 7e-5).
    let dopri = || {
        let settings = DopriSettings {
            max_step: 0.5,
            ..DopriSettings::new(1e-5, 1e-5)
        };
        DormandPrince::new(settings).unwrap()
    };
    let hidden = near_peak_times(&mut dopri(), 0.5, 0);
    let found = near_peak_times(&mut dopri(), 0.5, 4);
    assert!(hidden.is_empty(), "the end points show it: {hidden:?}");
    assert_eq!(found.len(), 1, "{found:?}");
    assert!((found[0] - exact).abs() < 3e-4, "{found:?} against {exact}");
}

#[test]
fn the_instant_converges_at_the_fixed_steps_order() {
    // x = cos t + 0.49 rises through 0.99 where cos t = 0.5, at
    // t = 2π − acos(0.5): RK4 with the Hermite interpolant, the error in
    // the instant falls as h⁴ (ratios of 16 when h halves).
    let exact = 2.0 * std::f64::consts::PI - 0.5f64.acos();
    let error = |h: f64| {
        let settings = RunSettings::new(0.0, 6.0, h, 6.0);
        let (result, recording) = record(&mut ShiftedPeak, &mut Rk4::new(), &settings);
        result.unwrap();
        (recording.events()[0].t - exact).abs()
    };
    let errors: Vec<f64> = [0.2, 0.1, 0.05].into_iter().map(error).collect();
    println!("RK4 event instant errors at h = 0.2, 0.1, 0.05: {errors:?}");
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((10.0..24.0).contains(&ratio), "{errors:?}");
    }
}

/// x = cos t + 0.49 (x'' = −(x − 0.49)), crossing 0.99 where cos t = 0.5.
struct ShiftedPeak;

impl Model for ShiftedPeak {
    autosim_test_support::model_header!(f64, "ShiftedPeak", states: ["x" in "m", "v" in "m/s"], outputs: 0);
    const EVENT_INDICATORS: &'static [EventIndicator] = NearPeak::EVENT_INDICATORS;
    fn derivatives(&mut self, _t: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        dx[0] = x[1];
        dx[1] = -(x[0] - 0.49);
        Ok(())
    }
    fn event_indicators(&mut self, _t: f64, x: &[f64; 2], g: &mut [f64]) -> Result<(), ModelError> {
        g[0] = x[0] - THRESHOLD;
        Ok(())
    }
    fn initial_state(&self) -> [f64; 2] {
        [1.49, 0.0]
    }
}

/// A clock x' = 1 with events at x = 0.3 (`early`) and x = 0.7 (`late`)
/// that each add 10 to a counter state, and a terminal event at x = 2.5.
struct Clock;

impl Model for Clock {
    autosim_test_support::model_header!(f64, "Clock", states: ["x" in "s", "count" in "1"], outputs: 0);
    const EVENT_INDICATORS: &'static [EventIndicator] = &[
        EventIndicator::rising("late"),
        EventIndicator::either("early"),
        EventIndicator::rising("end"),
    ];
    fn derivatives(&mut self, _t: f64, _x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        dx[0] = 1.0;
        dx[1] = 0.0;
        Ok(())
    }
    fn event_indicators(&mut self, _t: f64, x: &[f64; 2], g: &mut [f64]) -> Result<(), ModelError> {
        g[0] = x[0] - 0.7;
        g[1] = x[0] - 0.3;
        g[2] = x[0] - 2.5;
        Ok(())
    }
    fn event(
        &mut self,
        index: usize,
        _t: f64,
        x: &mut [f64; 2],
    ) -> Result<EventOutcome, ModelError> {
        if index == 2 {
            return Ok(EventOutcome::Stop);
        }
        x[1] += 10.0;
        Ok(EventOutcome::Continue)
    }
}

#[test]
fn several_events_in_one_step_fire_in_time_order_and_a_terminal_event_stops_the_run() {
    for stepper in 0..2 {
        let settings = RunSettings::new(0.0, 5.0, 1.0, 1.0);
        let mut rk4 = Rk4::new();
        let mut dopri = DormandPrince::with_tolerances(1e-10, 1e-10).unwrap();
        let (result, recording) = if stepper == 0 {
            record(&mut Clock, &mut rk4, &settings)
        } else {
            record(&mut Clock, &mut dopri, &settings)
        };
        let summary = result.unwrap();
        let events: Vec<(&str, f64, f64)> = recording
            .events()
            .iter()
            .map(|e| (e.name, e.t, e.after[1]))
            .collect();
        assert_eq!(events.len(), 3, "{events:?}");
        let expected = [
            ("early", 0.3, 10.0),
            ("late", 0.7, 20.0),
            ("end", 2.5, 20.0),
        ];
        for ((name, t, count), (n, te, c)) in events.iter().zip(expected) {
            assert_eq!((*name, *count), (n, c));
            assert!((t - te).abs() < 1e-12, "{name} at {t}");
        }
        assert_eq!(summary.terminal_event, Some(2));
        assert_eq!(summary.events, 3);
        assert!((summary.end_time - 2.5).abs() < 1e-12, "{summary:?}");
        // The last output is at the terminal event.
        assert!((recording.time().last().unwrap() - 2.5).abs() < 1e-12);
    }
}

#[test]
fn a_fixed_step_method_returns_to_its_grid_after_an_event() {
    // Outputs every 1 s with steps of 1 s: the event at 0.3 cuts the first
    // step; the outputs stay at whole seconds.
    let settings = RunSettings::new(0.0, 2.0, 1.0, 1.0);
    let (result, recording) = record(&mut Clock, &mut Rk4::new(), &settings);
    let summary = result.unwrap();
    let outputs: Vec<f64> = recording
        .time()
        .iter()
        .copied()
        .filter(|t| t.fract() == 0.0)
        .collect();
    assert_eq!(outputs, [0.0, 1.0, 2.0]);
    // Steps: [0, 1] cut at 0.3, [0.3, 1] cut at 0.7, [0.7, 1], [1, 2].
    assert_eq!(summary.steps, 4);
}

#[test]
fn zeno_chattering_ends_with_a_typed_error_naming_the_event() {
    // Restitution 0.9 and no minimum speed: the bounces accumulate at
    // t ≈ 8.6 s (0.45 s + 0.9·0.9 s/0.1).
    let settings = RunSettings::new(0.0, 20.0, 1e-3, 0.1);
    let dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let steppers: [Box<dyn Stepper<Ball>>; 2] = [Box::new(Rk4::new()), Box::new(dopri)];
    for mut stepper in steppers {
        let mut ball = Ball::new(0.9, 0.0);
        let (result, recording) = record(&mut ball, stepper.as_mut(), &settings);
        match result {
            Err(RunError::Integration(IntegrationError::Zeno {
                t, name, events, ..
            })) => {
                println!(
                    "{}: Zeno at t = {t} after {events} close events ({name})",
                    stepper.name()
                );
                assert_eq!(name, "bounce");
                assert!(t > 7.0 && t < 8.7, "t = {t}");
            }
            other => panic!("{}: {other:?}", stepper.name()),
        }
        assert!(recording.events().len() > 100);
    }
    // The documented fix: a minimum rebound speed (the ball then rests).
    let mut ball = Ball::new(0.9, 0.05);
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let (result, recording) = record(&mut ball, &mut dopri, &settings);
    let summary = result.unwrap();
    assert_eq!(ball.resting, 1.0);
    assert!(summary.events > 40, "{summary:?}");
    let last = recording
        .column("h")
        .unwrap()
        .values
        .last()
        .copied()
        .unwrap();
    assert!(last.abs() < 1e-9, "at rest on the floor: {last}");
}

#[test]
fn discrete_variables_and_events_are_written_to_the_csv() {
    let mut ball = Ball::new(0.9, 0.5);
    let mut x = ball.initial_state();
    let settings = RunSettings::new(0.0, 10.0, 1e-2, 1.0);
    let mut csv = CsvWriter::<Ball, _>::new(Vec::new()).unwrap();
    let summary = run(&mut ball, &mut Rk4::new(), &mut x, &settings, &mut csv).unwrap();
    let text = String::from_utf8(csv.into_inner().unwrap()).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("time [s],h [m],v [m/s],resting [1],energy [J/kg],event")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let event_rows: Vec<&Vec<&str>> = rows.iter().filter(|r| !r[5].is_empty()).collect();
    assert_eq!(event_rows.len() as u64, 2 * summary.events);
    // The first bounce: before and after at the same instant, v reversed.
    let (before, after) = (event_rows[0], event_rows[1]);
    assert_eq!((before[5], after[5]), ("bounce", "bounce"));
    assert_eq!(before[0], after[0]);
    let v = |r: &Vec<&str>| r[2].parse::<f64>().unwrap();
    assert!((v(after) + 0.9 * v(before)).abs() < 1e-12);
    // The ball comes to rest: the last output row has resting = 1.
    assert_eq!(rows.last().unwrap()[3], "1.0");
}

#[test]
fn discrete_variables_are_saved_and_restored_with_the_state() {
    let mut ball = Ball::new(0.5, 2.0);
    let settings = RunSettings::new(0.0, 3.0, 1e-2, 1.0);
    let mut x = ball.initial_state();
    run(
        &mut ball,
        &mut Rk4::new(),
        &mut x,
        &settings,
        &mut |_, _: &[f64; 2], _: &[f64; 1]| {},
    )
    .unwrap();
    let mut saved = [0.0];
    ball.discrete_values(&mut saved);
    assert_eq!(saved, [1.0]);
    let mut fresh = Ball::new(0.5, 2.0);
    fresh.set_discrete_values(&saved);
    let mut dx = [0.0; 2];
    fresh.derivatives(3.0, &x, &mut dx).unwrap();
    assert_eq!(dx, [0.0, 0.0], "the restored mode freezes the ball");
}

/// A room heated by a thermostat with a dead band: T' = (Ta − T)/τ + P·on.
/// The heater switches on when T falls through `low` and off when it
/// rises through `high` (two thresholds: hysteresis).
struct Thermostat {
    on: f64,
}

const TAU: f64 = 2.0;
const AMBIENT: f64 = 10.0;
const POWER: f64 = 8.0;
const LOW: f64 = 19.0;
const HIGH: f64 = 21.0;

impl Model for Thermostat {
    autosim_test_support::model_header!(f64, "Thermostat", states: ["T" in "degC"], outputs: 0);
    const EVENT_INDICATORS: &'static [EventIndicator] = &[
        EventIndicator::falling("heater_on"),
        EventIndicator::rising("heater_off"),
    ];
    const DISCRETE_NAMES: &'static [&'static str] = &["on"];
    const DISCRETE_UNITS: &'static [&'static str] = &["1"];
    fn derivatives(&mut self, _t: f64, x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
        dx[0] = (AMBIENT - x[0]) / TAU + POWER * self.on;
        Ok(())
    }
    fn event_indicators(&mut self, _t: f64, x: &[f64; 1], g: &mut [f64]) -> Result<(), ModelError> {
        g[0] = x[0] - LOW;
        g[1] = x[0] - HIGH;
        Ok(())
    }
    fn event(
        &mut self,
        index: usize,
        _t: f64,
        _x: &mut [f64; 1],
    ) -> Result<EventOutcome, ModelError> {
        self.on = if index == 0 { 1.0 } else { 0.0 };
        Ok(EventOutcome::Continue)
    }
    fn discrete_values(&self, values: &mut [f64]) {
        values[0] = self.on;
    }
    fn initial_state(&self) -> [f64; 1] {
        [HIGH]
    }
}

#[test]
fn a_thermostat_with_a_dead_band_switches_at_the_analytic_times() {
    // Off from 21: T = Ta + (21 − Ta)e^(−t/τ) reaches 19 after τ·ln(11/9).
    // On: T → Ta + Pτ = 26; from 19 to 21 takes τ·ln(7/5). Then it cycles.
    let off = TAU * (11.0f64 / 9.0).ln();
    let on = TAU * (7.0f64 / 5.0).ln();
    let mut model = Thermostat { on: 0.0 };
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let settings = RunSettings::new(0.0, 10.0, 1e-2, 1.0);
    let (result, recording) = record(&mut model, &mut dopri, &settings);
    result.unwrap();
    let events = recording.events();
    assert!(events.len() >= 8, "{events:?}");
    let mut t = 0.0;
    for (k, event) in events.iter().enumerate() {
        let (name, duration) = if k % 2 == 0 {
            ("heater_on", off)
        } else {
            ("heater_off", on)
        };
        t += duration;
        assert_eq!(event.name, name);
        assert!(
            (event.t - t).abs() < 1e-10,
            "event {k}: {} against {t}",
            event.t
        );
    }
}

/// A pendulum, linearized (θ'' = −ω²θ), with an end stop at θ = −s that
/// reverses its rate with restitution e: event `stop` (θ + s falling),
/// action θ' := −e·θ'.
struct EndStop {
    omega: f64,
    s: f64,
    e: f64,
}

impl Model for EndStop {
    autosim_test_support::model_header!(f64, "EndStop", states: ["theta" in "rad", "rate" in "rad/s"], outputs: 0);
    const EVENT_INDICATORS: &'static [EventIndicator] = &[EventIndicator::falling("stop")];
    fn derivatives(&mut self, _t: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        dx[0] = x[1];
        dx[1] = -self.omega * self.omega * x[0];
        Ok(())
    }
    fn event_indicators(&mut self, _t: f64, x: &[f64; 2], g: &mut [f64]) -> Result<(), ModelError> {
        g[0] = x[0] + self.s;
        Ok(())
    }
    fn event(
        &mut self,
        _index: usize,
        _t: f64,
        x: &mut [f64; 2],
    ) -> Result<EventOutcome, ModelError> {
        x[1] *= -self.e;
        Ok(EventOutcome::Continue)
    }
    fn initial_state(&self) -> [f64; 2] {
        [1.0, 0.0]
    }
}

#[test]
fn a_pendulum_against_an_end_stop_strikes_at_the_analytic_times() {
    // Released at θ = 1 from rest: the first strike where cos ωt = −s, at
    // rate ω√(1 − s²). After a strike at rate v (reversed: e·v, away from
    // the stop) θ = −s cos ωτ + (v/ω) sin ωτ returns to −s after
    // τ = 2·atan2(v/ω, −s)/ω, at rate −v.
    let (omega, s, e): (f64, f64, f64) = (2.0 * std::f64::consts::PI, 0.2, 0.7);
    let mut t = (-s).acos() / omega;
    let mut v = omega * (1.0 - s * s).sqrt();
    let mut exact = Vec::new();
    for _ in 0..10 {
        exact.push((t, v));
        v *= e;
        t += 2.0 * (v / omega).atan2(-s) / omega;
    }
    let mut model = EndStop { omega, s, e };
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let settings = RunSettings::new(0.0, exact[9].0 + 0.1, 1e-3, 0.1);
    let (result, recording) = record(&mut model, &mut dopri, &settings);
    result.unwrap();
    let strikes = recording.events();
    assert_eq!(strikes.len(), 10);
    let mut worst: f64 = 0.0;
    for (strike, (t, v)) in strikes.iter().zip(&exact) {
        worst = worst
            .max((strike.t - t).abs())
            .max((strike.before[1] + v).abs());
    }
    println!("end stop, Dormand-Prince 1e-12: 10 strike times and rates within {worst:.1e}");
    assert!(worst < 1e-9, "{worst:e}");
}

/// A held input `level` (set by a sampled controller) and the event
/// `threshold` when it rises through 0.5, which stops the run.
#[derive(Default)]
struct Level {
    level: f64,
}

impl Model for Level {
    autosim_test_support::model_header!(f64, "Level", states: ["x" in "1"], outputs: 0);
    const INPUT_NAMES: &'static [&'static str] = &["level"];
    const INPUT_UNITS: &'static [&'static str] = &["1"];
    const EVENT_INDICATORS: &'static [EventIndicator] = &[EventIndicator::rising("threshold")];
    fn derivatives(&mut self, _t: f64, _x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
        dx[0] = self.level;
        Ok(())
    }
    fn event_indicators(
        &mut self,
        _t: f64,
        _x: &[f64; 1],
        g: &mut [f64],
    ) -> Result<(), ModelError> {
        g[0] = self.level - 0.5;
        Ok(())
    }
    fn event(
        &mut self,
        _index: usize,
        _t: f64,
        _x: &mut [f64; 1],
    ) -> Result<EventOutcome, ModelError> {
        Ok(EventOutcome::Stop)
    }
    fn input_values(&self, values: &mut [f64]) {
        values[0] = self.level;
    }
    fn set_input_values(&mut self, values: &[f64]) {
        self.level = values[0];
    }
}

#[test]
fn an_input_set_by_a_sampled_controller_fires_its_event_at_the_sample() {
    // The controller raises the level by 0.2 at every sample (0, 0.3,
    // 0.6, ...): it passes 0.5 at the sample t = 0.6 (0.4 → 0.6), where the
    // terminal event stops the run; x integrates the held levels 0.2, 0.4
    // over 0.3 s each.
    let mut model = Level::default();
    let mut x = [0.0];
    let settings = RunSettings::new(0.0, 5.0, 0.1, 1.0);
    let mut recording = Recording::new();
    let mut controller = |_t: f64, _x: &[f64; 1], _y: &[f64; 0], inputs: &mut [f64]| {
        inputs[0] += 0.2;
    };
    let summary = run_sampled(
        &mut model,
        &mut Rk4::new(),
        &mut x,
        &settings,
        0.3,
        &mut controller,
        &mut recording,
    )
    .unwrap();
    assert_eq!(summary.terminal_event, Some(0));
    assert!((summary.end_time - 0.6).abs() < 1e-12, "{summary:?}");
    assert_eq!(recording.events().len(), 1);
    assert!((recording.events()[0].t - 0.6).abs() < 1e-12);
    assert!((x[0] - 0.18).abs() < 1e-12, "{x:?}");
    assert!((recording.time().last().unwrap() - 0.6).abs() < 1e-12);
}

#[test]
fn run_at_stops_at_a_terminal_event_with_an_output_there() {
    let settings = RunSettings::new(0.0, 5.0, 0.25, 1.0);
    let mut recording = Recording::new();
    let mut x = Clock.initial_state();
    let times = [0.0, 1.0, 2.0, 3.0, 4.0];
    let summary = run_at(
        &mut Clock,
        &mut Rk4::new(),
        &mut x,
        &settings,
        &times,
        &mut recording,
    )
    .unwrap();
    assert_eq!(summary.terminal_event, Some(2));
    let outputs: Vec<f64> = recording.time().to_vec();
    // 0, 1, 2 as asked, the rows of the three events, and 2.5 at the end.
    assert!((outputs.last().unwrap() - 2.5).abs() < 1e-12, "{outputs:?}");
    assert_eq!(summary.outputs, 4, "{outputs:?}");
    assert_eq!(x[1], 20.0);
}

#[test]
fn events_of_an_f32_model_are_located_to_f32_precision() {
    let exact = Ball::new(0.8, 0.0);
    let mut model = Ball::in_f32(0.8);
    let mut x = model.initial_state();
    let settings = RunSettings::new(0.0f32, 3.8, 0.01, 0.1);
    let mut bounces = Vec::new();
    let mut observer = BounceTimes(&mut bounces);
    run(
        &mut model,
        &mut Rk4::new(),
        &mut x,
        &settings,
        &mut observer,
    )
    .unwrap();
    assert!(bounces.len() >= 10, "{bounces:?}");
    for (n, t) in (1..=10).zip(&bounces) {
        let (exact_t, _) = exact.exact_bounce(n);
        assert!(
            (f64::from(*t) - exact_t).abs() < 2e-5,
            "bounce {n}: {t} against {exact_t}"
        );
    }
}

/// Keeps the times of the `bounce` events.
struct BounceTimes<'a>(&'a mut Vec<f32>);

impl autosim_runtime::Observer<Ball<f32>> for BounceTimes<'_> {
    type Error = std::convert::Infallible;
    fn observe(&mut self, _t: f32, _x: &[f32; 2], _y: &[f32; 1]) -> Result<(), Self::Error> {
        Ok(())
    }
    fn observe_event(
        &mut self,
        event: &autosim_runtime::EventRecord<'_, Ball<f32>>,
    ) -> Result<(), Self::Error> {
        if event.name == "bounce" {
            self.0.push(event.t);
        }
        Ok(())
    }
}
