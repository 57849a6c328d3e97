//! `autosim-constrained-bench MODE DIR [ROUNDS]`: the generated
//! `derivatives()` of the four-bar, the rolling disc and the bicycle at the
//! states `derive.py` drew (DIR/MODEL/states.bin), timed as ../peers times
//! the chains (batches of 1000 calls, about 0.04 s of batches per model and
//! round). With them `rolling_disc_lean` (models/rolling_disc_lean.sim: the
//! disc with its contact vector written along the lean axis, as SymPy's
//! model has it) at the rolling disc's states.
//!
//! - `bench DIR ROUNDS`: one JSON line per model, method `autosim`
//! - `dump DIR SUFFIX`: writes DIR/MODEL/dx_autosim_SUFFIX.bin
//!   (DIR/rolling_disc/dx_autosim_lean_SUFFIX.bin for the variant)
//! - `ops DIR`: one JSON line per model with `DERIVATIVE_OPS`

use autosim::runtime::{Model, OpCount};
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

autosim::include_model!(four_bar);
autosim::include_model!(rolling_disc);
autosim::include_model!(bicycle);
autosim::include_model!(rolling_disc_lean);

/// The states in DIR/MODEL/states.bin (float64, native endianness, as numpy
/// writes them).
fn states<const N: usize>(dir: &Path, model: &str) -> Vec<[f64; N]> {
    let path = dir.join(model).join("states.bin");
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(
        bytes.len() % (8 * N),
        0,
        "{}: not states of {N}",
        path.display()
    );
    bytes
        .chunks_exact(8 * N)
        .map(|s| {
            std::array::from_fn(|i| f64::from_ne_bytes(s[8 * i..8 * i + 8].try_into().unwrap()))
        })
        .collect()
}

/// Per-batch ns per call of `model` over `rounds` rounds.
fn time<M: Model<Float = f64, State = [f64; N]>, const N: usize>(
    mut model: M,
    states: &[[f64; N]],
    rounds: usize,
) -> Vec<f64> {
    let mut dx = [0.0; N];
    let mut pass = |m: &mut M| {
        let start = Instant::now();
        for x in states {
            let _ = black_box(m.derivatives(0.0, black_box(x), &mut dx));
        }
        start.elapsed().as_nanos() as f64 / states.len() as f64
    };
    let one = pass(&mut model); // warm-up and calibration, as the peers
    let batches = (0.04e9 / one.max(1.0)).clamp(7.0, 601.0) as usize;
    (0..rounds * batches).map(|_| pass(&mut model)).collect()
}

/// dx at every state of DIR/NAME, written next to them as FILE.
fn dump<M: Model<Float = f64, State = [f64; N]>, const N: usize>(
    mut model: M,
    dir: &Path,
    name: &str,
    file: &str,
) {
    let mut out = Vec::new();
    for x in states::<N>(dir, name) {
        let mut dx = [0.0; N];
        if let Err(e) = model.derivatives(0.0, &x, &mut dx) {
            eprintln!("{name}: {e} at {x:?}");
            std::process::exit(1);
        }
        out.extend(dx.iter().flat_map(|v| v.to_ne_bytes()));
    }
    let path = dir.join(name).join(file);
    std::fs::write(&path, out).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

fn ops_line(name: &str, ops: OpCount) {
    println!(
        "{{\"kind\": \"{name}\", \"adds\": {}, \"muls\": {}, \"divs\": {}, \"funcs\": {}, \"total\": {}}}",
        ops.adds,
        ops.muls,
        ops.divs,
        ops.funcs,
        ops.total()
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(mode), Some(dir)) = (args.get(1), args.get(2)) else {
        eprintln!("usage: autosim-constrained-bench bench|dump|ops DIR [ROUNDS|SUFFIX]");
        std::process::exit(2);
    };
    let dir = Path::new(dir);
    let (four_bar, disc, bicycle, lean) = (
        four_bar::FourBar::new(),
        rolling_disc::RollingDisc::new(),
        bicycle::Bicycle::new(),
        rolling_disc_lean::RollingDiscLean::new(),
    );
    match mode.as_str() {
        "ops" => {
            ops_line("four_bar", four_bar::FourBar::DERIVATIVE_OPS);
            ops_line("rolling_disc", rolling_disc::RollingDisc::DERIVATIVE_OPS);
            ops_line("bicycle", bicycle::Bicycle::DERIVATIVE_OPS);
            ops_line(
                "rolling_disc_lean",
                rolling_disc_lean::RollingDiscLean::DERIVATIVE_OPS,
            );
        }
        "dump" => {
            let suffix = args.get(3).map_or("default", String::as_str);
            let file = format!("dx_autosim_{suffix}.bin");
            dump(four_bar, dir, "four_bar", &file);
            dump(disc, dir, "rolling_disc", &file);
            dump(bicycle, dir, "bicycle", &file);
            dump(
                lean,
                dir,
                "rolling_disc",
                &format!("dx_autosim_lean_{suffix}.bin"),
            );
        }
        "bench" => {
            let rounds: usize = args.get(3).and_then(|r| r.parse().ok()).unwrap_or(1);
            let out = [
                ("four_bar", time(four_bar, &states(dir, "four_bar"), rounds)),
                (
                    "rolling_disc",
                    time(disc, &states(dir, "rolling_disc"), rounds),
                ),
                ("bicycle", time(bicycle, &states(dir, "bicycle"), rounds)),
                (
                    "rolling_disc_lean",
                    time(lean, &states(dir, "rolling_disc"), rounds),
                ),
            ];
            for (kind, batches) in out {
                let list: Vec<String> = batches.iter().map(|b| format!("{b:.3}")).collect();
                println!(
                    "{{\"kind\": \"{kind}\", \"tool\": \"autosim\", \"method\": \"autosim\", \"calls_per_batch\": 1000, \"batches_ns\": [{}]}}",
                    list.join(", ")
                );
            }
        }
        _ => {
            eprintln!("unknown mode {mode}");
            std::process::exit(2);
        }
    }
}
