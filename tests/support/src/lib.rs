//! What the workspace's tests share, so no test crate copies it:
//!
//! - [`reference`](mod@reference): the independent reference data in `tests/reference`
//!   (read from the repository, never from outside it);
//! - [`Rng`]: a small deterministic generator, so failures reproduce;
//! - [`rel_err`] and [`max_diff`]: the error norms the tests report;
//!   [`kinetic_energy`]: ½ uᵀ M u;
//! - [`tight_run`]: a run at tolerance 1e-12 keeping every output, as the
//!   reference trajectories are compared;
//! - [`quaternion`]: Euler parameters and 1-2-3 angles, for converting
//!   states between orientations;
//! - [`api`]: the reference models built through the core API, and their
//!   equations evaluated and solved numerically;
//! - [`alloc_count`]: a global allocator that counts allocations per
//!   thread, for the tests that prove code does not allocate;
//! - [`python`]: the one Python virtual environment of the tests that run
//!   Python (`SKIPPED: ...` when it cannot be had);
//! - [`features_user`]: the user code `examples/models/features.sim` is
//!   tested with.

pub mod alloc_count;
pub mod api;
pub mod features_user;
pub mod python;
pub mod quaternion;
pub mod reference;
mod rng;
mod run;

pub use reference::{
    SatelliteSample, floats, load, program_parameters, sample_error, satellite_samples,
};
pub use rng::Rng;
pub use run::{Outputs, tight_run};

/// Normwise relative error of `got` against `want`: the largest absolute
/// difference over the largest |want|.
pub fn rel_err(got: &[f64], want: &[f64]) -> f64 {
    assert_eq!(got.len(), want.len(), "compared vectors differ in length");
    let scale = want.iter().fold(0.0f64, |a, x| a.max(x.abs())).max(1e-300);
    max_diff(got, want) / scale
}

/// The largest absolute difference between two vectors (NaN if any
/// difference is NaN, so a NaN never passes a tolerance).
pub fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, worst_of)
}

/// The larger of two errors, NaN if either is NaN (`f64::max` would drop
/// the NaN and let a broken result pass).
pub fn worst_of(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// How closely generated code agrees with the reference files, normwise
/// relative (see [`rel_err`]). The files are double-precision solutions,
/// so their own rounding is the limit: chain-planar-10's differs from its
/// exact accelerations by 1.0e-13 (`tests/reference/gen/chain_exact.py`),
/// and the generated code measures at most 1.05e-13 against them.
pub const REFERENCE_AGREEMENT: f64 = 5e-13;

/// The kinetic energy ½ uᵀ M u of the speeds `u` with the mass matrix `mass`.
pub fn kinetic_energy<const N: usize>(mass: &[[f64; N]; N], u: &[f64]) -> f64 {
    (0..N)
        .flat_map(|i| (0..N).map(move |j| (i, j)))
        .map(|(i, j)| 0.5 * u[i] * mass[i][j] * u[j])
        .sum()
}

/// The associated types, name and state names of a hand-written model,
/// inside its `impl Model` (the other lists default to empty); `outputs`
/// is their number, or their names and units (`["energy" in "J"]`):
///
/// ```
/// use autosim_runtime::{Model, ModelError};
/// struct Decay;
/// impl Model for Decay {
///     autosim_test_support::model_header!(f64, "Decay", states: ["x" in "1"], outputs: 0);
///     fn derivatives(&mut self, _t: f64, x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
///         dx[0] = -x[0];
///         Ok(())
///     }
/// }
/// assert_eq!(Decay::STATE_NAMES, ["x"]);
/// ```
#[macro_export]
macro_rules! model_header {
    ($f:ty, $name:literal, states: [$($s:literal in $u:literal),* $(,)?], outputs: [$($o:literal in $ou:literal),* $(,)?]) => {
        $crate::model_header!($f, $name, states: [$($s in $u),*], outputs: [$($o),*].len());
        const OUTPUT_NAMES: &'static [&'static str] = &[$($o),*];
        const OUTPUT_UNITS: &'static [&'static str] = &[$($ou),*];
    };
    ($f:ty, $name:literal, states: [$($s:literal in $u:literal),* $(,)?], outputs: $n:expr) => {
        type Float = $f;
        type State = [$f; [$($s),*].len()];
        type Outputs = [$f; $n];
        const NAME: &'static str = $name;
        const STATE_NAMES: &'static [&'static str] = &[$($s),*];
        const STATE_UNITS: &'static [&'static str] = &[$($u),*];
    };
}

/// The parameters of a hand-written test model, `f64` fields of it, with
/// their units: `PARAMETER_NAMES`, `PARAMETER_UNITS`, `parameter_values`
/// and `set_parameter_values` of its `Model` implementation.
///
/// ```ignore
/// autosim_test_support::model_parameters!(omega in "rad/s", mass in "kg");
/// ```
#[macro_export]
macro_rules! model_parameters {
    ($($p:ident in $u:literal),* $(,)?) => {
        const PARAMETER_NAMES: &'static [&'static str] = &[$(stringify!($p)),*];
        const PARAMETER_UNITS: &'static [&'static str] = &[$($u),*];
        fn parameter_values(&self, values: &mut [f64]) {
            for (v, p) in values.iter_mut().zip([$(self.$p),*]) {
                *v = p;
            }
        }
        fn set_parameter_values(&mut self, values: &[f64]) {
            let mut values = values.iter();
            $(if let Some(v) = values.next() {
                self.$p = *v;
            })*
        }
    };
}

/// Models from one `.sim` file (a path relative to the calling crate),
/// each under its own name with its scene options, as `autosim::model!`
/// takes them:
///
/// ```ignore
/// autosim_test_support::models_from! { "examples/models/satellite.sim":
///     SatelliteF32, float = f32;
///     RigidBoom, lock = [q9, q10], outputs = [roll, pitch, yaw];
/// }
/// ```
#[macro_export]
macro_rules! models_from {
    ($file:tt: $($name:ident $(, $option:ident = $value:tt)*;)+) => {
        $(::autosim::model!(file = $file, name = $name $(, $option = $value)*);)+
    };
}
