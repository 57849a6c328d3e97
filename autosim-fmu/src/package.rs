//! The `.fmu` archive: `modelDescription.xml`, the shared library under
//! `binaries/<platform>/<modelIdentifier>.<ext>`, and the model's
//! Markdown documentation under `documentation/`.

use crate::{FmuError, Prepared, io};
use std::io::Write;
use std::path::Path;
use zip::write::SimpleFileOptions;

/// The FMI platform folder of the machine that builds (the library is
/// built for it).
pub fn platform() -> &'static str {
    match (std::env::consts::OS, std::env::consts::ARCH) {
        ("linux", "x86_64") => "linux64",
        ("linux", "x86") => "linux32",
        ("macos", _) => "darwin64",
        ("windows", "x86_64") => "win64",
        ("windows", "x86") => "win32",
        _ => "unknown",
    }
}

/// Writes the archive.
pub(crate) fn write(path: &Path, p: &Prepared, library: &Path) -> Result<(), FmuError> {
    let binary = std::fs::read(library).map_err(io(library))?;
    let file = std::fs::File::create(path).map_err(io(path))?;
    let mut zip = zip::ZipWriter::new(file);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    let lib_name = format!(
        "binaries/{}/{}{}",
        platform(),
        p.identifier,
        std::env::consts::DLL_SUFFIX
    );
    let entries: [(&str, &[u8]); 3] = [
        ("modelDescription.xml", p.description.as_bytes()),
        (&lib_name, &binary),
        ("documentation/model.md", p.markdown.as_bytes()),
    ];
    for (name, bytes) in entries {
        zip.start_file(name, options).map_err(|e| FmuError::Io {
            path: path.to_path_buf(),
            error: std::io::Error::other(e),
        })?;
        zip.write_all(bytes).map_err(io(path))?;
    }
    zip.finish().map_err(|e| FmuError::Io {
        path: path.to_path_buf(),
        error: std::io::Error::other(e),
    })?;
    Ok(())
}
