// Quiet user code for the satellite: thrusters on a dead band, fixed
// commands (the cost of the model, not of user code). Included with
// `include!` by `perf_models.rs` and by `bench/peers` (a crate outside the
// workspace), so both time the same user code.

/// Thrusters on a dead band, fixed commands.
#[derive(Clone, Copy)]
pub struct Quiet;

/// Implements the satellite's `Externs` traits, given by path, for
/// [`Quiet`].
macro_rules! quiet {
    ($($externs:path),+) => {
        $(impl $externs for Quiet {
            fn thrust(&mut self, _t: f64, _axis: f64, error: f64) -> f64 {
                if error > 0.0025 {
                    -1.0
                } else if error < -0.0025 {
                    1.0
                } else {
                    0.0
                }
            }
            fn cmd(&mut self, _t: f64) -> [f64; 2] {
                [0.8584074, -0.5]
            }
        })+
    };
}
