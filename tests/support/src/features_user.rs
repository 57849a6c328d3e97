//! The user code of `examples/models/features.sim` the tests run it with:
//! plain, smooth and deterministic, so two formulations (or an FMU and an
//! importer's finite differences) see the same values for the same
//! arguments. Included by path (`#[path]`) in the FMU crate
//! `tests/fmi/user/features`, which does not depend on this crate.

/// `extern fn friction(speed [m/s], normal [N]) -> [N]`: viscous friction,
/// 0.1 N per (m/s) and per newton of normal force, against the speed.
pub fn friction(speed: f64, normal: f64) -> f64 {
    -0.1 * speed * normal.abs()
}

/// `extern sub sensor(t, x) -> (s1 [m], s2 [m/s])`: a position reading
/// drifting 0.01 m/s, and half the position as the rate.
pub fn sensor(t: f64, x: f64) -> [f64; 2] {
    [x + 0.01 * t, 0.5 * x]
}
