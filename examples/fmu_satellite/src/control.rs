//! The satellite's user code for its FMU: the paper's slew commands
//! (SUBROUTINE CMD) and proportional thrusters that saturate smoothly, so
//! that any integrator, an importer's included, can take them (the
//! paper's bang-bang thrusters with their saved state need a fixed step).
//!
//! Written against the generated `satellite` module of the enclosing
//! crate: `tests/fmi.rs` includes this file beside its own compilation of
//! the model to run the same user code in autosim's own integrator.

use super::satellite::Externs;

/// The paper's user code, shared with the examples (its CMD is used here).
#[allow(dead_code, unused_macros)]
#[path = "../../common/figure8.rs"]
mod figure8;

/// The commands and the thrusters. No saved state: the FMU's states are
/// the model's.
#[derive(Clone, Copy, Debug, Default)]
pub struct Control;

/// Attitude error at which a thruster pair gives 76 % of its thrust (rad).
const BAND: f64 = 0.05;

impl Externs for Control {
    fn thrust(&mut self, _t: f64, _axis: f64, error: f64) -> f64 {
        -(error / BAND).tanh()
    }

    fn cmd(&mut self, t: f64) -> [f64; 2] {
        figure8::Figure8::commands_only().cmd(t)
    }
}
