//! No input makes the compiler panic, from the text to the formatted Rust:
//! a few hundred cases of the generators behind `examples/fuzz.rs` (random
//! models, mutated example models, soups). Long runs: `cargo run --release
//! -p autosim-core --example fuzz -- 100000`.

#[path = "support/fuzz_gen.rs"]
mod fuzz_gen;

use fuzz_gen::{Outcome, generate, run, silence_panics};

const CASES: u64 = 300;
const SEED: u64 = 0x5EED;

#[test]
fn pipeline_never_panics_on_generated_inputs() {
    silence_panics();
    let mut failures = Vec::new();
    let mut ok = 0;
    for case in 0..CASES {
        let (kind, text) = generate(SEED, case);
        match run(&text, case % 4 == 0) {
            Outcome::Ok => ok += 1,
            Outcome::Diagnostics(_) => {}
            Outcome::Panic(message) | Outcome::BadEmit(message) => {
                failures.push(format!(
                    "case {case} ({kind:?}): {message}\n--- input ---\n{text}"
                ));
            }
        }
    }
    let _ = std::panic::take_hook();
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    // The generators reach the back end, not only the diagnostics.
    assert!(ok > 0, "no generated input compiled");
}
