//! Speed against accuracy, measured: every integrator of the runtime over a
//! range of steps (or tolerances), in `f64` and `f32`, on four models, and
//! what the compile-time scene options (small variables, locks, selected
//! outputs, `f32`) buy on the paper's satellite.
//!
//! ```text
//! cargo run --release --example tradeoff [-- OUTPUT_FOLDER]
//! ```
//!
//! # Work–precision study
//!
//! | study | model | end time | error measure |
//! | --- | --- | --- | --- |
//! | `satellite` | `satellite.sim`, Figure 8 commands, thrusters off | 15 s | max abs error of the bus attitude q4, q5, q6 at 15 s |
//! | `satellite-small` | the same with `small = [B, E, F]` | 15 s | the same, against the **full** model's reference (model + integration error) |
//! | `satellite-thrusters` | `satellite.sim` with the Figure 8 thrusters on | 15 s | the same, against RK4 at h = 10 µs |
//! | `chain-spatial-5` | `chain_spatial_5.sim`, released from q = (0.6, -0.5, 0.4, 0.7, -0.3) | 5 s | max abs error of q1..q5 at 5 s |
//! | `chain-spatial-3-stiff` | `chain_spatial_3_stiff.sim` (k × 10⁴), released from q1 = 0.1 | 1 s | max abs error of q1..q3 at 1 s |
//!
//! The references are the `f64` models integrated with Dormand–Prince at
//! rtol = atol = 1e-12 (their own error, estimated against 1e-13, is
//! printed). The satellite study runs with the thrusters **off**: the
//! Figure 8 thrusters are a stateful bang-bang element whose switching
//! times depend on where each method evaluates the model (stage times,
//! rejected steps, Jacobian columns), so with them on no method converges
//! faster than first order and the error floor depends on the method; the
//! `satellite-thrusters` study shows exactly that. With the thrusters off,
//! the commanded slew of the clock and camera still swings the bus through
//! the reaction torques and the boom.
//!
//! Every method runs through [`run`] at steps h = T/n (fixed-step methods;
//! each h divides 1 s, so the kinks of the commands at 1 s and 11 s fall on
//! steps) or tolerances rtol = atol = tol (Dormand–Prince), in `f64` and in
//! `f32` (the same model files with the scene option `float = f32`). Cost is
//! derivative evaluations (exact) and wall time (median of 3 runs). Runs
//! that would take more than 10⁶ evaluations are skipped. A run that
//! fails is listed with its typed error (e.g. an explicit method beyond its
//! stability limit on the stiff chain stops with a non-finite state); one
//! that ends finite but more than 1 rad off is listed as diverged. Both are
//! left out of the plots.
//!
//! # Scene options
//!
//! The satellite compiled several ways from the one file (small variables
//! per body or coordinate, thresholds, locked boom, selected outputs, `f32`),
//! each flown through the paper's slew (Figure 8 user code, thrusters on,
//! RK4 at h = 1 ms): operation counts, nanoseconds per `derivatives()` call
//! (median over 101 rounds at 500 states of its own slew, the best of 7
//! passes interleaved over the scenes, since load from other processes only
//! adds time) and the largest attitude difference from the full `f64` model
//! over the 15 s.
//!
//! # Output (default folder `docs/tradeoff`)
//!
//! - `results.csv`: one row per run: study, float, method, `h` or `tol` and
//!   its value, accepted and rejected steps, evaluations, wall time [ms],
//!   `error` (against the study's reference; for `satellite-small` the full
//!   model's), `integration_error` (`satellite-small` only: against its own
//!   reference) and `status` (`ok`, `diverged (finite)`, or the typed error);
//! - `<study>.svg`: error against derivative evaluations, log–log, one line
//!   per method, `f64` solid and `f32` dashed;
//! - `<study>_time.svg`: error against wall time;
//! - `summary.md`: the cheapest run reaching each error level, the scene
//!   table, the references' own errors.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use autosim::runtime::integrate::{
    AbmOrder, AdamsBashforthMoulton, DormandPrince, Euler, Heun, Rk4, Sdirk3, SdirkSettings,
};
use autosim::runtime::io::{Axes, Corner, Scale, XySeries, write_xy_svg_plot};
use autosim::runtime::{Float, IntegrationError, Model, OpCount, RunSettings, Stepper, run};

// The paper's Figure 8 (CMD and THRUST), shared with `satellite.rs`.
#[macro_use]
#[path = "common/figure8.rs"]
mod figure8;
use figure8::Figure8;

/// The work–precision models: one file each, in `f64` and `f32`.
mod wp {
    autosim::model!(file = "examples/models/satellite.sim");
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = SatelliteF32,
        float = f32
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = SatelliteSmall,
        small = [B, E, F]
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = SatelliteSmallF32,
        small = [B, E, F],
        float = f32
    );
    autosim::model!(file = "examples/models/chain_spatial_5.sim");
    autosim::model!(
        file = "examples/models/chain_spatial_5.sim",
        name = ChainSpatial5F32,
        float = f32
    );
    autosim::model!(file = "examples/models/chain_spatial_3_stiff.sim");
    autosim::model!(
        file = "examples/models/chain_spatial_3_stiff.sim",
        name = ChainSpatial3StiffF32,
        float = f32
    );
}

/// The satellite tailored at the use site (scene options).
mod scene {
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = SmallBus,
        small = [B]
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = SmallBoom,
        small = [E, F]
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = SmallAngles,
        small = [q4, q5, q6, q9, q10]
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = SmallThreshold1,
        small = [B, E, F],
        threshold = 1
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = SmallThreshold3,
        small = [B, E, F],
        threshold = 3
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = Attitude,
        outputs = [roll, pitch, yaw]
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = RigidBoomAll,
        lock = [q9, q10]
    );
    autosim::model!(
        file = "examples/models/satellite.sim",
        name = RigidBoom,
        lock = [q9, q10],
        outputs = [roll, pitch, yaw]
    );
}

figure8_externs!(
    wp::satellite => f64,
    wp::satellite_f32 => f32,
    wp::satellite_small => f64,
    wp::satellite_small_f32 => f32,
    scene::small_bus => f64,
    scene::small_boom => f64,
    scene::small_angles => f64,
    scene::small_threshold1 => f64,
    scene::small_threshold3 => f64,
    scene::attitude => f64,
    scene::rigid_boom_all => f64,
    scene::rigid_boom => f64,
);

/// Runs costing more evaluations than this are skipped.
const MAX_EVALUATIONS: f64 = 1e6;
/// A run that ends finite but this far (rad) from the reference diverged.
const DIVERGED: f64 = 1.0;
/// Error levels of the summary tables.
const LEVELS: [f64; 4] = [1e-2, 1e-4, 1e-6, 1e-8];
/// Wall time is the median of this many runs.
const REPEATS: usize = 3;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Method {
    Euler,
    Heun,
    Rk4,
    Abm2,
    Abm4,
    Dopri,
    Sdirk3,
}

impl Method {
    const ALL: [Method; 7] = [
        Method::Euler,
        Method::Heun,
        Method::Rk4,
        Method::Abm2,
        Method::Abm4,
        Method::Dopri,
        Method::Sdirk3,
    ];

    fn name(self) -> &'static str {
        match self {
            Method::Euler => "Euler",
            Method::Heun => "Heun",
            Method::Rk4 => "RK4",
            Method::Abm2 => "ABM2",
            Method::Abm4 => "ABM4",
            Method::Dopri => "DOPRI5",
            Method::Sdirk3 => "SDIRK3",
        }
    }

    /// Palette index of the method's lines (distinct, legible colours).
    fn color(self) -> usize {
        match self {
            Method::Euler => 0,
            Method::Heun => 1,
            Method::Rk4 => 3,
            Method::Abm2 => 4,
            Method::Abm4 => 5,
            Method::Dopri => 10,
            Method::Sdirk3 => 7,
        }
    }

    /// Evaluations per step, roughly (to skip runs over the budget).
    fn evaluations_per_step(self, states: usize) -> f64 {
        match self {
            Method::Euler => 1.0,
            Method::Heun | Method::Abm2 | Method::Abm4 => 2.0,
            Method::Rk4 => 4.0,
            Method::Dopri => 6.0,
            Method::Sdirk3 => 1.0 + states as f64 + 6.0,
        }
    }
}

/// One study: a model in one float type, and how its runs are measured.
struct Study<'a> {
    name: &'static str,
    float: &'static str,
    t_end: f64,
    /// Step counts n (h = t_end / n) of the fixed-step methods.
    steps: &'a [u64],
    /// Tolerances of Dormand–Prince.
    tolerances: &'a [f64],
    /// The reference final state (f64) the error is measured against (for a
    /// small-variable model: the full model's).
    reference: &'a [f64],
    /// The model's own reference, when `reference` is another model's: the
    /// error against it is the integration error alone.
    own_reference: Option<&'a [f64]>,
    /// Error of a final state against a reference.
    measure: fn(&[f64], &[f64]) -> f64,
}

/// What one run gave.
#[derive(Clone, Debug)]
struct Row {
    study: &'static str,
    float: &'static str,
    method: Method,
    /// h (fixed step) or tol (Dormand–Prince).
    setting: f64,
    steps: u64,
    rejected: u64,
    evaluations: u64,
    wall_s: f64,
    /// Error against the study's reference (NaN if the run failed).
    error: f64,
    /// Error against the model's own reference, when the study's reference
    /// is another model's (NaN otherwise, or if the run failed).
    integration_error: f64,
    status: String,
}

/// The end of one run.
struct Outcome {
    x: Vec<f64>,
    steps: u64,
    rejected: u64,
    evaluations: u64,
    failure: Option<IntegrationError>,
}

/// Runs `stepper` from `x0` over [0, t_end] with one output at each end.
fn go<M, S, const N: usize>(
    model: &mut M,
    stepper: &mut S,
    x0: [M::Float; N],
    t_end: f64,
    step: f64,
) -> Outcome
where
    M: Model<State = [<M as Model>::Float; N]>,
    S: Stepper<M>,
{
    let f = <M::Float as Float>::from_f64;
    let settings = RunSettings::new(f(0.0), f(t_end), f(step), f(t_end)).with_max_steps(20_000_000);
    let mut x = x0;
    let result = run(model, stepper, &mut x, &settings, &mut |_, _: &_, _: &_| {});
    let (steps, rejected, failure) = match result {
        Ok(s) => (s.steps, s.rejected_steps, None),
        Err(e) => (0, 0, Some(IntegrationError::from(e))),
    };
    Outcome {
        x: x.iter().map(|v| v.to_f64()).collect(),
        steps,
        rejected,
        evaluations: stepper.evaluations(),
        failure,
    }
}

/// One run of `method` at `setting` (a step or a tolerance).
fn integrate<M, const N: usize>(
    model: &mut M,
    method: Method,
    setting: f64,
    x0: [M::Float; N],
    t_end: f64,
) -> Outcome
where
    M: Model<State = [<M as Model>::Float; N]>,
{
    let f = <M::Float as Float>::from_f64;
    match method {
        Method::Euler => go(model, &mut Euler::new(), x0, t_end, setting),
        Method::Heun => go(model, &mut Heun::new(), x0, t_end, setting),
        Method::Rk4 => go(model, &mut Rk4::new(), x0, t_end, setting),
        Method::Abm2 => go(
            model,
            &mut AdamsBashforthMoulton::new(AbmOrder::Two),
            x0,
            t_end,
            setting,
        ),
        Method::Abm4 => go(
            model,
            &mut AdamsBashforthMoulton::new(AbmOrder::Four),
            x0,
            t_end,
            setting,
        ),
        Method::Dopri => match DormandPrince::with_tolerances(f(setting), f(setting)) {
            Ok(mut dopri) => go(model, &mut dopri, x0, t_end, 1e-3),
            Err(e) => Outcome {
                x: Vec::new(),
                steps: 0,
                rejected: 0,
                evaluations: 0,
                failure: Some(e),
            },
        },
        Method::Sdirk3 => go(
            model,
            &mut Sdirk3::<M, N>::new(SdirkSettings::default()),
            x0,
            t_end,
            setting,
        ),
    }
}

/// A tight reference: Dormand–Prince at `tol` in f64.
fn reference<M, const N: usize>(mut model: M, x0: [f64; N], t_end: f64, tol: f64) -> Vec<f64>
where
    M: Model<Float = f64, State = [f64; N]>,
{
    let out = integrate(&mut model, Method::Dopri, tol, x0, t_end);
    if let Some(e) = out.failure {
        panic!("reference run of {} failed: {e}", M::NAME);
    }
    out.x
}

/// Every method over every setting of `study`.
fn sweep<M, const N: usize>(
    study: &Study<'_>,
    make: &dyn Fn() -> M,
    x0: [M::Float; N],
    rows: &mut Vec<Row>,
) where
    M: Model<State = [<M as Model>::Float; N]>,
{
    for method in Method::ALL {
        let settings: Vec<(f64, f64)> = if method == Method::Dopri {
            study.tolerances.iter().map(|&tol| (tol, 0.0)).collect()
        } else {
            study
                .steps
                .iter()
                .map(|&n| (study.t_end / n as f64, n as f64))
                .collect()
        };
        for (setting, n) in settings {
            if method != Method::Dopri && n * method.evaluations_per_step(N) > MAX_EVALUATIONS {
                continue;
            }
            let mut walls = Vec::with_capacity(REPEATS);
            let mut last = None;
            for _ in 0..REPEATS {
                let mut model = make();
                let start = Instant::now();
                let out = integrate(&mut model, method, setting, x0, study.t_end);
                walls.push(start.elapsed().as_secs_f64());
                let failed = out.failure.is_some();
                last = Some(out);
                if failed {
                    break;
                }
            }
            let out = last.expect("at least one run");
            walls.sort_by(f64::total_cmp);
            let wall_s = walls[walls.len() / 2];
            let (error, integration_error, status) = match out.failure {
                None => (
                    (study.measure)(&out.x, study.reference),
                    study
                        .own_reference
                        .map_or(f64::NAN, |r| (study.measure)(&out.x, r)),
                    "ok".to_string(),
                ),
                Some(e) => (f64::NAN, f64::NAN, short(&e)),
            };
            let status = if error > DIVERGED {
                "diverged (finite)".to_string()
            } else {
                status
            };
            let row = Row {
                study: study.name,
                float: study.float,
                method,
                setting,
                steps: out.steps,
                rejected: out.rejected,
                evaluations: out.evaluations,
                wall_s,
                error,
                integration_error,
                status,
            };
            print_row(&row);
            rows.push(row);
            // Tighter tolerances only cost more.
            if method == Method::Dopri && out.evaluations as f64 > MAX_EVALUATIONS {
                break;
            }
        }
    }
}

/// A failure in a few words.
fn short(e: &IntegrationError) -> String {
    match *e {
        IntegrationError::NonFinite { t, name, .. } => format!("non-finite {name} at t={t:.3}"),
        IntegrationError::StepSizeUnderflow { t, .. } => format!("step underflow at t={t:.3}"),
        IntegrationError::NewtonFailed { t, .. } => format!("Newton failed at t={t:.3}"),
        IntegrationError::SingularNewtonMatrix { t, .. } => {
            format!("singular Newton matrix at t={t:.3}")
        }
        IntegrationError::TooManySteps { t, .. } => format!("step limit at t={t:.3}"),
        IntegrationError::Model { t, error } => format!("model error at t={t:.3}: {error}"),
        ref other => other.to_string(),
    }
}

fn print_header() {
    println!(
        "{:<22} {:<4} {:<7} {:>10} {:>9} {:>10} {:>10} {:>10}  status",
        "study", "f", "method", "h or tol", "steps", "evals", "wall ms", "error"
    );
}

fn print_row(r: &Row) {
    println!(
        "{:<22} {:<4} {:<7} {:>10.2e} {:>9} {:>10} {:>10.3} {:>10.2e}  {}",
        r.study,
        r.float,
        r.method.name(),
        r.setting,
        r.steps,
        r.evaluations,
        r.wall_s * 1e3,
        r.error,
        r.status
    );
}

/// Largest |x_i - r_i| over the bus attitude q4, q5, q6.
fn attitude_error(x: &[f64], r: &[f64]) -> f64 {
    (3..6).map(|i| (x[i] - r[i]).abs()).fold(0.0, f64::max)
}

/// Largest |x_i - r_i| over the coordinates (the first half of the state).
fn coordinate_error(x: &[f64], r: &[f64]) -> f64 {
    (0..r.len() / 2)
        .map(|i| (x[i] - r[i]).abs())
        .fold(0.0, f64::max)
}

fn to_f32<const N: usize>(x: [f64; N]) -> [f32; N] {
    x.map(|v| v as f32)
}

/// The initial state of chain-spatial-5 (released at rest).
fn chain5_x0() -> [f64; 10] {
    let mut x = [0.0; 10];
    x[..5].copy_from_slice(&[0.6, -0.5, 0.4, 0.7, -0.3]);
    x
}

/// The initial state of the stiff chain: the first joint deflected.
fn stiff_x0() -> [f64; 6] {
    [0.1, 0.0, 0.0, 0.0, 0.0, 0.0]
}

/// What flying the slew with one scene gave.
struct SceneRun {
    label: &'static str,
    float: &'static str,
    states: usize,
    derivative_ops: OpCount,
    output_ops: OpCount,
    /// Times `derivatives()` (median ns per call over 101 rounds) at 500
    /// states of the scene's slew.
    timer: Box<dyn FnMut() -> f64>,
    /// The best of several timing passes, interleaved with the other scenes.
    ns_per_call: f64,
    /// q4..q6 after every step, thrusters on.
    attitude: Vec<[f64; 3]>,
    /// q4..q6 after every step, thrusters off.
    attitude_quiet: Vec<[f64; 3]>,
    /// Largest |Δ q4..q6| from the full f64 model over the slew, thrusters on.
    diff: f64,
    /// The same, thrusters off.
    diff_quiet: f64,
}

/// Flies the slew (Figure 8) with RK4 at 1 ms, thrusters on and off;
/// records the attitude after every step and keeps 500 of the trajectory's
/// states to time `derivatives()` at.
fn fly_scene<M, const N: usize>(
    label: &'static str,
    make: impl Fn(Figure8) -> M,
    derivative_ops: OpCount,
    output_ops: OpCount,
) -> SceneRun
where
    M: Model<State = [<M as Model>::Float; N]> + 'static,
{
    let (attitude, samples) = slew(label, &mut make(Figure8::new()));
    let (attitude_quiet, _) = slew(label, &mut make(Figure8::commands_only()));
    let mut model = make(Figure8::new());
    let timer = Box::new(move || time_derivatives(&mut model, &samples));
    SceneRun {
        label,
        float: if M::Float::EPSILON.to_f64() > 1e-10 {
            "f32"
        } else {
            "f64"
        },
        states: N,
        derivative_ops,
        output_ops,
        timer,
        ns_per_call: f64::INFINITY,
        attitude,
        attitude_quiet,
        diff: 0.0,
        diff_quiet: 0.0,
    }
}

/// The slew with RK4 at 1 ms: q4..q6 after every step, and every 30th state.
#[allow(clippy::type_complexity)]
fn slew<M, const N: usize>(label: &str, model: &mut M) -> (Vec<[f64; 3]>, Vec<[M::Float; N]>)
where
    M: Model<State = [<M as Model>::Float; N]>,
{
    let f = <M::Float as Float>::from_f64;
    let h = 1e-3;
    let steps = 15_000;
    let mut rk4 = Rk4::new();
    let mut x = model.initial_state();
    let mut attitude = Vec::with_capacity(steps + 1);
    let mut samples = Vec::with_capacity(steps / 30 + 1);
    let angles = |x: &[M::Float; N]| [x[3].to_f64(), x[4].to_f64(), x[5].to_f64()];
    attitude.push(angles(&x));
    for n in 0..steps {
        if let Err(e) = rk4.step(model, f(n as f64 * h), &mut x, f(h)) {
            panic!("{label}: the slew failed: {e}");
        }
        attitude.push(angles(&x));
        if n % 30 == 0 {
            samples.push(x);
        }
    }
    (attitude, samples)
}

/// Median nanoseconds per `derivatives()` call over 101 rounds at `states`
/// (as `examples/perf.rs`).
fn time_derivatives<M, const N: usize>(model: &mut M, states: &[[M::Float; N]]) -> f64
where
    M: Model<State = [<M as Model>::Float; N]>,
{
    use std::hint::black_box;
    let mut dx = [M::Float::ZERO; N];
    let t = <M::Float as Float>::from_f64(5.0);
    for x in states {
        let _ = model.derivatives(t, black_box(x), &mut dx);
    }
    let rounds = 101;
    let mut per_call = Vec::with_capacity(rounds);
    for _ in 0..rounds {
        let start = Instant::now();
        for x in states {
            let _ = black_box(model.derivatives(t, black_box(x), &mut dx));
            black_box(&mut dx);
        }
        per_call.push(start.elapsed().as_nanos() as f64 / states.len() as f64);
    }
    per_call.sort_by(f64::total_cmp);
    per_call[rounds / 2]
}

/// The cheapest successful run of each method reaching `target`.
fn cheapest<'a>(
    rows: &'a [Row],
    study: &str,
    float: &str,
    method: Method,
    target: f64,
) -> Option<&'a Row> {
    rows.iter()
        .filter(|r| r.study == study && r.float == float && r.method == method)
        .filter(|r| r.status == "ok" && r.error <= target)
        .min_by_key(|r| r.evaluations)
}

fn write_csv(path: &std::path::Path, rows: &[Row]) -> std::io::Result<()> {
    let mut s = String::from(
        "study,float,method,setting_kind,setting,steps,rejected_steps,evaluations,wall_ms,error,integration_error,status\n",
    );
    for r in rows {
        let kind = if r.method == Method::Dopri {
            "tol"
        } else {
            "h"
        };
        let num = |v: f64| {
            if v.is_finite() {
                format!("{v:e}")
            } else {
                String::new()
            }
        };
        let _ = writeln!(
            s,
            "{},{},{},{kind},{:e},{},{},{},{:.4},{},{},{}",
            r.study,
            r.float,
            r.method.name(),
            r.setting,
            r.steps,
            r.rejected,
            r.evaluations,
            r.wall_s * 1e3,
            num(r.error),
            num(r.integration_error),
            r.status.replace(',', ";")
        );
    }
    std::fs::write(path, s)
}

/// One line of a plot.
struct Line {
    name: String,
    x: Vec<f64>,
    y: Vec<f64>,
    color: usize,
    dashed: bool,
}

/// A study's plot: its name, title, y label, and an optional horizontal
/// line (name, level).
type Plot<'a> = (&'a str, &'a str, &'a str, Option<(&'a str, f64)>);

/// Work–precision plots of one study: error against evaluations and
/// against wall time, f64 solid, f32 dashed.
fn plot_study(
    folder: &std::path::Path,
    study: &str,
    title: &str,
    error_label: &str,
    rows: &[Row],
    floor: Option<(&str, f64)>,
) -> Result<Vec<PathBuf>, Box<dyn std::error::Error>> {
    let mut written = Vec::new();
    for (suffix, x_label, cost) in [
        (
            "",
            "derivative evaluations",
            (|r: &Row| r.evaluations as f64) as fn(&Row) -> f64,
        ),
        ("_time", "wall time [ms]", |r: &Row| r.wall_s * 1e3),
    ] {
        let mut lines: Vec<Line> = Vec::new();
        for method in Method::ALL.iter() {
            for float in ["f64", "f32"] {
                let mut pts: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.study == study && r.float == float && r.method == *method)
                    .filter(|r| r.status == "ok")
                    .map(|r| (cost(r), r.error.max(1e-16)))
                    .collect();
                if pts.is_empty() {
                    continue;
                }
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                let name = if float == "f64" {
                    method.name().to_string()
                } else {
                    format!("{} f32", method.name())
                };
                lines.push(Line {
                    name,
                    x: pts.iter().map(|p| p.0).collect(),
                    y: pts.iter().map(|p| p.1).collect(),
                    color: method.color(),
                    dashed: float == "f32",
                });
            }
        }
        if let Some((name, level)) = floor {
            let xs: Vec<f64> = lines.iter().flat_map(|l| l.x.iter().copied()).collect();
            let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = xs.iter().copied().fold(0.0, f64::max);
            lines.push(Line {
                name: name.to_string(),
                x: vec![lo, hi],
                y: vec![level, level],
                color: 19,
                dashed: true,
            });
        }
        let series: Vec<XySeries<'_>> = lines
            .iter()
            .map(|l| XySeries {
                name: &l.name,
                x: &l.x,
                y: &l.y,
                color: l.color,
                dashed: l.dashed,
            })
            .collect();
        let path = folder.join(format!("{study}{suffix}.svg"));
        write_xy_svg_plot(
            &path,
            title,
            &Axes {
                x_label,
                y_label: error_label,
                x_scale: Scale::Log,
                y_scale: Scale::Log,
                legend: Corner::LowerLeft,
            },
            &series,
        )?;
        written.push(path);
    }
    Ok(written)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let folder = match std::env::args_os().nth(1) {
        Some(a) if a == "-h" || a == "--help" => {
            println!("usage: cargo run --release --example tradeoff [-- OUTPUT_FOLDER]");
            println!(
                "writes results.csv, work-precision plots and summary.md (default: docs/tradeoff)"
            );
            return Ok(());
        }
        Some(a) => PathBuf::from(a),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/tradeoff"),
    };
    std::fs::create_dir_all(&folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    let started = Instant::now();

    // ---------------------------------------------------------------- references
    type Sat = wp::satellite::Satellite<Figure8>;
    type SatF32 = wp::satellite_f32::SatelliteF32<Figure8>;
    type Small = wp::satellite_small::SatelliteSmall<Figure8>;
    type SmallF32 = wp::satellite_small_f32::SatelliteSmallF32<Figure8>;
    type Chain5 = wp::chain_spatial5::ChainSpatial5;
    type Chain5F32 = wp::chain_spatial5_f32::ChainSpatial5F32;
    type Stiff = wp::chain_spatial3_stiff::ChainSpatial3Stiff;
    type StiffF32 = wp::chain_spatial3_stiff_f32::ChainSpatial3StiffF32;

    let quiet = Figure8::commands_only;
    let sat_x0 = Sat::new(quiet()).initial_state();
    let small_x0 = Small::new(quiet()).initial_state();
    let t_sat = 15.0;
    let (t_chain, t_stiff) = (5.0, 1.0);
    println!("References (Dormand-Prince, rtol = atol = 1e-12, f64; own error against 1e-13):");
    let mut reference_notes = Vec::new();
    let mut refs =
        |label: &'static str, a: Vec<f64>, b: Vec<f64>, measure: fn(&[f64], &[f64]) -> f64| {
            let e = measure(&a, &b);
            println!("  {label:<22} {e:.1e}");
            reference_notes.push((label, e));
            a
        };
    let sat_ref = refs(
        "satellite",
        reference(Sat::new(quiet()), sat_x0, t_sat, 1e-12),
        reference(Sat::new(quiet()), sat_x0, t_sat, 1e-13),
        attitude_error,
    );
    let small_ref = refs(
        "satellite-small",
        reference(Small::new(quiet()), small_x0, t_sat, 1e-12),
        reference(Small::new(quiet()), small_x0, t_sat, 1e-13),
        attitude_error,
    );
    let chain_ref = refs(
        "chain-spatial-5",
        reference(Chain5::new(), chain5_x0(), t_chain, 1e-12),
        reference(Chain5::new(), chain5_x0(), t_chain, 1e-13),
        coordinate_error,
    );
    let stiff_ref = refs(
        "chain-spatial-3-stiff",
        reference(Stiff::new(), stiff_x0(), t_stiff, 1e-12),
        reference(Stiff::new(), stiff_x0(), t_stiff, 1e-13),
        coordinate_error,
    );
    // With the thrusters on: RK4 at 10 µs (and 20 µs for its own error).
    let thrust_ref = {
        let run_rk4 = |n: u64| {
            let mut m = Sat::new(Figure8::new());
            integrate(&mut m, Method::Rk4, t_sat / n as f64, sat_x0, t_sat).x
        };
        refs(
            "satellite-thrusters",
            run_rk4(1_500_000),
            run_rk4(750_000),
            attitude_error,
        )
    };
    let small_model_error = attitude_error(&small_ref, &sat_ref);
    println!("  small-variable model vs full at 15 s (thrusters off): {small_model_error:.2e} rad");

    // ---------------------------------------------------------------- sweeps
    let sat_steps: &[u64] = &[
        150, 300, 750, 1_500, 3_000, 7_500, 15_000, 30_000, 75_000, 150_000, 300_000, 750_000,
        1_500_000,
    ];
    let chain_steps: &[u64] = &[
        50, 100, 250, 500, 1_000, 2_500, 5_000, 10_000, 25_000, 50_000, 100_000, 250_000, 500_000,
    ];
    let stiff_steps: &[u64] = &[
        10, 20, 50, 100, 200, 500, 1_000, 2_000, 5_000, 10_000, 20_000, 50_000, 100_000, 200_000,
        500_000,
    ];
    let tolerances: &[f64] = &[1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11];
    let mut rows = Vec::new();
    println!();
    print_header();

    let study = |name, float, t_end, steps, reference, own_reference, measure| Study {
        name,
        float,
        t_end,
        steps,
        tolerances,
        reference,
        own_reference,
        measure,
    };
    let sat = |float| {
        study(
            "satellite",
            float,
            t_sat,
            sat_steps,
            &sat_ref[..],
            None,
            attitude_error as fn(&[f64], &[f64]) -> f64,
        )
    };
    sweep(&sat("f64"), &|| Sat::new(quiet()), sat_x0, &mut rows);
    sweep(
        &sat("f32"),
        &|| SatF32::new(quiet()),
        to_f32(sat_x0),
        &mut rows,
    );
    // The small model against the full model's reference: what a user gets.
    let small = |float| {
        study(
            "satellite-small",
            float,
            t_sat,
            sat_steps,
            &sat_ref[..],
            Some(&small_ref[..]),
            attitude_error as fn(&[f64], &[f64]) -> f64,
        )
    };
    sweep(&small("f64"), &|| Small::new(quiet()), small_x0, &mut rows);
    sweep(
        &small("f32"),
        &|| SmallF32::new(quiet()),
        to_f32(small_x0),
        &mut rows,
    );
    let thrust = study(
        "satellite-thrusters",
        "f64",
        t_sat,
        sat_steps,
        &thrust_ref[..],
        None,
        attitude_error,
    );
    sweep(&thrust, &|| Sat::new(Figure8::new()), sat_x0, &mut rows);
    let chain = |float| {
        study(
            "chain-spatial-5",
            float,
            t_chain,
            chain_steps,
            &chain_ref[..],
            None,
            coordinate_error as fn(&[f64], &[f64]) -> f64,
        )
    };
    sweep(&chain("f64"), &Chain5::new, chain5_x0(), &mut rows);
    sweep(
        &chain("f32"),
        &Chain5F32::new,
        to_f32(chain5_x0()),
        &mut rows,
    );
    let stiff = |float| {
        study(
            "chain-spatial-3-stiff",
            float,
            t_stiff,
            stiff_steps,
            &stiff_ref[..],
            None,
            coordinate_error as fn(&[f64], &[f64]) -> f64,
        )
    };
    sweep(&stiff("f64"), &Stiff::new, stiff_x0(), &mut rows);
    sweep(&stiff("f32"), &StiffF32::new, to_f32(stiff_x0()), &mut rows);

    // With the thrusters on, how far apart do RK4 runs at h <= 10 ms land?
    let chatter = rows
        .iter()
        .filter(|r| r.study == "satellite-thrusters" && r.method == Method::Rk4)
        .filter(|r| r.status == "ok" && r.setting <= 0.01 * (1.0 + 1e-9))
        .map(|r| r.error)
        .fold(0.0, f64::max);
    println!();
    println!(
        "Thrusters on: RK4 runs at h <= 10 ms end up to {chatter:.1e} rad from RK4 at h = 10 us"
    );

    // ---------------------------------------------------------------- files
    let csv = folder.join("results.csv");
    write_csv(&csv, &rows)?;
    let mut files = vec![csv];
    let plots: [Plot<'_>; 5] = [
        (
            "satellite",
            "Satellite slew, thrusters off: bus attitude error at 15 s",
            "max |error| of q4, q5, q6 [rad]",
            None,
        ),
        (
            "satellite-small",
            "Small-variable satellite vs the full model's reference, 15 s",
            "max |error| of q4, q5, q6 [rad]",
            Some(("small-model error", small_model_error)),
        ),
        (
            "satellite-thrusters",
            "Satellite slew with bang-bang thrusters: attitude error at 15 s",
            "max |error| of q4, q5, q6 [rad]",
            None,
        ),
        (
            "chain-spatial-5",
            "chain-spatial-5: coordinate error at 5 s",
            "max |error| of q1..q5 [rad]",
            None,
        ),
        (
            "chain-spatial-3-stiff",
            "chain-spatial-3, joint stiffness x 1e4: coordinate error at 1 s",
            "max |error| of q1..q3 [rad]",
            None,
        ),
    ];
    for (study, title, label, floor) in plots {
        files.extend(plot_study(&folder, study, title, label, &rows, floor)?);
    }

    // ---------------------------------------------------------------- scenes
    println!();
    println!("Scene options on the satellite (slew, RK4 h = 1 ms, 15 s):");
    let mut scenes = vec![
        fly_scene::<_, 20>(
            "full (satellite.sim)",
            Sat::new,
            Sat::DERIVATIVE_OPS,
            Sat::OUTPUT_OPS,
        ),
        fly_scene::<_, 20>(
            "small = [B, E, F]",
            Small::new,
            Small::DERIVATIVE_OPS,
            Small::OUTPUT_OPS,
        ),
    ];
    {
        use scene::*;
        type Bus = small_bus::SmallBus<Figure8>;
        type Boom = small_boom::SmallBoom<Figure8>;
        type Angles = small_angles::SmallAngles<Figure8>;
        type T1 = small_threshold1::SmallThreshold1<Figure8>;
        type T3 = small_threshold3::SmallThreshold3<Figure8>;
        type Att = attitude::Attitude<Figure8>;
        type LockAll = rigid_boom_all::RigidBoomAll<Figure8>;
        type Lock = rigid_boom::RigidBoom<Figure8>;
        scenes.push(fly_scene::<_, 20>(
            "small = [B]",
            Bus::new,
            Bus::DERIVATIVE_OPS,
            Bus::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 20>(
            "small = [E, F]",
            Boom::new,
            Boom::DERIVATIVE_OPS,
            Boom::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 20>(
            "small = [q4, q5, q6, q9, q10]",
            Angles::new,
            Angles::DERIVATIVE_OPS,
            Angles::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 20>(
            "small = [B, E, F], threshold = 1",
            T1::new,
            T1::DERIVATIVE_OPS,
            T1::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 20>(
            "small = [B, E, F], threshold = 3",
            T3::new,
            T3::DERIVATIVE_OPS,
            T3::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 20>(
            "outputs = [roll, pitch, yaw]",
            Att::new,
            Att::DERIVATIVE_OPS,
            Att::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 16>(
            "lock = [q9, q10]",
            LockAll::new,
            LockAll::DERIVATIVE_OPS,
            LockAll::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 16>(
            "lock = [q9, q10], outputs = [roll, pitch, yaw]",
            Lock::new,
            Lock::DERIVATIVE_OPS,
            Lock::OUTPUT_OPS,
        ));
    }
    scenes.push(fly_scene::<_, 20>(
        "float = f32",
        SatF32::new,
        SatF32::DERIVATIVE_OPS,
        SatF32::OUTPUT_OPS,
    ));
    scenes.push(fly_scene::<_, 20>(
        "small = [B, E, F], float = f32",
        SmallF32::new,
        SmallF32::DERIVATIVE_OPS,
        SmallF32::OUTPUT_OPS,
    ));
    // Timing passes interleaved over the scenes, keeping each scene's best:
    // load from other processes only ever adds time.
    for _ in 0..7 {
        for s in &mut scenes {
            s.ns_per_call = s.ns_per_call.min((s.timer)());
        }
    }
    let largest_difference = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        a.iter()
            .zip(b)
            .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
            .fold(0.0, f64::max)
    };
    let full_attitude = scenes[0].attitude.clone();
    let full_quiet = scenes[0].attitude_quiet.clone();
    for s in &mut scenes {
        s.diff = largest_difference(&s.attitude, &full_attitude);
        s.diff_quiet = largest_difference(&s.attitude_quiet, &full_quiet);
    }
    let peak = |attitude: &[[f64; 3]]| {
        attitude
            .iter()
            .flat_map(|a| a.iter().map(|v| v.abs()))
            .fold(0.0, f64::max)
    };
    let (peak_on, peak_off) = (peak(&full_attitude), peak(&full_quiet));
    let mut scene_table = String::new();
    let _ = writeln!(
        scene_table,
        "| scene | float | states | `derivatives` ops (+ × ÷ fn) | `outputs` ops | ns / call | max \\|Δ attitude\\| vs full, thrusters on [rad] | thrusters off [rad] |"
    );
    let _ = writeln!(
        scene_table,
        "| --- | --- | ---: | --- | ---: | ---: | ---: | ---: |"
    );
    for s in &scenes {
        let d = s.derivative_ops;
        let diff = |v: f64| {
            if v == 0.0 {
                "0".to_string()
            } else {
                format!("{v:.1e}")
            }
        };
        let _ = writeln!(
            scene_table,
            "| `{}` | {} | {} | {} ({} + {} + {} + {}) | {} | {:.0} | {} | {} |",
            s.label,
            s.float,
            s.states,
            d.total(),
            d.adds,
            d.muls,
            d.divs,
            d.funcs,
            s.output_ops.total(),
            s.ns_per_call,
            diff(s.diff),
            diff(s.diff_quiet),
        );
    }
    print!("{scene_table}");
    println!(
        "(largest |attitude| of the full model over the slew: {peak_on:.2e} rad with the thrusters, {peak_off:.2e} rad without)"
    );

    // ---------------------------------------------------------------- summary
    let mut md = String::new();
    let _ = writeln!(md, "# Speed against accuracy: measurements\n");
    let _ = writeln!(
        md,
        "Generated by `cargo run --release --example tradeoff` (see the example's documentation for the set-up). \
         Error: largest absolute error at the end time, of the bus attitude q4..q6 (satellite, 15 s) or of the \
         coordinates (chains), against a Dormand–Prince reference at rtol = atol = 1e-12 in f64 \
         (satellite with thrusters: against RK4 at h = 10 µs). Cost: derivative evaluations, and wall time \
         on the machine that ran it (median of {REPEATS}).\n"
    );
    let _ = writeln!(
        md,
        "Own error of each reference (against a second, tighter run):\n"
    );
    for (label, e) in &reference_notes {
        let _ = writeln!(md, "- {label}: {e:.1e}");
    }
    let _ = writeln!(
        md,
        "- small-variable satellite against the full model (thrusters off, 15 s): {small_model_error:.2e} rad"
    );
    let _ = writeln!(
        md,
        "- thrusters on: RK4 runs at any h ≤ 10 ms end up to {chatter:.1e} rad from RK4 at h = 10 µs \
         (the bang-bang switching times move with the step: the attitude at 15 s is defined to about that)\n"
    );
    let _ = writeln!(
        md,
        "## The cheapest run reaching an error level\n\nEach cell: evaluations (wall time) of the cheapest setting whose error is at most the level; `—` if none did.\n"
    );
    for (study, _, _, _) in plots {
        for float in ["f64", "f32"] {
            if !rows.iter().any(|r| r.study == study && r.float == float) {
                continue;
            }
            let _ = writeln!(md, "### {study}, {float}\n");
            let heads: Vec<String> = LEVELS.iter().map(|l| format!("≤ {l:.0e}")).collect();
            let _ = writeln!(
                md,
                "| method | {} | smallest error reached |",
                heads.join(" | ")
            );
            let _ = writeln!(md, "| --- |{} --- |", " --- |".repeat(LEVELS.len()));
            for method in Method::ALL {
                let mut line = format!("| {} |", method.name());
                for target in LEVELS {
                    match cheapest(&rows, study, float, method, target) {
                        Some(r) => {
                            let setting = if method == Method::Dopri {
                                format!("tol {:.0e}", r.setting)
                            } else {
                                format!("h {:.0e}", r.setting)
                            };
                            let _ = write!(
                                line,
                                " {} ({:.2} ms, {setting}) |",
                                r.evaluations,
                                r.wall_s * 1e3
                            );
                        }
                        None => line.push_str(" — |"),
                    }
                }
                let best = rows
                    .iter()
                    .filter(|r| {
                        r.study == study
                            && r.float == float
                            && r.method == method
                            && r.status == "ok"
                    })
                    .map(|r| r.error)
                    .fold(f64::INFINITY, f64::min);
                let failures = rows
                    .iter()
                    .filter(|r| {
                        r.study == study
                            && r.float == float
                            && r.method == method
                            && r.status != "ok"
                    })
                    .count();
                if best.is_finite() {
                    let _ = write!(line, " {best:.1e}");
                } else {
                    line.push_str(" —");
                }
                if failures > 0 {
                    let _ = write!(
                        line,
                        " ({failures} setting{} failed or diverged)",
                        if failures == 1 { "" } else { "s" }
                    );
                }
                let _ = writeln!(md, "{line} |");
            }
            let _ = writeln!(md);
        }
    }
    let _ = writeln!(
        md,
        "## Scene options on the satellite\n\nThe slew with the Figure 8 user code, thrusters on and off, RK4 at h = 1 ms for 15 s. \
         ns / call: median over 101 rounds of `derivatives()` at 500 states of the scene's own slew \
         (including the Figure 8 user code), best of 7 passes interleaved over the scenes. Largest |attitude| of the full model over the slew: {peak_on:.2e} rad with the thrusters, {peak_off:.2e} rad without.\n"
    );
    md.push_str(&scene_table);
    let summary = folder.join("summary.md");
    std::fs::write(&summary, md)?;
    files.push(summary);

    println!();
    println!("Cheapest run reaching each error level (evaluations):");
    print!("{:<22} {:<4} {:<7}", "study", "f", "method");
    for level in LEVELS {
        print!(" {:>12}", format!("<= {level:.0e}"));
    }
    println!();
    for (study, _, _, _) in plots {
        for float in ["f64", "f32"] {
            for method in Method::ALL {
                if !rows
                    .iter()
                    .any(|r| r.study == study && r.float == float && r.method == method)
                {
                    continue;
                }
                print!("{:<22} {:<4} {:<7}", study, float, method.name());
                for level in LEVELS {
                    let cell = cheapest(&rows, study, float, method, level)
                        .map_or("-".to_string(), |r| r.evaluations.to_string());
                    print!(" {cell:>12}");
                }
                println!();
            }
        }
    }
    println!();
    println!("Written to {}:", folder.display());
    for f in &files {
        println!("  {}", f.file_name().unwrap_or_default().to_string_lossy());
    }
    println!("Total time {:.1} s", started.elapsed().as_secs_f64());
    Ok(())
}
