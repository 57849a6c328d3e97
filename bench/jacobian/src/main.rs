//! autosim's generated `linearize()` for every model `build.rs` compiled,
//! with the command line of `jac_bench.c` (the CasADi side):
//!
//! - `autosim_jacobian_bench bench ROUNDS STATES_DIR`: one JSON line per
//!   model, `{"model", "method": "autosim", "calls_per_batch": 1000,
//!   "batches_ns": [...]}`; every batch is one `linearize(0, x)` at each of
//!   the 1000 states of `STATES_DIR/<model>.txt`, batches per round
//!   calibrated to about 0.04 s (7..601), as the peers' harnesses.
//! - `autosim_jacobian_bench dump MODEL STATES_FILE`: `A`, `B`, `C`, `D`
//!   (row-major, empty ones skipped) at every state, one line each.
//! - `autosim_jacobian_bench list`: `model nx nw nlin ny ops`, one line
//!   each, `ops` being the model's `LINEARIZE_OPS.total()`.

use autosim::runtime::Linearize;
use std::hint::black_box;
use std::time::Instant;

/// What to do with a model.
enum Mode {
    List,
    Dump(String),
    Bench { rounds: usize, states_dir: String },
}

include!(concat!(env!("OUT_DIR"), "/registry.rs"));

const STATES: usize = 1000;

/// The states of a states file (rows of numbers), as the model's state type.
fn read_states<const N: usize>(path: &str) -> Vec<[f64; N]> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| fail(&format!("{path}: {e}")));
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|line| {
            let values: Vec<f64> = line
                .split_whitespace()
                .map(|v| {
                    v.parse()
                        .unwrap_or_else(|_| fail(&format!("{path}: not a number: {v}")))
                })
                .collect();
            values
                .try_into()
                .unwrap_or_else(|_| fail(&format!("{path}: a state is not {N} numbers")))
        })
        .collect()
}

fn fail(message: &str) -> ! {
    eprintln!("autosim_jacobian_bench: {message}");
    std::process::exit(2);
}

/// Runs `mode` on `model`, whose `linearize` is timed through `call`.
fn run<M, const N: usize>(
    mut model: M,
    ops: usize,
    mut call: impl FnMut(&mut M, &[f64; N]),
    name: &str,
    mode: &Mode,
) where
    M: Linearize<Float = f64, State = [f64; N]>,
{
    let (nlin, nw, ny) = (
        M::LINEAR_STATES.len(),
        M::INPUT_NAMES.len(),
        M::OUTPUT_NAMES.len(),
    );
    match mode {
        Mode::List => println!("{name} {N} {nw} {nlin} {ny} {ops}"),
        Mode::Dump(path) => {
            let (mut a, mut b) = (vec![0.0; nlin * nlin], vec![0.0; nlin * nw]);
            let (mut c, mut d) = (vec![0.0; ny * nlin], vec![0.0; ny * nw]);
            for x in read_states::<N>(path) {
                model
                    .linearize_into(0.0, &x, &mut a, &mut b, &mut c, &mut d)
                    .unwrap_or_else(|e| fail(&format!("{name}: {e}")));
                let all: Vec<String> = [&a, &b, &c, &d]
                    .into_iter()
                    .flatten()
                    .map(|v| format!("{v:e}"))
                    .collect();
                println!("{}", all.join(" "));
            }
        }
        Mode::Bench { rounds, states_dir } => {
            let states = read_states::<N>(&format!("{states_dir}/{name}.txt"));
            if states.len() < STATES {
                fail(&format!("{name}: fewer than {STATES} states"));
            }
            let mut pass = |m: &mut M| {
                let start = Instant::now();
                for x in &states[..STATES] {
                    call(m, black_box(x));
                }
                start.elapsed().as_nanos() as f64 / STATES as f64
            };
            pass(&mut model); // warm-up
            let one = pass(&mut model);
            let batches = (0.04e9 / one.max(1.0)).clamp(7.0, 601.0) as usize;
            let mut times = Vec::new();
            for _ in 0..*rounds {
                pass(&mut model); // warm-up, as the peers
                times.extend((0..batches).map(|_| pass(&mut model)));
            }
            let list: Vec<String> = times.iter().map(|t| format!("{t:.3}")).collect();
            println!(
                "{{\"model\": \"{name}\", \"method\": \"autosim\", \"calls_per_batch\": {STATES}, \"batches_ns\": [{}]}}",
                list.join(", ")
            );
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize| {
        args.get(i)
            .cloned()
            .unwrap_or_else(|| fail("missing arguments"))
    };
    match args.get(1).map(String::as_str) {
        Some("list") => MODELS.iter().for_each(|m| {
            dispatch(m, &Mode::List);
        }),
        Some("dump") => {
            if !dispatch(&arg(2), &Mode::Dump(arg(3))) {
                fail(&format!("no model {}", arg(2)));
            }
        }
        Some("bench") => {
            let rounds = arg(2).parse().unwrap_or_else(|_| fail("ROUNDS: a number"));
            let mode = Mode::Bench {
                rounds,
                states_dir: arg(3),
            };
            MODELS.iter().for_each(|m| {
                dispatch(m, &mode);
            });
        }
        _ => fail(
            "usage: autosim_jacobian_bench bench ROUNDS STATES_DIR | dump MODEL STATES_FILE | list",
        ),
    }
}
