//! The paper's slew in two forms, shared by `examples/sampled_control.rs`
//! and `tests/sampled_control.rs`: the thruster logic in the derivatives (a
//! stateful `extern fn`) and as a 100 Hz sampled controller. Include it
//! after `figure8.rs` (as `figure8`).

use autosim::runtime::{Model, RunSettings, Stepper, run, run_sampled};

pub mod models {
    autosim::model!(file = "examples/models/satellite.sim");
    autosim::model!(file = "examples/models/satellite_sampled.sim");
}
pub use models::satellite::Satellite;
pub use models::satellite_sampled::SatelliteSampled;

use super::figure8::Figure8;

figure8_externs!(models::satellite => f64);

/// The sampled model calls only the commands (a function of time).
impl models::satellite_sampled::Externs for Figure8 {
    fn cmd(&mut self, t: f64) -> [f64; 2] {
        Figure8::cmd(self, t)
    }
}

/// The slew's length.
pub const STOP: f64 = 15.0;

/// The slew's run settings: steps of `step` (the first trial step of an
/// adaptive stepper) and one output, at the end.
fn slew_settings(step: f64) -> RunSettings<f64> {
    RunSettings::new(0.0, STOP, step, STOP).with_max_steps(100_000_000)
}

/// A model of the slew made by `new` with the paper's thruster logic, and
/// its initial state.
fn at_start<M: Model>(new: fn(Figure8) -> M) -> (M, M::State) {
    let m = new(Figure8::new());
    let x = m.initial_state();
    (m, x)
}

/// Roll, pitch, yaw at the end and the derivative evaluations, the
/// thrusters in the derivatives.
pub fn in_derivatives<S: Stepper<Satellite<Figure8>>>(
    mut stepper: S,
    step: f64,
) -> ([f64; 3], u64) {
    let (mut m, mut x) = at_start(Satellite::new);
    let settings = slew_settings(step);
    let mut end = [0.0; 3];
    let mut keep_attitude = |_t, _x: &[f64; 20], y: &[f64; 6]| end = [y[0], y[1], y[2]];
    let summary = run(&mut m, &mut stepper, &mut x, &settings, &mut keep_attitude);
    (end, summary.expect("the slew runs").evaluations)
}

/// The same, the thruster logic sampled at 100 Hz (thrust held between
/// samples).
pub fn sampled<S: Stepper<SatelliteSampled<Figure8>>>(
    mut stepper: S,
    step: f64,
) -> ([f64; 3], u64) {
    let (mut m, mut x) = at_start(SatelliteSampled::new);
    let mut logic = Figure8::new();
    let mut controller = |t: f64, _x: &[f64; 20], y: &[f64; 9], w: &mut [f64]| {
        for axis in 0..3 {
            w[axis] = logic.thrust(t, (axis + 1) as f64, y[axis]);
        }
    };
    let mut end = [0.0; 3];
    let summary = run_sampled(
        &mut m,
        &mut stepper,
        &mut x,
        &slew_settings(step),
        0.01,
        &mut controller,
        &mut |_t, _x: &[f64; 20], y: &[f64; 9]| {
            end = [y[3], y[4], y[5]];
        },
    )
    .expect("the slew runs");
    (end, summary.evaluations)
}

/// The largest difference of two attitudes.
pub fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
}
