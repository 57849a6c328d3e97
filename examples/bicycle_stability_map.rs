//! The Whipple bicycle's stability map, a study: the eigenvalues of the
//! roll-steer motion (`examples/models/bicycle.sim`, linearized upright)
//! over forward speed × the rear frame's mass (rider and frame, inertia
//! held at the benchmark's), 201 × 37 = 7 437 linearizations on every
//! core. The picture shades where every eigenvalue has a negative real
//! part (self-stable), draws the weave and capsize speeds found on the
//! grid, and marks the published benchmark speeds at mB = 85 kg (weave
//! 4.292, capsize 6.024 m/s; Meijaard et al. 2007).
//!
//! `cargo run --release --example bicycle_stability_map [-- OUTPUT_FOLDER]`
//! (default folder: `target/bicycle`; writes `bicycle-stability-map.svg`).

use std::error::Error;

use autosim::runtime::Model;
use autosim::runtime::study::{Cases, Modes, Study};
use plotters::prelude::*;

#[path = "common/output_folder.rs"]
mod output_folder;
use output_folder::output_folder;

#[path = "common/legend.rs"]
mod legend;
use legend::draw_legend;

autosim::model!(file = "examples/models/bicycle.sim", linearize = true);
use bicycle::Bicycle;

/// Published benchmark speeds (Meijaard, Papadopoulos, Ruina & Schwab 2007).
const WEAVE: f64 = 4.29238253634111;
const CAPSIZE: f64 = 6.02426201538837;
const BENCHMARK_MASS: f64 = 85.0;
const R_REAR: f64 = 0.3;

/// The grid: speeds (m/s) and rear frame masses (kg).
fn grid() -> (Vec<f64>, Vec<f64>) {
    let speeds = (0..=200).map(|k| k as f64 * 0.05).collect();
    let masses = (0..=36).map(|k| 40.0 + k as f64 * 2.5).collect();
    (speeds, masses)
}

/// Where `f` crosses zero going from `a` to `b` between two grid values
/// (linear interpolation).
fn crossing(v0: f64, v1: f64, a: f64, b: f64) -> f64 {
    v0 + (v1 - v0) * a / (a - b)
}

fn main() -> Result<(), Box<dyn Error>> {
    let folder = output_folder("target/bicycle")?;
    let (speeds, masses) = grid();
    let cases = Cases::new().grid("mB", &masses)?.grid("v", &speeds)?;
    // The rear wheel's rate, the speed the state vector holds.
    let wheel_rate = Bicycle::STATE_NAMES
        .iter()
        .position(|n| *n == "u_thetaR")
        .ok_or("no state u_thetaR")?;
    let modes = Modes::<Bicycle>::new(Some(&["phi", "delta", "u_phi", "u_delta"]), None)?;
    let study = Study::new(Bicycle::new, cases, modes).setup(&["v"], move |v, _model, x| {
        x[wheel_rate] = v[0] / R_REAR;
        Ok(())
    });
    let results = study.run_cases(0..study.cases().len())?;
    assert_eq!(
        results.failures(),
        0,
        "{:?}",
        results.errors().iter().flatten().next()
    );
    // The largest real part of each case's eigenvalues (4 per case).
    let max_re: Vec<f64> = results
        .field("re")
        .ok_or("no field re")?
        .chunks(4)
        .map(|re| re.iter().copied().fold(f64::NEG_INFINITY, f64::max))
        .collect();
    // Per mass: the first and last speed of the stable band.
    let n = speeds.len();
    let mut band = Vec::new();
    for (row, m) in max_re.chunks(n).zip(&masses) {
        let stable = |k: usize| row[k] < 0.0;
        let Some(first) = (1..n).find(|k| stable(*k) && !stable(k - 1)) else {
            continue;
        };
        let last = (first..n - 1).find(|k| stable(*k) && !stable(k + 1));
        let weave = crossing(speeds[first - 1], speeds[first], row[first - 1], row[first]);
        let capsize = last.map(|k| crossing(speeds[k], speeds[k + 1], row[k], row[k + 1]));
        band.push((*m, weave, capsize));
    }
    let at_benchmark = band
        .iter()
        .find(|b| b.0 == BENCHMARK_MASS)
        .ok_or("no band at 85 kg")?;
    println!(
        "{} linearizations; at mB = 85 kg the grid (0.05 m/s) gives weave {:.3} m/s (published {WEAVE:.3}), capsize {:.3} m/s (published {CAPSIZE:.3})",
        results.len(),
        at_benchmark.1,
        at_benchmark.2.unwrap_or(f64::NAN)
    );
    for (m, weave, capsize) in band.iter().step_by(8) {
        println!(
            "  mB = {m:5.1} kg: stable from {weave:.3} to {:.3} m/s",
            capsize.unwrap_or(f64::NAN)
        );
    }
    let path = folder.join("bicycle-stability-map.svg");
    let mut svg = String::new();
    draw(&mut svg, &speeds, &masses, &max_re, &band).map_err(|e| e.to_string())?;
    std::fs::write(&path, svg)?;
    println!("wrote {}", path.display());
    Ok(())
}

/// A cell's color: green where stable; where not, red in five steps of
/// the growth rate (up to 4 /s and above).
fn shade(max_re: f64) -> RGBColor {
    if max_re < 0.0 {
        return RGBColor(120, 200, 120);
    }
    let s = (max_re / 4.0).clamp(0.0, 1.0);
    let level = (s * 4.0).round() / 4.0;
    RGBColor(
        255,
        (235.0 - 150.0 * level) as u8,
        (220.0 - 150.0 * level) as u8,
    )
}

/// The map: cells colored by the largest real part (green where stable),
/// the band's edges, the published speeds.
fn draw(
    svg: &mut String,
    speeds: &[f64],
    masses: &[f64],
    max_re: &[f64],
    band: &[(f64, f64, Option<f64>)],
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::with_string(svg, (900, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let (dv, dm) = (speeds[1] - speeds[0], masses[1] - masses[0]);
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Whipple bicycle: self-stable region (all Re λ < 0)",
            ("sans-serif", 22),
        )
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(64)
        .build_cartesian_2d(
            0.0..speeds[speeds.len() - 1] + dv / 2.0,
            masses[0] - dm / 2.0..masses[masses.len() - 1] + dm / 2.0,
        )?;
    chart
        .configure_mesh()
        .x_desc("forward speed v [m/s]")
        .y_desc("rear frame mass mB [kg]")
        .axis_desc_style(("sans-serif", 16))
        .disable_mesh()
        .draw()?;
    // A rectangle per run of equally colored cells along each row.
    let mut cells = Vec::new();
    for (i, m) in masses.iter().enumerate() {
        let row = &max_re[i * speeds.len()..(i + 1) * speeds.len()];
        let mut start = 0;
        for j in 1..=row.len() {
            if j == row.len() || shade(row[j]) != shade(row[start]) {
                let (v0, v1) = (speeds[start] - dv / 2.0, speeds[j - 1] + dv / 2.0);
                let color = shade(row[start]);
                cells.push(Rectangle::new(
                    [(v0, m - dm / 2.0), (v1, m + dm / 2.0)],
                    color.filled(),
                ));
                start = j;
            }
        }
    }
    chart.draw_series(cells)?;
    let weave: Vec<(f64, f64)> = band.iter().map(|b| (b.1, b.0)).collect();
    let capsize: Vec<(f64, f64)> = band.iter().filter_map(|b| b.2.map(|c| (c, b.0))).collect();
    chart
        .draw_series(LineSeries::new(weave, BLUE.stroke_width(2)))?
        .label("weave speed (grid)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    chart
        .draw_series(LineSeries::new(capsize, BLACK.stroke_width(2)))?
        .label("capsize speed (grid)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    let published = [(WEAVE, "weave 4.292 m/s"), (CAPSIZE, "capsize 6.024 m/s")];
    chart
        .draw_series(
            published
                .iter()
                .map(|(v, _)| Cross::new((*v, BENCHMARK_MASS), 7, RED.stroke_width(3))),
        )?
        .label("published, benchmark (mB = 85 kg)")
        .legend(|(x, y)| Cross::new((x + 10, y), 5, RED.stroke_width(3)));
    chart.draw_series(published.iter().map(|(v, label)| {
        Text::new(
            label.to_string(),
            (*v + 0.1, BENCHMARK_MASS + 3.0),
            ("sans-serif", 14),
        )
    }))?;
    draw_legend(&mut chart, SeriesLabelPosition::LowerRight)?;
    root.present()?;
    Ok(())
}
