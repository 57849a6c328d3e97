//! A study killed mid-run (`SIGKILL`, as `kill -9` sends) resumes where it
//! stopped, and the finished table equals an uninterrupted run's.
//!
//! The test runs this binary again as a child process (the ignored test
//! `child_runs_a_slow_study`, which does nothing without the environment
//! variable the parent sets), kills it once a few shards are on disk,
//! resumes the study in the folder, and compares.

use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use autosim::runtime::RunSettings;
use autosim::runtime::study::{
    Cases, Distribution, Format, Keep, Method, Parallelism, Simulate, Study, StudyDir,
};

autosim::model!(file = "examples/models/pendulum.sim");
use pendulum::Pendulum;

const CHILD_DIR: &str = "AUTOSIM_STUDY_KILL_DIR";
const CASES: u64 = 400;
const SHARD: u64 = 10;

fn study() -> Study<Pendulum, fn() -> Pendulum, Simulate<Pendulum>> {
    let cases = Cases::new()
        .random(
            CASES,
            7,
            &[
                ("q", Distribution::uniform(-2.0, 2.0)),
                ("m", Distribution::uniform(0.5, 3.0)),
            ],
        )
        .unwrap();
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.5);
    let keep = Keep::new().final_state().at(&[0.5], &["height"]);
    let task = Simulate::new(
        settings,
        Method::DormandPrince {
            rtol: 1e-8,
            atol: 1e-10,
        },
        keep,
    )
    .unwrap();
    Study::new(Pendulum::new as fn() -> Pendulum, cases, task)
        .progress(false)
        .parallelism(Parallelism::Threads(2))
}

/// Runs the study slowly (5 ms a case) in the folder the parent names.
#[test]
#[ignore = "the child process of killed_study_resumes_to_the_uninterrupted_table"]
fn child_runs_a_slow_study() {
    let Ok(dir) = std::env::var(CHILD_DIR) else {
        println!("(nothing to do: run by killed_study_resumes_to_the_uninterrupted_table)");
        return;
    };
    let slow = study().setup(&[], |_, _, _| {
        std::thread::sleep(Duration::from_millis(5));
        Ok(())
    });
    slow.run_in(dir, Format::Parquet, SHARD).unwrap();
}

#[test]
fn killed_study_resumes_to_the_uninterrupted_table() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("study-killed");
    let _ = std::fs::remove_dir_all(&dir);
    let mut child = Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "child_runs_a_slow_study",
            "--ignored",
            "--nocapture",
        ])
        .env(CHILD_DIR, &dir)
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    // Wait for 3 shards (of 40, about 25 ms each at 5 ms a case on 2
    // threads), then kill.
    let deadline = Instant::now() + Duration::from_secs(120);
    let shards = |dir: &PathBuf| {
        std::fs::read_dir(dir).map_or(0, |entries| {
            entries
                .flatten()
                .filter(|e| e.file_name().to_string_lossy().starts_with("part-"))
                .count()
        })
    };
    while shards(&dir) < 3 {
        assert!(
            Instant::now() < deadline,
            "the child wrote no shards in 2 minutes"
        );
        assert!(
            child.try_wait().unwrap().is_none(),
            "the child ended before it was killed"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
    child.kill().unwrap(); // SIGKILL
    let status = child.wait().unwrap();
    assert!(!status.success());
    let on_disk = StudyDir::open(&dir).unwrap();
    let written = (0..on_disk.shard_count())
        .filter(|k| on_disk.has_shard(*k))
        .count();
    assert!(
        written < on_disk.shard_count() as usize,
        "the child finished before the kill"
    );
    println!("killed after {written} of {} shards", on_disk.shard_count());

    let study = study();
    let summary = study.run_in(&dir, Format::Parquet, SHARD).unwrap();
    assert_eq!(summary.skipped, written as u64 * SHARD);
    assert_eq!(summary.ran + summary.skipped, CASES);
    let resumed = StudyDir::open(&dir).unwrap().read_all().unwrap();
    assert!(
        resumed == study.run_cases(0..CASES).unwrap(),
        "the resumed table differs"
    );
}
