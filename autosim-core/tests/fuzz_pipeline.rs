//! No input makes the compiler panic, from the text to the formatted Rust:
//! a few hundred cases of the generators behind `examples/fuzz.rs` (random
//! models, mutated example models, soups, pathological shapes, some with
//! scene options; see `support/fuzz/`). Long runs: `cargo run --release -p
//! autosim-core --example fuzz -- 100000`.

#[path = "support/fuzz/mod.rs"]
mod fuzz_gen;

use fuzz_gen::{Outcome, generate, run, silence_panics};

const CASES: u64 = 500;
const SEED: u64 = 0x5EED;

#[test]
fn pipeline_never_panics_on_generated_inputs() {
    // The stack a build script or the compiler's main thread has (a test
    // thread has 2 MiB): deep inputs are refused before they need more.
    let run_all = std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(run_all)
        .expect("spawn the fuzzing thread");
    let (ok, failures) = run_all.join().expect("the fuzzing thread");
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    // The generators reach the back end, not only the diagnostics.
    assert!(ok > 0, "no generated input compiled");
}

/// Runs every case: (how many compiled, the failures).
fn run_all() -> (usize, Vec<String>) {
    silence_panics();
    let mut failures = Vec::new();
    let mut ok = 0;
    for case in 0..CASES {
        let input = generate(SEED, case);
        match run(&input, case % 4 == 0) {
            Outcome::Ok => ok += 1,
            Outcome::Diagnostics(_) => {}
            Outcome::Panic(message) | Outcome::BadEmit(message) => {
                failures.push(format!(
                    "case {case} ({:?}, scene {:?}): {message}\n--- input ---\n{}",
                    input.kind, input.scene, input.text
                ));
            }
        }
    }
    let _ = std::panic::take_hook();
    (ok, failures)
}
