//! Python callables a simulation calls: an inputs function `u(t)` (an
//! input source, called at every evaluation) and a sampled controller
//! `controller(t, x, y)` (called once per sample period). Each takes the
//! GIL back for its call; the first exception is kept for the caller to
//! raise, and the inputs become NaN, which stops the integration.

use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::sync::{Arc, Mutex};

use crate::inputs::InputSource;
use crate::simulate::SampledControl;

/// A Python function's first exception, shared with the caller.
type Failure = Arc<Mutex<Option<PyErr>>>;

/// A Python callable `u(t)` as an input source.
pub struct Callable {
    function: Py<PyAny>,
    width: usize,
    failure: Failure,
}

impl Callable {
    /// `function` returning `width` inputs; its exception goes to `failure`.
    pub fn new(function: Py<PyAny>, width: usize, failure: Failure) -> Self {
        Callable {
            function,
            width,
            failure,
        }
    }
}

impl InputSource for Callable {
    fn at(&mut self, t: f64, u: &mut [f64]) -> bool {
        let (function, width) = (&self.function, self.width);
        let got = guarded(&self.failure, |py| {
            let value = function.call1(py, (t,))?;
            input_values(py, &value, width, "the inputs callable", t)
        });
        match got {
            Some(values) => u.copy_from_slice(&values),
            None => u.fill(f64::NAN),
        }
        true
    }
}

/// A Python callable `controller(t, x, y)` returning the inputs to hold
/// until the next sample (`x` the state, `y` the outputs, as NumPy arrays).
pub struct Controller {
    function: Py<PyAny>,
    width: usize,
    failure: Failure,
}

impl Controller {
    /// `function` returning `width` inputs; its exception goes to `failure`.
    pub fn new(function: Py<PyAny>, width: usize, failure: Failure) -> Self {
        Controller {
            function,
            width,
            failure,
        }
    }
}

impl SampledControl for Controller {
    fn sample(&mut self, t: f64, x: &[f64], y: &[f64], inputs: &mut [f64]) {
        let (function, width) = (&self.function, self.width);
        let got = guarded(&self.failure, |py| {
            let (x, y) = (PyArray1::from_slice(py, x), PyArray1::from_slice(py, y));
            let value = function.call1(py, (t, x, y))?;
            input_values(py, &value, width, "the controller", t)
        });
        match got {
            Some(values) => inputs.copy_from_slice(&values),
            None => inputs.fill(f64::NAN),
        }
    }
}

/// Runs `call` with the GIL unless an earlier call failed; its exception
/// is kept in `failure` (the first only) and gives `None`.
fn guarded(
    failure: &Failure,
    call: impl FnOnce(Python<'_>) -> PyResult<Vec<f64>>,
) -> Option<Vec<f64>> {
    let mut failure = failure.lock().unwrap_or_else(|p| p.into_inner());
    if failure.is_some() {
        return None;
    }
    match Python::attach(call) {
        Ok(values) => Some(values),
        Err(e) => {
            *failure = Some(e);
            None
        }
    }
}

/// A callable's result as `width` finite inputs: a number (one input) or
/// a sequence; a `ValueError` naming `who` and the time otherwise.
fn input_values(
    py: Python<'_>,
    value: &Py<PyAny>,
    width: usize,
    who: &str,
    t: f64,
) -> PyResult<Vec<f64>> {
    let values: Vec<f64> = match value.extract::<f64>(py) {
        Ok(v) => vec![v],
        Err(_) => value.extract(py)?,
    };
    if values.len() != width {
        return Err(PyValueError::new_err(format!(
            "{who} returned {} values at t = {t}; the model has {width} inputs",
            values.len()
        )));
    }
    if let Some((k, v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{who} returned {v} for input #{k} (model.input_names order) at t = {t}; inputs must be finite"
        )));
    }
    Ok(values)
}
