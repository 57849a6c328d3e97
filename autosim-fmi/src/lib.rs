//! FMI 2.0 for autosim models: the C functions of a Functional Mock-up
//! Unit's shared library (Model Exchange and Co-Simulation in one), generic
//! over any generated model.
//!
//! An FMU's library is a `cdylib` crate holding the generated model and one
//! [`export_fmi2!`] call, which writes every `fmi2*` function of the
//! standard. `autosim-fmu` (the command line and the build API) writes that
//! crate, its `modelDescription.xml` and the `.fmu` archive; a crate with
//! user code writes the call itself (the guide's FMI chapter).
//!
//! What an instance is:
//! - its own model, time and whole state vector (several instances at once,
//!   each with its own parameters);
//! - the standard's state machine ([`instance::Mode`]): a call in a mode
//!   where the standard forbids it returns `fmi2Error` and says why through
//!   the logger, never crashes; a panic inside a call is caught and
//!   returns `fmi2Fatal`;
//! - the FMU's continuous states are the model's states less the dependent
//!   coordinates of position constraints, which are solved (Newton's
//!   method from their last values) whenever the states change, first at
//!   `fmi2ExitInitializationMode`;
//! - Co-Simulation steps with the runtime's integrators ([`layout::Method`],
//!   parameter `cs.method`) through its run driver, the inputs held over
//!   each communication step, projected onto the position constraints
//!   after every integrator step, events located inside the steps;
//! - a model's events (the `Model` trait's event items) are the FMU's
//!   event indicators and discrete variables ([`events`]);
//! - directional derivatives from the model's generated linearization
//!   (when exported with `linearize: true`).

#![deny(missing_docs)]

pub mod entry;
pub mod ffi;
pub mod layout;
pub mod log;

mod cosim;
mod directional;
pub mod events;
pub mod instance;
mod state;

pub use events::EventInterface;
pub use layout::{Layout, Method, Setting, Variable};
pub use state::Snapshot;

use autosim_runtime::{Model, ModelError, StateArray};

/// What [`export_fmi2!`] knows about the exported model beyond the
/// [`Model`] trait.
pub trait Export: 'static {
    /// The model type.
    type Model: Model<Float = f64> + 'static;
    /// The GUID of the FMU's `modelDescription.xml` (checked by
    /// `fmi2Instantiate`).
    const GUID: &'static str;
    /// State-vector positions of the dependent coordinates (solved from
    /// position constraints; not FMU states).
    const DEPENDENT: &'static [usize];

    /// A model with its default parameters.
    fn new() -> Self::Model;

    /// `A`, `B`, `C`, `D` row-major (see `autosim_runtime::Linearize`), or
    /// `None` when the model has no linearization.
    fn linearize(
        model: &mut Self::Model,
        t: f64,
        x: &<Self::Model as Model>::State,
        matrices: [&mut [f64]; 4],
    ) -> Option<Result<(), ModelError>> {
        let _ = (model, t, x, matrices);
        None
    }

    /// The FMU's value-reference numbering.
    fn layout() -> Layout {
        type M<E> = <E as Export>::Model;
        Layout {
            parameters: M::<Self>::PARAMETER_NAMES.len(),
            inputs: M::<Self>::INPUT_NAMES.len(),
            states: <<M<Self> as Model>::State as StateArray<f64>>::LEN - Self::DEPENDENT.len(),
            outputs: <<M<Self> as Model>::Outputs as StateArray<f64>>::LEN,
            dependent: Self::DEPENDENT.len(),
            discrete: M::<Self>::DISCRETE_NAMES.len(),
        }
    }
}

#[doc(hidden)]
pub mod __private {
    pub use autosim_runtime::{Linearize, Model, ModelError};
}

/// Writes every `fmi2*` function of FMI 2.0 for one model, in the crate
/// that builds the FMU's shared library (`crate-type = ["cdylib"]`).
///
/// ```ignore
/// autosim_fmi::export_fmi2! {
///     model: quarter_car::QuarterCar,
///     new: quarter_car::QuarterCar::new(),
///     guid: "{d1c5b1a4-...}",
///     dependent: &[],
///     linearize: true,
/// }
/// ```
///
/// `model` is the generated type (with its `Externs` for a model with user
/// code, e.g. `satellite::Satellite<Thrusters>`), `new` an expression that
/// makes one with default parameters, `guid` the GUID written into
/// `modelDescription.xml`, `dependent` the state-vector positions of the
/// dependent coordinates, a `&'static [usize]` (`&DEPENDENT_COORDINATES` of
/// a model with position constraints, else `&[]`; `autosim_fmu::generate`
/// writes it as `<module>_fmu::DEPENDENT`), `linearize: true` when the model implements
/// `Linearize` (then `fmi2GetDirectionalDerivative` uses it). Only one call
/// per library: the functions have the standard's unprefixed names.
#[macro_export]
macro_rules! export_fmi2 {
    (
        model: $model:ty,
        new: $new:expr,
        guid: $guid:expr,
        dependent: $dep:expr,
        linearize: $lin:tt $(,)?
    ) => {
        #[doc(hidden)]
        pub struct __AutosimFmu;

        impl $crate::Export for __AutosimFmu {
            type Model = $model;
            const GUID: &'static str = $guid;
            const DEPENDENT: &'static [usize] = $dep;
            fn new() -> $model {
                $new
            }
            $crate::export_fmi2!(@linearize $lin, $model);
        }

        $crate::export_fmi2!(@functions __AutosimFmu);
    };
    (@linearize true, $model:ty) => {
        fn linearize(
            model: &mut $model,
            t: f64,
            x: &<$model as $crate::__private::Model>::State,
            [a, b, c, d]: [&mut [f64]; 4],
        ) -> Option<Result<(), $crate::__private::ModelError>> {
            Some(<$model as $crate::__private::Linearize>::linearize_into(model, t, x, a, b, c, d))
        }
    };
    (@linearize false, $model:ty) => {};
    (@functions $e:ty) => {
        $crate::fmi2_functions!($e);
    };
}

mod functions;
