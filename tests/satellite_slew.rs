//! The paper's slew maneuver (Sayers 1991, Figures 8 and 9): the full
//! satellite model with the Figure 8 user code (CMD and the stateful THRUST),
//! integrated with classic RK4 at h = 1 ms for 15 s, reproduces the
//! independent reference trajectory `tests/reference/satellite-slew.json`.
//!
//! The thrusters are a bang-bang element whose state changes inside the
//! derivative evaluations, so the trajectory depends on the integrator's
//! stage times and on the order of the user calls; both are asserted here:
//! stage times t_n, t_n + h/2, t_n + h/2, t_n + h with t_n = n h, and in
//! every evaluation `cmd` first, then `thrust` for axes 1, 2, 3.

use autosim::runtime::integrate::Rk4;
use autosim::runtime::{Model, Stepper};
use autosim_test_support::{floats, load, worst_of};

mod model {
    autosim::model!(file = "examples/models/satellite.sim");
}

use model::satellite::{Externs, Satellite};

// The paper's Figure 8 (CMD and THRUST), as the examples fly it.
#[allow(unused_macros)]
#[path = "../examples/common/figure8.rs"]
mod figure8;

/// The paper's Figure 8 user code, with every call checked against the
/// expected calling sequence.
struct Checked {
    figure8: figure8::Figure8,
    /// The call expected next within an evaluation: 0 = `cmd`, 1..=3 = `thrust(axis)`.
    next: usize,
    /// Times of the `cmd` calls of the current step (four per RK4 step).
    stage_times: Vec<f64>,
    evaluations: u64,
}

impl Checked {
    fn new() -> Self {
        Checked {
            figure8: figure8::Figure8::new(),
            next: 0,
            stage_times: Vec::with_capacity(4),
            evaluations: 0,
        }
    }
}

impl Externs for Checked {
    fn cmd(&mut self, t: f64) -> [f64; 2] {
        assert_eq!(
            self.next, 0,
            "cmd called before thrust(3) of the last evaluation at t = {t}"
        );
        self.next = 1;
        self.evaluations += 1;
        self.stage_times.push(t);
        self.figure8.cmd(t)
    }

    fn thrust(&mut self, t: f64, axis: f64, error: f64) -> f64 {
        assert_eq!(
            axis, self.next as f64,
            "thrust called for axis {axis}, expected axis {} (after cmd) at t = {t}",
            self.next
        );
        self.next = if self.next == 3 { 0 } else { self.next + 1 };
        self.figure8.thrust(t, axis, error)
    }
}

#[test]
fn slew_maneuver_matches_reference() {
    let data = load("satellite-slew");
    let mut model = Satellite::new(Checked::new());

    // The reference's parameters are the model's defaults (Table 13).
    let mut values = vec![0.0; <Satellite<Checked> as Model>::PARAMETER_NAMES.len()];
    model.parameter_values(&mut values);
    for (name, v) in <Satellite<Checked> as Model>::PARAMETER_NAMES
        .iter()
        .zip(&values)
    {
        let want = data["parameters"][*name].as_f64().unwrap();
        assert!(
            (v - want).abs() <= 1e-15 * want.abs(),
            "{name}: {v} vs {want}"
        );
    }

    // The model's own initial state: q7 = 4 - 3.1415926, q8 = -0.5, all else 0.
    let mut x = model.initial_state();
    let q0 = floats(&data["initial_state"]["q"]);
    let u0 = floats(&data["initial_state"]["u"]);
    for (i, want) in q0.iter().chain(&u0).enumerate() {
        assert!(
            (x[i] - want).abs() <= 1e-15,
            "initial state {i}: {} vs {want}",
            x[i]
        );
    }

    let records = data["records"].as_array().unwrap();
    let names = ["q4", "q5", "q6", "q7", "q8"];
    let h = 0.001;
    let steps = 15_000;
    let per_record = 100; // records every 0.1 s
    assert_eq!(records.len(), steps / per_record + 1);

    let mut worst = [0.0f64; 5];
    let mut compare = |t: f64, x: &[f64; 20], record: &serde_json::Value| {
        let t_ref = record["t"].as_f64().unwrap();
        assert!((t - t_ref).abs() < 1e-9, "record time {t_ref} vs {t}");
        for (k, name) in names.iter().enumerate() {
            let want = record[*name].as_f64().unwrap();
            let err = (x[3 + k] - want).abs();
            assert!(
                err < 1e-4,
                "{name} at t = {t}: {} vs reference {want}",
                x[3 + k]
            );
            worst[k] = worst[k].max(err);
        }
    };
    compare(0.0, &x, &records[0]);

    let mut rk4 = Rk4::new();
    for n in 0..steps {
        let t = n as f64 * h;
        model.externs.stage_times.clear();
        rk4.step(&mut model, t, &mut x, h).unwrap();
        assert_eq!(
            model.externs.stage_times,
            [t, t + 0.5 * h, t + 0.5 * h, t + h],
            "stage times of step {n}"
        );
        assert_eq!(model.externs.next, 0, "an evaluation skipped a thrust call");
        if (n + 1) % per_record == 0 {
            compare((n + 1) as f64 * h, &x, &records[(n + 1) / per_record]);
        }
    }
    assert_eq!(model.externs.evaluations, 4 * steps as u64);
    assert_eq!(rk4.evaluations(), 4 * steps as u64);

    // The final state of every coordinate and speed, for the record.
    let q_end = floats(&data["run_info"]["final_state_q"]);
    let u_end = floats(&data["run_info"]["final_state_u"]);
    let end_err = q_end
        .iter()
        .chain(&u_end)
        .zip(&x)
        .fold(0.0f64, |a, (w, g)| a.max((w - g).abs()));
    eprintln!(
        "satellite slew vs reference, max |error| over {} records: q4 {:.2e}, q5 {:.2e}, q6 {:.2e}, q7 {:.2e}, q8 {:.2e} rad; all states at 15 s {end_err:.2e}",
        records.len(),
        worst[0],
        worst[1],
        worst[2],
        worst[3],
        worst[4],
    );
}

/// The same slew through the runtime's run driver (RK4, h = 1 ms, outputs
/// every 0.1 s): the driver steps at `n h` exactly, so the stateful
/// thrusters see the reference's times and the records match as closely.
#[test]
fn slew_through_the_run_driver_matches_reference() {
    use autosim::runtime::{RunSettings, run};
    let data = load("satellite-slew");
    let records = data["records"].as_array().unwrap();
    let mut model = Satellite::new(Checked::new());
    let mut x = model.initial_state();
    let mut rk4 = Rk4::new();
    let mut k = 0;
    let mut worst: f64 = 0.0;
    let mut observe = |t: f64, x: &[f64; 20], _y: &[f64; 6]| {
        let record = &records[k];
        assert!((t - record["t"].as_f64().unwrap()).abs() < 1e-9);
        for (i, name) in ["q4", "q5", "q6", "q7", "q8"].iter().enumerate() {
            worst = worst_of(worst, (x[3 + i] - record[*name].as_f64().unwrap()).abs());
        }
        k += 1;
    };
    let settings = RunSettings::new(0.0, 15.0, 0.001, 0.1);
    let summary = run(&mut model, &mut rk4, &mut x, &settings, &mut observe).unwrap();
    assert_eq!(k, records.len());
    assert_eq!(summary.evaluations, 60_000);
    eprintln!("slew through run(): max |error| in q4..q8 {worst:.2e} rad");
    assert!(
        worst < 1e-9,
        "run driver slew differs from the reference by {worst:e} rad"
    );
}
