//! The satellite whose thrusters are inputs as an FMU: its one piece of
//! user code is the paper's commands (SUBROUTINE CMD); the importer drives
//! the thrusters through the inputs `thr1`..`thr3`.

include!(concat!(env!("OUT_DIR"), "/satellite_sampled.rs"));
include!(concat!(env!("OUT_DIR"), "/satellite_sampled_fmu.rs"));

#[allow(dead_code, unused_macros)]
#[path = "../../../../../examples/common/figure8.rs"]
mod figure8;

/// The paper's slew commands.
#[derive(Clone, Copy, Debug, Default)]
pub struct Commands;

impl satellite_sampled::Externs for Commands {
    fn cmd(&mut self, t: f64) -> [f64; 2] {
        figure8::Figure8::commands_only().cmd(t)
    }
}

autosim_fmi::export_fmi2! {
    model: satellite_sampled::SatelliteSampled<Commands>,
    new: satellite_sampled::SatelliteSampled::new(Commands),
    guid: satellite_sampled_fmu::GUID,
    dependent: satellite_sampled_fmu::DEPENDENT,
    linearize: false,
}
