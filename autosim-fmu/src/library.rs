//! What a built FMU library says of itself, asked through the functions
//! every `export_fmi2!` writes besides FMI's: its model's event indicators
//! and discrete variables (`autosim_fmi_event_interface`), so that whatever
//! implements the `Model` trait's event items (a generated model or a
//! hand-written one in a user crate) gets them in its
//! `modelDescription.xml`; and the GUID it was built for
//! (`autosim_fmi_guid`), so that a library whose model is not the
//! description's is refused before it is packaged.

use crate::FmuError;
use autosim_fmi::EventInterface;
use std::path::Path;

/// `autosim_fmi_…(buffer, length) -> full length`: writes what fits of a
/// text into `buffer` and returns its length.
type Query = unsafe extern "C" fn(*mut u8, usize) -> usize;

/// What the library told.
pub(crate) struct Told {
    /// Its model's events.
    pub events: EventInterface,
    /// The GUID its `fmi2Instantiate` accepts.
    pub guid: String,
}

impl Told {
    /// Asks the library at `path` (built for this machine).
    ///
    /// # Errors
    /// The library cannot be loaded, lacks one of the functions (built
    /// with another `autosim-fmi`), or answers something else.
    pub fn of(path: &Path) -> Result<Told, FmuError> {
        let fail = |why: String| {
            FmuError::Cargo(format!(
                "{}: cannot ask the built library about its model: {why}",
                path.display()
            ))
        };
        // SAFETY: the library was just built by cargo from a crate calling
        // `autosim_fmi::export_fmi2!`; loading it runs no code of the model.
        let library = unsafe { libloading::Library::new(path) }.map_err(|e| fail(e.to_string()))?;
        let events = text(&library, b"autosim_fmi_event_interface\0").map_err(fail)?;
        let guid = text(&library, b"autosim_fmi_guid\0").map_err(fail)?;
        Ok(Told {
            events: EventInterface::from_text(&events).map_err(fail)?,
            guid,
        })
    }

    /// Refuses a library built for another description than the one of
    /// GUID `expected` (FMPy and every importer would refuse to
    /// instantiate it); `user_crate` names the crate it was built from.
    pub fn check_guid(&self, expected: &str, user_crate: Option<&Path>) -> Result<(), FmuError> {
        if self.guid == expected {
            return Ok(());
        }
        let origin = match user_crate {
            Some(dir) => format!(
                "the crate {} builds its model otherwise (its build script's \
                 `autosim_fmu::generate` compiles the model file as it is, with no \
                 scene: give the FMU the same model file and no scene, or build it \
                 without the crate)",
                dir.display()
            ),
            None => "the generated crate is stale (remove the FMU's build folder)".into(),
        };
        Err(FmuError::Cargo(format!(
            "the built library is for another model description (GUID {}, the \
             description's {expected}): {origin}",
            self.guid
        )))
    }
}

/// The text a query function of `library` answers.
fn text(library: &libloading::Library, symbol: &[u8]) -> Result<String, String> {
    // SAFETY: `export_fmi2!` defines the symbol with this signature.
    let query = unsafe { library.get::<Query>(symbol) }.map_err(|e| e.to_string())?;
    // SAFETY: a null buffer of length 0 asks for the length; then a
    // buffer of that length.
    let n = unsafe { query(std::ptr::null_mut(), 0) };
    let mut text = vec![0u8; n];
    let written = unsafe { query(text.as_mut_ptr(), n) };
    if written != n {
        return Err("its answer changed length".into());
    }
    String::from_utf8(text).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn told(guid: &str) -> Told {
        Told {
            events: EventInterface::default(),
            guid: guid.into(),
        }
    }

    #[test]
    fn a_library_for_another_description_is_refused_naming_its_crate() {
        assert!(told("{a}").check_guid("{a}", None).is_ok());
        let refused = told("{a}")
            .check_guid("{b}", Some(Path::new("crates/tire")))
            .expect_err("another GUID");
        let message = refused.to_string();
        assert!(message.contains("GUID {a}"), "{message}");
        assert!(message.contains("crates/tire"), "{message}");
    }
}
