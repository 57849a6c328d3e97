//! Trim: states and inputs such that chosen derivatives vanish (static
//! equilibrium: every speed's rate and every speed zero; steady motion:
//! some speeds held at given values), by damped Newton with the model's
//! generated Jacobian (`A` and `B` of its linearization), as SD/FAST's
//! `sdstatic`/`sdsteady` with a lock list.
//!
//! The user names what is free (states and inputs the solver may change)
//! and what must vanish (the time derivatives of some states); everything
//! else is held at its value in the starting state. With position
//! constraints, the dependent coordinates follow (assembled after every
//! update).

use super::DMatrix;
use crate::{Linearize, ModelError};
use std::fmt;
use std::string::{String, ToString};
use std::vec::Vec;
use std::{format, vec};

/// What a trim solves.
#[derive(Clone, Debug, PartialEq)]
pub struct Trim {
    /// States the solver may change (names from `STATE_NAMES`; linear
    /// states only: not the dependent coordinates).
    pub free_states: Vec<String>,
    /// Inputs the solver may change (names from `INPUT_NAMES`).
    pub free_inputs: Vec<String>,
    /// States whose time derivative must vanish.
    pub steady: Vec<String>,
    /// Largest residual accepted (in the derivatives' units).
    pub tolerance: f64,
    /// Newton iterations allowed.
    pub max_iterations: usize,
    /// Largest change of an unknown in one Newton iteration, relative to
    /// `max(1, |value|)` (a step that would go further is shortened as a
    /// whole, keeping its direction): a trust region, so a nearly flat
    /// Jacobian far from the solution cannot throw the unknowns away.
    pub max_step: f64,
}

impl Trim {
    /// A trim with the default tolerance (1e-10) and iteration limit (50).
    pub fn new(free_states: &[&str], free_inputs: &[&str], steady: &[&str]) -> Trim {
        let own = |v: &[&str]| v.iter().map(|s| s.to_string()).collect();
        Trim {
            free_states: own(free_states),
            free_inputs: own(free_inputs),
            steady: own(steady),
            tolerance: 1e-10,
            max_iterations: 50,
            max_step: 1.0,
        }
    }
}

/// A Newton step longer than this, relative to `1 + max |unknown|`, means
/// the Jacobian is singular for all practical purposes (the linear model
/// has no nearby solution): reported as [`TrimError::Singular`].
const SINGULAR_STEP: f64 = 1e8;

/// What a converged trim did.
#[derive(Clone, Debug, PartialEq)]
pub struct TrimReport {
    /// Newton iterations.
    pub iterations: usize,
    /// The largest residual at the end.
    pub residual: f64,
}

/// Why a trim failed.
#[derive(Clone, Debug, PartialEq)]
pub enum TrimError {
    /// A name that is not a state, input, or linear state; no unknown or
    /// no residual; fewer unknowns than residuals (over-determined: in
    /// general no point makes every residual vanish); a `max_step` or
    /// `tolerance` that is not positive.
    Invalid(String),
    /// Newton's method did not bring the residuals below the tolerance:
    /// each steady state's derivative at the best point reached.
    NotConverged {
        /// Iterations done.
        iterations: usize,
        /// `(state, dx/dt)` of every steady state.
        residuals: Vec<(String, f64)>,
        /// No step along Newton's direction lowered the residuals (a
        /// local minimum of their size that is not a solution), before
        /// `max_iterations`.
        stalled: bool,
    },
    /// The Jacobian of the residuals by the unknowns is singular (or so
    /// nearly that its Newton step would go more than 1e8 times the
    /// unknowns' size): the free variables do not control the steady
    /// derivatives there (or not independently). Start elsewhere, or free
    /// other variables.
    Singular {
        /// The residuals at that point.
        residuals: Vec<(String, f64)>,
    },
    /// The model failed (singular mass matrix or constraints, assembly).
    Model(ModelError),
}

impl fmt::Display for TrimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let list = |r: &[(String, f64)]| {
            r.iter()
                .map(|(n, v)| format!("{n}' = {v:e}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        match self {
            TrimError::Invalid(m) => write!(f, "trim: {m}"),
            TrimError::NotConverged {
                iterations,
                residuals,
                stalled: true,
            } => write!(
                f,
                "trim stalled after {iterations} iterations (no step lowers the residuals: a local minimum of their size, not a solution; start elsewhere): {}",
                list(residuals)
            ),
            TrimError::NotConverged {
                iterations,
                residuals,
                ..
            } => write!(
                f,
                "trim did not converge in {iterations} iterations: {}",
                list(residuals)
            ),
            TrimError::Singular { residuals } => write!(
                f,
                "trim: the free variables do not control the steady derivatives (singular Jacobian) at {}",
                list(residuals)
            ),
            TrimError::Model(e) => write!(f, "trim: {e}"),
        }
    }
}

impl std::error::Error for TrimError {}

impl From<ModelError> for TrimError {
    fn from(e: ModelError) -> Self {
        TrimError::Model(e)
    }
}

/// Where the unknowns and residuals sit.
struct Layout {
    /// State index of each free state, and its column in `A`.
    states: Vec<(usize, usize)>,
    /// Input index of each free input.
    inputs: Vec<usize>,
    /// State index of each steady state, and its row in `A`.
    steady: Vec<(usize, usize)>,
}

fn layout<M: Linearize<Float = f64>>(spec: &Trim) -> Result<Layout, TrimError> {
    let state = |n: &String| -> Result<(usize, usize), TrimError> {
        let k = M::STATE_NAMES
            .iter()
            .position(|s| s == n)
            .ok_or_else(|| TrimError::Invalid(format!("`{n}` is not a state")))?;
        let col = M::LINEAR_STATES
            .iter()
            .position(|s| *s == k)
            .ok_or_else(|| {
                TrimError::Invalid(format!(
                    "`{n}` is a dependent coordinate: it follows the others (free them instead)"
                ))
            })?;
        Ok((k, col))
    };
    let states = spec
        .free_states
        .iter()
        .map(state)
        .collect::<Result<Vec<_>, _>>()?;
    let steady = spec
        .steady
        .iter()
        .map(state)
        .collect::<Result<Vec<_>, _>>()?;
    let inputs = spec
        .free_inputs
        .iter()
        .map(|n| {
            M::INPUT_NAMES
                .iter()
                .position(|s| s == n)
                .ok_or_else(|| TrimError::Invalid(format!("`{n}` is not an input")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if states.len() + inputs.len() == 0 || steady.is_empty() {
        return Err(TrimError::Invalid(
            "name at least one free state or input and one steady state".to_string(),
        ));
    }
    let unknowns = states.len() + inputs.len();
    if unknowns < steady.len() {
        return Err(TrimError::Invalid(format!(
            "{} steady derivative{} but {unknowns} free unknown{}: over-determined (free as many states or inputs as there are steady states)",
            steady.len(),
            if steady.len() == 1 { "" } else { "s" },
            if unknowns == 1 { "" } else { "s" },
        )));
    }
    if !(spec.max_step > 0.0 && spec.tolerance > 0.0) {
        return Err(TrimError::Invalid(
            "max_step and tolerance must be positive".to_string(),
        ));
    }
    Ok(Layout {
        states,
        inputs,
        steady,
    })
}

/// Solves `spec` from the state `x` and the model's current inputs; on
/// success `x` and the model's inputs hold the trimmed values.
///
/// Damped Newton: each step solves `J δ = −r` (least squares when the
/// unknowns outnumber the residuals) with `J` from the model's generated
/// `A` and `B`, is shortened to [`Trim::max_step`], and is halved until the
/// residual decreases.
///
/// # Errors
/// [`TrimError`]: a bad name, no convergence (with the residuals), a
/// singular Jacobian, or the model's error. `x` and the inputs are left
/// at the best point reached.
pub fn trim<M: Linearize<Float = f64>>(
    model: &mut M,
    t: f64,
    x: &mut M::State,
    spec: &Trim,
) -> Result<TrimReport, TrimError> {
    let lay = layout::<M>(spec)?;
    let nw = M::INPUT_NAMES.len();
    let mut w = vec![0.0; nw];
    model.input_values(&mut w);
    model.assemble(t, x)?;
    let mut r = residuals(model, t, x, &lay)?;
    for iteration in 0..spec.max_iterations {
        let size = norm(&r);
        if size <= spec.tolerance {
            return Ok(TrimReport {
                iterations: iteration,
                residual: size,
            });
        }
        let j = jacobian(model, t, x, &lay)?;
        let rhs = nalgebra::DVector::from_iterator(r.len(), r.iter().map(|v| -v));
        let singular = || TrimError::Singular {
            residuals: named::<M>(&lay, &r),
        };
        let mut step = solve(&j, &rhs).ok_or_else(singular)?;
        let size_of_unknowns = unknowns(&lay, x, &w).fold(0.0, |m: f64, v| m.max(v.abs()));
        if step.amax() > SINGULAR_STEP * (1.0 + size_of_unknowns) {
            return Err(singular());
        }
        // The trust region: shorten the whole step to `max_step`.
        let limit = unknowns(&lay, x, &w)
            .zip(step.iter())
            .map(|(v, d)| spec.max_step * v.abs().max(1.0) / d.abs())
            .fold(1.0, f64::min);
        step *= limit;
        let (mut lambda, mut accepted) = (1.0, false);
        for _ in 0..30 {
            let (mut xt, mut wt) = (*x, w.clone());
            apply(&lay, &step, lambda, &mut xt, &mut wt);
            model.set_input_values(&wt);
            let trial = model
                .assemble(t, &mut xt)
                .and_then(|_| residuals(model, t, &xt, &lay));
            if let Ok(rt) = trial
                && norm(&rt) < size
            {
                (*x, w, r, accepted) = (xt, wt, rt, true);
                break;
            }
            lambda *= 0.5;
        }
        model.set_input_values(&w);
        if !accepted {
            return Err(TrimError::NotConverged {
                iterations: iteration + 1,
                residuals: named::<M>(&lay, &r),
                stalled: true,
            });
        }
    }
    let size = norm(&r);
    if size <= spec.tolerance {
        return Ok(TrimReport {
            iterations: spec.max_iterations,
            residual: size,
        });
    }
    Err(TrimError::NotConverged {
        iterations: spec.max_iterations,
        residuals: named::<M>(&lay, &r),
        stalled: false,
    })
}

/// The unknowns' current values: the free states, then the free inputs.
fn unknowns<'a>(
    lay: &'a Layout,
    x: &'a impl AsRef<[f64]>,
    w: &'a [f64],
) -> impl Iterator<Item = f64> + 'a {
    let xs = x.as_ref();
    let states = lay.states.iter().map(move |(k, _)| xs[*k]);
    states.chain(lay.inputs.iter().map(move |k| w[*k]))
}

fn norm(r: &[f64]) -> f64 {
    r.iter().fold(0.0, |m, v| {
        if v.is_finite() {
            m.max(v.abs())
        } else {
            f64::INFINITY
        }
    })
}

/// The steady states' derivatives.
fn residuals<M: Linearize<Float = f64>>(
    model: &mut M,
    t: f64,
    x: &M::State,
    lay: &Layout,
) -> Result<Vec<f64>, ModelError> {
    let mut dx = *x;
    model.derivatives(t, x, &mut dx)?;
    Ok(lay.steady.iter().map(|(k, _)| dx.as_ref()[*k]).collect())
}

/// `∂(steady derivatives)/∂(free states, free inputs)` from `A` and `B`.
fn jacobian<M: Linearize<Float = f64>>(
    model: &mut M,
    t: f64,
    x: &M::State,
    lay: &Layout,
) -> Result<DMatrix<f64>, ModelError> {
    let (nl, nw, ny) = (
        M::LINEAR_STATES.len(),
        M::INPUT_NAMES.len(),
        M::OUTPUT_NAMES.len(),
    );
    let (mut a, mut b, mut c, mut d) = (
        vec![0.0; nl * nl],
        vec![0.0; nl * nw],
        vec![0.0; ny * nl],
        vec![0.0; ny * nw],
    );
    model.linearize_into(t, x, &mut a, &mut b, &mut c, &mut d)?;
    let cols = lay.states.len() + lay.inputs.len();
    Ok(DMatrix::from_fn(lay.steady.len(), cols, |i, j| {
        let row = lay.steady[i].1;
        match lay.states.get(j) {
            Some((_, col)) => a[row * nl + col],
            None => b[row * nw + lay.inputs[j - lay.states.len()]],
        }
    }))
}

/// `J δ = rhs`: LU when square, least squares (minimum norm) otherwise.
fn solve(j: &DMatrix<f64>, rhs: &nalgebra::DVector<f64>) -> Option<nalgebra::DVector<f64>> {
    let scale = j.amax();
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    let svd = j.clone().svd(true, true);
    let smallest = svd
        .singular_values
        .iter()
        .fold(f64::INFINITY, |m, s| m.min(*s));
    if smallest <= 1e-12 * scale {
        return None;
    }
    svd.solve(rhs, 1e-14 * scale).ok()
}

fn apply(
    lay: &Layout,
    step: &nalgebra::DVector<f64>,
    lambda: f64,
    x: &mut impl AsMut<[f64]>,
    w: &mut [f64],
) {
    let xs = x.as_mut();
    for (i, (k, _)) in lay.states.iter().enumerate() {
        xs[*k] += lambda * step[i];
    }
    for (i, k) in lay.inputs.iter().enumerate() {
        w[*k] += lambda * step[lay.states.len() + i];
    }
}

fn named<M: Linearize<Float = f64>>(lay: &Layout, r: &[f64]) -> Vec<(String, f64)> {
    lay.steady
        .iter()
        .zip(r)
        .map(|((k, _), v)| (M::STATE_NAMES[*k].to_string(), *v))
        .collect()
}
