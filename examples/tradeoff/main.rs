//! Speed against accuracy, measured: every integrator of the runtime over a
//! range of steps (or tolerances), in `f64` and `f32`, on four models, and
//! what the compile-time scene options (small variables, locks, selected
//! outputs, `f32`) buy on the paper's satellite.
//!
//! ```text
//! cargo run --release --example tradeoff [-- OUTPUT_FOLDER]
//! ```
//!
//! # Work–precision study
//!
//! | study | model | end time | error measure |
//! | --- | --- | --- | --- |
//! | `satellite` | `satellite.sim`, Figure 8 commands, thrusters off | 15 s | max abs error of the bus attitude q4, q5, q6 at 15 s |
//! | `satellite-small` | the same with `small = [B, E, F]` | 15 s | the same, against the **full** model's reference (model + integration error) |
//! | `satellite-thrusters` | `satellite.sim` with the Figure 8 thrusters on | 15 s | the same, against RK4 at h = 10 µs |
//! | `satellite-events` | `satellite_events.sim`: the thrusters as `discrete` modes and `event` items of the language | 15 s | the same, against Dormand–Prince at 1e-12 |
//! | `chain-spatial-5` | `chain_spatial_5.sim`, released from q = (0.6, -0.5, 0.4, 0.7, -0.3) | 5 s | max abs error of q1..q5 at 5 s |
//! | `chain-spatial-3-stiff` | `chain_spatial_3_stiff.sim` (k × 10⁴), released from q1 = 0.1 | 1 s | max abs error of q1..q3 at 1 s |
//!
//! The references are the `f64` models integrated with Dormand–Prince at
//! rtol = atol = 1e-12 (their own error, estimated against 1e-13, is
//! printed). The satellite study runs with the thrusters **off**: the
//! Figure 8 thrusters are a stateful bang-bang element whose switching
//! times depend on where each method evaluates the model (stage times,
//! rejected steps, Jacobian columns), so with them on no method converges
//! faster than first order and the error floor depends on the method; the
//! `satellite-thrusters` study shows exactly that; `satellite-events`
//! flies the same thrusters with their switching located as events, which
//! converges again like a smooth model. With the thrusters off,
//! the commanded slew of the clock and camera still swings the bus through
//! the reaction torques and the boom.
//!
//! Every method runs through [`run`](autosim::runtime::run) at steps h = T/n (fixed-step methods;
//! each h divides 1 s, so the kinks of the commands at 1 s and 11 s fall on
//! steps) or tolerances rtol = atol = tol (Dormand–Prince), in `f64` and in
//! `f32` (the same model files with the scene option `float = f32`). Cost is
//! derivative evaluations (exact) and wall time (median of 3 runs). Runs
//! that would take more than 10⁶ evaluations are skipped. A run that
//! fails is listed with its typed error (e.g. an explicit method beyond its
//! stability limit on the stiff chain stops with a non-finite state); one
//! that ends finite but more than 1 rad off is listed as diverged. Both are
//! left out of the plots.
//!
//! # Scene options
//!
//! The satellite compiled several ways from the one file (small variables
//! per body or coordinate, thresholds, locked boom, selected outputs, `f32`),
//! each flown through the paper's slew (Figure 8 user code, thrusters on,
//! RK4 at h = 1 ms): operation counts, nanoseconds per `derivatives()` call
//! (median over 101 rounds at 500 states of its own slew, the best of 7
//! passes interleaved over the scenes, since load from other processes only
//! adds time) and the largest attitude difference from the full `f64` model
//! over the 15 s.
//!
//! # Output (default folder `docs/tradeoff`)
//!
//! - `results.csv`: one row per run: study, float, method, `h` or `tol` and
//!   its value, accepted and rejected steps, evaluations, wall time [ms],
//!   `error` (against the study's reference; for `satellite-small` the full
//!   model's), `integration_error` (`satellite-small` only: against its own
//!   reference) and `status` (`ok`, `diverged (finite)`, or the typed error);
//! - `<study>.svg`: error against derivative evaluations, log–log, one line
//!   per method, `f64` solid and `f32` dashed;
//! - `<study>_time.svg`: error against wall time;
//! - `summary.md`: the cheapest run reaching each error level, the scene
//!   table, the references' own errors.

use std::path::PathBuf;
use std::time::Instant;

// The paper's Figure 8 (CMD and THRUST), shared with `satellite.rs`.
#[macro_use]
#[path = "../common/figure8.rs"]
mod figure8;
use figure8::Figure8;

mod method;
mod report;
mod scenes;
mod study;

/// Models from one file, each named and tailored by scene options.
macro_rules! from_file {
    ($file:tt: $($name:ident $(, $option:ident = $value:tt)*;)+) => {
        $(autosim::model!(file = $file, name = $name $(, $option = $value)*);)+
    };
}

/// The work–precision models: one file each, in `f64` and `f32`.
mod wp {
    from_file!("examples/models/satellite.sim":
        Satellite;
        SatelliteF32, float = f32;
        SatelliteSmall, small = [B, E, F];
        SatelliteSmallF32, small = [B, E, F], float = f32;
    );
    // The thrusters as events in the model language (the paper's Figure 8
    // decisions at located instants); its only user code is CMD.
    from_file!("examples/models/satellite_events.sim":
        SatelliteEvents;
    );
    from_file!("examples/models/chain_spatial_5.sim":
        ChainSpatial5;
        ChainSpatial5F32, float = f32;
    );
    from_file!("examples/models/chain_spatial_3_stiff.sim":
        ChainSpatial3Stiff;
        ChainSpatial3StiffF32, float = f32;
    );
}

/// The satellite tailored at the use site (scene options).
mod scene {
    from_file!("examples/models/satellite.sim":
        SmallBus, small = [B];
        SmallBoom, small = [E, F];
        SmallAngles, small = [q4, q5, q6, q9, q10];
        SmallThreshold1, small = [B, E, F], threshold = 1;
        SmallThreshold3, small = [B, E, F], threshold = 3;
        Attitude, outputs = [roll, pitch, yaw];
        RigidBoomAll, lock = [q9, q10];
        RigidBoom, lock = [q9, q10], outputs = [roll, pitch, yaw];
    );
}

figure8_externs!(
    wp::satellite => f64,
    wp::satellite_f32 => f32,
    wp::satellite_small => f64,
    wp::satellite_small_f32 => f32,
    scene::small_bus => f64,
    scene::small_boom => f64,
    scene::small_angles => f64,
    scene::small_threshold1 => f64,
    scene::small_threshold3 => f64,
    scene::attitude => f64,
    scene::rigid_boom_all => f64,
    scene::rigid_boom => f64,
);

impl wp::satellite_events::Externs for Figure8 {
    fn cmd(&mut self, t: f64) -> [f64; 2] {
        Figure8::cmd(self, t)
    }
}

/// The satellite with its thrusters switched by events (the language form;
/// the user code gives the commands only).
type SatEvents = wp::satellite_events::SatelliteEvents<Figure8>;
/// The satellite with the Figure 8 user code, in `f64`.
type Sat = wp::satellite::Satellite<Figure8>;
/// The satellite in `f32`.
type SatF32 = wp::satellite_f32::SatelliteF32<Figure8>;
/// The satellite with `small = [B, E, F]`.
type Small = wp::satellite_small::SatelliteSmall<Figure8>;
/// The small-variable satellite in `f32`.
type SmallF32 = wp::satellite_small_f32::SatelliteSmallF32<Figure8>;
/// The spatial five-link chain.
type Chain5 = wp::chain_spatial5::ChainSpatial5;
/// The spatial five-link chain in `f32`.
type Chain5F32 = wp::chain_spatial5_f32::ChainSpatial5F32;
/// The stiff spatial three-link chain.
type Stiff = wp::chain_spatial3_stiff::ChainSpatial3Stiff;
/// The stiff spatial three-link chain in `f32`.
type StiffF32 = wp::chain_spatial3_stiff_f32::ChainSpatial3StiffF32;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let folder = match std::env::args_os().nth(1) {
        Some(a) if a == "-h" || a == "--help" => {
            println!("usage: cargo run --release --example tradeoff [-- OUTPUT_FOLDER]");
            println!(
                "writes results.csv, work-precision plots and summary.md (default: docs/tradeoff)"
            );
            return Ok(());
        }
        Some(a) => PathBuf::from(a),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/tradeoff"),
    };
    std::fs::create_dir_all(&folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    let started = Instant::now();

    let refs = study::references();
    let rows = study::sweeps(&refs);
    let chatter = study::thruster_chatter(&rows);

    let plots = report::plots(refs.small_model_error);
    let mut files = report::write_files(&folder, &rows, &plots)?;
    let scenes = scenes::compare();
    files.push(report::write_summary(
        &folder, &rows, &plots, &refs, chatter, &scenes,
    )?);
    report::print_cheapest(&rows, &plots);

    println!();
    println!("Written to {}:", folder.display());
    for f in &files {
        println!("  {}", f.file_name().unwrap_or_default().to_string_lossy());
    }
    println!("Total time {:.1} s", started.elapsed().as_secs_f64());
    Ok(())
}
