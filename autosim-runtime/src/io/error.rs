//! Errors of the file formats.

use std::format;
use std::prelude::rust_2024::*;

use std::path::PathBuf;

/// Why a parameter file could not be written, read or applied.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ParameterError {
    /// The file could not be opened, read or written.
    #[error("parameter file {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The text is not valid TOML.
    #[error("parameter file is not valid TOML: {message}")]
    Syntax {
        /// The TOML parser's message, with line and column.
        message: String,
    },
    /// A key is not a parameter of the model.
    #[error(
        "`{key}` is not a parameter of model {model}{}",
        match suggestion {
            Some(s) => format!("; did you mean `{s}`?"),
            None => format!("; its parameters are: {}", known.join(", ")),
        }
    )]
    UnknownParameter {
        /// The model's name.
        model: &'static str,
        /// The key as written in the file.
        key: String,
        /// The closest parameter name, if one is close.
        suggestion: Option<&'static str>,
        /// All parameter names of the model.
        known: &'static [&'static str],
    },
    /// A parameter's value is not a number.
    #[error("parameter `{key}` must be a number, but the file gives a {found}")]
    NotANumber {
        /// The parameter.
        key: String,
        /// The TOML type found instead (`"string"`, `"table"`, ...).
        found: &'static str,
    },
}

/// Why an output file (CSV or plot) could not be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OutputError {
    /// The file could not be created or written.
    #[error("output file {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// Writing a CSV row failed.
    #[cfg(feature = "csv")]
    #[error("CSV output: {0}")]
    Csv(#[from] csv::Error),
    /// A requested column does not exist.
    #[error(
        "no column `{name}` in the recording{}",
        match suggestion {
            Some(s) => format!("; did you mean `{s}`?"),
            None => String::new(),
        }
    )]
    UnknownColumn {
        /// The name asked for.
        name: String,
        /// The closest column name, if one is close.
        suggestion: Option<&'static str>,
    },
    /// The plot could not be drawn (no data, or a drawing failure).
    #[error("plot: {0}")]
    Plot(String),
}
