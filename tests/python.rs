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
//!
//! Before pytest runs, the reference study (below) runs here in Rust,
//! serially and on 2 threads (equal bits asserted), and is written to
//! `target/python-study-reference` (CSV shards); `python/tests/test_study.py`
//! runs the same study from Python, on threads, in chunks, through a Dask
//! `LocalCluster` and through a loopback scheduler with workers, and
//! asserts every result equals this one bit for bit.

use autosim::runtime::RunSettings;
use autosim::runtime::study::{
    Cases, Distribution, Format, Keep, Method, Parallelism, Simulate, Statistic, Study, StudyDir,
};
use autosim_test_support::python::{
    PythonEnv, lock_environment, python_env, skip, target_dir, workspace_root,
};
use std::path::PathBuf;
use std::process::Output;

autosim::model!(file = "examples/models/pendulum.sim");

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

/// The study `python/tests/test_study.py` builds from Python
/// (`reference_study` there): 2 torques × 40 draws of mass, length and
/// initial angle, Dormand–Prince for 2 s, keeping the final state, the
/// height at 1 s, its maximum and the angle's history.
fn reference_study()
-> Study<pendulum::Pendulum, fn() -> pendulum::Pendulum, Simulate<pendulum::Pendulum>> {
    let cases = Cases::new()
        .grid("torque", &[0.0, 0.5])
        .and_then(|c| {
            c.random(
                40,
                2026,
                &[
                    ("m", Distribution::uniform(0.5, 2.0)),
                    ("L", Distribution::normal(0.7, 0.05)),
                    ("q", Distribution::uniform(-1.0, 1.0)),
                ],
            )
        })
        .expect("a valid table");
    let settings = RunSettings::new(0.0, 2.0, 0.01, 0.1).with_max_steps(10_000_000);
    let keep = Keep::new()
        .final_state()
        .at(&[1.0], &["height"])
        .statistic("height", Statistic::Max)
        .history(&["q"]);
    let method = Method::DormandPrince {
        rtol: 1e-9,
        atol: 1e-12,
    };
    let task = Simulate::new(settings, method, keep).expect("valid settings");
    Study::new(pendulum::Pendulum::new as fn() -> _, cases, task).progress(false)
}

/// Runs the reference study serially and on 2 threads (asserting equal
/// bits) and writes it to a folder for the Python tests; returns the
/// folder.
fn write_reference_study() -> PathBuf {
    let study = reference_study().parallelism(Parallelism::Serial);
    let serial = study.run_cases(0..80).expect("the study runs");
    assert_eq!(serial.failures(), 0);
    let threads = reference_study().parallelism(Parallelism::Threads(2));
    assert!(
        threads.run_cases(0..80).expect("the study runs") == serial,
        "serial and 2 threads differ"
    );
    let folder = target_dir().join("python-study-reference");
    let _ = std::fs::remove_dir_all(&folder);
    study
        .run_in(&folder, Format::Csv, 16)
        .expect("the study is written");
    let read = StudyDir::open(&folder).and_then(|d| d.read_all());
    assert!(read.expect("read back") == serial);
    folder
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
        "dask[distributed]",
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
    let reference = write_reference_study();
    let out = env
        .command()
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs"])
        .arg(workspace_root().join("python/tests"))
        .env("AUTOSIM_CACHE", target_dir().join("python-cache"))
        .env("AUTOSIM_STUDY_REFERENCE", &reference)
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
