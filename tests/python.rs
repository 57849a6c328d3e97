//! The Python package (`python/`): builds and installs it into the shared
//! virtual environment (`target/python-env`) the way a user does,
//! `pip install ./python`, and runs its pytest suite (`python/tests`: the
//! checks against PyDy and SymPy, the model object, the cache, the
//! diagnostics, the tutorial `docs/python.md`). So `cargo test
//! --workspace` runs the Python tests too.
//!
//! The package's build goes to `target/python-build`, the models' cache
//! (their crates and one shared target folder) to `target/python-cache`,
//! so later runs rebuild only what changed. Without Python, or without
//! the Python or crate registries, the test prints a `SKIPPED: ...` line.

use autosim_test_support::python::{
    PythonEnv, lock_environment, python_env, skip, target_dir, workspace_root,
};
use std::process::Output;

const WHAT: &str = "the Python package's tests (python/tests)";

/// Words in cargo's or pip's output that mean a registry could not be
/// reached (the only failure that skips instead of failing).
const OFFLINE: [&str; 6] = [
    "failed to download",
    "Could not resolve host",
    "failed to get successful HTTP response",
    "Unable to update registry",
    "Network is unreachable",
    "No matching distribution found",
];

fn text(output: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

/// `pip install ./python` into `env` (maturin from the environment, no
/// build isolation), holding the environment's lock.
fn install(env: &PythonEnv) -> Result<(), String> {
    let _lock = lock_environment()?;
    let out = env
        .pip_install()
        .args(["--no-build-isolation", "--no-deps", "--force-reinstall"])
        .arg(workspace_root().join("python"))
        .env("CARGO_TARGET_DIR", target_dir().join("python-build"))
        .output()
        .map_err(|e| format!("pip could not run: {e}"))?;
    if out.status.success() {
        Ok(())
    } else {
        Err(text(&out))
    }
}

#[test]
fn python_package_tests_pass() {
    let env = match python_env(&[
        "maturin>=1.9.4,<2",
        "numpy",
        "scipy",
        "pytest",
        "pandas",
        "control",
    ]) {
        Ok(env) => env,
        Err(why) => return skip(WHAT, &why),
    };
    if let Err(log) = install(&env) {
        if OFFLINE.iter().any(|w| log.contains(w)) {
            return skip(WHAT, "a registry is not reachable to build the package");
        }
        panic!("pip install ./python failed:\n{log}");
    }
    let out = env
        .command()
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs"])
        .arg(workspace_root().join("python/tests"))
        .env("AUTOSIM_CACHE", target_dir().join("python-cache"))
        .current_dir(workspace_root())
        .output()
        .expect("pytest runs");
    let log = text(&out);
    println!("{log}");
    if !out.status.success() && OFFLINE.iter().any(|w| log.contains(w)) {
        return skip(
            WHAT,
            "a registry is not reachable to build a model's module",
        );
    }
    assert!(out.status.success(), "pytest failed:\n{log}");
    let summary = log.lines().rfind(|l| l.contains(" passed")).unwrap_or("");
    assert!(summary.contains("passed"), "no Python test ran:\n{log}");
    println!("Python tests: {}", summary.trim());
}
