//! autosim: a symbolic multibody compiler for Rust.
//!
//! Describe a mechanical system (bodies, joints, forces, moments, outputs,
//! and the user code it calls); at compile time autosim derives the
//! equations of motion symbolically (Kane's method) and writes Rust that
//! reads as if a careful dynamicist had written it by hand: no allocation,
//! common subexpressions named once, constants computed once per parameter
//! set, an unrolled solve of the mass matrix.
//!
//! ```
//! autosim::model! {
//!     /// A pendulum with a damped hinge.
//!     model Pendulum;
//!     parameters { m = 1 [kg], l = 0.5 [m], g = 9.81 [m/s^2], c = 0.05 [N m s/rad] }
//!     body P { rotate: 1, mass: m, cm: [0, 0, -l], inertia: 0 }
//!     moment hinge { on: P, reaction: N, about: n1, magnitude: -c*u(P) }
//!     gravity = -g*n3;
//!     output height [m] = dot(pos(P.cm), n3);
//! }
//!
//! use autosim::runtime::Model;
//! let mut model = pendulum::Pendulum::new();
//! let x = [0.3, 0.0];
//! let mut dx = [0.0; 2];
//! model.derivatives(0.0, &x, &mut dx).unwrap();
//! assert!(dx[1] < 0.0); // swings back
//! ```
#![no_std]
#![deny(missing_docs)]

pub use autosim_macros::model;
pub use autosim_runtime as runtime;

/// Compiling `.sim` models from build scripts (feature `build`): write
/// `autosim::build::compile("models/pendulum.sim")?` in `build.rs` (its
/// `main` returning `Result<(), Box<dyn std::error::Error>>`; the error's
/// `Debug` is the readable diagnostics) and
/// `autosim::include_model!(pendulum);` where the module should appear.
#[cfg(feature = "build")]
pub use autosim_core::build_script as build;

/// Functional Mock-up Units (feature `fmu`): `autosim::fmu::Fmu::new(
/// "models/quarter_car.sim").build()?` writes `QuarterCar.fmu` (FMI 2.0,
/// Model Exchange and Co-Simulation) from a build script or any tool; see
/// the guide's FMI chapter.
#[cfg(feature = "fmu")]
pub use autosim_fmu as fmu;

/// Includes a model compiled by a build script (`autosim::build`): expands
/// to the generated module `$name` from `OUT_DIR/$name.rs`. `$name` is the
/// model's name in snake case (`model CartPole;` → `cart_pole`,
/// `model FourBarH;` → `four_bar_h`), not the file's; given the file's name,
/// it fails with an error naming the right module.
#[macro_export]
macro_rules! include_model {
    ($name:ident) => {
        include!(concat!(env!("OUT_DIR"), "/", stringify!($name), ".rs"));
    };
}

/// The language reference (`docs/language.md` in the repository): its Rust
/// examples are compiled and run by `cargo test`.
#[doc = include_str!("../docs/language.md")]
pub mod language {}

/// The user's guide, chapter by chapter (`docs/guide/` in the repository):
/// every code block is compiled and run by `cargo test`.
pub mod guide {
    #[doc = include_str!("../docs/guide/01_first_model.md")]
    pub mod first_model {}
    #[doc = include_str!("../docs/guide/02_parameters_inputs_outputs.md")]
    pub mod parameters_inputs_outputs {}
    #[doc = include_str!("../docs/guide/03_user_code.md")]
    pub mod user_code {}
    #[doc = include_str!("../docs/guide/04_build_scripts.md")]
    pub mod build_scripts {}
    #[doc = include_str!("../docs/guide/05_scenes.md")]
    pub mod scenes {}
    #[doc = include_str!("../docs/guide/06_f32_and_embedded.md")]
    pub mod f32_and_embedded {}
    #[doc = include_str!("../docs/guide/07_generated_code.md")]
    pub mod generated_code {}
    #[doc = include_str!("../docs/guide/08_constraints_and_linearization.md")]
    pub mod constraints_and_linearization {}
    #[doc = include_str!("../docs/guide/09_fmi.md")]
    pub mod fmi {}
    #[doc = include_str!("../docs/guide/10_studies.md")]
    #[cfg(feature = "study")]
    pub mod studies {}
    #[doc = include_str!("../docs/guide/11_events.md")]
    pub mod events {}
}

/// The README's example, compiled and run as a doctest.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
