//! What the tests of stability at the extremes share (`extremes_*.rs`
//! include it as `mod extremes;`). Each case states its expected behaviour
//! and asserts it: the run passes (with a stated accuracy), or it stops with
//! a typed error that names the cause. Never a silent NaN, a hang or a
//! panic. The models are small files in `tests/models/extremes/` so every
//! case runs in well under a second in a debug build (the 10⁶-step runs use
//! a one-degree-of-freedom oscillator).
//!
//! - `extremes_integration.rs`: stiff springs, mass and inertia ratios,
//!   very large speeds and steps far beyond the stability limit, on the
//!   two-link model;
//! - `extremes_singular.rs`: singular mass matrices, found at compile time
//!   or at run time;
//! - `extremes_rotations.rs`: the 1-2-3 singularity, and Euler parameters
//!   that have none;
//! - `extremes_drift.rs`: the energy drift of each integrator over 10⁶
//!   steps.

use autosim::runtime::{IntegrationError, Model, RunSettings, RunSummary, Stepper, run};

/// Runs from 0 to `stop` (one output at each end) and returns the summary
/// or the integration error; `x` ends at the last good state.
pub fn run_to<M, S>(
    model: &mut M,
    stepper: &mut S,
    x: &mut M::State,
    stop: f64,
    step: f64,
    max_steps: u64,
) -> Result<RunSummary<f64>, IntegrationError>
where
    M: Model<Float = f64>,
    S: Stepper<M> + ?Sized,
{
    let settings = RunSettings::new(0.0, stop, step, stop).with_max_steps(max_steps);
    run(model, stepper, x, &settings, &mut |_, _: &_, _: &_| {}).map_err(IntegrationError::from)
}
