//! The model behind the Python object, as an object-safe trait on slices:
//! [`Engine`], implemented for every generated model by [`Adapter`]. Loops
//! over many states live here, inside the generic code, so a vectorized
//! call is one virtual call, not one per state.

use crate::Generated;
use crate::inputs::InputSource;
use crate::interrupt::Poll;
use crate::simulate::{Failure, Request, Sampler, Trajectory, simulate};
use crate::study::{self, Outcome, Plan};
use autosim_runtime::analysis::Trim;
use autosim_runtime::study::Layout;
use autosim_runtime::{Model, ModelError, StateArray};

/// Sizes of a model's vectors.
#[derive(Clone, Copy, Debug)]
pub struct Sizes {
    /// States.
    pub states: usize,
    /// Independent generalized speeds.
    pub speeds: usize,
    /// Inputs.
    pub inputs: usize,
    /// Outputs.
    pub outputs: usize,
    /// Parameters.
    pub parameters: usize,
    /// Discrete variables.
    pub discrete: usize,
}

/// Why a call on many states failed: the row and the model's error.
pub type RowError = (usize, ModelError);

/// A model as the Python object uses it: every vector a slice of the
/// length [`Engine::sizes`] gives (checked by the caller).
pub trait Engine: Send + Sync {
    /// The vector sizes.
    fn sizes(&self) -> Sizes;
    /// The state's names, in order.
    fn state_names(&self) -> &'static [&'static str];
    /// The interface JSON.
    fn interface(&self) -> &'static str;
    /// A copy (same parameters and inputs).
    fn boxed_clone(&self) -> Box<dyn Engine>;
    /// Parameter values in declaration order.
    fn parameters(&self) -> Vec<f64>;
    /// Sets every parameter value (recomputing the constants).
    fn set_parameters(&mut self, values: &[f64]);
    /// Input values in declaration order.
    fn inputs(&self) -> Vec<f64>;
    /// Sets every input value.
    fn set_inputs(&mut self, values: &[f64]);
    /// The model's default initial state.
    fn initial_state(&self) -> Vec<f64>;
    /// The discrete variables' values (declaration order): their initial
    /// values, which the equations read outside a simulation.
    fn discrete(&self) -> Vec<f64>;
    /// Sets every discrete variable (what the equations read until they
    /// are set again).
    fn set_discrete(&mut self, values: &[f64]);
    /// `dx/dt` at `(t, x)` with the current inputs.
    fn derivatives(&mut self, t: f64, x: &[f64], dx: &mut [f64]) -> Result<(), ModelError>;
    /// Outputs at `(t, x)` with the current inputs.
    fn outputs(&mut self, t: f64, x: &[f64], y: &mut [f64]) -> Result<(), ModelError>;
    /// `dx/dt` (or the outputs, `outputs = true`) for each row of `x`
    /// (row-major, `sizes().states` columns) at the times `t` (one, or one
    /// per row), with the inputs `u` (one row per state row) or the
    /// current inputs; restores the current inputs afterwards.
    fn many(
        &mut self,
        outputs: bool,
        t: &[f64],
        x: &[f64],
        u: Option<&[f64]>,
        out: &mut [f64],
    ) -> Result<(), RowError>;
    /// The mass matrix, row-major.
    fn mass_matrix(&mut self, t: f64, x: &[f64], m: &mut [f64]);
    /// The forcing vector.
    fn forcing(&mut self, t: f64, x: &[f64], f: &mut [f64]);
    /// `A, B, C, D` (`None` without a generated linearization).
    fn linearize(
        &mut self,
        t: f64,
        x: &[f64],
        abcd: [&mut [f64]; 4],
    ) -> Option<Result<(), ModelError>>;
    /// Solves the position constraints for the dependent coordinates.
    fn assemble(&mut self, t: f64, x: &mut [f64]) -> Result<(), ModelError>;
    /// Trims `x` (and the model's free inputs) as `spec` says: the
    /// iterations and the final residual, the error's message, or `None`
    /// without a generated linearization.
    fn trim(&mut self, t: f64, x: &mut [f64], spec: &Trim) -> Option<Result<(usize, f64), String>>;
    /// Integrates as `request` says with the inputs from `inputs` or set
    /// by `sampler`, until `poll` says stop.
    fn simulate(
        &mut self,
        request: &Request,
        inputs: Box<dyn InputSource>,
        sampler: Option<Sampler>,
        poll: Poll,
    ) -> Result<Trajectory, Failure>;
    /// Runs a study of copies of this model (its parameters and inputs as
    /// they are now).
    fn study(&self, plan: &Plan, request: study::Request<'_>) -> Result<Outcome, String>;
    /// A study's description, output times and layout (its columns
    /// checked).
    fn describe_study(&self, plan: &Plan) -> Result<(String, Vec<f64>, Layout), String>;
}

/// Rows [`derivatives_batch`] hands the model per call: enough for the
/// lanes, few enough to stay in the first-level cache (the whole array at
/// once cost more than twice the time of one call per row: 94 against
/// 41 ns per row, 100 000 rows of a six-state model; 46 in batches of 64).
const BATCH: usize = 64;

/// The derivatives at `rows` states (row-major in `x`) at one time with
/// the current inputs, through the model's `Model::derivatives_batch`,
/// [`BATCH`] rows per call (a model generated with `lanes = true`
/// evaluates four states per call of its lanes function); the first
/// failing row's error, as one call per row would give.
fn derivatives_batch<M: Model<Float = f64>>(
    model: &mut M,
    t: f64,
    x: &[f64],
    rows: usize,
    out: &mut [f64],
) -> Result<(), RowError> {
    let ns = M::STATE_NAMES.len();
    let mut states = vec![M::State::zeros(); BATCH.min(rows)];
    let mut rates = states.clone();
    let mut status = vec![Ok(()); states.len()];
    for first in (0..rows).step_by(BATCH) {
        let n = BATCH.min(rows - first);
        for (l, s) in states.iter_mut().enumerate().take(n) {
            let row = first + l;
            *s = state::<M>(&x[row * ns..(row + 1) * ns]);
        }
        model.derivatives_batch(t, &states[..n], &mut rates[..n], &mut status[..n]);
        for (l, (rate, done)) in rates.iter().zip(&status).enumerate().take(n) {
            let row = first + l;
            (*done).map_err(|e| (row, e))?;
            out[row * ns..(row + 1) * ns].copy_from_slice(rate.as_ref());
        }
    }
    Ok(())
}

/// The derivatives at `rows` states (row-major in `x`), each at its own
/// time (`t`: one, or one per row) and with its own inputs (`u`: one row
/// per state row, or the model's current inputs), through
/// `Model::derivatives_each` on four copies of `model` at a time (a model
/// generated with `lanes = true` evaluates the four in one call, each lane
/// at its time with its inputs); the first failing row's error, as one
/// call per row would give.
fn derivatives_each_row<M: Model<Float = f64> + Clone>(
    model: &M,
    t: &[f64],
    x: &[f64],
    u: Option<&[f64]>,
    out: &mut [f64],
) -> Result<(), RowError> {
    const LANES: usize = autosim_runtime::batch::LANES;
    let (ns, ni) = (M::STATE_NAMES.len(), M::INPUT_NAMES.len());
    let rows = x.len().checked_div(ns).unwrap_or(0);
    let mut group: [M; LANES] = core::array::from_fn(|_| model.clone());
    let mut values = vec![autosim_runtime::Lanes::ZERO; M::LANE_VALUES];
    if u.is_none() {
        // The same four models throughout: gathered once.
        M::lane_values(&group, &mut values);
    }
    for first in (0..rows).step_by(LANES) {
        let n = LANES.min(rows - first);
        if let Some(u) = u {
            for (l, m) in group.iter_mut().enumerate().take(n) {
                let row = first + l;
                m.set_input_values(&u[row * ni..(row + 1) * ni]);
            }
            M::lane_values(&group, &mut values);
        }
        let mut times = [0.0; LANES];
        let mut states = [M::State::zeros(); LANES];
        let lanes = times.iter_mut().zip(states.iter_mut());
        for (l, (time, x_row)) in lanes.enumerate().take(n) {
            let row = first + l;
            *time = if t.len() == 1 { t[0] } else { t[row] };
            *x_row = state::<M>(&x[row * ns..(row + 1) * ns]);
        }
        let mut rates = [M::State::zeros(); LANES];
        let mut status = [Ok(()); LANES];
        let values = if n == LANES { &values[..] } else { &[] };
        M::derivatives_each(
            &mut group[..n],
            values,
            &times[..n],
            &states[..n],
            &mut rates[..n],
            &mut status[..n],
        );
        for (l, (rate, done)) in rates.iter().zip(status).enumerate().take(n) {
            let row = first + l;
            done.map_err(|e| (row, e))?;
            out[row * ns..(row + 1) * ns].copy_from_slice(rate.as_ref());
        }
    }
    Ok(())
}

/// A generated model as an [`Engine`].
#[derive(Clone)]
pub struct Adapter<M>(pub M);

/// A state array of `M` from a slice of the same length.
pub fn state<M: Model<Float = f64>>(x: &[f64]) -> M::State {
    let mut s = M::State::zeros();
    s.as_mut().copy_from_slice(x);
    s
}

impl<M: Generated> Engine for Adapter<M> {
    fn state_names(&self) -> &'static [&'static str] {
        M::STATE_NAMES
    }

    fn sizes(&self) -> Sizes {
        Sizes {
            states: M::STATE_NAMES.len(),
            speeds: M::N_SPEEDS,
            inputs: M::INPUT_NAMES.len(),
            outputs: M::OUTPUT_NAMES.len(),
            parameters: M::PARAMETER_NAMES.len(),
            discrete: M::DISCRETE_NAMES.len(),
        }
    }

    fn interface(&self) -> &'static str {
        M::INTERFACE
    }

    fn boxed_clone(&self) -> Box<dyn Engine> {
        Box::new(self.clone())
    }

    fn parameters(&self) -> Vec<f64> {
        let mut v = vec![0.0; M::PARAMETER_NAMES.len()];
        self.0.parameter_values(&mut v);
        v
    }

    fn set_parameters(&mut self, values: &[f64]) {
        self.0.set_parameter_values(values);
    }

    fn inputs(&self) -> Vec<f64> {
        let mut v = vec![0.0; M::INPUT_NAMES.len()];
        self.0.input_values(&mut v);
        v
    }

    fn set_inputs(&mut self, values: &[f64]) {
        self.0.set_input_values(values);
    }

    fn initial_state(&self) -> Vec<f64> {
        self.0.initial_state().as_ref().to_vec()
    }

    fn discrete(&self) -> Vec<f64> {
        let mut v = vec![0.0; M::DISCRETE_NAMES.len()];
        self.0.discrete_values(&mut v);
        v
    }

    fn set_discrete(&mut self, values: &[f64]) {
        self.0.set_discrete_values(values);
    }

    fn derivatives(&mut self, t: f64, x: &[f64], dx: &mut [f64]) -> Result<(), ModelError> {
        let mut d = M::State::zeros();
        self.0.derivatives(t, &state::<M>(x), &mut d)?;
        dx.copy_from_slice(d.as_ref());
        Ok(())
    }

    fn outputs(&mut self, t: f64, x: &[f64], y: &mut [f64]) -> Result<(), ModelError> {
        let mut o = M::Outputs::zeros();
        self.0.outputs(t, &state::<M>(x), &mut o)?;
        y.copy_from_slice(o.as_ref());
        Ok(())
    }

    fn many(
        &mut self,
        outputs: bool,
        t: &[f64],
        x: &[f64],
        u: Option<&[f64]>,
        out: &mut [f64],
    ) -> Result<(), RowError> {
        let (ns, ni) = (M::STATE_NAMES.len(), M::INPUT_NAMES.len());
        let width = if outputs { M::OUTPUT_NAMES.len() } else { ns };
        let rows = x.len().checked_div(ns).unwrap_or(0);
        // A model with lanes evaluates four rows per call; another one,
        // one call per row below (its batch would be the same calls, with
        // copies around them).
        if !outputs && M::LOCKSTEP {
            if t.len() == 1 && u.is_none() {
                return derivatives_batch(&mut self.0, t[0], x, rows, out);
            }
            return derivatives_each_row(&self.0, t, x, u, out);
        }
        let saved = self.inputs();
        let mut result = Ok(());
        for k in 0..rows {
            let tk = if t.len() == 1 { t[0] } else { t[k] };
            if let Some(u) = u {
                self.0.set_input_values(&u[k * ni..(k + 1) * ni]);
            }
            let xk = state::<M>(&x[k * ns..(k + 1) * ns]);
            let row = &mut out[k * width..(k + 1) * width];
            let done = if outputs {
                let mut o = M::Outputs::zeros();
                self.0
                    .outputs(tk, &xk, &mut o)
                    .map(|()| row.copy_from_slice(o.as_ref()))
            } else {
                let mut d = M::State::zeros();
                self.0
                    .derivatives(tk, &xk, &mut d)
                    .map(|()| row.copy_from_slice(d.as_ref()))
            };
            if let Err(e) = done {
                result = Err((k, e));
                break;
            }
        }
        self.0.set_input_values(&saved);
        result
    }

    fn mass_matrix(&mut self, t: f64, x: &[f64], m: &mut [f64]) {
        self.0.mass_matrix_into(t, &state::<M>(x), m);
    }

    fn forcing(&mut self, t: f64, x: &[f64], f: &mut [f64]) {
        self.0.forcing_into(t, &state::<M>(x), f);
    }

    fn linearize(
        &mut self,
        t: f64,
        x: &[f64],
        abcd: [&mut [f64]; 4],
    ) -> Option<Result<(), ModelError>> {
        self.0.linearize_rows(t, &state::<M>(x), abcd)
    }

    fn assemble(&mut self, t: f64, x: &mut [f64]) -> Result<(), ModelError> {
        let mut s = state::<M>(x);
        self.0.assemble(t, &mut s)?;
        x.copy_from_slice(s.as_ref());
        Ok(())
    }

    fn trim(&mut self, t: f64, x: &mut [f64], spec: &Trim) -> Option<Result<(usize, f64), String>> {
        let mut s = state::<M>(x);
        let done = self.0.trim_with(t, &mut s, spec)?;
        x.copy_from_slice(s.as_ref());
        Some(
            done.map(|r| (r.iterations, r.residual))
                .map_err(|e| e.to_string()),
        )
    }

    fn simulate(
        &mut self,
        request: &Request,
        inputs: Box<dyn InputSource>,
        sampler: Option<Sampler>,
        poll: Poll,
    ) -> Result<Trajectory, Failure> {
        simulate(&self.0, request, inputs, sampler, poll)
    }

    fn study(&self, plan: &Plan, request: study::Request<'_>) -> Result<Outcome, String> {
        study::run(&self.0, plan, request)
    }

    fn describe_study(&self, plan: &Plan) -> Result<(String, Vec<f64>, Layout), String> {
        study::describe(&self.0, plan)
    }
}
