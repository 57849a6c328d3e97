//! `autosim._compiler`: the autosim compiler (autosim-core) as a Python
//! module. `compile` turns model text into the generated Rust module and
//! its interface (names, units, defaults, docs as JSON), or raises
//! `autosim.errors.CompileError` with the spanned diagnostics a Rust user
//! sees; `sources` hands out the runtime and wrapper crates a per-model
//! build needs (embedded at build time by `rust/build.rs`).

use autosim_core::diag::SourceFile;
use autosim_core::emit::{EmitOptions, format_tokens, header, model_tokens};
use autosim_core::model::{FloatType, Formulation, Scene};
use autosim_core::pipeline::compile_source_scene;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

mod interface;

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/sources.rs"));
}

/// The compiler's version and the fingerprint of its sources (a cache key
/// part: a different compiler never reuses a model built by another).
#[pyfunction]
fn version() -> (String, String) {
    (
        env!("CARGO_PKG_VERSION").to_string(),
        embedded::FINGERPRINT.to_string(),
    )
}

/// The Rust sources a per-model build needs, as `(relative path, text)`
/// pairs: `autosim-runtime/...` and `autosim-python-model/...`.
#[pyfunction]
fn sources() -> Vec<(&'static str, &'static str)> {
    embedded::SOURCES.to_vec()
}

/// Options of a use site (a scene), as `autosim.load` takes them.
#[derive(Default)]
struct Options {
    name: Option<String>,
    linearize: Option<bool>,
    lanes: Option<bool>,
    formulation: Option<String>,
    small: Option<Vec<String>>,
    lock: Option<Vec<String>>,
    outputs: Option<Vec<String>>,
    threshold: Option<i16>,
}

impl Options {
    /// Reads the options from keyword arguments, refusing unknown ones.
    fn from_dict(dict: &Bound<'_, pyo3::types::PyDict>) -> PyResult<Options> {
        const KNOWN: [&str; 8] = [
            "name",
            "linearize",
            "lanes",
            "formulation",
            "small",
            "lock",
            "outputs",
            "threshold",
        ];
        for key in dict.keys() {
            let key: String = key.extract()?;
            if !KNOWN.contains(&key.as_str()) {
                return Err(PyValueError::new_err(format!(
                    "unknown option {key:?}: the options are {}",
                    KNOWN.join(", ")
                )));
            }
        }
        fn get<'py, T: FromPyObjectOwned<'py>>(
            dict: &Bound<'py, pyo3::types::PyDict>,
            key: &str,
        ) -> PyResult<Option<T>> {
            match dict.get_item(key)? {
                Some(v) if !v.is_none() => Ok(Some(v.extract().map_err(Into::into)?)),
                _ => Ok(None),
            }
        }
        Ok(Options {
            name: get(dict, "name")?,
            linearize: get(dict, "linearize")?,
            lanes: get(dict, "lanes")?,
            formulation: get(dict, "formulation")?,
            small: get(dict, "small")?,
            lock: get(dict, "lock")?,
            outputs: get(dict, "outputs")?,
            threshold: get(dict, "threshold")?,
        })
    }

    fn scene(self) -> Result<Scene, String> {
        let names = |v: Option<Vec<String>>| -> Vec<_> {
            v.unwrap_or_default()
                .iter()
                .map(|n| Scene::name(n))
                .collect()
        };
        let formulation = match self.formulation.as_deref() {
            None => None,
            Some(text) => Some(Formulation::named(text).ok_or_else(|| {
                format!(
                    "formulation {text:?} is not one of {:?}",
                    Formulation::NAMES
                )
            })?),
        };
        Ok(Scene {
            name: self.name.as_deref().map(Scene::name),
            float: None,
            threshold: self.threshold,
            outputs: self
                .outputs
                .map(|o| o.iter().map(|n| Scene::name(n)).collect()),
            linearize: self.linearize,
            lanes: self.lanes,
            formulation,
            small: names(self.small),
            lock: names(self.lock),
        })
    }
}

/// Compiles model `text` (shown in diagnostics as `path`) with the scene
/// options `name`, `linearize`, `lanes`, `formulation`, `small`, `lock`, `outputs`,
/// `threshold`; returns `(rust, interface_json)`: the generated module
/// (runtime path `::autosim_runtime`) and its interface.
///
/// Raises `autosim.errors.CompileError` with the rendered diagnostics when
/// the model has errors.
#[pyfunction]
#[pyo3(signature = (text, path, **options))]
fn compile(
    py: Python<'_>,
    text: &str,
    path: &str,
    options: Option<&Bound<'_, pyo3::types::PyDict>>,
) -> PyResult<(String, String)> {
    let options: Options = match options {
        Some(dict) => Options::from_dict(dict)?,
        None => Options::default(),
    };
    // The compiler's values hold spans that are not `Send`: everything
    // from the scene to the texts happens on the detached thread.
    match py.detach(|| compile_text(text, path, options)) {
        Ok(texts) => Ok(texts),
        Err(Failure::Options(message)) => Err(PyValueError::new_err(message)),
        Err(Failure::Model(diagnostics)) => Err(compile_error(py, diagnostics)),
    }
}

/// Why `compile` failed.
enum Failure {
    /// A bad option (a `ValueError`).
    Options(String),
    /// The rendered diagnostics of the model (a `CompileError`).
    Model(String),
}

fn compile_text(text: &str, path: &str, options: Options) -> Result<(String, String), Failure> {
    let scene = options.scene().map_err(Failure::Options)?;
    let file = SourceFile::new(path, text.to_string());
    let compiled =
        compile_source_scene(&file, &scene).map_err(|d| Failure::Model(d.render(&file)))?;
    let interface = &compiled.program.interface;
    if interface.float == FloatType::F32 {
        return Err(Failure::Model(format!(
            "{path}: error: model `{}` computes in f32 (`float = f32`); NumPy arrays are float64, so the Python package loads f64 models only\n  = help: remove the f32 setting\n",
            interface.model.name
        )));
    }
    let emit = EmitOptions {
        module_name: Some("generated".to_string()),
        ..EmitOptions::with_runtime_path("::autosim_runtime").expect("a constant Rust path")
    };
    let rust = format!(
        "{}{}",
        header(path, text),
        format_tokens(&model_tokens(&compiled.program, &emit))
    );
    Ok((rust, interface::to_json(interface)))
}

/// `autosim.errors.CompileError(text)`.
fn compile_error(py: Python<'_>, text: String) -> PyErr {
    let class = py
        .import("autosim.errors")
        .and_then(|m| m.getattr("CompileError"));
    match class {
        Ok(class) => match class.call1((text.clone(),)) {
            Ok(instance) => PyErr::from_value(instance),
            Err(e) => e,
        },
        Err(_) => PyValueError::new_err(text),
    }
}

#[pymodule]
fn _compiler(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add_function(wrap_pyfunction!(compile, module)?)?;
    module.add_function(wrap_pyfunction!(sources, module)?)?;
    module.add_function(wrap_pyfunction!(version, module)?)?;
    Ok(())
}
