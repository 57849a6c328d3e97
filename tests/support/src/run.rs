//! The tight runs the tests compare with the reference trajectories.

use autosim_runtime::integrate::DormandPrince;
use autosim_runtime::{Model, RunSettings, RunSummary, run};

/// Every output of a run: the time, the state and the outputs.
pub type Outputs<M> = Vec<(f64, <M as Model>::State, <M as Model>::Outputs)>;

/// Runs `model` from `x` over [0, `stop`] with Dormand–Prince at relative
/// and absolute tolerance 1e-12 (first step 1e-3, at most 10^6 steps), an
/// output every `every` seconds, and keeps every output.
pub fn tight_run<M: Model<Float = f64>>(
    model: &mut M,
    x: &mut M::State,
    stop: f64,
    every: f64,
) -> (RunSummary<f64>, Outputs<M>) {
    let mut dopri = DormandPrince::<M>::with_tolerances(1e-12, 1e-12).unwrap();
    let settings = RunSettings::new(0.0, stop, 1e-3, every).with_max_steps(1_000_000);
    let mut out = Vec::new();
    let summary = run(
        model,
        &mut dopri,
        x,
        &settings,
        &mut |t, x: &M::State, y: &M::Outputs| out.push((t, *x, *y)),
    )
    .unwrap();
    (summary, out)
}
