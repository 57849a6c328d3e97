//! The paper's spacecraft slew maneuver, end to end (Sayers, "A Symbolic
//! Computer Language for Multibody Systems", JGCD 1991, Figures 6-9).
//!
//! The clock and camera of the spacecraft slew from (4 - π, -0.5) rad to
//! (3.75 - π, -0.4) rad over t = 1..11 s while three pairs of bang-bang
//! thrusters hold the attitude of the bus inside a dead zone of 0.0025 rad.
//! The model is written twice in the model language: `satellite.sim` (exact)
//! and `satellite_small.sim` (the paper's small-variable option: the bus
//! motion and the boom angles are small). The only hand-written part of the
//! simulation is the paper's Figure 8 (CMD and THRUST), in Rust in
//! `common/figure8.rs`.
//!
//! ```text
//! cargo run --release --example satellite [-- OUTPUT_FOLDER]
//! ```
//!
//! Both models are integrated with classic RK4, h = 1 ms, for 15 s. The
//! program writes into the output folder (default `target/satellite`):
//! - `satellite_full.csv`, `satellite_small.csv`: time histories of every
//!   state and output every 10 ms, with names and units in the header;
//! - `attitude.svg`: the attitude of the bus (q4, q5, q6) of both
//!   formulations against time, like the paper's Figure 9;
//! - `clock_camera.svg`: the commanded slew of the clock and the camera;
//!
//! and prints how far apart the two formulations are, what each run cost,
//! and the operation counts of the generated code.

use std::error::Error;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use autosim::runtime::integrate::Rk4;
use autosim::runtime::io::{CsvWriter, Series, write_svg_plot};
use autosim::runtime::{Model, Observer, OpCount, Stepper};
use indicatif::{ProgressBar, ProgressStyle};

mod full {
    autosim::model!(file = "examples/models/satellite.sim");
}
mod small {
    autosim::model!(file = "examples/models/satellite_small.sim");
}

use full::satellite::Satellite;
use small::satellite_small::SatelliteSmall;

// The paper's Figure 8 (CMD and THRUST), shared with `tradeoff.rs`; the
// same user code serves both generated models.
#[macro_use]
#[path = "common/figure8.rs"]
mod figure8;
use figure8::Figure8;

figure8_externs!(full::satellite => f64, small::satellite_small => f64);

/// Integration step (s).
const H: f64 = 0.001;
/// Steps of the 15 s maneuver.
const STEPS: usize = 15_000;
/// Steps between rows of the CSV files and points of the plots (10 ms).
const OUTPUT_EVERY: usize = 10;

type State = [f64; 20];
type Outputs = [f64; 6];

/// The operation counts a generated model publishes.
struct Ops {
    derivatives: OpCount,
    outputs: OpCount,
    constants: OpCount,
    mass_matrix: OpCount,
    forcing: OpCount,
}

/// What one run produced.
struct Flight {
    /// Output times with the state and the outputs (every `OUTPUT_EVERY` steps).
    rows: Vec<(f64, State, Outputs)>,
    /// q4, q5, q6 after every step (and at t = 0).
    attitude: Vec<[f64; 3]>,
    evaluations: u64,
    wall: Duration,
    /// Thruster bursts started (a pair switching on or reversing), seen at step ends.
    firings: usize,
}

/// Flies the maneuver: RK4 at t_n = n h (stage times t_n, t_n + h/2,
/// t_n + h/2, t_n + h, as the reference). `fire` reads the thrusters' state.
fn fly<M>(
    model: &mut M,
    fire: impl Fn(&M) -> [f64; 3],
    bar: &ProgressBar,
) -> Result<Flight, Box<dyn Error>>
where
    M: Model<Float = f64, State = State, Outputs = Outputs>,
{
    let mut rows = Vec::with_capacity(STEPS / OUTPUT_EVERY + 1);
    let mut attitude = Vec::with_capacity(STEPS + 1);
    let mut rk4 = Rk4::new();
    let mut x = model.initial_state();
    let mut y = [0.0; 6];
    let mut firings = 0;
    let mut was = fire(model);

    let start = Instant::now();
    model.outputs(0.0, &x, &mut y)?;
    rows.push((0.0, x, y));
    attitude.push([x[3], x[4], x[5]]);
    for n in 0..STEPS {
        rk4.step(model, n as f64 * H, &mut x, H)?;
        let t = (n + 1) as f64 * H;
        attitude.push([x[3], x[4], x[5]]);
        let now = fire(model);
        firings += now
            .iter()
            .zip(&was)
            .filter(|(now, was)| **now != 0.0 && now != was)
            .count();
        was = now;
        if (n + 1) % OUTPUT_EVERY == 0 {
            model.outputs(t, &x, &mut y)?;
            rows.push((t, x, y));
        }
        if (n + 1) % 100 == 0 {
            bar.inc(100);
        }
    }
    let wall = start.elapsed();
    bar.finish();
    Ok(Flight {
        rows,
        attitude,
        evaluations: rk4.evaluations(),
        wall,
        firings,
    })
}

/// Writes a run as CSV: `time [s]`, the states, then the outputs, each
/// headed `name [unit]`.
fn write_csv<M>(path: &Path, rows: &[(f64, State, Outputs)]) -> Result<(), Box<dyn Error>>
where
    M: Model<Float = f64, State = State, Outputs = Outputs>,
{
    let mut csv = CsvWriter::<M, _>::create(path)?;
    for (t, x, y) in rows {
        csv.observe(*t, x, y)?;
    }
    csv.into_inner()?;
    Ok(())
}

fn progress_bar(label: &str) -> ProgressBar {
    let bar = ProgressBar::new(STEPS as u64);
    bar.set_style(
        ProgressStyle::with_template("{prefix:>28} [{bar:40}] {pos}/{len} steps")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_prefix(label.to_string());
    bar
}

/// The independent reference trajectory of the full model
/// (`tests/reference/satellite-slew.json`).
fn reference() -> Option<serde_json::Value> {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference/satellite-slew.json");
    let text = std::fs::read_to_string(path).ok()?;
    serde_json::from_str(&text).ok()
}

/// The bus attitude angles, as the plot and the comparison name them.
const ATTITUDE_NAMES: [&str; 3] = ["q4 (roll)", "q5 (pitch)", "q6 (yaw)"];

fn main() -> Result<(), Box<dyn Error>> {
    let Some(folder) = output_folder()? else {
        return Ok(());
    };

    println!("Slew maneuver of Sayers (1991), Figures 8-9: classic RK4, h = {H} s, t = 0..15 s");

    let mut full_model = Satellite::new(Figure8::default());
    let bar = progress_bar("satellite.sim (full)");
    let full = fly(&mut full_model, |m| m.externs.fire, &bar)?;
    let mut small_model = SatelliteSmall::new(Figure8::default());
    let bar = progress_bar("satellite_small.sim (small)");
    let small = fly(&mut small_model, |m| m.externs.fire, &bar)?;

    let files = write_outputs(&folder, &full, &small)?;
    println!();
    println!("Output folder: {}", folder.display());
    for path in &files {
        println!(
            "  {}",
            path.file_name().unwrap_or_default().to_string_lossy()
        );
    }

    print_differences(&full, &small);
    if let Some(data) = reference() {
        print_reference_errors(&full, &data);
    }
    print_costs(&full, &small);
    print_operations();
    Ok(())
}

/// The output folder named on the command line (default
/// `target/satellite`), created and made absolute; `None` after printing
/// the help.
fn output_folder() -> Result<Option<PathBuf>, Box<dyn Error>> {
    let folder = match std::env::args_os().nth(1) {
        Some(a) if a == "-h" || a == "--help" => {
            println!("usage: cargo run --release --example satellite [-- OUTPUT_FOLDER]");
            println!("writes CSV time histories and SVG plots (default folder: target/satellite)");
            return Ok(None);
        }
        Some(a) => PathBuf::from(a),
        None => PathBuf::from("target/satellite"),
    };
    std::fs::create_dir_all(&folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    Ok(Some(folder.canonicalize()?))
}

/// State `i` at every output row.
fn column(rows: &[(f64, State, Outputs)], i: usize) -> Vec<f64> {
    rows.iter().map(|r| r.1[i]).collect::<Vec<f64>>()
}

/// Writes the CSV files of both runs and the two plots into `folder`;
/// returns their paths.
fn write_outputs(
    folder: &Path,
    full: &Flight,
    small: &Flight,
) -> Result<[PathBuf; 4], Box<dyn Error>> {
    let full_csv = folder.join("satellite_full.csv");
    let small_csv = folder.join("satellite_small.csv");
    write_csv::<Satellite<Figure8>>(&full_csv, &full.rows)?;
    write_csv::<SatelliteSmall<Figure8>>(&small_csv, &small.rows)?;
    let time: Vec<f64> = full.rows.iter().map(|r| r.0).collect();
    let full_att: Vec<Vec<f64>> = (3..6).map(|i| column(&full.rows, i)).collect();
    let small_att: Vec<Vec<f64>> = (3..6).map(|i| column(&small.rows, i)).collect();
    let labels: Vec<(String, String)> = ATTITUDE_NAMES
        .iter()
        .map(|n| (format!("{n}, full"), format!("{n}, small")))
        .collect();
    let mut series = Vec::new();
    for k in 0..3 {
        series.push(Series {
            name: &labels[k].0,
            unit: "rad",
            values: &full_att[k],
        });
        series.push(Series {
            name: &labels[k].1,
            unit: "rad",
            values: &small_att[k],
        });
    }
    let attitude_svg = folder.join("attitude.svg");
    write_svg_plot(
        &attitude_svg,
        "Attitude of the spacecraft bus, two formulations (Figure 9)",
        &time,
        &series,
    )?;
    let clock = column(&full.rows, 6);
    let camera = column(&full.rows, 7);
    let clock_camera_svg = folder.join("clock_camera.svg");
    write_svg_plot(
        &clock_camera_svg,
        "Slew of the clock and the camera (full model)",
        &time,
        &[
            Series {
                name: "q7 (clock)",
                unit: "rad",
                values: &clock,
            },
            Series {
                name: "q8 (camera)",
                unit: "rad",
                values: &camera,
            },
        ],
    )?;
    Ok([full_csv, small_csv, attitude_svg, clock_camera_svg])
}

/// How far apart the two formulations are: the largest difference of
/// each attitude angle over every step.
fn print_differences(full: &Flight, small: &Flight) {
    println!();
    println!("Max |full - small| over all {} steps:", STEPS);
    for (k, name) in ATTITUDE_NAMES.iter().enumerate() {
        let (mut worst, mut at) = (0.0f64, 0.0);
        let mut peak = 0.0f64;
        for (n, (a, b)) in full.attitude.iter().zip(&small.attitude).enumerate() {
            peak = peak.max(a[k].abs());
            let d = (a[k] - b[k]).abs();
            if d > worst {
                worst = d;
                at = n as f64 * H;
            }
        }
        println!(
            "  {name:<11} {worst:.3e} rad at t = {at:.3} s  (largest |angle| {peak:.3e} rad, {:.2} %)",
            100.0 * worst / peak.max(f64::MIN_POSITIVE)
        );
    }
}

/// The full model's largest errors in q4..q8 against the independent
/// reference trajectory, at the reference's records.
fn print_reference_errors(full: &Flight, data: &serde_json::Value) {
    let mut worst = [0.0f64; 5];
    let records = data["records"].as_array().map(Vec::as_slice).unwrap_or(&[]);
    for record in records {
        let t = record["t"].as_f64().unwrap_or(f64::NAN);
        let Some(row) = full.rows.iter().find(|r| (r.0 - t).abs() < 1e-9) else {
            continue;
        };
        for (k, w) in worst.iter_mut().enumerate() {
            let want = record[format!("q{}", k + 4)].as_f64().unwrap_or(f64::NAN);
            *w = w.max((row.1[3 + k] - want).abs());
        }
    }
    println!(
        "Full model vs the independent reference ({} records): max |error| q4 {:.1e}, q5 {:.1e}, q6 {:.1e}, q7 {:.1e}, q8 {:.1e} rad",
        records.len(),
        worst[0],
        worst[1],
        worst[2],
        worst[3],
        worst[4]
    );
}

/// One row of the two-column tables (full, small).
fn row(label: &str, a: String, b: String) {
    println!("{label:<34}{a:>28}{b:>28}");
}

/// What each run cost: evaluations, wall time, thruster bursts, and where
/// it ended.
fn print_costs(full: &Flight, small: &Flight) {
    println!();
    println!("{:<34}{:>28}{:>28}", "", "full", "small");
    row(
        "derivative evaluations",
        full.evaluations.to_string(),
        small.evaluations.to_string(),
    );
    row(
        "wall time",
        format!("{:.1} ms", ms(full.wall)),
        format!("{:.1} ms", ms(small.wall)),
    );
    row(
        "per evaluation",
        format!("{:.0} ns", per_eval(full.wall, full.evaluations)),
        format!("{:.0} ns", per_eval(small.wall, small.evaluations)),
    );
    row(
        "thruster bursts started",
        full.firings.to_string(),
        small.firings.to_string(),
    );
    let end = |f: &Flight| {
        let a = f.attitude.last().copied().unwrap_or_default();
        format!("{:.2e} {:.2e} {:.2e}", a[0], a[1], a[2])
    };
    row("q4 q5 q6 at 15 s [rad]", end(full), end(small));
}

/// The operation counts of both generated models.
fn print_operations() {
    println!();
    println!(
        "Operations of the generated code (adds + multiplies + divides + functions; user calls):"
    );
    // The counts are constants of each generated model type.
    macro_rules! ops_of {
        ($model:ty) => {
            Ops {
                derivatives: <$model>::DERIVATIVE_OPS,
                outputs: <$model>::OUTPUT_OPS,
                constants: <$model>::CONSTANT_OPS,
                mass_matrix: <$model>::MASS_MATRIX_OPS,
                forcing: <$model>::FORCING_OPS,
            }
        };
    }
    let full_ops = ops_of!(Satellite<Figure8>);
    let small_ops = ops_of!(SatelliteSmall<Figure8>);
    let ops = |o: OpCount| {
        format!(
            "{}+{}+{}+{}; {}",
            o.adds, o.muls, o.divs, o.funcs, o.user_calls
        )
    };
    for (label, get) in [
        (
            "derivatives (one evaluation)",
            (|o: &Ops| o.derivatives) as fn(&Ops) -> OpCount,
        ),
        ("mass_matrix() M(q), alone", |o: &Ops| o.mass_matrix),
        ("forcing() f(q, u, t), alone", |o: &Ops| o.forcing),
        ("outputs", |o: &Ops| o.outputs),
        ("constants (per parameter set)", |o: &Ops| o.constants),
    ] {
        row(label, ops(get(&full_ops)), ops(get(&small_ops)));
    }
    row(
        "derivatives, total operations",
        full_ops.derivatives.total().to_string(),
        small_ops.derivatives.total().to_string(),
    );
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn per_eval(d: Duration, evaluations: u64) -> f64 {
    d.as_secs_f64() * 1e9 / evaluations.max(1) as f64
}
