//! Where an example writes its files: the folder given as its first
//! argument, or a default, created if missing.

use std::path::PathBuf;

/// The first command-line argument, or `default`, as a folder that exists.
pub fn output_folder(default: &str) -> std::io::Result<PathBuf> {
    let folder = std::env::args_os()
        .nth(1)
        .map_or_else(|| PathBuf::from(default), PathBuf::from);
    std::fs::create_dir_all(&folder)?;
    Ok(folder)
}
