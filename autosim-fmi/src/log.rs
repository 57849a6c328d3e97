//! Messages to the importer through its logger callback.

use crate::ffi::{CallbackFunctions, Status};
use std::ffi::CString;

/// The log categories the FMU declares in `modelDescription.xml`, each
/// with its description.
pub const CATEGORIES: [(&str, &str); 2] = [
    (
        "logStatusError",
        "Calls that return fmi2Error or fmi2Fatal, with the reason",
    ),
    ("logCalls", "Every call of an fmi2 function"),
];

/// An instance's logger: its name, the importer's callback, and which
/// categories are on.
pub struct Log {
    name: CString,
    callbacks: CallbackFunctions,
    /// `loggingOn` of `fmi2Instantiate` / `fmi2SetDebugLogging`.
    on: bool,
    /// Per category of [`CATEGORIES`].
    categories: [bool; CATEGORIES.len()],
}

impl Log {
    /// A logger; with `on`, every category is on until
    /// `fmi2SetDebugLogging` names some.
    pub fn new(name: String, callbacks: CallbackFunctions, on: bool) -> Log {
        Log {
            name: c_string(name),
            callbacks,
            on,
            categories: [true; CATEGORIES.len()],
        }
    }

    /// The instance name.
    pub fn name(&self) -> &str {
        self.name.to_str().unwrap_or("")
    }

    /// `fmi2SetDebugLogging`: logging on or off, for the named categories
    /// (all when none are named). Unknown names are an error.
    pub fn configure(&mut self, on: bool, names: &[String]) -> Result<(), String> {
        let mut categories = [names.is_empty(); CATEGORIES.len()];
        for n in names {
            let k = CATEGORIES
                .iter()
                .position(|(c, _)| c == n)
                .ok_or_else(|| format!("unknown log category {n:?}"))?;
            categories[k] = true;
        }
        self.on = on;
        self.categories = if on { categories } else { [false; 2] };
        Ok(())
    }

    /// Logs a failed call. Errors are always passed on (an importer that
    /// gets fmi2Error should be able to say why).
    pub fn error(&self, status: Status, message: &str) {
        self.send(status, CATEGORIES[0].0, message);
    }

    /// Logs a call (category `logCalls`), when on.
    pub fn call(&self, message: impl FnOnce() -> String) {
        if self.on && self.categories[1] {
            self.send(Status::Ok, CATEGORIES[1].0, &message());
        }
    }

    fn send(&self, status: Status, category: &str, message: &str) {
        if let Some(logger) = self.callbacks.logger {
            let category = c_string(category.to_string());
            let message = c_string(message.to_string());
            // SAFETY: the importer's logger, called with the importer's
            // own environment pointer and NUL-terminated strings; the
            // message goes through "%s" so that `%` in it is not a format.
            unsafe {
                logger(
                    self.callbacks.component_environment,
                    self.name.as_ptr(),
                    status,
                    category.as_ptr(),
                    c"%s".as_ptr(),
                    message.as_ptr(),
                );
            }
        }
    }
}

/// A C string of `text`, interior NULs replaced.
fn c_string(text: String) -> CString {
    CString::new(text.replace('\0', " ")).unwrap_or_default()
}
