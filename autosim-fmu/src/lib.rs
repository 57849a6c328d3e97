//! Functional Mock-up Units (FMI 2.0, Model Exchange and Co-Simulation in
//! one) from autosim models: `modelDescription.xml` from the compiler's
//! data, the shared library built with cargo (the FMI functions of
//! `autosim-fmi`), and the `.fmu` archive.
//!
//! From the command line:
//!
//! ```text
//! cargo run -p autosim-fmu -- examples/models/quarter_car.sim target/fmu
//! ```
//!
//! From Rust (a build script, a test, a tool):
//!
//! ```no_run
//! let built = autosim_fmu::Fmu::new("models/quarter_car.sim").build()?;
//! println!("{}", built.fmu.display()); // target/fmu/QuarterCar.fmu
//! # Ok::<(), autosim_fmu::FmuError>(())
//! ```
//!
//! A model with user code is built from the user's own crate, which
//! compiles the model with [`generate`] in its build script and calls
//! `autosim_fmi::export_fmi2!` with its `Externs`; [`Fmu::user_crate`]
//! then builds and packages that crate (the guide's FMI chapter).

#![deny(missing_docs)]

mod cargo;
pub mod description;
mod library;
mod package;
pub mod units;

pub use description::Experiment;

use autosim_core::build_script::Config;
use autosim_core::diag::{SourceFile, Span};
use autosim_core::model::{FloatType, Scene};
use autosim_core::opt::Program;
use autosim_core::opt::dependencies::Dependencies;
use autosim_core::pipeline::compile_source_scene;
use std::fmt;
use std::path::{Path, PathBuf};

/// Why an FMU could not be made.
#[derive(Debug)]
pub enum FmuError {
    /// The model has errors (rendered with their source lines).
    Model(String),
    /// Reading or writing a file failed.
    Io {
        /// The file.
        path: PathBuf,
        /// The error.
        error: std::io::Error,
    },
    /// Building the shared library failed (cargo's messages).
    Cargo(String),
}

impl fmt::Display for FmuError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FmuError::Model(text) => write!(f, "{text}"),
            FmuError::Io { path, error } => write!(f, "{}: {error}", path.display()),
            FmuError::Cargo(text) => write!(f, "building the FMU's library failed:\n{text}"),
        }
    }
}

impl std::error::Error for FmuError {}

/// An I/O error at `path`.
pub(crate) fn io(path: &Path) -> impl FnOnce(std::io::Error) -> FmuError + '_ {
    move |error| FmuError::Io {
        path: path.to_path_buf(),
        error,
    }
}

/// One FMU to build: the model file and the options.
#[derive(Clone, Debug)]
pub struct Fmu {
    model: PathBuf,
    scene: Scene,
    experiment: Experiment,
    out_dir: Option<PathBuf>,
    work_dir: Option<PathBuf>,
    user_crate: Option<PathBuf>,
    opt_level: Option<u8>,
}

/// What [`Fmu::build`] made.
#[derive(Clone, Debug)]
pub struct Built {
    /// The `.fmu` archive.
    pub fmu: PathBuf,
    /// The model's name, also the FMU's `modelIdentifier`.
    pub identifier: String,
    /// The GUID in `modelDescription.xml` and the library.
    pub guid: String,
    /// The `modelDescription.xml` text.
    pub description: String,
}

impl Fmu {
    /// An FMU of the model in `path` (a `.sim` file), default options.
    pub fn new(path: impl Into<PathBuf>) -> Fmu {
        Fmu {
            model: path.into(),
            scene: Scene::default(),
            experiment: Experiment::default(),
            out_dir: None,
            work_dir: None,
            user_crate: None,
            opt_level: None,
        }
    }

    /// Compiles the model for a scene (name, small or locked degrees of
    /// freedom, selected outputs; see `autosim_core::model::Scene`).
    pub fn scene(mut self, scene: Scene) -> Fmu {
        self.scene = scene;
        self
    }

    /// The `DefaultExperiment` (default: 0 to 10 s, step 0.01 s,
    /// tolerance 1e-6).
    pub fn experiment(mut self, experiment: Experiment) -> Fmu {
        self.experiment = experiment;
        self
    }

    /// Where the `.fmu` goes (default: `OUT_DIR` in a build script, else
    /// `target/fmu`).
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Fmu {
        self.out_dir = Some(dir.into());
        self
    }

    /// Where the library's crate and its cargo target folder go (default:
    /// `build` inside the output folder). FMUs built with one work folder
    /// share their compiled dependencies.
    pub fn work_dir(mut self, dir: impl Into<PathBuf>) -> Fmu {
        self.work_dir = Some(dir.into());
        self
    }

    /// Builds the library from this crate (a `cdylib` that compiles the
    /// model with [`generate`] and calls `autosim_fmi::export_fmi2!`)
    /// instead of writing one: how a model with user code becomes an FMU.
    pub fn user_crate(mut self, dir: impl Into<PathBuf>) -> Fmu {
        self.user_crate = Some(dir.into());
        self
    }

    /// Compiles the model's own code (the generated crate, or the user
    /// crate's package, not their dependencies) at this `opt-level`
    /// (0 to 3) instead of the release profile's 3: a large model builds
    /// in a fraction of the time and computes the same numbers, more
    /// slowly (the guide's FMI chapter gives the figures).
    pub fn opt_level(mut self, level: u8) -> Fmu {
        self.opt_level = Some(level.min(3));
        self
    }

    /// Builds the FMU.
    ///
    /// # Errors
    /// The model's errors, I/O errors, or cargo's when the library does
    /// not build.
    pub fn build(&self) -> Result<Built, FmuError> {
        let mut built = build_all(std::slice::from_ref(self))?;
        built
            .pop()
            .ok_or_else(|| FmuError::Cargo("nothing was built".into()))
    }

    fn out(&self) -> PathBuf {
        match (&self.out_dir, std::env::var_os("OUT_DIR")) {
            (Some(d), _) => d.clone(),
            (None, Some(d)) => PathBuf::from(d),
            (None, None) => PathBuf::from("target/fmu"),
        }
    }

    fn work(&self) -> PathBuf {
        self.work_dir
            .clone()
            .unwrap_or_else(|| self.out().join("build"))
    }
}

/// Builds several FMUs with one cargo run (they share the work folder of
/// the first, so dependencies compile once).
///
/// # Errors
/// As [`Fmu::build`].
pub fn build_all(fmus: &[Fmu]) -> Result<Vec<Built>, FmuError> {
    let Some(first) = fmus.first() else {
        return Ok(Vec::new());
    };
    let work = first.work();
    let mut prepared = Vec::with_capacity(fmus.len());
    for fmu in fmus {
        prepared.push(prepare(fmu)?);
    }
    let libraries = cargo::build(&work, fmus, &prepared)?;
    let mut out = Vec::with_capacity(fmus.len());
    for ((fmu, mut p), library) in fmus.iter().zip(prepared).zip(libraries) {
        let told = library::Told::of(&library)?;
        told.check_guid(&p.guid, fmu.user_crate.as_deref())?;
        p.add_events(told.events);
        let dir = fmu.out();
        std::fs::create_dir_all(&dir).map_err(io(&dir))?;
        let path = dir.join(format!("{}.fmu", p.identifier));
        package::write(&path, &p, &library)?;
        out.push(Built {
            fmu: path,
            identifier: p.identifier,
            guid: p.guid,
            description: p.description,
        });
    }
    Ok(out)
}

/// A model compiled for an FMU: everything but the library.
#[derive(Clone, Debug)]
pub(crate) struct Prepared {
    pub program: Program,
    pub deps: Dependencies,
    pub options: description::Options,
    pub identifier: String,
    pub module: String,
    pub guid: String,
    pub description: String,
    pub markdown: String,
    /// The model's Rust, for a generated crate.
    pub rust: String,
    pub dependent: Vec<usize>,
    pub linearize: bool,
    pub has_externs: bool,
}

/// The scene an FMU compiles: the user's, with the linearization on
/// (directional derivatives) unless the model calls user code, whose
/// derivatives the linearization cannot know.
fn fmu_scene(path: &Path, scene: &Scene) -> Result<(Scene, Program), FmuError> {
    let mut scene = scene.clone();
    // FMI's Real is a double: an `f32` model is exported in `f64`.
    scene.float = Some(FloatType::F64);
    let scene = &scene;
    let file = SourceFile::read(path, path, Span::unknown())
        .map_err(|d| FmuError::Model(d.render(&SourceFile::new(path, String::new()))))?;
    let compile = |scene: &Scene| {
        compile_source_scene(&file, scene).map_err(|d| FmuError::Model(d.render(&file)))
    };
    let plain = compile(scene)?;
    if plain.program.interface.has_externs() {
        let mut s = scene.clone();
        s.linearize = Some(false);
        let program = compile(&s)?.program;
        return Ok((s, program));
    }
    let mut s = scene.clone();
    s.linearize = Some(true);
    let program = compile(&s)?.program;
    Ok((s, program))
}

/// Compiles the model and writes its description.
fn prepare(fmu: &Fmu) -> Result<Prepared, FmuError> {
    let (scene, program) = fmu_scene(&fmu.model, &fmu.scene)?;
    let deps = Dependencies::of(&program);
    let identifier = program.interface.model.name.clone();
    let linearize = program.interface.linear_states.is_some();
    let mut options = description::Options {
        identifier: identifier.clone(),
        guid: String::new(),
        experiment: fmu.experiment,
        directional: linearize,
        events: autosim_fmi::EventInterface::default(),
    };
    let identity = description::Options {
        experiment: Experiment::default(),
        ..options.clone()
    };
    options.guid = description::guid(&description::model_description(&program, &deps, &identity));
    let text = description::model_description(&program, &deps, &options);
    let sources = model_sources(&fmu.work(), &identifier, &fmu.model, scene)?;
    Ok(Prepared {
        identifier,
        module: sources.module,
        guid: options.guid.clone(),
        description: text,
        markdown: sources.markdown,
        rust: sources.rust,
        dependent: deps.dependent.clone(),
        linearize,
        has_externs: program.interface.has_externs(),
        program,
        deps,
        options,
    })
}

impl Prepared {
    /// The description with the model's event indicators and discrete
    /// variables, as the built library reports them (the GUID stays the
    /// one of the description without them, which the library holds).
    fn add_events(&mut self, events: autosim_fmi::EventInterface) {
        if events.is_empty() {
            return;
        }
        self.options.events = events;
        self.description = description::model_description(&self.program, &self.deps, &self.options);
    }
}

/// The generated Rust and Markdown of a model.
struct Sources {
    module: String,
    rust: String,
    markdown: String,
}

/// Compiles the model's Rust (runtime path `::autosim_runtime`) and
/// Markdown through the build API into `work/sources/<identifier>`.
fn model_sources(
    work: &Path,
    identifier: &str,
    model: &Path,
    scene: Scene,
) -> Result<Sources, FmuError> {
    let dir = work.join("sources").join(identifier);
    let compiled = Config::new()
        .out_dir(&dir)
        .markdown(true)
        .quiet(true)
        .runtime_path("::autosim_runtime")
        .scene(scene)
        .compile(&[model])
        .map_err(|e| FmuError::Model(e.to_string()))?;
    let c = compiled
        .into_iter()
        .next()
        .ok_or_else(|| FmuError::Model("the model was not compiled".into()))?;
    let read = |p: &Path| std::fs::read_to_string(p).map_err(io(p));
    let markdown = match &c.markdown_file {
        Some(p) => read(p)?,
        None => String::new(),
    };
    Ok(Sources {
        rust: read(&c.rust_file)?,
        markdown,
        module: c.module,
    })
}

/// What [`generate`] wrote.
#[derive(Clone, Debug)]
pub struct Generated {
    /// The generated module's name.
    pub module: String,
    /// The model's Rust file (`<module>.rs`, for `include!`).
    pub rust_file: PathBuf,
    /// `<module>_fmu.rs`: `pub mod <module>_fmu` with the FMU's `GUID` and
    /// `DEPENDENT` coordinates, for `autosim_fmi::export_fmi2!`.
    pub fmu_file: PathBuf,
}

/// For a user crate's build script: compiles the model as an FMU compiles
/// it and writes `<module>.rs` (the model, runtime path
/// `::autosim_runtime`) and `<module>_fmu.rs` (its GUID and dependent
/// coordinates) into `OUT_DIR` (or `out_dir` when given).
///
/// # Errors
/// The model's errors and I/O errors.
pub fn generate(model: impl AsRef<Path>, out_dir: Option<&Path>) -> Result<Generated, FmuError> {
    let model = model.as_ref();
    let dir = match out_dir {
        Some(d) => d.to_path_buf(),
        None => std::env::var_os("OUT_DIR")
            .map(PathBuf::from)
            .ok_or_else(|| FmuError::Model("OUT_DIR is not set: pass an output folder".into()))?,
    };
    println!("cargo::rerun-if-changed={}", model.display());
    let p = prepare(&Fmu::new(model).work_dir(&dir))?;
    let rust_file = dir.join(format!("{}.rs", p.module));
    std::fs::write(&rust_file, &p.rust).map_err(io(&rust_file))?;
    let fmu_file = dir.join(format!("{}_fmu.rs", p.module));
    let text = format!(
        "/// The FMU's constants for `autosim_fmi::export_fmi2!` (generated).\npub mod {}_fmu {{\n    /// The GUID of the FMU's modelDescription.xml.\n    pub const GUID: &str = {:?};\n    /// State-vector positions of the dependent coordinates.\n    pub const DEPENDENT: &[usize] = &{:?};\n}}\n",
        p.module, p.guid, p.dependent
    );
    std::fs::write(&fmu_file, text).map_err(io(&fmu_file))?;
    Ok(Generated {
        module: p.module,
        rust_file,
        fmu_file,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A user crate's build script knows no experiment: the GUID must not
    /// depend on it, the description must say it.
    #[test]
    fn the_guid_does_not_depend_on_the_default_experiment() {
        let model =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models/quarter_car.sim");
        let work = std::env::temp_dir().join(format!("autosim-fmu-guid-{}", std::process::id()));
        let plain = prepare(&Fmu::new(&model).work_dir(&work)).expect("compiles");
        let short = Experiment {
            stop: 3.0,
            step: 0.001,
            ..Experiment::default()
        };
        let other = prepare(&Fmu::new(&model).work_dir(&work).experiment(short)).expect("compiles");
        let _ = std::fs::remove_dir_all(&work);
        assert_eq!(plain.guid, other.guid);
        assert_ne!(plain.description, other.description);
        assert!(
            other.description.contains("stopTime=\"3.0\""),
            "{}",
            other.description
        );
    }
}
