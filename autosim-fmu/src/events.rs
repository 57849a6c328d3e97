//! The events of a built FMU library: its model's event indicators and
//! discrete variables, asked from the library itself (the
//! `autosim_fmi_event_interface` function every `export_fmi2!` writes), so
//! that whatever implements the `Model` trait's event items (a generated
//! model or a hand-written one in a user crate) gets them in its
//! `modelDescription.xml`.

use crate::FmuError;
use autosim_fmi::EventInterface;
use std::path::Path;

/// `autosim_fmi_event_interface(buffer, length) -> full length`.
type Query = unsafe extern "C" fn(*mut u8, usize) -> usize;

/// The event interface of the library at `path` (built for this machine).
///
/// # Errors
/// The library cannot be loaded, has no `autosim_fmi_event_interface`
/// (built with another `autosim-fmi`), or answers something else.
pub(crate) fn of_library(path: &Path) -> Result<EventInterface, FmuError> {
    let fail = |why: String| {
        FmuError::Cargo(format!(
            "{}: cannot read the model's events from the library: {why}",
            path.display()
        ))
    };
    // SAFETY: the library was just built by cargo from a crate calling
    // `autosim_fmi::export_fmi2!`; loading it runs no code of the model.
    let library = unsafe { libloading::Library::new(path) }.map_err(|e| fail(e.to_string()))?;
    // SAFETY: `export_fmi2!` defines the symbol with this signature.
    let query = unsafe { library.get::<Query>(b"autosim_fmi_event_interface\0") }
        .map_err(|e| fail(e.to_string()))?;
    // SAFETY: a null buffer of length 0 asks for the length; then a
    // buffer of that length.
    let n = unsafe { query(std::ptr::null_mut(), 0) };
    let mut text = vec![0u8; n];
    let written = unsafe { query(text.as_mut_ptr(), n) };
    if written != n {
        return Err(fail("its answer changed length".into()));
    }
    let text = String::from_utf8(text).map_err(|e| fail(e.to_string()))?;
    EventInterface::from_text(&text).map_err(fail)
}
