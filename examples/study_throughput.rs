//! Throughput of a study: cases per second for 10⁴ simulations of a small
//! model (the pendulum, random angle and mass, RK4 for 2 s at h = 1 ms:
//! 8 000 derivative evaluations a case), serially and on every core,
//! interleaved over rounds; prints the medians, the speed-up and the
//! parallel efficiency (speed-up / threads). Results are checked equal,
//! bit for bit, in every round.
//!
//! ```text
//! cargo run --release --example study_throughput [-- ROUNDS [CASES]]
//! ```

use std::error::Error;
use std::time::Instant;

use autosim::runtime::RunSettings;
use autosim::runtime::study::{Cases, Distribution, Keep, Method, Parallelism, Simulate, Study};

autosim::model!(file = "examples/models/pendulum.sim");
use pendulum::Pendulum;

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1).map(|a| a.parse::<u64>());
    let rounds = args.next().transpose()?.unwrap_or(5);
    let count = args.next().transpose()?.unwrap_or(10_000);
    let cases = Cases::new().random(
        count,
        3,
        &[
            ("q", Distribution::uniform(-2.0, 2.0)),
            ("m", Distribution::uniform(0.5, 2.0)),
        ],
    )?;
    let settings = RunSettings::new(0.0, 2.0, 0.001, 0.1);
    let task = Simulate::new(settings, Method::Rk4, Keep::new().final_state())?;
    let mut study = Study::new(Pendulum::new, cases, task).progress(false);
    let threads = std::thread::available_parallelism()?.get();
    let (mut serial, mut parallel) = (vec![], vec![]);
    for _ in 0..rounds {
        let mut timed = |p: Parallelism| -> Result<_, Box<dyn Error>> {
            study.set_parallelism(p);
            let start = Instant::now();
            let results = study.run_cases(0..count)?;
            Ok((count as f64 / start.elapsed().as_secs_f64(), results))
        };
        let (s, a) = timed(Parallelism::Serial)?;
        let (p, b) = timed(Parallelism::AllCores)?;
        assert!(a == b, "serial and parallel results differ");
        serial.push(s);
        parallel.push(p);
    }
    let (s, p) = (median(&mut serial), median(&mut parallel));
    println!(
        "{count} pendulum runs (RK4, 2000 steps each), median of {rounds} interleaved rounds:"
    );
    println!("  serial:     {s:>9.0} cases/s");
    println!("  {threads} threads:  {p:>9.0} cases/s");
    println!(
        "  speed-up {:.2}, parallel efficiency {:.0} %",
        p / s,
        100.0 * p / s / threads as f64
    );
    Ok(())
}
