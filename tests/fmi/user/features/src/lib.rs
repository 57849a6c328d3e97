//! The model of every language feature as an FMU: its user function
//! `friction` and user subroutine `sensor` are the ones the workspace's
//! tests run it with (`tests/support/src/features_user.rs`).

include!(concat!(env!("OUT_DIR"), "/features.rs"));
include!(concat!(env!("OUT_DIR"), "/features_fmu.rs"));

#[path = "../../../../support/src/features_user.rs"]
mod user;

/// The user code: no state of its own.
#[derive(Clone, Copy, Debug, Default)]
pub struct User;

impl features::Externs for User {
    fn friction(&mut self, speed: f64, normal: f64) -> f64 {
        user::friction(speed, normal)
    }

    fn sensor(&mut self, t: f64, x: f64) -> [f64; 2] {
        user::sensor(t, x)
    }
}

autosim_fmi::export_fmi2! {
    model: features::Features<User>,
    new: features::Features::new(User),
    guid: features_fmu::GUID,
    dependent: features_fmu::DEPENDENT,
    linearize: false,
}
