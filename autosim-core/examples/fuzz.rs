//! Fuzzes the whole compiler: `cargo run --release -p autosim-core --example
//! fuzz -- <cases> [seed] [first]` runs cases `first..first + cases` of the
//! seeded generators (random models, mutated example models, character
//! soups: see `tests/support/fuzz_gen.rs`) through parse, resolve, Kane's
//! equations, the program, token emission, formatting and Markdown, and
//! counts how each ended. No input may panic, and generated code must parse.
//!
//! Panicking inputs are written to `<target>/fuzz-failures/<case>.sim`
//! (`<target>` is `$CARGO_TARGET_DIR` or the workspace's `target`), and the
//! run exits non-zero. Cases slower than 2 s are reported (and saved as
//! `slow-<case>.sim`); one still running after 60 s is saved as
//! `hang-<case>.sim` while the run waits for it. The input being run is
//! always in `in-progress.sim`, for crashes that cannot be caught (stack
//! overflow, abort). `fuzz -- show <case> [seed]` prints one case's input.

#[path = "../tests/support/fuzz_gen.rs"]
mod fuzz_gen;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use fuzz_gen::{Kind, Outcome, generate, run, silence_panics};

const SLOW: Duration = Duration::from_secs(2);
const HANG: Duration = Duration::from_secs(60);

fn failures_dir() -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => PathBuf::from(dir).join("fuzz-failures"),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target/fuzz-failures"),
    }
}

fn usage() -> ! {
    eprintln!("usage: fuzz <cases> [seed] [first]   or   fuzz show <case> [seed]");
    std::process::exit(2);
}

fn arg(args: &[String], i: usize, default: u64) -> u64 {
    match args.get(i) {
        None => default,
        Some(a) => a.replace('_', "").parse().unwrap_or_else(|_| usage()),
    }
}

/// The case being run, for the watchdog.
struct Current {
    case: u64,
    started: Instant,
    text: String,
    reported: bool,
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("show") {
        let (case, seed) = (arg(&args, 1, 0), arg(&args, 2, 1));
        let (kind, text) = generate(seed, case);
        eprintln!("case {case} (seed {seed}): {kind:?}");
        print!("{text}");
        return;
    }
    if args.is_empty() {
        usage();
    }
    let (cases, seed, first) = (arg(&args, 0, 0), arg(&args, 1, 1), arg(&args, 2, 0));
    let dir = failures_dir();
    if let Err(e) = std::fs::create_dir_all(&dir) {
        eprintln!("cannot create {}: {e}", dir.display());
        std::process::exit(2);
    }
    let in_progress = dir.join("in-progress.sim");

    // A watchdog: reports (does not kill) a case that runs far too long.
    let current = Arc::new(Mutex::new(Current {
        case: 0,
        started: Instant::now(),
        text: String::new(),
        reported: true,
    }));
    {
        let current = Arc::clone(&current);
        let dir = dir.clone();
        std::thread::spawn(move || {
            loop {
                std::thread::sleep(Duration::from_secs(1));
                let mut c = current.lock().unwrap_or_else(|e| e.into_inner());
                if !c.reported && c.started.elapsed() > HANG {
                    c.reported = true;
                    let path = dir.join(format!("hang-{}.sim", c.case));
                    let _ = std::fs::write(&path, &c.text);
                    eprintln!(
                        "case {} still running after {} s: input in {}",
                        c.case,
                        HANG.as_secs(),
                        path.display()
                    );
                }
            }
        });
    }

    silence_panics();
    let start = Instant::now();
    let mut counts: BTreeMap<&str, [u64; 4]> = BTreeMap::new();
    let (mut ok, mut diags, mut panics, mut bad_emits) = (0u64, 0u64, 0u64, 0u64);
    let mut slowest = (Duration::ZERO, first);
    let mut slow: Vec<(u64, Kind, Duration)> = Vec::new();
    // Distinct panic messages, with their first case and count.
    let mut distinct: BTreeMap<String, (u64, u64)> = BTreeMap::new();
    let progress_every = (cases / 20).clamp(1, 5000);
    eprintln!(
        "fuzz: cases {first}..{} of seed {seed}; failures go to {}",
        first + cases,
        dir.display()
    );
    for case in first..first + cases {
        let (kind, text) = generate(seed, case);
        let _ = std::fs::write(&in_progress, &text);
        {
            let mut c = current.lock().unwrap_or_else(|e| e.into_inner());
            *c = Current {
                case,
                started: Instant::now(),
                text: text.clone(),
                reported: false,
            };
        }
        let t0 = Instant::now();
        let outcome = run(&text, case % 4 == 0);
        let took = t0.elapsed();
        current.lock().unwrap_or_else(|e| e.into_inner()).reported = true;

        let kind_name = match kind {
            Kind::Grammar => "grammar",
            Kind::Mutation => "mutation",
            Kind::Soup => "soup",
        };
        let slot = counts.entry(kind_name).or_default();
        match &outcome {
            Outcome::Ok => {
                ok += 1;
                slot[0] += 1;
            }
            Outcome::Diagnostics(_) => {
                diags += 1;
                slot[1] += 1;
            }
            Outcome::Panic(message) | Outcome::BadEmit(message) => {
                let is_panic = matches!(outcome, Outcome::Panic(_));
                if is_panic {
                    panics += 1;
                    slot[2] += 1;
                } else {
                    bad_emits += 1;
                    slot[3] += 1;
                }
                let path = dir.join(format!("{case}.sim"));
                let _ = std::fs::write(&path, &text);
                // Group by the first line (message and location).
                let key = format!(
                    "{}: {}",
                    if is_panic { "panic" } else { "bad emit" },
                    message.lines().next().unwrap_or("")
                );
                let entry = distinct.entry(key.clone()).or_insert((case, 0));
                entry.1 += 1;
                if entry.1 == 1 {
                    eprintln!(
                        "case {case} ({kind_name}): {key}\n  input in {}",
                        path.display()
                    );
                }
            }
        }
        if took > slowest.0 {
            slowest = (took, case);
        }
        if took > SLOW {
            slow.push((case, kind, took));
            let path = dir.join(format!("slow-{case}.sim"));
            let _ = std::fs::write(&path, &text);
            eprintln!(
                "case {case} ({kind_name}) took {:.2} s: input in {}",
                took.as_secs_f64(),
                path.display()
            );
        }
        let done = case - first + 1;
        if done % progress_every == 0 {
            eprintln!(
                "[{done}/{cases}] {ok} ok, {diags} diagnostics, {panics} panics, {bad_emits} bad emits; {:.1} s",
                start.elapsed().as_secs_f64()
            );
        }
    }
    let _ = std::fs::remove_file(&in_progress);

    for (kind, [k_ok, k_diag, k_panic, k_bad]) in &counts {
        eprintln!(
            "  {kind:>8}: {k_ok} ok, {k_diag} diagnostics, {k_panic} panics, {k_bad} bad emits"
        );
    }
    for (message, (case, n)) in &distinct {
        eprintln!("  {n} × {message} (first: case {case})");
    }
    for (case, kind, took) in &slow {
        eprintln!("  slow: case {case} ({kind:?}) {:.2} s", took.as_secs_f64());
    }
    println!(
        "fuzz: {cases} cases (seed {seed}): {ok} ok, {diags} diagnostics, {panics} panics, {bad_emits} bad emits; slowest {:.3} s (case {}); total {:.1} s",
        slowest.0.as_secs_f64(),
        slowest.1,
        start.elapsed().as_secs_f64()
    );
    if panics + bad_emits > 0 {
        std::process::exit(1);
    }
}
