//! A Monte Carlo of the paper's spacecraft slew, a study: the final
//! attitude error of the bus over thruster misalignment and inertia
//! uncertainty. Each of 1 000 cases draws the bus's principal inertias
//! (IB11, IB22, IB33: normal, 5 % standard deviation) and tilts each
//! thruster pair's couple away from its axis by two small angles (normal,
//! standard deviation 1°), then flies the 15 s maneuver of
//! `examples/satellite.rs` (classic RK4, h = 1 ms, the paper's Figure 8
//! controller and thrusters as Rust user code). The picture is the
//! histogram of the attitude error |(roll, pitch, yaw)| at t = 15 s, with
//! the nominal case (no misalignment, nominal inertia) marked.
//!
//! Misalignment lives in the user code: pair k's couple acts along
//! `d_k = (b_k + α_k b_{k+1} + β_k b_{k+2}) / |…|`, so the moment the model
//! applies about `b_j` (`LTTj · thrust(t, j, error)`) is the sum over the
//! pairs of `LTTk · fire_k · (d_k · b_j)`. The thrust of each pair is its
//! firing state as of its latest call (the model calls the three pairs in
//! one evaluation; a pair called later in the evaluation is seen as it was
//! at the stage before: at most one stage late at a switch, as the
//! thrusters' switching itself is only seen at stages).
//!
//! `cargo run --release --example satellite_monte_carlo [-- OUTPUT_FOLDER [CASES]]`
//! (default folder: `target/satellite_monte_carlo`; writes
//! `satellite-monte-carlo.svg`).

use std::error::Error;

use autosim::runtime::RunSettings;
use autosim::runtime::study::{Cases, Distribution, Keep, Method, Simulate, Study};
use plotters::prelude::*;

#[path = "common/output_folder.rs"]
mod output_folder;
use output_folder::output_folder;

#[path = "common/legend.rs"]
mod legend;
use legend::draw_legend;

#[allow(dead_code, unused_macros)] // the Monte Carlo uses thrust and cmd only
#[path = "common/figure8.rs"]
mod figure8;
use figure8::Figure8;

mod full {
    autosim::model!(file = "examples/models/satellite.sim");
}
use full::satellite::{Externs, Satellite};

/// The paper's Figure 8 with misaligned thruster pairs.
#[derive(Clone, Debug)]
struct Misaligned {
    figure8: Figure8,
    /// `couple[j][k]`: moment about `b_j` per unit of the model's
    /// `LTTj · thrust` from pair `k` firing (`LTTk/LTTj · d_k · b_j`).
    couple: [[f64; 3]; 3],
}

impl Misaligned {
    /// Every pair along its axis (the paper's spacecraft).
    fn aligned() -> Misaligned {
        let mut couple = [[0.0; 3]; 3];
        for (k, row) in couple.iter_mut().enumerate() {
            row[k] = 1.0;
        }
        Misaligned {
            figure8: Figure8::new(),
            couple,
        }
    }

    /// Pairs tilted by `angles = [α1, β1, α2, β2, α3, β3]` (rad) toward the
    /// next two axes, with lever arms `ltt`.
    fn tilted(angles: &[f64], ltt: [f64; 3]) -> Misaligned {
        let mut couple = [[0.0; 3]; 3];
        for k in 0..3 {
            let (a, b) = (angles[2 * k], angles[2 * k + 1]);
            let norm = (1.0 + a * a + b * b).sqrt();
            let mut d = [0.0; 3];
            d[k] = 1.0 / norm;
            d[(k + 1) % 3] = a / norm;
            d[(k + 2) % 3] = b / norm;
            for j in 0..3 {
                couple[j][k] = ltt[k] / ltt[j] * d[j];
            }
        }
        Misaligned {
            figure8: Figure8::new(),
            couple,
        }
    }
}

impl Externs for Misaligned {
    fn thrust(&mut self, t: f64, axis: f64, error: f64) -> f64 {
        self.figure8.thrust(t, axis, error);
        let j = axis as usize - 1;
        (0..3)
            .map(|k| self.couple[j][k] * self.figure8.fire[k])
            .sum()
    }
    fn cmd(&mut self, t: f64) -> [f64; 2] {
        self.figure8.cmd(t)
    }
}

/// Standard deviations: each tilt angle (rad, 1°) and each principal
/// inertia (relative, 5 %).
const TILT: f64 = 1.0 * std::f64::consts::PI / 180.0;
const INERTIA: f64 = 0.05;
const TILTS: [&str; 6] = ["a1", "b1", "a2", "b2", "a3", "b3"];

fn main() -> Result<(), Box<dyn Error>> {
    let folder = output_folder("target/satellite_monte_carlo")?;
    let count: u64 = std::env::args()
        .nth(2)
        .map(|a| a.parse())
        .transpose()?
        .unwrap_or(1000);
    let nominal = Satellite::new(Misaligned::aligned());
    let p = *nominal.parameters();
    let ltt = [p.LTT1, p.LTT2, p.LTT3];
    let mut columns = vec![
        ("IB11", Distribution::normal(p.IB11, INERTIA * p.IB11)),
        ("IB22", Distribution::normal(p.IB22, INERTIA * p.IB22)),
        ("IB33", Distribution::normal(p.IB33, INERTIA * p.IB33)),
    ];
    columns.extend(TILTS.iter().map(|n| (*n, Distribution::normal(0.0, TILT))));
    let cases = Cases::new().random(count, 1991, &columns)?;
    let settings = RunSettings::new(0.0, 15.0, 0.001, 0.5);
    let keep = Keep::new().at(&[15.0], &["roll", "pitch", "yaw"]);
    let task = Simulate::new(settings, Method::Rk4, keep)?;
    let study = Study::new(|| Satellite::new(Misaligned::aligned()), cases, task).setup(
        &TILTS,
        move |angles, model, _x| {
            model.externs = Misaligned::tilted(angles, ltt);
            Ok(())
        },
    );
    let start = std::time::Instant::now();
    let results = study.run_cases(0..count)?;
    println!(
        "{} slews ({} failed) on every core in {:.1} s",
        results.len(),
        results.failures(),
        start.elapsed().as_secs_f64()
    );
    let field = |name: &str| results.field(&format!("{name}@15")).ok_or("no field");
    let (roll, pitch, yaw) = (field("roll")?, field("pitch")?, field("yaw")?);
    let mut errors: Vec<f64> = (0..roll.len())
        .map(|k| 1e3 * (roll[k].powi(2) + pitch[k].powi(2) + yaw[k].powi(2)).sqrt())
        .filter(|e| e.is_finite())
        .collect();
    errors.sort_by(f64::total_cmp);
    let nominal_error = 1e3 * nominal_final_error(nominal)?;
    let quantile = |q: f64| errors[((errors.len() - 1) as f64 * q).round() as usize];
    println!(
        "final attitude error [mrad]: nominal {nominal_error:.3}; min {:.3}, median {:.3}, 95 % {:.3}, max {:.3}",
        errors[0],
        quantile(0.5),
        quantile(0.95),
        errors[errors.len() - 1]
    );
    let path = folder.join("satellite-monte-carlo.svg");
    let mut svg = String::new();
    draw(&mut svg, &errors, nominal_error, quantile(0.95)).map_err(|e| e.to_string())?;
    std::fs::write(&path, svg)?;
    println!("wrote {}", path.display());
    Ok(())
}

/// |(roll, pitch, yaw)| at 15 s of the nominal spacecraft (one case of a
/// one-case study: the same run as every case of the Monte Carlo).
fn nominal_final_error(model: Satellite<Misaligned>) -> Result<f64, Box<dyn Error>> {
    let settings = RunSettings::new(0.0, 15.0, 0.001, 0.5);
    let keep = Keep::new().at(&[15.0], &["roll", "pitch", "yaw"]);
    let task = Simulate::new(settings, Method::Rk4, keep)?;
    let results = Study::new(move || model.clone(), Cases::new(), task)
        .progress(false)
        .run_cases(0..1)?;
    let v = results.values();
    if let Some(e) = &results.errors()[0] {
        return Err(e.clone().into());
    }
    Ok((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
}

/// The histogram (40 bins), the nominal case and the 95th percentile.
fn draw(svg: &mut String, errors: &[f64], nominal: f64, p95: f64) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::with_string(svg, (900, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let (low, high) = (
        errors[0].min(nominal),
        errors[errors.len() - 1].max(nominal),
    );
    let pad = 0.05 * (high - low);
    let (low, top) = (low - pad, high + pad);
    let bins = 40;
    let width = (top - low) / bins as f64;
    let mut counts = vec![0u32; bins];
    for e in errors {
        counts[(((e - low) / width) as usize).min(bins - 1)] += 1;
    }
    let highest = *counts.iter().max().unwrap_or(&1) as f64;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "Satellite slew: final attitude error, {} cases (thrusters tilted 1° σ, inertia 5 % σ)",
                errors.len()
            ),
            ("sans-serif", 20),
        )
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(56)
        .build_cartesian_2d(low..top, 0.0..highest * 1.1)?;
    chart
        .configure_mesh()
        .x_desc("|(roll, pitch, yaw)| at t = 15 s [mrad]")
        .y_desc("cases")
        .axis_desc_style(("sans-serif", 16))
        .disable_x_mesh()
        .draw()?;
    chart.draw_series(counts.iter().enumerate().map(|(k, c)| {
        let x0 = low + k as f64 * width;
        Rectangle::new(
            [(x0, 0.0), (x0 + width, f64::from(*c))],
            RGBColor(90, 130, 200).filled(),
        )
    }))?;
    let line = |x: f64, color: RGBColor| {
        LineSeries::new(vec![(x, 0.0), (x, highest * 1.1)], color.stroke_width(2))
    };
    chart
        .draw_series(line(nominal, BLACK))?
        .label(format!("nominal spacecraft ({nominal:.2} mrad)"))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    chart
        .draw_series(line(p95, RED))?
        .label(format!("95th percentile ({p95:.2} mrad)"))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    root.present()?;
    Ok(())
}
