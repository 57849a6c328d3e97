//! The Whipple bicycle benchmark (Meijaard, Papadopoulos, Ruina & Schwab
//! 2007) from the nonlinear model `examples/models/bicycle.sim`: the
//! linearized roll-steer matrices M, C1, K0, K2, the weave and capsize
//! speeds, the eigenvalues from 0 to 10 m/s (an SVG plot), and the linear
//! model at 5 m/s exported for MATLAB/Octave and Python.
//!
//! `cargo run --release --example bicycle_benchmark [-- OUTPUT_FOLDER]`
//! (default folder: `target/bicycle`).

use autosim::runtime::analysis::{LinearSystem, Sweep, find_crossing};
use std::error::Error;

#[path = "common/output_folder.rs"]
mod output_folder;
use output_folder::output_folder;

autosim::model!(file = "examples/models/bicycle.sim", linearize = true);
use bicycle::Bicycle;

const G: f64 = 9.81;
const R_REAR: f64 = 0.3;
const ROLL_STEER: [&str; 4] = ["phi", "delta", "u_phi", "u_delta"];

/// Upright, straight running at `v` m/s.
fn upright(v: f64) -> [f64; 11] {
    let mut x = [0.0; 11];
    x[9] = v / R_REAR;
    x
}

/// The linear model in roll and steer (the other coordinates are
/// ignorable, the rear wheel's speed is `v`).
fn roll_steer(v: f64) -> Result<LinearSystem, Box<dyn Error>> {
    let mut model = Bicycle::new();
    Ok(LinearSystem::of(&mut model, 0.0, &upright(v))?.restricted(&ROLL_STEER)?)
}

type Matrix2 = [[f64; 2]; 2];

/// `−M · block` of `A` (rows u_phi, u_delta; columns from `first`).
fn times_mass(m: &Matrix2, sys: &LinearSystem, first: usize) -> Matrix2 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            -(m[i][0] * sys.a[(2, first + j)] + m[i][1] * sys.a[(3, first + j)])
        })
    })
}

fn main() -> Result<(), Box<dyn Error>> {
    let folder = output_folder("target/bicycle")?;
    let mut model = Bicycle::new();
    let mut full = [[0.0; 3]; 3];
    model.mass_matrix(0.0, &upright(0.0), &mut full);
    let m = [[full[0][0], full[0][2]], [full[2][0], full[2][2]]];
    let v = 5.0;
    let k0 = times_mass(&m, &roll_steer(0.0)?, 0).map(|r| r.map(|x| x / G));
    let k_v = times_mass(&m, &roll_steer(v)?, 0);
    let k2: Matrix2 =
        std::array::from_fn(|i| std::array::from_fn(|j| (k_v[i][j] - G * k0[i][j]) / (v * v)));
    let c1 = times_mass(&m, &roll_steer(v)?, 2).map(|r| r.map(|x| x / v));
    println!("Whipple bicycle, benchmark parameters (roll, steer):");
    for (name, x) in [("M", m), ("C1", c1), ("K0", k0), ("K2", k2)] {
        println!(
            "  {name:2} = [[{:.14}, {:.14}], [{:.14}, {:.14}]]",
            x[0][0], x[0][1], x[1][0], x[1][1]
        );
    }
    let weave = |v: f64| max_real(v, true);
    let capsize = |v: f64| max_real(v, false);
    let v_weave = find_crossing(weave, 3.0, 5.0, 1e-13).ok_or("no weave speed in 3-5 m/s")?;
    let v_capsize = find_crossing(capsize, 5.0, 7.0, 1e-13).ok_or("no capsize speed in 5-7 m/s")?;
    println!("  weave speed {v_weave:.14} m/s (published 4.29238253634111)");
    println!("  capsize speed {v_capsize:.14} m/s (published 6.02426201538837)");

    let speeds: Vec<f64> = (0..=200).map(|k| k as f64 * 0.05).collect();
    let sweep = Sweep::run("forward speed v [m/s]", &speeds, roll_steer)?;
    let plot = folder.join("bicycle-eigenvalues.svg");
    std::fs::write(
        &plot,
        sweep.eigenvalues_svg("Whipple bicycle: eigenvalues against speed")?,
    )?;
    let at_5 = roll_steer(5.0)?;
    println!("\nmodes at 5 m/s:\n{}", at_5.modes_report());
    std::fs::write(
        folder.join("bicycle_5ms.m"),
        at_5.to_matlab("Bicycle at 5 m/s"),
    )?;
    std::fs::write(
        folder.join("bicycle_5ms.py"),
        at_5.to_python("Bicycle at 5 m/s"),
    )?;
    std::fs::write(folder.join("bicycle_5ms.json"), at_5.to_json())?;
    println!(
        "wrote {} and the linear model at 5 m/s (.m, .py, .json) in {}",
        plot.display(),
        folder.display()
    );
    Ok(())
}

/// The largest real part among the oscillatory (`true`) or real
/// eigenvalues at `v`.
fn max_real(v: f64, oscillatory: bool) -> f64 {
    match roll_steer(v) {
        Ok(sys) => sys
            .eigenvalues()
            .iter()
            .filter(|l| (l.im.abs() > 1e-9) == oscillatory)
            .map(|l| l.re)
            .fold(f64::NEG_INFINITY, f64::max),
        Err(_) => f64::NAN,
    }
}
