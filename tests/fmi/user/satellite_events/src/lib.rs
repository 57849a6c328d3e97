//! The paper's slew with its thrusters as events and discrete modes as an
//! FMU: the commanded slew (the paper's SUBROUTINE CMD) is its only user
//! code.

include!(concat!(env!("OUT_DIR"), "/satellite_events.rs"));
include!(concat!(env!("OUT_DIR"), "/satellite_events_fmu.rs"));

#[allow(dead_code, unused_macros)] // the command only: the thrusters are events
#[path = "../../../../../examples/common/figure8.rs"]
mod figure8;

/// The commanded clock and camera angles of the paper's Figure 8.
pub struct Command;

impl satellite_events::Externs for Command {
    fn cmd(&mut self, t: f64) -> [f64; 2] {
        figure8::Figure8::new().cmd(t)
    }
}

autosim_fmi::export_fmi2! {
    model: satellite_events::SatelliteEvents<Command>,
    new: satellite_events::SatelliteEvents::new(Command),
    guid: satellite_events_fmu::GUID,
    dependent: satellite_events_fmu::DEPENDENT,
    linearize: false,
}
