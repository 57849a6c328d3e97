//! What runs for each case ([`Task`]), what it keeps ([`Field`]), and why a
//! case failed ([`CaseError`]).

use std::string::{String, ToString};
use std::vec::Vec;

use crate::batch::LANES;
use crate::{IntegrationError, Lanes, Model, ModelError};

/// A kept quantity: `len` values per case under one name (1 for a
/// number; more for a time history or a list of eigenvalues).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Field {
    /// The name (a column of the results).
    pub name: String,
    /// Values per case.
    pub len: usize,
}

impl Field {
    /// A field of `len` values named `name`.
    pub fn new(name: &str, len: usize) -> Field {
        Field {
            name: name.to_string(),
            len,
        }
    }
}

/// Why a case failed. The study records it (as text) beside the case and
/// goes on with the others.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CaseError {
    /// The run stopped: a non-finite state, a step-size underflow, a
    /// failed Newton iteration, a model error (among them a failed
    /// assembly), the step limit.
    #[error("{0}")]
    Run(#[from] IntegrationError),
    /// The model failed outside a run (linearizing, assembling).
    #[error("{0}")]
    Model(#[from] ModelError),
    /// The task's own reason (a trim that did not converge, a check of a
    /// user task).
    #[error("{0}")]
    Other(String),
    /// The case panicked (the message; the panic was caught, the study
    /// went on).
    #[error("panicked: {0}")]
    Panic(String),
}

/// What a study does with each case: simulate ([`Simulate`](super::Simulate)),
/// linearize and keep the eigenvalues ([`Modes`](super::Modes), feature
/// `analysis`), or anything a closure does ([`Custom`]).
///
/// A task must be deterministic: the same model, parameters and initial
/// state give the same values, bit for bit (every task of this module is).
pub trait Task<M: Model>: Sync {
    /// The quantities kept per case, in order.
    fn fields(&self) -> Vec<Field>;

    /// Runs one case: `model` has the case's parameters and inputs, `x` its
    /// initial state. Writes the kept values into `out` (the sum of the
    /// fields' lengths, in field order).
    ///
    /// # Errors
    /// Why the case failed; the study fills its values with NaN.
    fn run(&self, model: &mut M, x: &mut M::State, out: &mut [f64]) -> Result<(), CaseError>;

    /// Text that identifies the task in a study's manifest: a study
    /// resumed with a different description is refused.
    fn describe(&self) -> String;

    /// Whether [`Task::run_group`] runs cases together (see
    /// [`lockstep`](super#lockstep)). `false` by default: every case
    /// through [`Task::run`].
    fn runs_in_lockstep(&self) -> bool {
        false
    }

    /// Runs cases together, case `k` on `models[k]` (with its parameters
    /// and inputs; `values`, what [`Model::lane_values`] gathered from
    /// `models`) from its initial state `xs[k]`: writes case `k`'s kept
    /// values into `outs[k]` and sets `done[k]` when it finished exactly
    /// as [`Task::run`] would have, bit for bit. A case left not done (one
    /// that fails, or every case, as the default does) is run again alone
    /// by the study on a fresh model, so it fails as it does alone; its
    /// row is then written again. `models` and `values` may come back
    /// changed (reordered, as lanes leave).
    fn run_group(
        &self,
        models: &mut [M],
        values: &mut [Lanes<LANES>],
        xs: &[M::State],
        outs: &mut [&mut [f64]],
        done: &mut [bool],
    ) {
        let _ = (models, values, xs, outs, done);
    }
}

/// A task written as a closure `|model, x, out| -> Result<(), CaseError>`
/// that writes `fields` into `out` (for stiff models, runs with events
/// of your own, anything [`Simulate`](super::Simulate) does not do).
///
/// ```
/// use autosim_runtime::study::{Cases, Custom, Field, Study};
/// use autosim_runtime::{Model, ModelError};
///
/// struct Decay { k: f64 }
/// impl Model for Decay {
///     type Float = f64;
///     type State = [f64; 1];
///     type Outputs = [f64; 0];
///     const NAME: &'static str = "Decay";
///     const STATE_NAMES: &'static [&'static str] = &["x"];
///     const STATE_UNITS: &'static [&'static str] = &["1"];
///     const PARAMETER_NAMES: &'static [&'static str] = &["k"];
///     fn derivatives(&mut self, _: f64, x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
///         dx[0] = -self.k * x[0];
///         Ok(())
///     }
///     fn parameter_values(&self, p: &mut [f64]) { p[0] = self.k; }
///     fn set_parameter_values(&mut self, p: &[f64]) { self.k = p[0]; }
/// }
///
/// // Keep the initial slope dx/dt and the time constant.
/// let task = Custom::new("slope and time constant v1", &[Field::new("slope", 1), Field::new("tau", 1)],
///     |model: &mut Decay, x: &mut [f64; 1], out: &mut [f64]| {
///         let mut dx = [0.0];
///         model.derivatives(0.0, x, &mut dx)?;
///         out[0] = dx[0];
///         out[1] = 1.0 / model.k;
///         Ok(())
///     });
/// let cases = Cases::new().grid("k", &[1.0, 4.0]).unwrap().grid("x", &[2.0]).unwrap();
/// let results = Study::new(|| Decay { k: 0.0 }, cases, task).run_cases(0..2).unwrap();
/// assert_eq!(results.values(), [-2.0, 1.0, -8.0, 0.25]);
/// ```
pub struct Custom<C> {
    name: String,
    fields: Vec<Field>,
    run: C,
}

impl<C> Custom<C> {
    /// A task named `name` (its description in the manifest: change the
    /// name when the closure changes, or a resumed study mixes old and new
    /// results) keeping `fields`, computed by `run`.
    pub fn new<M>(name: &str, fields: &[Field], run: C) -> Custom<C>
    where
        M: Model,
        C: Fn(&mut M, &mut M::State, &mut [f64]) -> Result<(), CaseError>,
    {
        Custom {
            name: name.to_string(),
            fields: fields.to_vec(),
            run,
        }
    }
}

impl<M, C> Task<M> for Custom<C>
where
    M: Model,
    C: Fn(&mut M, &mut M::State, &mut [f64]) -> Result<(), CaseError> + Sync,
{
    fn fields(&self) -> Vec<Field> {
        self.fields.clone()
    }

    fn run(&self, model: &mut M, x: &mut M::State, out: &mut [f64]) -> Result<(), CaseError> {
        (self.run)(model, x, out)
    }

    fn describe(&self) -> String {
        std::format!("custom `{}` {:?}", self.name, self.fields)
    }
}
