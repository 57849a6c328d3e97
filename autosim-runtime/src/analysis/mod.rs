//! Linear analysis of a model (feature `analysis`; trim alone with feature
//! `trim`): the linear model with
//! its names (`LinearSystem`), its modes (eigenvalues by faer, eigenvectors
//! by nalgebra, as natural frequency, damping ratio or time constant, mode
//! shapes labelled by state), sweeps of eigenvalues over a speed or
//! parameter with plots, trim (equilibrium and steady motion), and exports
//! (JSON, MATLAB/Octave, Python, Markdown).
//!
//! ```
//! # #[cfg(feature = "analysis")] {
//! use autosim_runtime::analysis::LinearSystem;
//! # use nalgebra::DMatrix;
//! // An undamped oscillator x'' = -4 x: eigenvalues ±2i.
//! let sys = LinearSystem::from_matrices(
//!     DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, 0.0]),
//!     &["x", "v"],
//! );
//! let modes = sys.modes();
//! assert!((modes[0].natural_frequency - 2.0).abs() < 1e-12);
//! assert!(modes[0].damping_ratio.abs() < 1e-12);
//! # }
//! ```

#[cfg(feature = "analysis")]
mod export;
#[cfg(feature = "analysis")]
mod modes;
#[cfg(feature = "analysis")]
mod sweep;
#[cfg(feature = "analysis")]
mod system;
mod trim;

#[cfg(feature = "analysis")]
pub use modes::Mode;
pub use nalgebra::{Complex, DMatrix};
#[cfg(feature = "analysis")]
pub use sweep::{Sweep, find_crossing};
#[cfg(feature = "analysis")]
pub use system::{LinearSystem, Named};
pub use trim::{Trim, TrimError, TrimReport, trim};
