//! The build-script API: compile `.sim` files into formatted Rust files in
//! `OUT_DIR` (written only when they change), with optional Markdown
//! documentation. Shaped like prost-build: a one-call [`compile`] and a
//! [`Config`] builder.

use crate::diag::{SourceFile, Span};
use crate::emit::{EmitOptions, format_tokens, header, markdown, model_tokens, snake_case};
pub use crate::model::Scene;
/// The types a [`Scene`]'s fields take (`Scene::name("Fast")` makes a
/// [`Name`]).
pub use crate::opt::{FloatType, Formulation};
use crate::pipeline::compile_source_scene;
pub use crate::syntax::ast::Name;
use std::fmt;
use std::path::{Path, PathBuf};

/// Why a model could not be compiled in a build script.
///
/// `Debug` prints the same text as `Display` (the diagnostics with their
/// file, line and fix), so `autosim::build::compile(...)?` in a build
/// script's `fn main() -> Result<(), Box<dyn std::error::Error>>` shows
/// them readably.
pub enum BuildError {
    /// Reading a model or writing an output failed.
    Io {
        /// The file.
        path: PathBuf,
        /// The error.
        error: std::io::Error,
    },
    /// The model has errors; the text lists them as `path:line:col` with
    /// excerpts.
    Model(String),
    /// `OUT_DIR` is not set (not running in a build script) and no output
    /// directory was configured.
    NoOutDir,
    /// The path given to [`Config::runtime_path`] is not a Rust path.
    RuntimePath {
        /// The path as given.
        path: String,
        /// Why it does not parse.
        error: String,
    },
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::Io { path, error } => write!(f, "{}: {error}", path.display()),
            BuildError::Model(text) => write!(f, "{text}"),
            BuildError::NoOutDir => write!(
                f,
                "OUT_DIR is not set: call autosim::build from a build script, or set Config::out_dir"
            ),
            BuildError::RuntimePath { path, error } => write!(
                f,
                "Config::runtime_path(\"{path}\") is not a Rust path ({error}): write it as `::autosim::runtime` or `::autosim_runtime`"
            ),
        }
    }
}

impl fmt::Debug for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

impl std::error::Error for BuildError {}

/// Options for compiling models in a build script.
#[derive(Clone, Debug, Default)]
pub struct Config {
    out_dir: Option<PathBuf>,
    markdown: bool,
    /// The runtime's path as given (checked when compiling).
    runtime_path: Option<String>,
    quiet: bool,
    scene: Scene,
}

/// What one compiled model produced.
#[derive(Clone, Debug)]
pub struct Compiled {
    /// The model's name.
    pub model: String,
    /// The generated module's name (use it with `autosim::include_model!`).
    pub module: String,
    /// The Rust file.
    pub rust_file: PathBuf,
    /// The Markdown documentation, if requested.
    pub markdown_file: Option<PathBuf>,
    /// Whether the Rust file was (re)written.
    pub changed: bool,
}

impl Config {
    /// Default options: output into `OUT_DIR`, no Markdown.
    pub fn new() -> Config {
        Config::default()
    }

    /// Writes into `dir` instead of `OUT_DIR`.
    pub fn out_dir(&mut self, dir: impl Into<PathBuf>) -> &mut Config {
        self.out_dir = Some(dir.into());
        self
    }

    /// Also writes `<module>.md`: parameters with units and defaults,
    /// states, inputs, outputs, operation counts and the equations.
    pub fn markdown(&mut self, yes: bool) -> &mut Config {
        self.markdown = yes;
        self
    }

    /// The path generated code uses for the runtime crate (default
    /// `::autosim::runtime`; use `::autosim_runtime` when depending on the
    /// runtime directly). A path that is not a Rust path makes
    /// [`Config::compile`] fail with [`BuildError::RuntimePath`].
    pub fn runtime_path(&mut self, path: &str) -> &mut Config {
        self.runtime_path = Some(path.to_string());
        self
    }

    /// How generated code is written: the runtime's path checked.
    fn emit_options(&self) -> Result<EmitOptions, BuildError> {
        let mut emit = EmitOptions::default();
        if let Some(path) = &self.runtime_path {
            emit.runtime_path = syn::parse_str(path).map_err(|e| BuildError::RuntimePath {
                path: path.clone(),
                error: e.to_string(),
            })?;
        }
        Ok(emit)
    }

    /// Compiles the next models for a scene: a new model name, float type,
    /// threshold, selected outputs, small or locked degrees of freedom (see
    /// [`Scene`]).
    pub fn scene(&mut self, scene: Scene) -> &mut Config {
        self.scene = scene;
        self
    }

    /// Does not print `cargo::rerun-if-changed` lines (for use outside build
    /// scripts, e.g. in tests).
    pub fn quiet(&mut self, yes: bool) -> &mut Config {
        self.quiet = yes;
        self
    }

    /// Compiles model files (paths as given, usually relative to the crate
    /// root where build scripts run).
    pub fn compile(&self, paths: &[impl AsRef<Path>]) -> Result<Vec<Compiled>, BuildError> {
        let emit = self.emit_options()?;
        let out_dir = match &self.out_dir {
            Some(d) => d.clone(),
            None => std::env::var_os("OUT_DIR")
                .map(PathBuf::from)
                .ok_or(BuildError::NoOutDir)?,
        };
        std::fs::create_dir_all(&out_dir).map_err(|error| BuildError::Io {
            path: out_dir.clone(),
            error,
        })?;
        let mut out = Vec::with_capacity(paths.len());
        for p in paths {
            out.push(self.compile_one(p.as_ref(), &out_dir, &emit)?);
        }
        for (p, compiled) in paths.iter().zip(&out) {
            write_misnamed_module(p.as_ref(), compiled, &out, &out_dir)?;
        }
        Ok(out)
    }

    fn compile_one(
        &self,
        path: &Path,
        out_dir: &Path,
        emit: &EmitOptions,
    ) -> Result<Compiled, BuildError> {
        if !self.quiet {
            println!("cargo::rerun-if-changed={}", path.display());
        }
        let file = SourceFile::read(path, path, Span::unknown())
            .map_err(|d| BuildError::Model(d.render(&SourceFile::new(path, String::new()))))?;
        let compiled = compile_source_scene(&file, &self.scene)
            .map_err(|d| BuildError::Model(d.render(&file)))?;
        let name = compiled.program.interface.model.name.clone();
        let module = emit
            .module_name
            .clone()
            .unwrap_or_else(|| snake_case(&name));
        let shown = path.display().to_string();
        let text = format!(
            "{}{}",
            header(&shown, &file.text),
            format_tokens(&model_tokens(&compiled.program, emit))
        );
        let rust_file = out_dir.join(format!("{module}.rs"));
        let changed = write_if_changed(&rust_file, &text)?;
        let markdown_file = if self.markdown {
            let md = out_dir.join(format!("{module}.md"));
            write_if_changed(&md, &markdown(&compiled.program, &shown))?;
            Some(md)
        } else {
            None
        };
        Ok(Compiled {
            model: name,
            module,
            rust_file,
            markdown_file,
            changed,
        })
    }
}

/// The first line of a `<stem>.rs` that only names the right module.
const MISNAMED_HEADER: &str = "// @generated by autosim: a helpful error for include_model!(";

/// `include_model!(cartpole)` for `cartpole.sim` holding `model CartPole;`
/// would fail with "couldn't read .../cartpole.rs": the module is named
/// after the model (`cart_pole`), not the file. Where the file's stem is
/// another identifier and no model of this build has that module, nor
/// one built before into the folder (a file compiled once as it is and
/// again renamed by a scene), write `<stem>.rs` holding a `compile_error!`
/// that names the right module.
fn write_misnamed_module(
    path: &Path,
    compiled: &Compiled,
    all: &[Compiled],
    out_dir: &Path,
) -> Result<(), BuildError> {
    let Some(stem) = path.file_stem().and_then(|s| s.to_str()) else {
        return Ok(());
    };
    let identifier = stem
        .chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
        && stem.chars().all(|c| c.is_alphanumeric() || c == '_');
    let target = out_dir.join(format!("{stem}.rs"));
    let built = std::fs::read_to_string(&target).is_ok_and(|old| !old.starts_with(MISNAMED_HEADER));
    if !identifier || built || all.iter().any(|c| c.module == stem) {
        return Ok(());
    }
    let message = format!(
        "{} defines `model {};`, whose module is `{}` (the model's name in snake case, not the file's): write `autosim::include_model!({});`",
        path.display(),
        compiled.model,
        compiled.module,
        compiled.module
    );
    let text = format!("{MISNAMED_HEADER}{stem}).\ncompile_error!({message:?});\n");
    write_if_changed(&target, &text).map(|_| ())
}

/// Writes `text` to `path` unless the file already holds exactly that text
/// (so unchanged models do not trigger rebuilds). Returns whether it wrote.
fn write_if_changed(path: &Path, text: &str) -> Result<bool, BuildError> {
    if std::fs::read_to_string(path).is_ok_and(|old| old == text) {
        return Ok(false);
    }
    std::fs::write(path, text).map_err(|error| BuildError::Io {
        path: path.to_path_buf(),
        error,
    })?;
    Ok(true)
}

/// Compiles one model file into `OUT_DIR` with default options; include it
/// with `autosim::include_model!(<module>)`.
pub fn compile(path: impl AsRef<Path>) -> Result<Compiled, BuildError> {
    let mut v = Config::new().compile(&[path])?;
    v.pop().ok_or(BuildError::NoOutDir)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A runtime path that is not a Rust path is an error, before anything
    /// is read or written; a good one is accepted.
    #[test]
    fn a_bad_runtime_path_is_an_error() {
        let dir = std::env::temp_dir().join("autosim-runtime-path-test");
        let err = Config::new()
            .out_dir(&dir)
            .quiet(true)
            .runtime_path("::autosim runtime")
            .compile(&["does-not-exist.sim"])
            .expect_err("a bad path");
        assert!(
            matches!(&err, BuildError::RuntimePath { path, .. } if path == "::autosim runtime"),
            "{err}"
        );
        assert!(err.to_string().contains("is not a Rust path"), "{err}");
        let ok = Config::new()
            .runtime_path("::autosim_runtime")
            .emit_options();
        let path = ok.expect("a good path").runtime_path;
        assert_eq!(quote::quote!(#path).to_string(), ":: autosim_runtime");
    }

    /// A fresh folder under the system's temporary directory.
    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("autosim-build-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create a scratch folder");
        dir
    }

    #[test]
    fn the_files_name_gets_a_module_that_names_the_right_one() {
        let dir = scratch("misnamed");
        let sim = dir.join("cartpole.sim");
        std::fs::write(
            &sim,
            "model CartPole;\nbody A { translate: 1, mass: 1, inertia: 0 }\n",
        )
        .expect("write the model");
        let out = Config::new()
            .out_dir(dir.join("out"))
            .quiet(true)
            .compile(&[&sim])
            .expect("compiles");
        assert_eq!(out[0].module, "cart_pole");
        assert!(dir.join("out/cart_pole.rs").exists());
        let alias = std::fs::read_to_string(dir.join("out/cartpole.rs")).expect("the alias");
        assert!(alias.contains("compile_error!"), "{alias}");
        assert!(
            alias.contains(
                "defines `model CartPole;`, whose module is `cart_pole` (the model's name in snake case, not the file's): write `autosim::include_model!(cart_pole);`"
            ),
            "{alias}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A file compiled as it is, then renamed by scenes in later runs of
    /// the build (a new user's build script): the module named after the
    /// file stays the model, not the note naming the renamed one.
    #[test]
    fn a_renamed_scene_keeps_the_model_compiled_before_it() {
        let dir = scratch("scenes");
        let sim = dir.join("engine.sim");
        std::fs::write(
            &sim,
            "model Engine;\nbody A { translate: 1, mass: 1, inertia: 0 }\n",
        )
        .expect("write the model");
        let out = dir.join("out");
        Config::new()
            .out_dir(&out)
            .quiet(true)
            .compile(&[&sim])
            .expect("compiles");
        let fast = Scene {
            name: Some(Scene::name("EngineFast")),
            float: Some(FloatType::F32),
            ..Scene::default()
        };
        Config::new()
            .out_dir(&out)
            .quiet(true)
            .scene(fast)
            .compile(&[&sim])
            .expect("compiles");
        let engine = std::fs::read_to_string(out.join("engine.rs")).expect("the model");
        assert!(engine.contains("pub struct Engine"), "{engine}");
        assert!(out.join("engine_fast.rs").exists());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn debug_prints_the_diagnostics_as_display_does() {
        let dir = scratch("debug");
        let sim = dir.join("pendulum.sim");
        std::fs::write(&sim, "model Pendulum;\nbody P { rotate: 1, mas: 1 }\n").expect("write");
        let e = Config::new()
            .out_dir(dir.join("out"))
            .quiet(true)
            .compile(&[&sim])
            .expect_err("a misspelled option");
        assert_eq!(format!("{e:?}"), e.to_string());
        assert!(format!("{e:?}").contains("did you mean `mass`?"), "{e:?}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
