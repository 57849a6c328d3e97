//! A quarter car hitting its bump stop: the stop's spring switched on and
//! off by events (a discrete mode), checked against the exact solution of
//! each linear mode with the switches located by bisection in 40-digit
//! arithmetic (`tests/reference/gen/quarter_car_bump_stop.py`, which
//! states the model).

use autosim_runtime::integrate::{DopriSettings, DormandPrince, Rk4};
use autosim_runtime::io::Recording;
use autosim_runtime::{EventIndicator, EventOutcome, Model, ModelError, RunSettings, Stepper, run};
use autosim_test_support::{floats, load, sample_error};
use serde_json::Value;

/// The quarter car of the reference script, its parameters read from the
/// reference file.
struct QuarterCar {
    ms: f64,
    mu: f64,
    ks: f64,
    cs: f64,
    kt: f64,
    ls: f64,
    lt: f64,
    g: f64,
    kb: f64,
    gap: f64,
    contact: f64,
}

impl QuarterCar {
    fn from(reference: &Value) -> Self {
        let p = |name: &str| reference["parameters"][name].as_f64().unwrap();
        Self {
            ms: p("ms"),
            mu: p("mu"),
            ks: p("ks"),
            cs: p("cs"),
            kt: p("kt"),
            ls: p("Ls"),
            lt: p("Lt"),
            g: p("g"),
            kb: p("kb"),
            gap: p("gap"),
            contact: 0.0,
        }
    }

    /// Compression beyond the bump stop's gap.
    fn past_the_gap(&self, x: &[f64; 4]) -> f64 {
        self.ls - (x[1] - x[0]) - self.gap
    }
}

impl Model for QuarterCar {
    autosim_test_support::model_header!(f64, "QuarterCarBumpStop", states: ["zu" in "m", "zs" in "m", "vu" in "m/s", "vs" in "m/s"], outputs: 0);
    const EVENT_INDICATORS: &'static [EventIndicator] = &[
        EventIndicator::rising("bump"),
        EventIndicator::falling("rebound"),
    ];
    const DISCRETE_NAMES: &'static [&'static str] = &["contact"];
    const DISCRETE_UNITS: &'static [&'static str] = &["1"];

    fn derivatives(&mut self, _t: f64, x: &[f64; 4], dx: &mut [f64; 4]) -> Result<(), ModelError> {
        let [zu, zs, vu, vs] = *x;
        let stop = self.contact * self.kb * self.past_the_gap(x);
        let suspension = self.ks * (self.ls - (zs - zu)) - self.cs * (vs - vu) + stop;
        dx[0] = vu;
        dx[1] = vs;
        dx[2] = (-self.kt * (zu - self.lt) - suspension) / self.mu - self.g;
        dx[3] = suspension / self.ms - self.g;
        Ok(())
    }
    fn event_indicators(&mut self, _t: f64, x: &[f64; 4], g: &mut [f64]) -> Result<(), ModelError> {
        let c = self.past_the_gap(x);
        g[0] = c;
        g[1] = c;
        Ok(())
    }
    fn event(
        &mut self,
        index: usize,
        _t: f64,
        _x: &mut [f64; 4],
    ) -> Result<EventOutcome, ModelError> {
        self.contact = if index == 0 { 1.0 } else { 0.0 };
        Ok(EventOutcome::Continue)
    }
    fn discrete_values(&self, values: &mut [f64]) {
        values[0] = self.contact;
    }
}

/// The largest differences of the switch times and of the sampled states
/// from the reference.
fn errors<S: Stepper<QuarterCar>>(stepper: &mut S, step: f64) -> (f64, f64) {
    let reference = load("quarter-car-bump-stop");
    let mut car = QuarterCar::from(&reference);
    let x0 = floats(&reference["initial_state"]);
    let mut x = [x0[0], x0[1], x0[2], x0[3]];
    let settings = RunSettings::new(0.0, 1.5, step, 0.1);
    let mut recording = Recording::new();
    run(&mut car, stepper, &mut x, &settings, &mut recording).unwrap();
    let switches = reference["switches"].as_array().unwrap();
    let events = recording.events();
    assert_eq!(events.len(), switches.len(), "{events:?}");
    let mut time_error: f64 = 0.0;
    for (event, switch) in events.iter().zip(switches) {
        assert_eq!(event.name, switch["event"].as_str().unwrap());
        time_error = time_error.max((event.t - switch["t"].as_f64().unwrap()).abs());
    }
    let state_error = sample_error(&reference["samples"], recording.time(), |i, k| {
        recording.columns()[i].values[k]
    });
    (time_error, state_error)
}

#[test]
fn the_bump_stop_switches_where_the_exact_solution_does() {
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let (times, states) = errors(&mut dopri, 1e-3);
    println!("Dormand-Prince 1e-12: switch times within {times:.1e} s, states within {states:.1e}");
    assert!(times < 1e-10 && states < 1e-9, "{times:e} {states:e}");
    // RK4 converges at its order through the switches (errors fall ~16x
    // per halving of h).
    let mut last = None;
    for h in [4e-4, 2e-4, 1e-4] {
        let (times, states) = errors(&mut Rk4::new(), h);
        println!("RK4 h = {h}: switch times within {times:.1e} s, states within {states:.1e}");
        if let Some((t0, s0)) = last {
            let (rt, rs) = (t0 / times, s0 / states);
            assert!(rt > 10.0 && rs > 10.0, "ratios {rt} {rs}");
        }
        last = Some((times, states));
    }
    let (times, states) = last.unwrap();
    assert!(times < 1e-8 && states < 1e-8, "{times:e} {states:e}");
}
