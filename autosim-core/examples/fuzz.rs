//! Fuzzes the whole compiler: `cargo run --release -p autosim-core --example
//! fuzz -- <cases> [seed] [first]` runs cases `first..first + cases` of the
//! seeded generators (random models, mutated example models, soups,
//! pathological shapes; some with use-site options: see
//! `tests/support/fuzz/`) through parse, resolve, Kane's equations,
//! the program, token emission, formatting and Markdown (and, for one case
//! in four, the macro's token front end), and counts how each ended. No
//! input may panic, and generated code must parse as Rust.
//!
//! Panicking inputs are written to `<target>/fuzz-failures/<case>.sim`
//! (`<target>` is `$CARGO_TARGET_DIR` or the workspace's `target`; a scene
//! goes to `<case>.scene.txt`), and the run exits non-zero. Cases slower
//! than 2 s are reported (and saved as `slow-<case>.sim`); one still running
//! after 60 s is saved as `hang-<case>.sim` while the run waits for it. The
//! input being run is always in `in-progress.sim`, for crashes that cannot
//! be caught (stack overflow, abort).
//!
//! `fuzz -- show <case> [seed]` prints one case's input; `fuzz -- write
//! <dir> <cases> [seed]` writes the generated Rust of every case that
//! compiles, to check with rustc (include the files from a crate that
//! depends on `autosim`, under `#![deny(warnings)]`).
//!
//! Integer overflow panics only with overflow checks, as in the debug build
//! a proc macro runs in: for long runs, add
//! `CARGO_PROFILE_RELEASE_OVERFLOW_CHECKS=true
//! CARGO_PROFILE_RELEASE_DEBUG_ASSERTIONS=true`.

#[path = "../tests/support/fuzz/mod.rs"]
mod fuzz_gen;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use fuzz_gen::{Case, Kind, Outcome, generate, generated_code, run, silence_panics};

const SLOW: Duration = Duration::from_secs(2);
const HANG: Duration = Duration::from_secs(60);

fn failures_dir() -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => PathBuf::from(dir).join("fuzz-failures"),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target/fuzz-failures"),
    }
}

/// Writes a case's text to `<stem>.sim` (and its scene, if any, to
/// `<stem>.scene.txt`); returns the text's path.
fn save(dir: &Path, stem: &str, case: &Case) -> PathBuf {
    write_input(
        dir,
        stem,
        &case.text,
        case.scene.as_ref().map(|s| format!("{s:#?}\n")),
    )
}

fn write_input(dir: &Path, stem: &str, text: &str, scene: Option<String>) -> PathBuf {
    let path = dir.join(format!("{stem}.sim"));
    let _ = std::fs::write(&path, text);
    if let Some(scene) = scene {
        let _ = std::fs::write(dir.join(format!("{stem}.scene.txt")), scene);
    }
    path
}

fn usage() -> ! {
    eprintln!(
        "usage: fuzz <cases> [seed] [first]  |  fuzz show <case> [seed]  |  fuzz write <dir> <cases> [seed]"
    );
    std::process::exit(2);
}

fn arg(args: &[String], i: usize, default: u64) -> u64 {
    match args.get(i) {
        None => default,
        Some(a) => a.replace('_', "").parse().unwrap_or_else(|_| usage()),
    }
}

/// The case being run, for the watchdog (text and scene as written).
struct Current {
    case: u64,
    started: Instant,
    text: String,
    scene: Option<String>,
    reported: bool,
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("show") => show(&args),
        Some("write") => write_generated(&args),
        None => usage(),
        Some(_) => fuzz(&args),
    }
}

/// `fuzz show <case> [seed]`: prints one case's input (its kind and scene
/// to stderr).
fn show(args: &[String]) {
    let (case, seed) = (arg(args, 1, 0), arg(args, 2, 1));
    let input = generate(seed, case);
    eprintln!("case {case} (seed {seed}): {:?}", input.kind);
    if let Some(scene) = &input.scene {
        eprintln!("{scene:#?}");
    }
    print!("{}", input.text);
}

/// `fuzz write <dir> <cases> [seed]`: the generated Rust of every case that
/// compiles, one file each, for checking with rustc (`case_<n>.rs`, runtime
/// at `::autosim::runtime`).
fn write_generated(args: &[String]) {
    let Some(dir) = args.get(1) else { usage() };
    let (cases, seed) = (arg(args, 2, 100), arg(args, 3, 1));
    let _ = std::fs::create_dir_all(dir);
    silence_panics();
    let mut written = 0;
    for case in 0..cases {
        let input = generate(seed, case);
        if !matches!(run(&input, false), Outcome::Ok) {
            continue;
        }
        if let Some(code) = generated_code(&input) {
            let _ = std::fs::write(Path::new(dir).join(format!("case_{case}.rs")), code);
            written += 1;
        }
    }
    println!("fuzz: wrote {written} generated files of {cases} cases (seed {seed}) to {dir}");
}

/// `fuzz <cases> [seed] [first]`: runs the cases, saves the failing and
/// slow ones, prints the counts; exits non-zero if any case panicked or
/// emitted bad code.
fn fuzz(args: &[String]) {
    let (cases, seed, first) = (arg(args, 0, 0), arg(args, 1, 1), arg(args, 2, 0));
    let dir = failures_dir();
    if let Err(e) = std::fs::create_dir_all(&dir) {
        eprintln!("cannot create {}: {e}", dir.display());
        std::process::exit(2);
    }
    let in_progress = dir.join("in-progress.sim");
    let current = watchdog(&dir);

    silence_panics();
    let start = Instant::now();
    let mut tally = Tally::new(first);
    let progress_every = (cases / 20).clamp(1, 5000);
    eprintln!(
        "fuzz: cases {first}..{} of seed {seed}; failures go to {}",
        first + cases,
        dir.display()
    );
    for case in first..first + cases {
        let input = generate(seed, case);
        let (outcome, took) = run_watched(&current, &dir, case, &input);
        tally.record(&dir, case, &input, &outcome, took);
        let done = case - first + 1;
        if done % progress_every == 0 {
            let Tally {
                ok,
                diags,
                panics,
                bad_emits,
                ..
            } = tally;
            eprintln!(
                "[{done}/{cases}] {ok} ok, {diags} diagnostics, {panics} panics, {bad_emits} bad emits; {:.1} s",
                start.elapsed().as_secs_f64()
            );
        }
    }
    let _ = std::fs::remove_file(&in_progress);
    let _ = std::fs::remove_file(dir.join("in-progress.scene.txt"));

    tally.report(cases, seed, start);
    if tally.panics + tally.bad_emits > 0 {
        std::process::exit(1);
    }
}

/// A watchdog thread: reports (does not kill) a case that runs far too
/// long, saving its input as `hang-<case>.sim` in `dir`.
fn watchdog(dir: &Path) -> Arc<Mutex<Current>> {
    let current = Arc::new(Mutex::new(Current {
        case: 0,
        started: Instant::now(),
        text: String::new(),
        scene: None,
        reported: true,
    }));
    let watched = Arc::clone(&current);
    let dir = dir.to_path_buf();
    std::thread::spawn(move || {
        loop {
            std::thread::sleep(Duration::from_secs(1));
            let mut c = watched.lock().unwrap_or_else(|e| e.into_inner());
            if !c.reported && c.started.elapsed() > HANG {
                c.reported = true;
                let stem = format!("hang-{}", c.case);
                let path = write_input(&dir, &stem, &c.text, c.scene.clone());
                eprintln!(
                    "case {} still running after {} s: input in {}",
                    c.case,
                    HANG.as_secs(),
                    path.display()
                );
            }
        }
    });
    current
}

/// Runs one case under the watchdog (its input saved as `in-progress`
/// first); returns how it ended and how long it took.
fn run_watched(
    current: &Mutex<Current>,
    dir: &Path,
    case: u64,
    input: &Case,
) -> (Outcome, Duration) {
    save(dir, "in-progress", input);
    {
        let mut c = current.lock().unwrap_or_else(|e| e.into_inner());
        *c = Current {
            case,
            started: Instant::now(),
            text: input.text.clone(),
            scene: input.scene.as_ref().map(|s| format!("{s:#?}\n")),
            reported: false,
        };
    }
    let t0 = Instant::now();
    let outcome = run(input, case.is_multiple_of(4));
    let took = t0.elapsed();
    current.lock().unwrap_or_else(|e| e.into_inner()).reported = true;
    (outcome, took)
}

/// How the cases run so far ended.
struct Tally {
    /// Per kind of input: ok, diagnostics, panics, bad emits.
    counts: BTreeMap<&'static str, [u64; 4]>,
    ok: u64,
    diags: u64,
    panics: u64,
    bad_emits: u64,
    /// The longest a case took, and that case.
    slowest: (Duration, u64),
    /// Cases slower than `SLOW`.
    slow: Vec<(u64, Kind, Duration)>,
    /// Distinct panic messages, with their first case and count.
    distinct: BTreeMap<String, (u64, u64)>,
}

impl Tally {
    fn new(first: u64) -> Tally {
        Tally {
            counts: BTreeMap::new(),
            ok: 0,
            diags: 0,
            panics: 0,
            bad_emits: 0,
            slowest: (Duration::ZERO, first),
            slow: Vec::new(),
            distinct: BTreeMap::new(),
        }
    }

    /// Counts one case; saves its input into `dir` (and says so) if it
    /// failed or was slow.
    fn record(&mut self, dir: &Path, case: u64, input: &Case, outcome: &Outcome, took: Duration) {
        let kind = input.kind;
        let kind_name = match kind {
            Kind::Grammar => "grammar",
            Kind::Mutation => "mutation",
            Kind::Soup => "soup",
            Kind::Deep => "deep",
        };
        let slot = self.counts.entry(kind_name).or_default();
        match outcome {
            Outcome::Ok => {
                self.ok += 1;
                slot[0] += 1;
            }
            Outcome::Diagnostics(_) => {
                self.diags += 1;
                slot[1] += 1;
            }
            Outcome::Panic(message) | Outcome::BadEmit(message) => {
                let is_panic = matches!(outcome, Outcome::Panic(_));
                if is_panic {
                    self.panics += 1;
                    slot[2] += 1;
                } else {
                    self.bad_emits += 1;
                    slot[3] += 1;
                }
                let path = save(dir, &case.to_string(), input);
                // Group by the first line (message and location).
                let key = format!(
                    "{}: {}",
                    if is_panic { "panic" } else { "bad emit" },
                    message.replace('\n', " ")
                );
                let entry = self.distinct.entry(key.clone()).or_insert((case, 0));
                entry.1 += 1;
                if entry.1 == 1 {
                    eprintln!(
                        "case {case} ({kind_name}): {key}\n  input in {}",
                        path.display()
                    );
                }
            }
        }
        if took > self.slowest.0 {
            self.slowest = (took, case);
        }
        if took > SLOW {
            self.slow.push((case, kind, took));
            let path = save(dir, &format!("slow-{case}"), input);
            eprintln!(
                "case {case} ({kind_name}) took {:.2} s: input in {}",
                took.as_secs_f64(),
                path.display()
            );
        }
    }

    /// The counts per kind, the distinct failures and the slow cases (to
    /// stderr), and the summary line (to stdout).
    fn report(&self, cases: u64, seed: u64, start: Instant) {
        for (kind, [k_ok, k_diag, k_panic, k_bad]) in &self.counts {
            eprintln!(
                "  {kind:>8}: {k_ok} ok, {k_diag} diagnostics, {k_panic} panics, {k_bad} bad emits"
            );
        }
        for (message, (case, n)) in &self.distinct {
            eprintln!("  {n} × {message} (first: case {case})");
        }
        for (case, kind, took) in &self.slow {
            eprintln!("  slow: case {case} ({kind:?}) {:.2} s", took.as_secs_f64());
        }
        let Tally {
            ok,
            diags,
            panics,
            bad_emits,
            slowest,
            ..
        } = self;
        println!(
            "fuzz: {cases} cases (seed {seed}): {ok} ok, {diags} diagnostics, {panics} panics, {bad_emits} bad emits; slowest {:.3} s (case {}); total {:.1} s",
            slowest.0.as_secs_f64(),
            slowest.1,
            start.elapsed().as_secs_f64()
        );
    }
}
