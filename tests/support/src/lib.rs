//! What the workspace's tests share, so no test crate copies it:
//!
//! - [`reference`]: the independent reference data in `tests/reference`
//!   (read from the repository, never from outside it);
//! - [`Rng`]: a small deterministic generator, so failures reproduce;
//! - [`rel_err`] and [`max_diff`]: the error norms the tests report;
//! - [`quaternion`]: Euler parameters and 1-2-3 angles, for converting
//!   states between orientations;
//! - [`api`]: the reference models built through the core API, and their
//!   equations evaluated and solved numerically.

pub mod api;
pub mod quaternion;
pub mod reference;
mod rng;

pub use reference::{floats, load};
pub use rng::Rng;

/// Normwise relative error of `got` against `want`: the largest absolute
/// difference over the largest |want|.
pub fn rel_err(got: &[f64], want: &[f64]) -> f64 {
    assert_eq!(got.len(), want.len(), "compared vectors differ in length");
    let scale = want.iter().fold(0.0f64, |a, x| a.max(x.abs())).max(1e-300);
    max_diff(got, want) / scale
}

/// The largest absolute difference between two vectors.
pub fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}
