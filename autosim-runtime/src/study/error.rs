//! Why a study could not run (a failed case is not an error of the study:
//! it is recorded with its [`CaseError`](super::CaseError)).

use std::path::PathBuf;
use std::string::String;
use std::vec::Vec;

use crate::IntegrationError;

/// Why a study could not be set up, run, written or read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StudyError {
    /// The case table is malformed (the reason names the column).
    #[error("case table: {0}")]
    InvalidCases(String),
    /// A column of the case table sets nothing.
    #[error("column `{name}` of the case table: {why} (model {model})")]
    UnknownColumn {
        /// The column.
        name: String,
        /// The model's name.
        model: &'static str,
        /// Why it does not resolve.
        why: String,
    },
    /// A bare column name is several things of the model.
    #[error("column `{name}` of the case table is ambiguous: it names a {} (write `KIND:{name}`)", kinds.join(" and a "))]
    AmbiguousColumn {
        /// The column.
        name: String,
        /// What it names (`parameter`, `input`, `state`, `setup`).
        kinds: Vec<&'static str>,
    },
    /// A quantity to keep is not a state, output or discrete variable of
    /// the model.
    #[error("`{name}` is not a state, output or discrete variable of model {model}; it has: {}", known.join(", "))]
    UnknownQuantity {
        /// The name given.
        name: String,
        /// The model's name.
        model: &'static str,
        /// The names it has.
        known: Vec<String>,
    },
    /// A time of [`Keep::at`](super::Keep::at) is not an output time of
    /// the run.
    #[error(
        "t = {t} is not an output time of the run (the start, the stop, or start + k·output_interval)"
    )]
    NotAnOutputTime {
        /// The time given.
        t: f64,
    },
    /// The run settings or the method's tolerances are invalid.
    #[error("{0}")]
    InvalidSettings(#[from] IntegrationError),
    /// Cases out of the table's range were asked for.
    #[error("cases {start}..{end} are not all in the table of {len} cases")]
    OutOfRange {
        /// First case asked for.
        start: u64,
        /// End of the range asked for.
        end: u64,
        /// Cases in the table.
        len: u64,
    },
    /// The thread pool could not be made.
    #[error("thread pool: {0}")]
    ThreadPool(String),
    /// A file or folder could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// A folder holds a different study (resuming it would mix results).
    #[error("{} holds a different study (its manifest differs: {what}); use another folder or delete it", path.display())]
    Mismatch {
        /// The folder.
        path: PathBuf,
        /// What differs.
        what: String,
    },
    /// A shard or manifest could not be parsed or does not match the
    /// study's layout.
    #[error("corrupt study data: {0}")]
    Corrupt(String),
    /// The format is not available (Parquet without feature `parquet`).
    #[error("{0}")]
    Unsupported(String),
    /// The study's [`Cancel`](super::Cancel) was set: it stopped before
    /// its last case (a folder keeps the shards written before).
    #[error("the study was cancelled")]
    Cancelled,
}

impl StudyError {
    pub(super) fn io(path: impl Into<PathBuf>) -> impl FnOnce(std::io::Error) -> StudyError {
        let path = path.into();
        move |source| StudyError::Io { path, source }
    }
}
