//! Studies from Python: the runtime's [`Study`] of one model, built from
//! plain data (the case table, run settings, the method by name, what to
//! keep) and run on a range of cases. The study is the runtime's own, so a
//! case gives the same bits from Python, from Rust, serially, on threads
//! or in chunks on other machines.

use core::ops::Range;
use std::path::Path;

use autosim_runtime::RunSettings;
use autosim_runtime::integrate::AbmOrder;
use autosim_runtime::study::{
    Cancel, Cases, Distribution, Format, Keep, Method, Parallelism, Results, Simulate, Statistic,
    Study, StudyDir, StudyError, StudySummary,
};

use crate::Generated;

/// One factor of a case table as Python sends it.
pub enum Factor {
    /// A grid axis: a column and its values.
    Grid(String, Vec<f64>),
    /// Given rows: the columns and their values, row-major.
    Rows(Vec<String>, Vec<f64>),
    /// Random draws: count, seed, and per column `(name, kind, a, b)`
    /// with kind `uniform` (a = low, b = high) or `normal` (a = mean,
    /// b = standard deviation).
    Random(u64, u64, Vec<(String, String, f64, f64)>),
}

/// What to keep, as Python sends it.
#[derive(Default)]
pub struct KeepSpec {
    /// Keep the final state.
    pub final_state: bool,
    /// `(time, quantity)` pairs.
    pub at: Vec<(f64, String)>,
    /// `(quantity, statistic)` with statistic `min`, `max`, `mean`, `rms`
    /// or `maxabs`.
    pub statistics: Vec<(String, String)>,
    /// Quantities whose whole history is kept.
    pub history: Vec<String>,
}

/// A simulation study of any model, resolved into the runtime's types
/// (what [`crate::Engine::study`] runs).
pub struct Plan {
    /// The case table.
    pub cases: Cases,
    /// Start, stop, step, output interval, step limit.
    pub settings: RunSettings<f64>,
    /// The integrator.
    pub method: Method,
    /// What each case keeps.
    pub keep: Keep,
    /// Where the cases run.
    pub parallelism: Parallelism,
    /// Whether to draw a progress bar (on a terminal only).
    pub progress: bool,
    /// Stops the study (Ctrl-C: see [`crate::interrupt`]).
    pub cancel: Cancel,
}

/// The integrators a study runs, by the names Python uses (SDIRK3 is not
/// among them: the runtime's `Simulate` takes explicit methods).
pub const STUDY_METHODS: [&str; 6] = ["dopri", "rk4", "heun", "euler", "abm4", "abm2"];

/// The runtime's [`Method`] named `name`.
///
/// # Errors
/// A sentence naming the methods when `name` is not one.
pub fn method(name: &str, rtol: f64, atol: f64) -> Result<Method, String> {
    Ok(match name {
        "dopri" => Method::DormandPrince { rtol, atol },
        "rk4" => Method::Rk4,
        "heun" => Method::Heun,
        "euler" => Method::Euler,
        "abm4" => Method::AdamsBashforthMoulton(AbmOrder::Four),
        "abm2" => Method::AdamsBashforthMoulton(AbmOrder::Two),
        other => {
            return Err(format!(
                "a study cannot run method {other:?}: use one of {}",
                STUDY_METHODS.join(", ")
            ));
        }
    })
}

/// The case table of `factors`.
///
/// # Errors
/// The runtime's reason (a repeated column, no values, a value that is not
/// finite, a bad distribution), or an unknown distribution kind.
pub fn cases(factors: &[Factor]) -> Result<Cases, String> {
    let mut cases = Cases::new();
    for factor in factors {
        cases = match factor {
            Factor::Grid(name, values) => cases.grid(name, values),
            Factor::Rows(names, values) => {
                let names: Vec<&str> = names.iter().map(String::as_str).collect();
                cases.rows(&names, values)
            }
            Factor::Random(count, seed, columns) => {
                let mut drawn = Vec::with_capacity(columns.len());
                for (name, kind, a, b) in columns {
                    let d = match kind.as_str() {
                        "uniform" => Distribution::uniform(*a, *b),
                        "normal" => Distribution::normal(*a, *b),
                        other => {
                            return Err(format!(
                                "column `{name}`: unknown distribution {other:?} (uniform or normal)"
                            ));
                        }
                    };
                    drawn.push((name.as_str(), d));
                }
                cases.random(*count, *seed, &drawn)
            }
        }
        .map_err(|e| e.to_string())?;
    }
    Ok(cases)
}

/// The runtime's [`Keep`] of `spec`.
///
/// # Errors
/// An unknown statistic.
pub fn keep(spec: &KeepSpec) -> Result<Keep, String> {
    let mut keep = Keep::new();
    if spec.final_state {
        keep = keep.final_state();
    }
    for (t, quantity) in &spec.at {
        keep = keep.at(&[*t], &[quantity.as_str()]);
    }
    for (quantity, statistic) in &spec.statistics {
        let s = match statistic.as_str() {
            "min" => Statistic::Min,
            "max" => Statistic::Max,
            "mean" => Statistic::Mean,
            "rms" => Statistic::Rms,
            "maxabs" => Statistic::MaxAbs,
            other => {
                return Err(format!(
                    "unknown statistic {other:?}: use min, max, mean, rms or maxabs"
                ));
            }
        };
        keep = keep.statistic(quantity, s);
    }
    let history: Vec<&str> = spec.history.iter().map(String::as_str).collect();
    Ok(keep.history(&history))
}

/// `threads` as Python gives it: `None` every core, 1 serial, `n` a pool
/// of `n`.
pub fn parallelism(threads: Option<usize>) -> Parallelism {
    match threads {
        None => Parallelism::AllCores,
        Some(0 | 1) => Parallelism::Serial,
        Some(n) => Parallelism::Threads(n),
    }
}

/// The study of `plan` on copies of `model` (its parameters and inputs as
/// they are now: each case starts from a fresh copy).
fn study<M: Generated>(
    model: &M,
    plan: &Plan,
) -> Result<Study<M, impl Fn() -> M + Sync + use<M>, Simulate<M>>, StudyError> {
    let base = model.clone();
    let task = Simulate::<M>::new(plan.settings, plan.method, plan.keep.clone())?;
    Ok(Study::new(move || base.clone(), plan.cases.clone(), task)
        .parallelism(plan.parallelism)
        .progress(plan.progress)
        .cancel_with(plan.cancel.clone()))
}

/// What Python asks of a study of `M`.
pub enum Request<'a> {
    /// Run cases `range` into memory.
    Run(Range<u64>),
    /// Run every case into shards in a folder (CSV), resuming.
    RunIn(&'a Path, u64),
}

/// What a [`Request`] gave.
pub enum Outcome {
    /// The results in memory.
    Results(Results),
    /// What a run into a folder did.
    Summary(StudySummary),
}

/// Runs `request` on the study of `plan` over copies of `model`.
///
/// # Errors
/// Why the study could not run (a column that sets nothing, a quantity
/// the model does not have, bad settings, an I/O error); failed cases are
/// recorded in the results, not errors.
pub fn run<M: Generated>(model: &M, plan: &Plan, request: Request<'_>) -> Result<Outcome, String> {
    let study = study(model, plan).map_err(|e| e.to_string())?;
    match request {
        Request::Run(range) => study.run_cases(range).map(Outcome::Results),
        Request::RunIn(folder, shard_size) => study
            .run_in(folder, Format::Csv, shard_size)
            .map(Outcome::Summary),
    }
    .map_err(|e| e.to_string())
}

/// The study's description (its identity in a folder's manifest), the
/// output times of every run, and the layout of its results; checks that
/// every column sets something.
///
/// # Errors
/// As [`run`].
pub fn describe<M: Generated>(
    model: &M,
    plan: &Plan,
) -> Result<(String, Vec<f64>, autosim_runtime::study::Layout), String> {
    let study = study(model, plan).map_err(|e| e.to_string())?;
    // An empty range resolves the columns without running anything.
    study.run_cases(0..0).map_err(|e| e.to_string())?;
    let times = Simulate::<M>::new(plan.settings, plan.method, plan.keep.clone())
        .map_err(|e| e.to_string())?
        .output_times();
    Ok((study.describe(), times, study.layout()))
}

/// The results of a study written to `folder` (every shard), and its
/// manifest's description.
///
/// # Errors
/// No manifest, a missing or corrupt shard.
pub fn read(folder: &Path) -> Result<(Results, String), String> {
    let dir = StudyDir::open(folder).map_err(|e| e.to_string())?;
    let description = dir.description().to_string();
    Ok((dir.read_all().map_err(|e| e.to_string())?, description))
}
