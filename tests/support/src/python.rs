//! One Python virtual environment for every test that runs Python (the
//! Python package, the FMU checks with FMPy, the Dask studies).
//!
//! The environment lives in the workspace's `target/python-env` (created on
//! first use with the machine's `python3 -m venv`; packages installed from
//! the Python registry on demand, each requirement once). Tests call
//! [`python_env`] with the requirements they need; when Python or a package
//! cannot be had, it returns the reason and the test prints a
//! `SKIPPED: ...` line through [`skip`], so a missing Python is never a
//! silent pass.
//!
//! Several test binaries and threads may ask at once: installation holds an
//! exclusive lock on `target/python-env.lock`.

use std::fs::{File, OpenOptions};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A ready virtual environment.
#[derive(Clone, Debug)]
pub struct PythonEnv {
    /// The environment's folder.
    pub root: PathBuf,
    /// Its interpreter.
    pub python: PathBuf,
}

impl PythonEnv {
    /// A command running the environment's interpreter (its `bin` folder
    /// first on `PATH`, so scripts it installed are found).
    pub fn command(&self) -> Command {
        let mut command = Command::new(&self.python);
        let bin = self.root.join("bin");
        let path = std::env::var_os("PATH").unwrap_or_default();
        let mut paths = vec![bin];
        paths.extend(std::env::split_paths(&path));
        if let Ok(joined) = std::env::join_paths(paths) {
            command.env("PATH", joined);
        }
        command.env("VIRTUAL_ENV", &self.root);
        command.env_remove("PYTHONHOME");
        command
    }

    /// `python -m pip install --quiet` in the environment: add the
    /// requirements (or paths) and run it. Hold [`lock_environment`] while
    /// it runs.
    pub fn pip_install(&self) -> Command {
        let mut command = self.command();
        command.args([
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
        ]);
        command
    }

    /// Runs the interpreter with `args`, returning its output.
    pub fn run(&self, args: &[&str]) -> std::io::Result<Output> {
        self.command().args(args).output()
    }
}

/// The workspace's `target` folder (honours `CARGO_TARGET_DIR`).
pub fn target_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("CARGO_TARGET_DIR") {
        return PathBuf::from(dir);
    }
    workspace_root().join("target")
}

/// The workspace root (the folder of the root `Cargo.toml`).
pub fn workspace_root() -> PathBuf {
    // This crate lives in `<root>/tests/support`.
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap_or_else(|_| Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
}

/// The shared environment with `requirements` installed (pip requirement
/// strings, e.g. `"numpy"` or `"fmpy==0.3.22"`), or why it cannot be had.
///
/// # Errors
/// A sentence saying what is missing: no `python3`, no `venv` module, or a
/// package the registry did not give.
pub fn python_env(requirements: &[&str]) -> Result<PythonEnv, String> {
    let target = target_dir();
    std::fs::create_dir_all(&target).map_err(|e| format!("cannot create {target:?}: {e}"))?;
    let lock = lock_file(&target.join("python-env.lock"))?;
    let root = target.join("python-env");
    let python = root.join("bin").join("python");
    if !python.exists() {
        let made = Command::new("python3")
            .args(["-m", "venv"])
            .arg(&root)
            .output()
            .map_err(|e| format!("python3 is not available ({e})"))?;
        if !made.status.success() {
            return Err(format!(
                "python3 -m venv failed: {}",
                String::from_utf8_lossy(&made.stderr).trim()
            ));
        }
    }
    let env = PythonEnv { root, python };
    let missing: Vec<&str> = requirements
        .iter()
        .copied()
        .filter(|r| !installed(&env, r))
        .collect();
    if !missing.is_empty() {
        let out = env
            .pip_install()
            .args(&missing)
            .output()
            .map_err(|e| format!("pip could not run ({e})"))?;
        if !out.status.success() {
            return Err(format!(
                "pip could not install {}: {}",
                missing.join(" "),
                last_line(&out.stderr)
            ));
        }
        for requirement in &missing {
            mark_installed(&env, requirement);
        }
    }
    drop(lock);
    Ok(env)
}

/// The shared environment's lock (what [`python_env`] holds while it
/// installs), held until the file is dropped: for tests that install more
/// into the environment themselves.
///
/// # Errors
/// A sentence when the lock file cannot be opened or locked.
pub fn lock_environment() -> Result<File, String> {
    let target = target_dir();
    std::fs::create_dir_all(&target).map_err(|e| format!("cannot create {target:?}: {e}"))?;
    lock_file(&target.join("python-env.lock"))
}

/// Prints the `SKIPPED: ...` line a test prints when it cannot run.
pub fn skip(what: &str, why: &str) {
    eprintln!("SKIPPED: {what}: {why}");
    println!("SKIPPED: {what}: {why}");
}

fn lock_file(path: &Path) -> Result<File, String> {
    let file = OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(path)
        .map_err(|e| format!("cannot open {path:?}: {e}"))?;
    file.lock()
        .map_err(|e| format!("cannot lock {path:?}: {e}"))?;
    Ok(file)
}

/// Requirements already installed are recorded one per line in
/// `<env>/autosim-requirements.txt` (pip's own check would cost a second a
/// call).
fn installed(env: &PythonEnv, requirement: &str) -> bool {
    std::fs::read_to_string(env.root.join("autosim-requirements.txt"))
        .map(|text| text.lines().any(|line| line == requirement))
        .unwrap_or(false)
}

fn mark_installed(env: &PythonEnv, requirement: &str) {
    use std::io::Write;
    if let Ok(mut file) = OpenOptions::new()
        .create(true)
        .append(true)
        .open(env.root.join("autosim-requirements.txt"))
    {
        let _ = writeln!(file, "{requirement}");
    }
}

fn last_line(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes)
        .lines()
        .rfind(|l| !l.trim().is_empty())
        .unwrap_or("")
        .trim()
        .to_string()
}
