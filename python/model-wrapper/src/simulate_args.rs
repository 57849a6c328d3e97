//! A simulation between Python and Rust: the event settings Python sends,
//! a [`Trajectory`] as a dict of NumPy arrays, and a [`Failure`] as the
//! exception Python raises (`autosim.errors.ZenoError` for chattering
//! events, `SimulationError` otherwise).

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use autosim_runtime::run::EventSettings;
use numpy::PyArray1;

use crate::engine::Sizes;
use crate::native::rows;
use crate::simulate::{Failure, Trajectory};

/// The event settings from `(time_tolerance, interior_samples,
/// zeno_events, zeno_interval)`, checked.
///
/// # Errors
/// `ValueError` naming the wrong setting.
pub fn event_settings(
    (time_tolerance, interior_samples, zeno_events, zeno_interval): (f64, u32, u32, f64),
) -> PyResult<EventSettings<f64>> {
    let settings = EventSettings {
        time_tolerance,
        interior_samples,
        zeno_events,
        zeno_interval,
    };
    settings
        .validate()
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(settings)
}

/// The exception for `failure`: `autosim.errors.ZenoError(message, event,
/// t, events)` or `autosim.errors.SimulationError(message)` (a
/// `RuntimeError` if the package cannot be imported).
pub fn failure_error(py: Python<'_>, failure: Failure) -> PyErr {
    let errors = py.import("autosim.errors");
    let made = match &failure {
        Failure::Message(message) => errors
            .and_then(|m| m.getattr("SimulationError"))
            .and_then(|class| class.call1((message.as_str(),))),
        Failure::Zeno {
            message,
            event,
            t,
            events,
        } => errors
            .and_then(|m| m.getattr("ZenoError"))
            .and_then(|class| class.call1((message.as_str(), *event, *t, *events))),
    };
    match made {
        Ok(instance) => PyErr::from_value(instance),
        Err(_) => PyRuntimeError::new_err(failure.message().to_string()),
    }
}

/// A finished run as a dict: `t`, `x`, `y`, `u`, `d` (discrete variables
/// at the output times), the counts `steps`, `rejected_steps`,
/// `evaluations`, `terminal_event` (an index or `None`) and `events`, a
/// dict of the events' `t`, `index`, `x_before`, `x_after`, `d_before`,
/// `d_after`.
///
/// # Errors
/// Python's, when an array cannot be made (sizes that disagree: a bug).
pub fn trajectory_dict<'py>(
    py: Python<'py>,
    run: Trajectory,
    sizes: &Sizes,
) -> PyResult<Bound<'py, PyDict>> {
    let n = run.t.len();
    let recorded = if run.u.len() == n * sizes.inputs {
        sizes.inputs
    } else {
        0
    };
    let out = PyDict::new(py);
    out.set_item("t", PyArray1::from_vec(py, run.t))?;
    out.set_item("x", rows(py, run.x, n, sizes.states)?)?;
    out.set_item("y", rows(py, run.y, n, sizes.outputs)?)?;
    out.set_item("u", rows(py, run.u, n, recorded)?)?;
    out.set_item("d", rows(py, run.d, n, sizes.discrete)?)?;
    out.set_item("steps", run.steps)?;
    out.set_item("rejected_steps", run.rejected_steps)?;
    out.set_item("evaluations", run.evaluations)?;
    out.set_item("terminal_event", run.terminal_event)?;
    let log = run.events;
    let count = log.t.len();
    let events = PyDict::new(py);
    events.set_item("t", PyArray1::from_vec(py, log.t))?;
    events.set_item("index", log.index)?;
    events.set_item("x_before", rows(py, log.x_before, count, sizes.states)?)?;
    events.set_item("x_after", rows(py, log.x_after, count, sizes.states)?)?;
    events.set_item("d_before", rows(py, log.d_before, count, sizes.discrete)?)?;
    events.set_item("d_after", rows(py, log.d_after, count, sizes.discrete)?)?;
    out.set_item("events", events)?;
    Ok(out)
}
