//! Linear analysis of three models: the pendulum's modes, the quarter
//! car's static ride height (a trim problem) and its bounce and hop modes,
//! and the paper's satellite linearized about its rest attitude (its boom
//! and camera modes), each exported as MATLAB/Octave, Python and JSON.
//!
//! `cargo run --release --example linear_analysis [-- OUTPUT_FOLDER]`
//! (default folder: `target/linear`).

use autosim::runtime::Model;
use autosim::runtime::analysis::{LinearSystem, Trim, trim};
use std::error::Error;
use std::path::Path;

#[path = "common/output_folder.rs"]
mod output_folder;
use output_folder::output_folder;

autosim::model!(file = "examples/models/pendulum.sim");
autosim::model!(file = "examples/models/quarter_car.sim");
autosim::model!(file = "examples/models/satellite.sim", linearize = true);

/// Thrusters off, the clock and camera commanded to where they are in the
/// initial state (4 − π and −0.5 rad): the satellite is at rest there, an
/// equilibrium to linearize about.
struct AtRest;
impl satellite::Externs for AtRest {
    fn thrust(&mut self, _t: f64, _axis: f64, _error: f64) -> f64 {
        0.0
    }
    // The model's initial clock angle is written `4 - 3.1415926`.
    #[allow(clippy::approx_constant)]
    fn cmd(&mut self, _t: f64) -> [f64; 2] {
        [4.0 - 3.1415926, -0.5]
    }
}

fn export(folder: &Path, name: &str, sys: &LinearSystem) -> Result<(), Box<dyn Error>> {
    std::fs::write(folder.join(format!("{name}.m")), sys.to_matlab(name))?;
    std::fs::write(folder.join(format!("{name}.py")), sys.to_python(name))?;
    std::fs::write(folder.join(format!("{name}.json")), sys.to_json())?;
    std::fs::write(folder.join(format!("{name}.md")), sys.to_markdown())?;
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let folder = output_folder("target/linear")?;

    let mut pendulum = pendulum::Pendulum::new();
    let hanging = LinearSystem::of(&mut pendulum, 0.0, &[0.0, 0.0])?;
    println!(
        "pendulum, hanging (sqrt(g/L) = {:.6} rad/s):",
        (9.81f64 / 0.7).sqrt()
    );
    print!("{}", hanging.modes_report());
    export(&folder, "pendulum", &hanging)?;

    let mut car = quarter_car::QuarterCar::new();
    let mut x = car.initial_state();
    let report = trim(
        &mut car,
        0.0,
        &mut x,
        &Trim::new(&["zu", "zs"], &[], &["vu", "vs"]),
    )?;
    println!(
        "\nquarter car at rest: wheel {:.6} m, body {:.6} m ({} Newton iterations)",
        x[0], x[1], report.iterations
    );
    let ride = LinearSystem::of(&mut car, 0.0, &x)?;
    print!("{}", ride.modes_report());
    export(&folder, "quarter_car", &ride)?;

    let mut sat = satellite::Satellite::new(AtRest);
    let rest = sat.initial_state();
    let attitude = LinearSystem::of(&mut sat, 0.0, &rest)?;
    println!(
        "\nsatellite at its rest attitude ({} states):",
        attitude.states.len()
    );
    print!("{}", attitude.modes_report());
    export(&folder, "satellite", &attitude)?;
    println!(
        "\nwrote the linear models (.m, .py, .json, .md) in {}",
        folder.display()
    );
    Ok(())
}
