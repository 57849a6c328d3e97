//! The Python class of a loaded model, `NativeModel`: NumPy arrays in and
//! out, lengths checked (a `ValueError` naming the argument, never a
//! panic), the long loops run with the GIL released, model and integrator
//! failures raised as `autosim.errors.SimulationError`. The friendly
//! object users see (`autosim.Model`: names, units, dicts, pandas) is
//! Python code on top of this one.

use crate::Generated;
use crate::callables::{Callable, Controller};
use crate::engine::{Adapter, Engine, RowError, Sizes};
use crate::inputs::{Held, InputSource, Table};
use crate::interrupt::{signals, watched};
use crate::simulate::{Failure, Request, Sampler, Trajectory};
use crate::simulate_args::{event_settings, failure_error, trajectory_dict};
use crate::study::{self, Outcome};
use crate::study_args::{plan, results_dict, summary_dict};
use autosim_runtime::ModelError;
use autosim_runtime::analysis::Trim;
use numpy::ndarray::Array2;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// A study's description, output times, case columns and fields.
type Described<'py> = (
    String,
    Bound<'py, PyArray1<f64>>,
    Vec<String>,
    Vec<(String, usize)>,
);

/// A trimmed state, the Newton iterations and the final residual.
type Trimmed<'py> = (Bound<'py, PyArray1<f64>>, usize, f64);

/// A compiled model: the low-level object behind `autosim.Model`.
#[pyclass(module = "autosim")]
pub struct NativeModel {
    engine: Box<dyn Engine>,
    sizes: Sizes,
}

/// Adds the class and `prototype` (a model with its defaults) to the
/// extension module of model `M`.
///
/// # Errors
/// Python's, when the module cannot take the attributes.
pub fn register<M: Generated>(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add_class::<NativeModel>()?;
    let engine: Box<dyn Engine> = Box::new(Adapter(M::create()));
    let sizes = engine.sizes();
    module.add("prototype", NativeModel { engine, sizes })?;
    module.add("INTERFACE", M::INTERFACE)?;
    Ok(())
}

/// `autosim.errors.SimulationError(message)` (a `RuntimeError` if the
/// package cannot be imported).
fn simulation_error(py: Python<'_>, message: String) -> PyErr {
    match py
        .import("autosim.errors")
        .and_then(|m| m.getattr("SimulationError"))
        .and_then(|class| class.call1((message.clone(),)))
    {
        Ok(instance) => PyErr::from_value(instance),
        Err(_) => PyRuntimeError::new_err(message),
    }
}

/// Runs `f` (a loop over the model or an integration, on a detached
/// thread), turning a Rust panic — a bug, never a user's mistake — into
/// the message of a `SimulationError` rather than PyO3's
/// `PanicException` (a `BaseException`, which `except Exception` misses).
pub(crate) fn unpanicked<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(|payload| {
        let text = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        format!("internal error, a bug in autosim (please report it): {text}")
    })
}

fn model_error(py: Python<'_>, e: ModelError) -> PyErr {
    simulation_error(py, e.to_string())
}

fn row_error(py: Python<'_>, (row, e): RowError) -> PyErr {
    simulation_error(py, format!("row {row}: {e}"))
}

/// The values of a 1-D array of `len` entries named `what`.
fn vector<'a>(
    a: &'a PyReadonlyArray1<'_, f64>,
    len: usize,
    what: &str,
) -> PyResult<Cow<'a, [f64]>> {
    if a.len() != len {
        return Err(PyValueError::new_err(format!(
            "{what} has {} entries; the model needs {len}",
            a.len()
        )));
    }
    Ok(match a.as_slice() {
        Ok(s) => Cow::Borrowed(s),
        Err(_) => Cow::Owned(a.as_array().iter().copied().collect()),
    })
}

/// The rows of a 2-D array of `width` columns named `what`.
fn matrix<'a>(
    a: &'a PyReadonlyArray2<'_, f64>,
    width: usize,
    what: &str,
) -> PyResult<Cow<'a, [f64]>> {
    let shape = a.shape();
    if shape[1] != width {
        return Err(PyValueError::new_err(format!(
            "{what} has {} columns; the model needs {width}",
            shape[1]
        )));
    }
    Ok(match a.as_slice() {
        Ok(s) => Cow::Borrowed(s),
        Err(_) => Cow::Owned(a.as_array().iter().copied().collect()),
    })
}

/// `values` as an `n × width` array.
pub(crate) fn rows<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    n: usize,
    width: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let array = Array2::from_shape_vec((n, width), values)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py))
}

impl NativeModel {
    /// Runs `request` on the study `spec` of copies of this model with the
    /// GIL released, on a thread of its own: Ctrl-C cancels it (no new
    /// case starts) and raises `KeyboardInterrupt` here.
    fn run_study(
        &self,
        py: Python<'_>,
        spec: &Bound<'_, PyDict>,
        request: study::Request<'_>,
    ) -> PyResult<Outcome> {
        let plan = plan(spec)?;
        let cancel = plan.cancel.clone();
        let engine = &self.engine;
        watched(py, move || cancel.cancel(), || engine.study(&plan, request))?
            .map_err(|message| simulation_error(py, message))?
            .map_err(PyValueError::new_err)
    }

    /// `dx/dt` (or the outputs, `outputs = true`) at `(t, x)`; a state
    /// that is not finite is a `ValueError` naming it (as Python's check
    /// does).
    fn evaluate<'py>(
        &mut self,
        py: Python<'py>,
        t: f64,
        x: PyReadonlyArray1<'_, f64>,
        outputs: bool,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let x = vector(&x, self.sizes.states, "x")?;
        if let Some((k, v)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            let name = self.engine.state_names().get(k).copied().unwrap_or("?");
            let v = if v.is_nan() {
                "nan"
            } else if *v > 0.0 {
                "inf"
            } else {
                "-inf"
            };
            return Err(PyValueError::new_err(format!(
                "x is not finite in state '{name}' (#{k}): {v}"
            )));
        }
        let width = if outputs {
            self.sizes.outputs
        } else {
            self.sizes.states
        };
        let mut out = vec![0.0; width];
        let done = if outputs {
            self.engine.outputs(t, &x, &mut out)
        } else {
            self.engine.derivatives(t, &x, &mut out)
        };
        done.map_err(|e| model_error(py, e))?;
        Ok(PyArray1::from_vec(py, out))
    }
}

#[pymethods]
impl NativeModel {
    /// A copy with the same parameters and inputs.
    fn copy(&self) -> NativeModel {
        NativeModel {
            engine: self.engine.boxed_clone(),
            sizes: self.sizes,
        }
    }

    /// The interface JSON (names, units, defaults, docs).
    fn interface(&self) -> &'static str {
        self.engine.interface()
    }

    /// Parameter values in declaration order.
    fn parameters<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.engine.parameters())
    }

    /// Sets every parameter (declaration order); NaN and infinities are
    /// refused, naming the parameter's position.
    fn set_parameters(&mut self, values: PyReadonlyArray1<'_, f64>) -> PyResult<()> {
        let v = vector(&values, self.sizes.parameters, "parameters")?;
        if let Some(k) = v.iter().position(|p| !p.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "parameter #{k} is not finite: {}",
                v[k]
            )));
        }
        self.engine.set_parameters(&v);
        Ok(())
    }

    /// Input values in declaration order.
    fn inputs<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.engine.inputs())
    }

    /// Sets every input (declaration order).
    fn set_inputs(&mut self, values: PyReadonlyArray1<'_, f64>) -> PyResult<()> {
        let v = vector(&values, self.sizes.inputs, "inputs")?;
        self.engine.set_inputs(&v);
        Ok(())
    }

    /// The model's default initial state.
    fn initial_state<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.engine.initial_state())
    }

    /// The discrete variables' values (declaration order): their initial
    /// values unless `set_discrete` changed them.
    fn discrete<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.engine.discrete())
    }

    /// Sets every discrete variable (declaration order).
    fn set_discrete(&mut self, values: PyReadonlyArray1<'_, f64>) -> PyResult<()> {
        let values = vector(&values, self.sizes.discrete, "discrete")?;
        self.engine.set_discrete(&values);
        Ok(())
    }

    /// `dx/dt` at `(t, x)` with the current inputs.
    fn derivatives<'py>(
        &mut self,
        py: Python<'py>,
        t: f64,
        x: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.evaluate(py, t, x, false)
    }

    /// The outputs at `(t, x)` with the current inputs.
    fn outputs<'py>(
        &mut self,
        py: Python<'py>,
        t: f64,
        x: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.evaluate(py, t, x, true)
    }

    /// `dx/dt` (or the outputs) for every row of `x`, at the times `t` (one
    /// or one per row), with inputs `u` (one row per state row) or the
    /// current inputs; the GIL is released during the loop.
    #[pyo3(signature = (t, x, u=None, outputs=false))]
    fn many<'py>(
        &mut self,
        py: Python<'py>,
        t: PyReadonlyArray1<'_, f64>,
        x: PyReadonlyArray2<'_, f64>,
        u: Option<PyReadonlyArray2<'_, f64>>,
        outputs: bool,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let n = x.shape()[0];
        let xs = matrix(&x, self.sizes.states, "x")?;
        if t.len() != 1 && t.len() != n {
            return Err(PyValueError::new_err(format!(
                "t has {} entries; give one time or one per state row ({n})",
                t.len()
            )));
        }
        let ts = vector(&t, t.len(), "t")?;
        let us = match &u {
            Some(u) => {
                if u.shape()[0] != n {
                    return Err(PyValueError::new_err(format!(
                        "u has {} rows; give one per state row ({n})",
                        u.shape()[0]
                    )));
                }
                Some(matrix(u, self.sizes.inputs, "u")?)
            }
            None => None,
        };
        let width = if outputs {
            self.sizes.outputs
        } else {
            self.sizes.states
        };
        let mut out = vec![0.0; n * width];
        let engine = &mut self.engine;
        py.detach(|| unpanicked(|| engine.many(outputs, &ts, &xs, us.as_deref(), &mut out)))
            .map_err(|message| simulation_error(py, message))?
            .map_err(|e| row_error(py, e))?;
        rows(py, out, n, width)
    }

    /// The mass matrix at `(t, x)`.
    fn mass_matrix<'py>(
        &mut self,
        py: Python<'py>,
        t: f64,
        x: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let x = vector(&x, self.sizes.states, "x")?;
        let n = self.sizes.speeds;
        let mut m = vec![0.0; n * n];
        self.engine.mass_matrix(t, &x, &mut m);
        rows(py, m, n, n)
    }

    /// The forcing vector at `(t, x)` with the current inputs.
    fn forcing<'py>(
        &mut self,
        py: Python<'py>,
        t: f64,
        x: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let x = vector(&x, self.sizes.states, "x")?;
        let mut f = vec![0.0; self.sizes.speeds];
        self.engine.forcing(t, &x, &mut f);
        Ok(PyArray1::from_vec(py, f))
    }

    /// `(A, B, C, D)` at `(t, x)` with the current inputs over `nx` linear
    /// states, or `None` when the model was compiled without them.
    fn linearize<'py>(
        &mut self,
        py: Python<'py>,
        t: f64,
        x: PyReadonlyArray1<'_, f64>,
        nx: usize,
    ) -> PyResult<Option<Vec<Bound<'py, PyArray2<f64>>>>> {
        let x = vector(&x, self.sizes.states, "x")?;
        let (ni, ny) = (self.sizes.inputs, self.sizes.outputs);
        let (mut a, mut b, mut c, mut d) = (
            vec![0.0; nx * nx],
            vec![0.0; nx * ni],
            vec![0.0; ny * nx],
            vec![0.0; ny * ni],
        );
        match self
            .engine
            .linearize(t, &x, [&mut a, &mut b, &mut c, &mut d])
        {
            None => Ok(None),
            Some(Err(e)) => Err(model_error(py, e)),
            Some(Ok(())) => Ok(Some(vec![
                rows(py, a, nx, nx)?,
                rows(py, b, nx, ni)?,
                rows(py, c, ny, nx)?,
                rows(py, d, ny, ni)?,
            ])),
        }
    }

    /// `x` with its dependent coordinates solved from the position
    /// constraints (a copy; unchanged for models without them).
    fn assemble<'py>(
        &mut self,
        py: Python<'py>,
        t: f64,
        x: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let mut x = vector(&x, self.sizes.states, "x")?.into_owned();
        self.engine
            .assemble(t, &mut x)
            .map_err(|e| model_error(py, e))?;
        Ok(PyArray1::from_vec(py, x))
    }

    /// Trims from `x`: the states in `free_states` and inputs in
    /// `free_inputs` change until the derivatives of the `steady` states
    /// vanish (the runtime's damped Newton). Returns the state, the
    /// iterations and the residual; the model keeps the trimmed inputs.
    /// `None` without a generated linearization.
    #[pyo3(signature = (t, x, free_states, free_inputs, steady, tolerance, max_iterations, max_step))]
    #[allow(clippy::too_many_arguments)]
    fn trim<'py>(
        &mut self,
        py: Python<'py>,
        t: f64,
        x: PyReadonlyArray1<'_, f64>,
        free_states: Vec<String>,
        free_inputs: Vec<String>,
        steady: Vec<String>,
        tolerance: f64,
        max_iterations: usize,
        max_step: f64,
    ) -> PyResult<Option<Trimmed<'py>>> {
        let mut x = vector(&x, self.sizes.states, "x")?.into_owned();
        let spec = Trim {
            free_states,
            free_inputs,
            steady,
            tolerance,
            max_iterations,
            max_step,
        };
        let engine = &mut self.engine;
        let done = py
            .detach(|| unpanicked(|| engine.trim(t, &mut x, &spec)))
            .map_err(|message| simulation_error(py, message))?;
        match done {
            None => Ok(None),
            Some(Err(message)) => Err(simulation_error(py, message)),
            Some(Ok((iterations, residual))) => {
                Ok(Some((PyArray1::from_vec(py, x), iterations, residual)))
            }
        }
    }

    /// Integrates from `x0` at `t0` to `t_end` with `method`, reporting at
    /// `times`; inputs held (`inputs=None`), from a table (`table=(t, u)`)
    /// or from a callable, or set by a `controller = (callable, period)`
    /// called with `(t, x, y)` every period; the discrete variables starting at `discrete0`
    /// (default: the model's), events located as `events` =
    /// `(time_tolerance, interior_samples, zeno_events, zeno_interval)`
    /// says. Returns the dict of `simulate_args::trajectory_dict`. The GIL
    /// is released (a callable takes it back at each call, and the run
    /// every 0.1 s to check for Ctrl-C, which stops it and raises
    /// `KeyboardInterrupt`).
    #[pyo3(signature = (method, t0, t_end, h, rtol, atol, times, x0, max_steps, table=None, function=None, discrete0=None, events=(0.0, 4, 100, 0.0), controller=None))]
    #[allow(clippy::too_many_arguments)]
    fn simulate<'py>(
        &mut self,
        py: Python<'py>,
        method: String,
        t0: f64,
        t_end: f64,
        h: f64,
        rtol: f64,
        atol: f64,
        times: PyReadonlyArray1<'_, f64>,
        x0: PyReadonlyArray1<'_, f64>,
        max_steps: u64,
        table: Option<(PyReadonlyArray1<'_, f64>, PyReadonlyArray2<'_, f64>)>,
        function: Option<Py<PyAny>>,
        discrete0: Option<PyReadonlyArray1<'_, f64>>,
        events: (f64, u32, u32, f64),
        controller: Option<(Py<PyAny>, f64)>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let x0 = vector(&x0, self.sizes.states, "x0")?.into_owned();
        let times = vector(&times, times.len(), "t_eval")?.into_owned();
        let discrete0 = match &discrete0 {
            Some(d) => Some(vector(d, self.sizes.discrete, "discrete0")?.into_owned()),
            None => None,
        };
        let ni = self.sizes.inputs;
        let failure = Arc::new(Mutex::new(None));
        let source: Box<dyn InputSource> = match (table, function) {
            (Some((tt, uu)), _) => {
                let tt = vector(&tt, tt.len(), "input times")?.into_owned();
                let uu = matrix(&uu, ni, "input values")?.into_owned();
                Box::new(Table::new(tt, uu, ni).map_err(PyValueError::new_err)?)
            }
            (None, Some(function)) => Box::new(Callable::new(function, ni, Arc::clone(&failure))),
            (None, None) => Box::new(Held),
        };
        let sampler = controller.map(|(function, period)| Sampler {
            period,
            control: Box::new(Controller::new(function, ni, Arc::clone(&failure))),
        });
        let request = Request {
            method,
            t0,
            t_end,
            h,
            rtol,
            atol,
            times,
            x0,
            max_steps,
            discrete0,
            events: event_settings(events)?,
        };
        let poll = signals(Arc::clone(&failure));
        let engine = &mut self.engine;
        let result = py
            .detach(|| unpanicked(|| engine.simulate(&request, source, sampler, poll)))
            .map_err(Failure::Message)
            .and_then(|r| r);
        if let Some(e) = failure.lock().unwrap_or_else(|p| p.into_inner()).take() {
            return Err(e);
        }
        let run: Trajectory = result.map_err(|e| failure_error(py, e))?;
        trajectory_dict(py, run, &self.sizes)
    }

    /// A study's description, the output times of its runs and its
    /// layout `(case_columns, [(field, length)])`, from the specification
    /// dict `autosim.Study` sends; checks every column sets something.
    fn study_describe<'py>(
        &self,
        py: Python<'py>,
        spec: &Bound<'py, PyDict>,
    ) -> PyResult<Described<'py>> {
        let plan = plan(spec)?;
        let (description, times, layout) = self
            .engine
            .describe_study(&plan)
            .map_err(PyValueError::new_err)?;
        let fields = layout
            .fields
            .iter()
            .map(|f| (f.name.clone(), f.len))
            .collect();
        Ok((
            description,
            PyArray1::from_vec(py, times),
            layout.case_columns,
            fields,
        ))
    }

    /// Runs cases `start..end` of the study `spec` on copies of this model,
    /// the GIL released; returns the results as a dict of arrays. Failed
    /// cases carry their error; a study that cannot run raises
    /// `ValueError`.
    fn study_run<'py>(
        &self,
        py: Python<'py>,
        spec: &Bound<'py, PyDict>,
        start: u64,
        end: u64,
    ) -> PyResult<Bound<'py, PyDict>> {
        match self.run_study(py, spec, study::Request::Run(start..end))? {
            Outcome::Results(results) => results_dict(py, &results),
            Outcome::Summary(_) => Err(PyRuntimeError::new_err("a run gave a summary")),
        }
    }

    /// Runs the study `spec` into `folder` (CSV shards of `shard_size`
    /// cases, resuming a study already there), the GIL released; returns
    /// the summary as a dict.
    fn study_run_in<'py>(
        &self,
        py: Python<'py>,
        spec: &Bound<'py, PyDict>,
        folder: PathBuf,
        shard_size: u64,
    ) -> PyResult<Bound<'py, PyDict>> {
        match self.run_study(py, spec, study::Request::RunIn(&folder, shard_size))? {
            Outcome::Summary(summary) => summary_dict(py, &summary),
            Outcome::Results(_) => Err(PyRuntimeError::new_err("a run in a folder gave results")),
        }
    }

    /// The results of the study in `folder` (every shard) and the
    /// description in its manifest.
    #[staticmethod]
    fn study_read<'py>(py: Python<'py>, folder: PathBuf) -> PyResult<(Bound<'py, PyDict>, String)> {
        let (results, description) = py
            .detach(|| study::read(&folder))
            .map_err(PyValueError::new_err)?;
        Ok((results_dict(py, &results)?, description))
    }
}
