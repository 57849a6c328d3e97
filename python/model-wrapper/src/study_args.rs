//! A study between Python and Rust: the specification dict
//! `autosim.Study` sends, read into a [`Plan`], and the runtime's
//! [`Results`] as a dict of NumPy arrays.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use autosim_runtime::RunSettings;
use autosim_runtime::study::{Cancel, Results, StudySummary};

use crate::native::rows;
use crate::simulate_args::event_settings;
use crate::study::{Factor, KeepSpec, Plan, cases, keep, method, parallelism};

/// Item `key` of `spec`, which must be there.
fn item<'py, T: FromPyObjectOwned<'py>>(spec: &Bound<'py, PyDict>, key: &str) -> PyResult<T> {
    match spec.get_item(key)? {
        Some(value) => value.extract::<T>().map_err(|e| {
            let e: PyErr = e.into();
            PyValueError::new_err(format!("study specification `{key}`: {e}"))
        }),
        None => Err(PyValueError::new_err(format!(
            "study specification without `{key}`"
        ))),
    }
}

/// One factor: `("grid", name, values)`, `("rows", names, values)` or
/// `("random", count, seed, [(name, kind, a, b), ...])`.
fn factor(tuple: &Bound<'_, PyTuple>) -> PyResult<Factor> {
    let kind: String = tuple.get_item(0)?.extract()?;
    Ok(match kind.as_str() {
        "grid" => Factor::Grid(tuple.get_item(1)?.extract()?, tuple.get_item(2)?.extract()?),
        "rows" => Factor::Rows(tuple.get_item(1)?.extract()?, tuple.get_item(2)?.extract()?),
        "random" => Factor::Random(
            tuple.get_item(1)?.extract()?,
            tuple.get_item(2)?.extract()?,
            tuple.get_item(3)?.extract()?,
        ),
        other => {
            return Err(PyValueError::new_err(format!(
                "unknown kind of factor {other:?}"
            )));
        }
    })
}

/// The [`Plan`] of a specification dict (keys `factors`, `t0`, `t_end`,
/// `h`, `output_interval`, `max_steps`, `events`, `method`, `rtol`, `atol`,
/// `final_state`, `at`, `statistics`, `history`, `threads`, `progress`).
///
/// # Errors
/// `ValueError` with the runtime's reason for anything malformed.
pub fn plan(spec: &Bound<'_, PyDict>) -> PyResult<Plan> {
    let factors: Vec<Bound<'_, PyTuple>> = item(spec, "factors")?;
    let factors = factors.iter().map(factor).collect::<PyResult<Vec<_>>>()?;
    let keep_spec = KeepSpec {
        final_state: item(spec, "final_state")?,
        at: item(spec, "at")?,
        statistics: item(spec, "statistics")?,
        history: item(spec, "history")?,
    };
    let settings = RunSettings::new(
        item(spec, "t0")?,
        item(spec, "t_end")?,
        item(spec, "h")?,
        item(spec, "output_interval")?,
    )
    .with_max_steps(item(spec, "max_steps")?)
    .with_events(event_settings(item(spec, "events")?)?);
    let method_name: String = item(spec, "method")?;
    Ok(Plan {
        cases: cases(&factors).map_err(PyValueError::new_err)?,
        settings,
        method: method(&method_name, item(spec, "rtol")?, item(spec, "atol")?)
            .map_err(PyValueError::new_err)?,
        keep: keep(&keep_spec).map_err(PyValueError::new_err)?,
        parallelism: parallelism(item(spec, "threads")?),
        progress: item(spec, "progress")?,
        cancel: Cancel::new(),
    })
}

/// `results` as a dict: `first_case`, `case_columns`, `fields` (name,
/// length), `case_values` (cases × columns), `values` (cases × width),
/// `errors` (a message or `None` per case).
///
/// # Errors
/// Python's, when the dict cannot be filled.
pub fn results_dict<'py>(py: Python<'py>, results: &Results) -> PyResult<Bound<'py, PyDict>> {
    let layout = results.layout();
    let n = results.len();
    let out = PyDict::new(py);
    out.set_item("first_case", results.first_case())?;
    out.set_item("case_columns", layout.case_columns.clone())?;
    let fields: Vec<(String, usize)> = layout
        .fields
        .iter()
        .map(|f| (f.name.clone(), f.len))
        .collect();
    out.set_item("fields", fields)?;
    out.set_item(
        "case_values",
        rows(
            py,
            results.case_values().to_vec(),
            n,
            layout.case_columns.len(),
        )?,
    )?;
    out.set_item(
        "values",
        rows(py, results.values().to_vec(), n, layout.width())?,
    )?;
    out.set_item("errors", results.errors().to_vec())?;
    Ok(out)
}

/// A folder run's summary as a dict: `cases`, `ran`, `skipped`,
/// `failed`, `seconds`.
///
/// # Errors
/// Python's, when the dict cannot be filled.
pub fn summary_dict<'py>(py: Python<'py>, summary: &StudySummary) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("cases", summary.cases)?;
    out.set_item("ran", summary.ran)?;
    out.set_item("skipped", summary.skipped)?;
    out.set_item("failed", summary.failed)?;
    out.set_item("seconds", summary.elapsed.as_secs_f64())?;
    Ok(out)
}
