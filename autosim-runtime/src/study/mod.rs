//! Studies (feature `study`): one model run over a table of cases on every
//! core, results as a table in memory or in shards on disk.
//!
//! A study is fully determined by four things: a model (a function that
//! makes one), a [`Cases`] table (grids, rows, random draws with a stream
//! per draw), a [`Task`] run for each case ([`Simulate`], [`Modes`],
//! [`Custom`]), and the range of case indices run. Each case starts from
//! a freshly made model and a fresh stepper, so its values depend on its
//! index alone: a study run serially, on any number of threads, or in
//! chunks on different machines gives the same results bit for bit
//! (chunks concatenated with [`Results::append`]).
//!
//! ```
//! use autosim_runtime::study::{Cases, Keep, Method, Parallelism, Simulate, Study};
//! use autosim_runtime::{Model, ModelError, RunSettings};
//!
//! /// x'' = -k x (with k a parameter).
//! struct Spring { k: f64 }
//! impl Model for Spring {
//!     type Float = f64;
//!     type State = [f64; 2];
//!     type Outputs = [f64; 0];
//!     const NAME: &'static str = "Spring";
//!     const STATE_NAMES: &'static [&'static str] = &["x", "v"];
//!     const STATE_UNITS: &'static [&'static str] = &["m", "m/s"];
//!     const PARAMETER_NAMES: &'static [&'static str] = &["k"];
//!     fn derivatives(&mut self, _t: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
//!         *dx = [x[1], -self.k * x[0]];
//!         Ok(())
//!     }
//!     fn parameter_values(&self, p: &mut [f64]) { p[0] = self.k; }
//!     fn set_parameter_values(&mut self, p: &[f64]) { self.k = p[0]; }
//! }
//!
//! # fn main() -> Result<(), autosim_runtime::study::StudyError> {
//! // Stiffness 1, 4, 9 times initial displacement 0.1, 0.2: six cases.
//! let cases = Cases::new().grid("k", &[1.0, 4.0, 9.0])?.grid("x", &[0.1, 0.2])?;
//! let settings = RunSettings::new(0.0, 1.0, 0.001, 0.1);
//! let task = Simulate::new(settings, Method::Rk4, Keep::new().final_state())?;
//! let study = Study::new(|| Spring { k: 0.0 }, cases, task).parallelism(Parallelism::Threads(2));
//! let results = study.run_cases(0..6)?;
//! assert_eq!(results.failures(), 0);
//! let x_end = results.field("final:x").unwrap();
//! // x(1) = x0 cos(√k): case 5 is k = 9, x0 = 0.2.
//! assert!((x_end[5] - 0.2 * 3f64.cos()).abs() < 1e-9);
//! // The same study serially, bit for bit:
//! assert_eq!(study.parallelism(Parallelism::Serial).run_cases(0..6)?, results);
//! # Ok(())
//! # }
//! ```
//!
//! [`Study::run_in`] writes the results as shards in a folder (CSV, or
//! Parquet with feature `parquet`), resumes an interrupted study, and
//! [`StudyDir`] reads a finished one back.
//!
//! # Lockstep
//!
//! A [`Simulate`] task, with any [`Method`] (the fixed-step ones take the
//! same times in every case, each Adams–Bashforth–Moulton case with its
//! own derivative history; each Dormand–Prince case takes its own steps,
//! at its own times), of a model that allows it
//! ([`Model::LOCKSTEP`]: models generated with the `lanes` option) and has
//! no events or discrete variables, in a study without a
//! [`setup`](Study::setup) function, integrates four neighbouring cases
//! of the table together, whatever their parameters, inputs and initial
//! states, each on its own model: each stage evaluates their states in
//! one [`Model::derivatives_each`] call (four states per call of
//! `derivatives_lanes`, each lane reading its own case's parameters,
//! constants and inputs). The results are the same bits as
//! one case at a time, failures included (a case that fails is run again
//! alone, and fails as it does alone); other studies run one case at a
//! time. [`Study::lockstep`] turns it off.

mod cancel;
mod cases;
mod csv_shard;
mod error;
mod execute;
mod lockstep;
mod method;
#[cfg(feature = "analysis")]
mod modes;
#[cfg(feature = "parquet")]
mod parquet_shard;
mod progress;
mod results;
mod simulate;
mod store;
mod targets;
mod task;

pub use cancel::Cancel;
pub use cases::{Cases, Distribution};
pub use error::StudyError;
pub use method::{Method, MethodStepper};
#[cfg(feature = "analysis")]
pub use modes::Modes;
pub use results::{Layout, Results};
pub use simulate::{Keep, Simulate, Statistic};
pub use store::{Format, StudyDir, StudySummary};
pub use task::{CaseError, Custom, Field, Task};

use std::boxed::Box;
use std::string::{String, ToString};
use std::vec::Vec;

use crate::Model;

/// A setup function: the values of the columns it reads, the model and
/// the initial state, after the table's parameters, inputs and states are
/// set.
type SetupFn<M> =
    Box<dyn Fn(&[f64], &mut M, &mut <M as Model>::State) -> Result<(), CaseError> + Send + Sync>;

/// Where a study's cases run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Parallelism {
    /// One case after the other on the calling thread.
    Serial,
    /// On a pool of this many threads (made for the call).
    Threads(usize),
    /// On rayon's global pool (every core, or `RAYON_NUM_THREADS`).
    #[default]
    AllCores,
}

/// A study: a model, a table of cases, and a task run for each case.
///
/// The columns of the table set the model's parameters, inputs, initial
/// states and discrete variables' initial values by name
/// (`parameter:NAME`, `input:NAME`, `state:NAME`, `discrete:NAME` when a
/// name is ambiguous); columns read by a [`setup`](Study::setup) function
/// can set anything else.
pub struct Study<M: Model, F, T> {
    make_model: F,
    cases: Cases,
    task: T,
    setup_columns: Vec<String>,
    setup: Option<SetupFn<M>>,
    parallelism: Parallelism,
    progress: bool,
    lockstep: bool,
    cancel: Option<Cancel>,
}

impl<M, F, T> Study<M, F, T>
where
    M: Model,
    F: Fn() -> M + Sync,
    T: Task<M>,
{
    /// A study of the models `make_model` makes (one per case, so nothing
    /// a model keeps leaks from one case into the next) over `cases`,
    /// running `task` for each, on every core, with a progress bar on a
    /// terminal.
    pub fn new(make_model: F, cases: Cases, task: T) -> Study<M, F, T> {
        Study {
            make_model,
            cases,
            task,
            setup_columns: Vec::new(),
            setup: None,
            parallelism: Parallelism::AllCores,
            progress: true,
            lockstep: true,
            cancel: None,
        }
    }

    /// Runs `setup(values, model, x)` for every case after the table's
    /// parameters, inputs and initial states are set, with `values` the
    /// case's values of `columns` (in that order): for what a column
    /// sets that is not a model value (a forward speed that sets a wheel's
    /// rate; a trim).
    pub fn setup(
        mut self,
        columns: &[&str],
        setup: impl Fn(&[f64], &mut M, &mut M::State) -> Result<(), CaseError> + Send + Sync + 'static,
    ) -> Study<M, F, T> {
        self.setup_columns = columns.iter().map(|c| c.to_string()).collect();
        self.setup = Some(Box::new(setup));
        self
    }

    /// Where the cases run (all cores by default).
    pub fn parallelism(mut self, parallelism: Parallelism) -> Study<M, F, T> {
        self.parallelism = parallelism;
        self
    }

    /// Changes where the cases run (see [`Study::parallelism`]).
    pub fn set_parallelism(&mut self, parallelism: Parallelism) {
        self.parallelism = parallelism;
    }

    /// Whether to show a progress bar (cases, cases per second, ETA) on
    /// standard error. On by default; never drawn when standard error is
    /// not a terminal.
    pub fn progress(mut self, progress: bool) -> Study<M, F, T> {
        self.progress = progress;
        self
    }

    /// Whether cases that can run in lockstep do (see [the module
    /// docs](self#lockstep)); on by default. The results are the same
    /// either way, bit for bit: off is for measuring what it buys.
    pub fn lockstep(mut self, lockstep: bool) -> Study<M, F, T> {
        self.lockstep = lockstep;
        self
    }

    /// Stops the study when `cancel` is set (see [`Cancel`]): no new case
    /// starts, and the run returns [`StudyError::Cancelled`].
    pub fn cancel_with(mut self, cancel: Cancel) -> Study<M, F, T> {
        self.cancel = Some(cancel);
        self
    }

    /// Whether the study was given a [`Cancel`] that is set.
    fn cancelled(&self) -> bool {
        self.cancel.as_ref().is_some_and(Cancel::is_cancelled)
    }

    /// Turns lockstep on or off (see [`Study::lockstep`]).
    pub fn set_lockstep(&mut self, lockstep: bool) {
        self.lockstep = lockstep;
    }

    /// The case table.
    pub fn cases(&self) -> &Cases {
        &self.cases
    }

    /// The columns of the results.
    pub fn layout(&self) -> Layout {
        Layout {
            case_columns: self.cases.names().to_vec(),
            fields: self.task.fields(),
        }
    }

    /// What identifies this study in a folder's manifest: the model's
    /// name and [fingerprint](Model::FINGERPRINT) (a generated model's
    /// code), what the function that makes the model gives (fingerprints
    /// of the made model's parameter, input and discrete values and of
    /// its initial state), the table, the columns' targets and the task.
    /// Not what a setup function does, nor the inside of user code the
    /// model calls, nor the runtime library: a study resumed after those
    /// change mixes old and new results.
    pub fn describe(&self) -> String {
        std::format!(
            "model {} {:016x}\n{}\n{}setup {:?}\n{}\n",
            M::NAME,
            M::FINGERPRINT,
            self.made(),
            self.cases.describe(),
            self.setup_columns,
            self.task.describe()
        )
    }

    /// [`made`] of a model the study makes (a function that panics
    /// there is described as such: its cases fail the same way).
    fn made(&self) -> String {
        let made = || made(&(self.make_model)());
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(made))
            .unwrap_or_else(|_| "made: the function that makes the model panicked".to_string())
    }
}

/// The values a study's function that makes the model gives, as
/// fingerprints for the manifest: `made parameters … inputs … discrete …
/// state …`.
fn made<M: Model>(model: &M) -> String {
    use crate::Float;
    let values = |n: usize, read: &dyn Fn(&mut [M::Float])| {
        let mut v = std::vec![M::Float::ZERO; n];
        read(&mut v);
        cases::hash(&v.iter().map(|x| x.to_f64()).collect::<Vec<f64>>())
    };
    let state: Vec<f64> = model
        .initial_state()
        .as_ref()
        .iter()
        .map(|x| x.to_f64())
        .collect();
    std::format!(
        "made parameters {:016x} inputs {:016x} discrete {:016x} state {:016x}",
        values(M::PARAMETER_NAMES.len(), &|v| model.parameter_values(v)),
        values(M::INPUT_NAMES.len(), &|v| model.input_values(v)),
        values(M::DISCRETE_NAMES.len(), &|v| model.discrete_values(v)),
        cases::hash(&state)
    )
}
