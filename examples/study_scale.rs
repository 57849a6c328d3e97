//! A large study of a tiny model: 10⁶ pendulum runs (random initial
//! angle and bob mass; RK4, 1 s at h = 10 ms) written as Parquet shards of
//! 10⁴ cases, with flat memory: one shard in memory at a time. Kill it
//! (`kill -9`) and run it again on the same folder: it resumes where it
//! stopped. `compare` checks two finished folders hold the same table, bit
//! for bit, shard by shard.
//!
//! ```text
//! cargo run --release --example study_scale -- run FOLDER [CASES [SHARD [THREADS]]]
//! cargo run --release --example study_scale -- compare FOLDER_A FOLDER_B
//! ```
//!
//! Defaults: 1 000 000 cases, shards of 10 000, every core. The peak
//! memory: `/usr/bin/time -v` (maximum resident set size).

use std::error::Error;

use autosim::runtime::RunSettings;
use autosim::runtime::study::{
    Cases, Distribution, Format, Keep, Method, Parallelism, Simulate, Statistic, Study, StudyDir,
};

autosim::model!(file = "examples/models/pendulum.sim");
use pendulum::Pendulum;

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args
        .iter()
        .map(String::as_str)
        .collect::<Vec<_>>()
        .as_slice()
    {
        ["run", folder, rest @ ..] => {
            let number = |k: usize, default: u64| rest.get(k).map_or(Ok(default), |s| s.parse());
            run(
                folder,
                number(0, 1_000_000)?,
                number(1, 10_000)?,
                number(2, 0)?,
            )
        }
        ["compare", a, b] => compare(a, b),
        _ => Err(
            "usage: study_scale run FOLDER [CASES [SHARD [THREADS]]] | compare FOLDER_A FOLDER_B"
                .into(),
        ),
    }
}

fn run(folder: &str, cases: u64, shard: u64, threads: u64) -> Result<(), Box<dyn Error>> {
    let table = Cases::new().random(
        cases,
        1,
        &[
            ("q", Distribution::uniform(-3.0, 3.0)),
            ("m", Distribution::uniform(0.5, 2.0)),
        ],
    )?;
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.1);
    let keep = Keep::new()
        .final_state()
        .statistic("height", Statistic::Max);
    let task = Simulate::new(settings, Method::Rk4, keep)?;
    let parallelism = match threads {
        0 => Parallelism::AllCores,
        n => Parallelism::Threads(n as usize),
    };
    let study = Study::new(Pendulum::new, table, task).parallelism(parallelism);
    let summary = study.run_in(folder, Format::Parquet, shard)?;
    println!(
        "{} cases: {} run now ({} failed), {} already on disk; {:.1} s, {:.0} cases/s",
        summary.cases,
        summary.ran,
        summary.failed,
        summary.skipped,
        summary.elapsed.as_secs_f64(),
        summary.cases_per_second()
    );
    Ok(())
}

fn compare(a: &str, b: &str) -> Result<(), Box<dyn Error>> {
    let (a, b) = (StudyDir::open(a)?, StudyDir::open(b)?);
    if a.layout() != b.layout() || a.cases() != b.cases() || a.shard_count() != b.shard_count() {
        return Err("the folders hold different studies".into());
    }
    for k in 0..a.shard_count() {
        if a.read_shard(k)? != b.read_shard(k)? {
            return Err(format!("shard {k} differs").into());
        }
    }
    println!(
        "{} cases in {} shards: identical, bit for bit",
        a.cases(),
        a.shard_count()
    );
    Ok(())
}
