//! A `#![no_std]` crate that declares a generated model and steps it with
//! the runtime's RK4. It builds only if the generated code and the runtime
//! need nothing beyond `core` (and `libm` for the math functions):
//! `cargo build -p autosim-no-std-check` is the check, and
//! `cargo test -p autosim-no-std-check` compares the result with the
//! independent reference trajectory.
#![no_std]
#![deny(missing_docs)]

use autosim::runtime::integrate::Rk4;
use autosim::runtime::{IntegrationError, Model, Stepper};

mod model {
    // Relative to this crate's manifest directory.
    autosim::model!(file = "../../examples/models/chain_planar_3.sim");
}

pub use model::chain_planar3::{ChainPlanar3, Parameters};

mod single {
    autosim::model!(
        file = "../../examples/models/chain_planar_3.sim",
        name = ChainPlanar3F32,
        float = f32
    );
}

pub use single::chain_planar3_f32::ChainPlanar3F32;

/// The embedded check's run: the 3-link planar chain in `f32`, from
/// `q = (0.3, -0.2, 0.1)` at rest, 2000 RK4 steps of 1 ms with the default
/// parameters. The Cortex-M4F build (`tests/embedded`, run in QEMU) and the
/// host compute this same function; their final states must agree.
///
/// # Errors
/// The integrator's error.
pub fn swing_f32() -> Result<[f32; 6], IntegrationError> {
    let mut model = ChainPlanar3F32::new();
    let mut rk4 = Rk4::new();
    let mut x = [0.3, -0.2, 0.1, 0.0, 0.0, 0.0];
    let h = 1e-3f32;
    for n in 0..2000u16 {
        rk4.step(&mut model, f32::from(n) * h, &mut x, h)?;
    }
    Ok(x)
}

/// One `derivatives` call of the `f32` chain (the embedded check measures
/// its stack).
///
/// # Errors
/// The model's error (a singular mass matrix).
pub fn derivatives_f32(
    model: &mut ChainPlanar3F32,
    x: &[f32; 6],
    dx: &mut [f32; 6],
) -> Result<(), autosim::runtime::ModelError> {
    model.derivatives(0.0, x, dx)
}

mod closed_loop {
    autosim::model!(file = "../../examples/models/four_bar.sim");
}

pub use closed_loop::four_bar::FourBar;

/// What [`swing`] returns: the final state and the work done.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Swing {
    /// The state after the last step: q1, q2, q3, u1, u2, u3.
    pub state: [f64; 6],
    /// Derivative evaluations made.
    pub evaluations: u64,
}

/// Swings the 3-link planar chain from `x0` for `steps` classic RK4 steps
/// of `h`, with the model's parameters (in `ChainPlanar3::PARAMETER_NAMES`
/// order) set to `parameters`. No allocation, no `std`.
///
/// # Errors
/// The integrator's error (a non-finite state or a singular mass matrix).
pub fn swing(
    parameters: &[f64],
    x0: [f64; 6],
    h: f64,
    steps: u32,
) -> Result<Swing, IntegrationError> {
    let mut model = ChainPlanar3::new();
    model.set_parameter_values(parameters);
    let mut rk4 = Rk4::new();
    let mut x = x0;
    for n in 0..steps {
        rk4.step(&mut model, f64::from(n) * h, &mut x, h)?;
    }
    Ok(Swing {
        state: x,
        evaluations: rk4.evaluations(),
    })
}

/// Runs the four-bar linkage (a closed loop) from `x0` for `steps` RK4
/// steps of `h`: assembled first, projected back onto the loop after each
/// step, as the run driver does. Returns the final state.
///
/// # Errors
/// The integrator's error, or the model's (the loop cannot be closed).
pub fn crank(x0: [f64; 4], h: f64, steps: u32) -> Result<[f64; 4], IntegrationError> {
    let mut model = FourBar::new();
    let mut rk4 = Rk4::new();
    let mut x = x0;
    let model_error = |t: f64| move |error| IntegrationError::Model { t, error };
    model.assemble(0.0, &mut x).map_err(model_error(0.0))?;
    for n in 0..steps {
        let t = f64::from(n) * h;
        rk4.step(&mut model, t, &mut x, h)?;
        model
            .project(t + h, &mut x, 0.0)
            .map_err(model_error(t + h))?;
    }
    Ok(x)
}
