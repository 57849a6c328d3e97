//! The generic Python wrapper of an autosim model.
//!
//! `autosim.load` compiles a model into a small crate whose `lib.rs` is
//! the generated module plus one macro call:
//!
//! ```ignore
//! autosim_python_model::export_model!(autosim_model_3f2a..., generated, Pendulum, linearize);
//! ```
//!
//! The macro implements [`Generated`] for the model (what the Python side
//! needs beyond [`Model`]: mass matrix, forcing, linearization, the stiff
//! integrator of its size) and defines the extension module, whose one
//! function `new()` returns a [`NativeModel`]. Everything else — argument
//! checks, NumPy conversion, the vectorized loops with the GIL released,
//! the integrators and input schedules — is generic code here, compiled
//! once per model for its fixed-size state.

use autosim_runtime::integrate::{SdirkSettings, Stepper};
use autosim_runtime::{Model, ModelError};

mod callables;
mod engine;
mod inputs;
mod interrupt;
mod native;
mod simulate;
mod simulate_args;
pub mod study;
mod study_args;

pub use engine::{Adapter, Engine};
pub use native::NativeModel;
#[doc(hidden)]
pub use native::register;
#[doc(hidden)]
pub use {autosim_runtime, pyo3};

/// What the wrapper needs from a generated model beyond [`Model`]
/// (implemented by [`export_model!`] from the generated module's inherent
/// functions and constants).
pub trait Generated: Model<Float = f64> + Clone + Send + Sync + 'static {
    /// Number of independent generalized speeds (the mass matrix is
    /// `N_SPEEDS × N_SPEEDS`).
    const N_SPEEDS: usize;
    /// The interface JSON the compiler wrote (names, units, docs).
    const INTERFACE: &'static str;
    /// The model with its default parameters and inputs.
    fn create() -> Self;
    /// `M(q)` of `M du/dt = f`, row-major into `m` (`N_SPEEDS²`).
    fn mass_matrix_into(&mut self, t: f64, x: &Self::State, m: &mut [f64]);
    /// `f(q, u, t)` of `M du/dt = f` into `f` (`N_SPEEDS`).
    fn forcing_into(&mut self, t: f64, x: &Self::State, f: &mut [f64]);
    /// `A, B, C, D` row-major, or `None` when the model was compiled
    /// without its linearization.
    fn linearize_rows(
        &mut self,
        t: f64,
        x: &Self::State,
        abcd: [&mut [f64]; 4],
    ) -> Option<Result<(), ModelError>>;
    /// Trims as `spec` says (the runtime's `analysis::trim`: damped
    /// Newton on the linearization), or `None` without a generated
    /// linearization.
    fn trim_with(
        &mut self,
        t: f64,
        x: &mut Self::State,
        spec: &autosim_runtime::analysis::Trim,
    ) -> Option<Result<autosim_runtime::analysis::TrimReport, autosim_runtime::analysis::TrimError>>;
    /// Alexander's SDIRK3 for this model's state size, stepping `W` (the
    /// model with its input schedule).
    fn sdirk3<W: Model<Float = f64, State = Self::State> + 'static>(
        settings: SdirkSettings<f64>,
    ) -> Box<dyn Stepper<W>>;
}

/// Implements [`Generated`] for `$module::$model` and defines the
/// extension module `$name` (its `new()` returns a [`NativeModel`]).
/// Append `linearize` when the model was compiled with its linearization.
#[macro_export]
macro_rules! export_model {
    ($name:ident, $module:ident, $model:ident, interface = $interface:expr $(, $linearize:ident)?) => {
        impl $crate::Generated for $module::$model {
            const N_SPEEDS: usize = $module::N_SPEEDS;
            const INTERFACE: &'static str = $interface;
            fn create() -> Self {
                $module::$model::new()
            }
            fn mass_matrix_into(&mut self, t: f64, x: &Self::State, m: &mut [f64]) {
                let mut rows = [[0.0; $module::N_SPEEDS]; $module::N_SPEEDS];
                self.mass_matrix(t, x, &mut rows);
                $crate::autosim_runtime::linear::copy_rows(&rows, m);
            }
            fn forcing_into(&mut self, t: f64, x: &Self::State, f: &mut [f64]) {
                let mut v = [0.0; $module::N_SPEEDS];
                self.forcing(t, x, &mut v);
                f.copy_from_slice(&v);
            }
            fn linearize_rows(
                &mut self,
                t: f64,
                x: &Self::State,
                abcd: [&mut [f64]; 4],
            ) -> Option<Result<(), $crate::autosim_runtime::ModelError>> {
                $crate::export_model!(@linearize self, t, x, abcd $(, $linearize)?)
            }
            fn trim_with(
                &mut self,
                t: f64,
                x: &mut Self::State,
                spec: &$crate::autosim_runtime::analysis::Trim,
            ) -> Option<
                Result<
                    $crate::autosim_runtime::analysis::TrimReport,
                    $crate::autosim_runtime::analysis::TrimError,
                >,
            > {
                $crate::export_model!(@trim self, t, x, spec $(, $linearize)?)
            }
            fn sdirk3<W>(
                settings: $crate::autosim_runtime::integrate::SdirkSettings<f64>,
            ) -> Box<dyn $crate::autosim_runtime::integrate::Stepper<W>>
            where
                W: $crate::autosim_runtime::Model<Float = f64, State = Self::State> + 'static,
            {
                Box::new($crate::autosim_runtime::integrate::Sdirk3::<W, { $module::N_STATES }>::new(
                    settings,
                ))
            }
        }

        #[$crate::pyo3::pymodule]
        #[pyo3(crate = "::autosim_python_model::pyo3")]
        fn $name(module: &$crate::pyo3::Bound<'_, $crate::pyo3::types::PyModule>) -> $crate::pyo3::PyResult<()> {
            $crate::register::<$module::$model>(module)
        }
    };
    (@linearize $self:ident, $t:ident, $x:ident, $abcd:ident, linearize) => {{
        let [a, b, c, d] = $abcd;
        Some($crate::autosim_runtime::Linearize::linearize_into($self, $t, $x, a, b, c, d))
    }};
    (@linearize $self:ident, $t:ident, $x:ident, $abcd:ident) => {{
        let _ = ($self, $t, $x, $abcd);
        None
    }};
    (@trim $self:ident, $t:ident, $x:ident, $spec:ident, linearize) => {
        Some($crate::autosim_runtime::analysis::trim($self, $t, $x, $spec))
    };
    (@trim $self:ident, $t:ident, $x:ident, $spec:ident) => {{
        let _ = ($self, $t, $x, $spec);
        None
    }};
}
