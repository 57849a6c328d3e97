//! The satellite model (`examples/models/satellite.sim`) and its user code
//! as the shared library of an FMU: the model compiled by the build script
//! (`autosim_fmu::generate`), the `Externs` in [`control`], and every FMI
//! 2.0 function from one `export_fmi2!`.

include!(concat!(env!("OUT_DIR"), "/satellite.rs"));
include!(concat!(env!("OUT_DIR"), "/satellite_fmu.rs"));

pub mod control;

autosim_fmi::export_fmi2! {
    model: satellite::Satellite<control::Control>,
    new: satellite::Satellite::new(control::Control),
    guid: satellite_fmu::GUID,
    dependent: satellite_fmu::DEPENDENT,
    linearize: false,
}
