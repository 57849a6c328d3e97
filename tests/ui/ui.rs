//! Compile errors a user sees: every `tests/ui/<topic>/*.rs` must fail to
//! compile with exactly the diagnostics in the `.stderr` beside it.
//! Regenerate with `TRYBUILD=overwrite cargo test -p autosim-ui-tests`,
//! then read every changed `.stderr` as a user would.

use std::path::{Path, PathBuf};
use std::process::Command;

#[test]
fn ui() {
    copy_model_files();
    let t = trybuild::TestCases::new();
    t.compile_fail("*/*.rs");
}

/// `model!(file = "...")` reads a path relative to `CARGO_MANIFEST_DIR`,
/// which under trybuild is the project trybuild generates in
/// `<target>/tests/trybuild/autosim/`, not this crate. Copy the model files
/// the cases use there, under the same relative paths, so the cases read
/// like user code (`file = "tests/ui/files/bad_syntax.sim"`) and the
/// expected output holds no absolute path.
fn copy_model_files() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let from = root.join("files");
    let to = trybuild_project_dir().join("tests/ui/files");
    std::fs::create_dir_all(&to).expect("create the trybuild project's model folder");
    for entry in std::fs::read_dir(&from).expect("tests/ui/files exists") {
        let path = entry.expect("readable directory entry").path();
        if path.extension().is_some_and(|e| e == "sim") {
            let name = path.file_name().expect("a file name");
            std::fs::copy(&path, to.join(name)).expect("copy a model file");
        }
    }
}

/// Where trybuild builds the cases: `<target dir>/tests/trybuild/<crate>`,
/// with the target directory cargo reports (it honours `CARGO_TARGET_DIR`).
fn trybuild_project_dir() -> PathBuf {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let output = Command::new(cargo)
        .args(["metadata", "--format-version=1", "--no-deps", "--offline"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run `cargo metadata`");
    assert!(output.status.success(), "`cargo metadata` failed");
    let metadata: serde_json::Value =
        serde_json::from_slice(&output.stdout).expect("`cargo metadata` prints JSON");
    let target = metadata["target_directory"]
        .as_str()
        .expect("`cargo metadata` reports the target directory");
    Path::new(target)
        .join("tests/trybuild")
        .join(env!("CARGO_PKG_NAME"))
}
