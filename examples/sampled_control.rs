//! The thruster logic of the paper's slew in the derivatives (a stateful
//! `extern fn`) and as a 100 Hz sampled controller, over integrators and
//! steps: how far each form's attitude at 15 s moves with the integrator.
//! Writes `docs/tradeoff/sampled.md` (or the folder given).
//!
//! `cargo run --release --example sampled_control [-- OUTPUT_FOLDER]`

use autosim::runtime::integrate::{AbmOrder, AdamsBashforthMoulton, DormandPrince, Rk4};
use std::fmt::Write;

#[macro_use]
#[allow(unused_macros, dead_code)]
#[path = "common/figure8.rs"]
mod figure8;
#[path = "common/output_folder.rs"]
mod output_folder;
#[path = "common/slew_forms.rs"]
mod slew_forms;
use output_folder::output_folder;
use slew_forms::{distance, in_derivatives, sampled};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let folder = output_folder("docs/tradeoff")?;
    // References: Dormand–Prince at 1e-12 in each form.
    let (ref_in, _) = in_derivatives(DormandPrince::with_tolerances(1e-12, 1e-12)?, 1e-3);
    let (ref_sampled, _) = sampled(DormandPrince::with_tolerances(1e-12, 1e-12)?, 1e-3);
    let mut md = String::new();
    writeln!(
        md,
        "# Sampled control against user code in the derivatives\n"
    )?;
    writeln!(
        md,
        "The paper's slew (15 s), its thruster logic (FUNCTION THRUST, with saved state) either called from the derivatives at every evaluation, or run by `run_sampled` at 100 Hz with the thrust held between samples. Difference of the bus attitude at 15 s from Dormand–Prince at 1e-12 in the same form (largest of roll, pitch, yaw), and derivative evaluations.\n"
    )?;
    writeln!(
        md,
        "Command: `cargo run --release --example sampled_control`.\n"
    )?;
    writeln!(
        md,
        "| method | setting | in the derivatives [rad] | evaluations | sampled at 100 Hz [rad] | evaluations |"
    )?;
    writeln!(md, "| --- | --- | ---: | ---: | ---: | ---: |")?;
    for h in [0.5e-3, 1e-3, 2e-3, 5e-3, 10e-3] {
        let (a, na) = in_derivatives(Rk4::new(), h);
        let (b, nb) = sampled(Rk4::new(), h);
        writeln!(
            md,
            "| RK4 | h = {} ms | {:.1e} | {na} | {:.1e} | {nb} |",
            h * 1e3,
            distance(a, ref_in),
            distance(b, ref_sampled)
        )?;
    }
    for h in [1e-3, 5e-3] {
        let (a, na) = in_derivatives(AdamsBashforthMoulton::new(AbmOrder::Four), h);
        let (b, nb) = sampled(AdamsBashforthMoulton::new(AbmOrder::Four), h);
        writeln!(
            md,
            "| ABM4 | h = {} ms | {:.1e} | {na} | {:.1e} | {nb} |",
            h * 1e3,
            distance(a, ref_in),
            distance(b, ref_sampled)
        )?;
    }
    for tol in [1e-6, 1e-9] {
        let (a, na) = in_derivatives(DormandPrince::with_tolerances(tol, tol)?, 1e-3);
        let (b, nb) = sampled(DormandPrince::with_tolerances(tol, tol)?, 1e-3);
        writeln!(
            md,
            "| Dormand–Prince | tol {tol:e} | {:.1e} | {na} | {:.1e} | {nb} |",
            distance(a, ref_in),
            distance(b, ref_sampled)
        )?;
    }
    writeln!(
        md,
        "\nIn the derivatives the thrusters' saved state advances at every stage and every rejected trial step, so the answer moves with the integrator and does not converge as the step shrinks; sampled, every integrator converges to the same trajectory (the thrust is a fixed function of time between samples)."
    )?;
    let path = folder.join("sampled.md");
    std::fs::write(&path, &md)?;
    print!("{md}");
    println!("\nwrote {}", path.display());
    Ok(())
}
