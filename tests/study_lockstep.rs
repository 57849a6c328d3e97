//! Studies in lockstep (`runtime::study`, "Lockstep"): groups of cases
//! integrated together, one `derivatives_batch` call per stage, give the
//! bits of one case at a time (`Study::lockstep(false)`): on a model with
//! `derivatives_lanes` (`lanes = true`), on a hand-written one that allows
//! lockstep with the default batch (one `derivatives` call per state),
//! and on a plain generated model (which runs one case at a time), with Euler,
//! Heun, RK4, Adams–Bashforth–Moulton of order 2 and 4 (each case its
//! own history, also when projections reset some cases' histories and not
//! the others') and Dormand–Prince (each case its own steps and times,
//! rejections and failed stages included), every kind of kept value, output times on and off the
//! step grid, case counts that leave a partial group, serially and on two
//! threads. A case that fails (a non-finite state, a model error, a
//! non-finite output, a panic) fails with the error it has alone and the
//! others of its group finish; cases with different parameters run
//! together, each lane with its own (a parameter sweep of the lanes
//! model).

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use autosim::runtime::integrate::AbmOrder;
use autosim::runtime::study::{
    Cases, Distribution, Keep, Method, Parallelism, Results, Simulate, Statistic, Study,
};
use autosim::runtime::{Lanes, Model, ModelError, RunSettings};

autosim::model!(file = "examples/models/chain_planar_3.sim", lanes = true);
use chain_planar3::ChainPlanar3;

autosim::model!(file = "examples/models/pendulum.sim");
use pendulum::Pendulum;

autosim::model! {
    /// A pendulum driven by a torque that varies in time: with
    /// Dormand–Prince each lane is at its own time.
    model DrivenPendulum;
    settings { lanes: true }
    parameters {
        m = 1.3 [kg],
        L = 0.7 [m],
        g = 9.81 [m/s^2],
        A = 2.0 [N m],
        w = 3.0 [rad/s],
    }
    body Rod { rotate: 1, q: [q], u: [u], mass: m, cm: [0, 0, -L], inertia: 0 }
    moment drive { on: Rod, reaction: N, about: n1, magnitude: A*sin(w*t) }
    gravity = -g*n3;
    output height [m] = dot(pos(Rod.cm), n3);
}
use driven_pendulum::DrivenPendulum;

/// The methods that run in lockstep: every one.
const METHODS: [Method; 7] = [
    Method::Euler,
    Method::Heun,
    Method::Rk4,
    Method::AdamsBashforthMoulton(AbmOrder::Two),
    Method::AdamsBashforthMoulton(AbmOrder::Four),
    Method::DormandPrince {
        rtol: 1e-6,
        atol: 1e-9,
    },
    Method::DormandPrince {
        rtol: 1e-3,
        atol: 1e-6,
    },
];

/// Runs `study` with and without lockstep (serially and on two threads)
/// and checks the results are the same bits; returns them.
fn same_either_way<M, F>(study: Study<M, F, Simulate<M>>, count: u64) -> Results
where
    M: Model<Float = f64>,
    F: Fn() -> M + Sync,
{
    let mut study = study.progress(false);
    let mut run = |lockstep: bool, parallelism: Parallelism| {
        study.set_lockstep(lockstep);
        study.set_parallelism(parallelism);
        study.run_cases(0..count).unwrap()
    };
    let alone = run(false, Parallelism::Serial);
    assert_eq!(run(true, Parallelism::Serial), alone, "serial");
    assert_eq!(run(true, Parallelism::Threads(2)), alone, "two threads");
    alone
}

/// Random initial coordinates and speeds (no parameter or input column:
/// every group shares one model).
fn initial_states(names: &[&str], count: u64, seed: u64) -> Cases {
    let columns: Vec<(&str, Distribution)> = names
        .iter()
        .map(|n| (*n, Distribution::uniform(-1.5, 1.5)))
        .collect();
    Cases::new().random(count, seed, &columns).unwrap()
}

#[test]
fn lockstep_gives_the_bits_of_one_case_at_a_time() {
    // Outputs every 0.1 s on the 0.01 s grid; every 0.07 s off the 0.03 s one.
    let settings = [
        RunSettings::new(0.0, 0.6, 0.01, 0.1),
        RunSettings::new(0.0, 0.5, 0.03, 0.07),
    ];
    for (settings, method) in settings.iter().flat_map(|s| METHODS.map(|m| (s, m))) {
        // A model with derivatives_lanes: 4k + 3 cases.
        let keep = Keep::new()
            .final_state()
            .at(&[settings.output_interval], &["q2", "tip_height"])
            .statistic("tip_height", Statistic::Max)
            .statistic("u3", Statistic::Rms)
            .history(&["q1"]);
        let task = Simulate::new(*settings, method, keep).unwrap();
        let cases = initial_states(&["q1", "q2", "q3", "u1", "u2", "u3"], 11, 5);
        let results = same_either_way(Study::new(ChainPlanar3::new, cases, task), 11);
        assert_eq!(results.failures(), 0, "{method:?}");
        // A plain model (one case at a time, lockstep or not): 4k + 1 cases.
        let keep = Keep::new()
            .final_state()
            .statistic("height", Statistic::Mean)
            .history(&["u"]);
        let task = Simulate::new(*settings, method, keep).unwrap();
        let cases = initial_states(&["q", "u"], 9, 6);
        let results = same_either_way(Study::new(Pendulum::new, cases, task), 9);
        assert_eq!(results.failures(), 0, "{method:?}");
    }
}

#[test]
fn a_parameter_sweep_in_lockstep_gives_the_bits_of_one_case_at_a_time() {
    // Every case its own stiffness, damping, gravity, masses and lengths
    // (lengths enter the constants computed from the parameters) and
    // initial angles: each lane reads its own case's values.
    let columns = [
        ("k", Distribution::uniform(0.5, 5.0)),
        ("c", Distribution::uniform(0.0, 0.5)),
        ("g", Distribution::uniform(1.0, 20.0)),
        ("m2", Distribution::uniform(0.5, 2.0)),
        ("L1", Distribution::uniform(0.2, 0.8)),
        ("L3", Distribution::uniform(0.2, 0.8)),
        ("Ixx3", Distribution::uniform(0.01, 0.03)),
        ("q1", Distribution::uniform(-1.0, 1.0)),
        ("u3", Distribution::uniform(-1.0, 1.0)),
    ];
    let settings = RunSettings::new(0.0, 0.5, 0.01, 0.1);
    for method in METHODS {
        let keep = Keep::new()
            .final_state()
            .statistic("tip_height", Statistic::Max)
            .history(&["q2"]);
        let task = Simulate::new(settings, method, keep).unwrap();
        let cases = Cases::new().random(14, 8, &columns).unwrap();
        let results = same_either_way(Study::new(ChainPlanar3::new, cases, task), 14);
        assert_eq!(results.failures(), 0, "{method:?}");
    }
}

#[test]
fn cases_at_their_own_times_in_lockstep_give_the_bits_of_one_case_at_a_time() {
    // Adaptive steps: each case of a group at its own time, reading it in
    // its own lane.
    let columns = [
        ("A", Distribution::uniform(0.0, 8.0)),
        ("w", Distribution::uniform(1.0, 20.0)),
        ("q", Distribution::uniform(-2.0, 2.0)),
        ("u", Distribution::uniform(-2.0, 2.0)),
    ];
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.1);
    for method in METHODS {
        let keep = Keep::new()
            .final_state()
            .statistic("height", Statistic::Max)
            .history(&["q"]);
        let task = Simulate::new(settings, method, keep).unwrap();
        let cases = Cases::new().random(13, 4, &columns).unwrap();
        let results = same_either_way(Study::new(DrivenPendulum::new, cases, task), 13);
        assert_eq!(results.failures(), 0, "{method:?}");
    }
}

#[test]
fn a_failing_case_of_a_lanes_model_fails_as_alone() {
    // Speeds of 1e200 overflow the derivatives (non-finite, in the batch
    // of four and again alone).
    let names = ["q1", "q2", "q3", "u1", "u2", "u3"];
    let mut rows = Vec::new();
    for k in 0..10 {
        let u = if k == 2 || k == 9 {
            1e200
        } else {
            0.1 * k as f64
        };
        rows.extend([0.1, -0.2, 0.3, u, 0.0, -u]);
    }
    let cases = Cases::new().rows(&names, &rows).unwrap();
    let settings = RunSettings::new(0.0, 0.3, 0.01, 0.1);
    let task = Simulate::new(settings, Method::Rk4, Keep::new().final_state()).unwrap();
    let results = same_either_way(Study::new(ChainPlanar3::new, cases, task), 10);
    let failed: Vec<usize> = (0..10).filter(|&k| results.errors()[k].is_some()).collect();
    assert_eq!(failed, [2, 9], "{:?}", results.errors());
}

/// `x' = k x²` with `y = √(x + 10)`; its derivatives fail below -5 (a model
/// error) and panic at exactly 7; it allows lockstep, with the default
/// `derivatives_each`, and counts its calls of more than one model.
struct Quirky {
    k: f64,
    batches: Arc<AtomicU64>,
}

impl Model for Quirky {
    type Float = f64;
    type State = [f64; 1];
    type Outputs = [f64; 1];
    const NAME: &'static str = "Quirky";
    const STATE_NAMES: &'static [&'static str] = &["x"];
    const STATE_UNITS: &'static [&'static str] = &["1"];
    const PARAMETER_NAMES: &'static [&'static str] = &["k"];
    const OUTPUT_NAMES: &'static [&'static str] = &["y"];
    const LOCKSTEP: bool = true;
    fn derivatives(&mut self, _: f64, x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
        assert!(x[0] != 7.0, "a deliberate panic at x = 7");
        if x[0] < -5.0 {
            return Err(ModelError::SingularMassMatrix {
                speed: 0,
                name: "x",
            });
        }
        dx[0] = self.k * x[0] * x[0];
        Ok(())
    }
    fn derivatives_each(
        models: &mut [Quirky],
        _: &[Lanes<4>],
        t: &[f64],
        x: &[[f64; 1]],
        dx: &mut [[f64; 1]],
        status: &mut [Result<(), ModelError>],
    ) {
        if x.len() > 1 {
            models[0].batches.fetch_add(1, Ordering::Relaxed);
        }
        autosim::runtime::batch::each_alone(models, t, x, dx, status);
    }
    fn outputs(&mut self, _: f64, x: &[f64; 1], y: &mut [f64; 1]) -> Result<(), ModelError> {
        y[0] = (x[0] + 10.0).sqrt();
        Ok(())
    }
    fn parameter_values(&self, p: &mut [f64]) {
        p[0] = self.k;
    }
    fn set_parameter_values(&mut self, p: &[f64]) {
        self.k = p[0];
    }
}

/// The study of `Quirky` over the table `columns`/`rows` with `method`
/// to t = 1; returns its results (the same with and without lockstep) and
/// the `derivatives_each` calls of more than one model with lockstep.
fn quirky(columns: &[&str], rows: &[f64], method: Method) -> (Results, u64) {
    let count = (rows.len() / columns.len()) as u64;
    let cases = Cases::new().rows(columns, rows).unwrap();
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.25);
    let keep = Keep::new().final_state().statistic("y", Statistic::Max);
    let batches = Arc::new(AtomicU64::new(0));
    let make = {
        let batches = batches.clone();
        move || Quirky {
            k: 1.0,
            batches: batches.clone(),
        }
    };
    let task = Simulate::new(settings, method, keep).unwrap();
    let study = Study::new(make, cases, task).progress(false);
    let results = same_either_way(study, count);
    (results, batches.load(Ordering::Relaxed))
}

#[test]
fn a_failing_case_fails_as_alone_and_the_others_of_its_group_finish() {
    // 11 cases: a panic (7), a model error (-6), a blow-up (x' = x² from 3
    // passes infinity before t = 1/3), a non-finite output (√-1).
    let x0 = [0.1, 0.2, 7.0, 0.3, -6.0, 0.4, 3.0, -11.0, 0.5, 0.6, 0.7];
    let dopri = Method::DormandPrince {
        rtol: 1e-6,
        atol: 1e-9,
    };
    for method in [
        Method::Rk4,
        Method::AdamsBashforthMoulton(AbmOrder::Four),
        dopri,
    ] {
        let (results, batches) = quirky(&["x"], &x0, method);
        assert!(batches > 0, "no group ran in lockstep ({method:?})");
        let errors = results.errors();
        let has = |k: usize, text: &str| {
            let e = errors[k].as_deref().unwrap_or_default();
            assert!(e.contains(text), "case {k} ({method:?}): {e:?}");
        };
        has(2, "a deliberate panic at x = 7");
        has(4, "singular");
        // Dormand–Prince shrinks its steps toward the blow-up instead.
        let adaptive = matches!(method, Method::DormandPrince { .. });
        has(
            6,
            if adaptive {
                "step size underflow"
            } else {
                "non-finite"
            },
        );
        has(7, "not finite");
        for k in [0, 1, 3, 5, 8, 9, 10] {
            assert!(
                errors[k].is_none(),
                "case {k} ({method:?}): {:?}",
                errors[k]
            );
        }
        assert_eq!(results.failures(), 4, "{method:?}");
    }
}

#[test]
fn cases_with_different_parameters_run_together() {
    // Groups of four: the first shares k = 1 but for case 1; the second
    // is all k = 0.5; the third has a different k in each case.
    let rows = [
        1.0, 0.1, 2.0, 0.2, 1.0, 0.3, 1.0, 0.4, //
        0.5, 0.1, 0.5, 0.2, 0.5, 0.3, 0.5, 0.4, //
        0.1, 0.1, 0.2, 0.2, 0.3, 0.3, 0.4, 0.4, //
        0.9, 0.5,
    ];
    let (results, batches) = quirky(&["k", "x"], &rows, Method::Rk4);
    assert!(batches > 0, "no group ran in lockstep");
    assert_eq!(results.failures(), 0, "{:?}", results.errors());
}

/// The oscillator `x' = v`, `v' = -k x`, whose state is projected back
/// onto its energy at the start (`k x² + v²`, recorded by `assemble`) when
/// it drifts by more than the tolerance: each case projects at its own
/// steps, so an Adams group in lockstep has cases with a history and
/// cases starting over at once, and a Dormand–Prince group cases with
/// their first stage in hand and cases without. It allows lockstep with
/// the default `derivatives_each` and counts that function's calls by
/// size.
struct Drifting {
    k: f64,
    energy: f64,
    /// Calls of `derivatives_each` with one model, with four.
    calls: Arc<[AtomicU64; 2]>,
}

impl Drifting {
    fn energy(&self, x: &[f64; 2]) -> f64 {
        self.k * x[0] * x[0] + x[1] * x[1]
    }
}

impl Model for Drifting {
    type Float = f64;
    type State = [f64; 2];
    type Outputs = [f64; 0];
    const NAME: &'static str = "Drifting";
    const STATE_NAMES: &'static [&'static str] = &["x", "v"];
    const STATE_UNITS: &'static [&'static str] = &["1", "1"];
    const PARAMETER_NAMES: &'static [&'static str] = &["k"];
    const LOCKSTEP: bool = true;
    fn derivatives(&mut self, _: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        *dx = [x[1], -self.k * x[0]];
        Ok(())
    }
    fn derivatives_each(
        models: &mut [Drifting],
        _: &[Lanes<4>],
        t: &[f64],
        x: &[[f64; 2]],
        dx: &mut [[f64; 2]],
        status: &mut [Result<(), ModelError>],
    ) {
        match models.len() {
            1 => models[0].calls[0].fetch_add(1, Ordering::Relaxed),
            4 => models[0].calls[1].fetch_add(1, Ordering::Relaxed),
            _ => 0,
        };
        autosim::runtime::batch::each_alone(models, t, x, dx, status);
    }
    fn assemble(&mut self, _: f64, x: &mut [f64; 2]) -> Result<(), ModelError> {
        self.energy = self.energy(x);
        Ok(())
    }
    fn project(&mut self, _: f64, x: &mut [f64; 2], tolerance: f64) -> Result<bool, ModelError> {
        let energy = self.energy(x);
        if (energy - self.energy).abs() <= tolerance * self.energy {
            return Ok(false);
        }
        let scale = (self.energy / energy).sqrt();
        *x = [x[0] * scale, x[1] * scale];
        Ok(true)
    }
    fn parameter_values(&self, p: &mut [f64]) {
        p[0] = self.k;
    }
    fn set_parameter_values(&mut self, p: &[f64]) {
        self.k = p[0];
    }
}

#[test]
fn cases_keep_their_own_histories_in_lockstep() {
    let columns = [
        ("k", Distribution::uniform(0.01, 40.0)),
        ("x", Distribution::uniform(-1.0, 1.0)),
        ("v", Distribution::uniform(-1.0, 1.0)),
    ];
    // Tolerances between the drifts of slow and fast cases: the local
    // error of order p is about (√k h)^(p + 1) per step.
    let dopri = Method::DormandPrince {
        rtol: 1e-5,
        atol: 1e-8,
    };
    let methods = [
        (Method::AdamsBashforthMoulton(AbmOrder::Two), 1e-6),
        (Method::AdamsBashforthMoulton(AbmOrder::Four), 1e-10),
        (dopri, 1e-9),
    ];
    for (method, tolerance) in methods {
        let calls = Arc::new([AtomicU64::new(0), AtomicU64::new(0)]);
        let make = {
            let calls = calls.clone();
            move || Drifting {
                k: 1.0,
                energy: 1.0,
                calls: calls.clone(),
            }
        };
        let settings = RunSettings::new(0.0, 2.0, 0.01, 0.1).with_projection_tolerance(tolerance);
        let keep = Keep::new().final_state().history(&["x"]);
        let task = Simulate::new(settings, method, keep).unwrap();
        let cases = Cases::new().random(16, 3, &columns).unwrap();
        let results = same_either_way(Study::new(make, cases, task), 16);
        assert_eq!(results.failures(), 0, "{method:?}");
        let [ones, fours] = [0, 1].map(|k| calls[k].load(Ordering::Relaxed));
        // Both kinds of step in one group: start-up stages for some lanes
        // alone, the rest of the evaluations for all four.
        assert!(
            ones > 0 && fours > 0,
            "{method:?}: {ones} single, {fours} of four"
        );
    }
}
