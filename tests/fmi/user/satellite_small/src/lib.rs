//! The satellite with the paper's small variables as an FMU: the user code
//! of `examples/fmu_satellite` (smooth thrusters, the paper's commands).

include!(concat!(env!("OUT_DIR"), "/satellite_small.rs"));
include!(concat!(env!("OUT_DIR"), "/satellite_small_fmu.rs"));

/// The module `control.rs` implements the `Externs` of.
mod satellite {
    pub use super::satellite_small::Externs;
}

#[path = "../../../../../examples/fmu_satellite/src/control.rs"]
pub mod control;

autosim_fmi::export_fmi2! {
    model: satellite_small::SatelliteSmall<control::Control>,
    new: satellite_small::SatelliteSmall::new(control::Control),
    guid: satellite_small_fmu::GUID,
    dependent: satellite_small_fmu::DEPENDENT,
    linearize: false,
}
