//! What lockstep buys a study: cases per second of a Monte Carlo over the
//! initial state of chain-spatial-10 generated with `lanes = true` (ten
//! random joint angles and rates; 0.5 s at h = 1 ms with RK4, 2 000
//! derivative evaluations a case, and with Adams–Bashforth–Moulton of
//! order 4, about 1 000; with Dormand–Prince at rtol 1e-6, atol 1e-9,
//! each case its own steps), and of one over its parameters too
//! (every parameter within ±20 % of its default: each case its own
//! model), one case at a time (`Study::lockstep(false)`) and in lockstep
//! (groups of four cases, one `derivatives_each` call per stage: four
//! states per call of `derivatives_lanes`, each lane reading its own
//! case's parameters); and the same model generated without lanes (one
//! case at a time either way). Serial (one thread), interleaved over
//! rounds; prints the medians. Results are checked equal, bit for bit, in
//! every round.
//!
//! ```text
//! cargo run --release --example study_lockstep [-- ROUNDS [CASES]]
//! ```

use std::error::Error;
use std::time::Instant;

use autosim::runtime::integrate::AbmOrder;
use autosim::runtime::study::{Cases, Distribution, Keep, Method, Parallelism, Simulate, Study};
use autosim::runtime::{Model, RunSettings};

mod lanes {
    autosim::model!(file = "examples/models/chain_spatial_10.sim", lanes = true);
}
mod plain {
    autosim::model!(file = "examples/models/chain_spatial_10.sim");
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Random initial angles and rates of every joint; with `parameters`,
/// every parameter of `model` within ±20 % of its value too.
fn cases<M: Model<Float = f64>>(
    model: &M,
    parameters: bool,
    count: u64,
) -> Result<Cases, Box<dyn Error>> {
    let mut columns: Vec<(&str, Distribution)> = M::STATE_NAMES
        .iter()
        .map(|n| (*n, Distribution::uniform(-0.5, 0.5)))
        .collect();
    if parameters {
        let mut values = vec![0.0; M::PARAMETER_NAMES.len()];
        model.parameter_values(&mut values);
        for (name, v) in M::PARAMETER_NAMES.iter().zip(values) {
            columns.push((name, Distribution::uniform(0.8 * v, 1.2 * v)));
        }
    }
    Ok(Cases::new().random(count, 7, &columns)?)
}

/// Cases per second (median of `rounds`) one at a time and in lockstep.
fn measure<M, F>(
    make: F,
    (method, parameters): (Method, bool),
    rounds: usize,
    count: u64,
) -> Result<(f64, f64), Box<dyn Error>>
where
    M: Model<Float = f64>,
    F: Fn() -> M + Sync,
{
    let settings = RunSettings::new(0.0, 0.5, 0.001, 0.05);
    let task = Simulate::new(settings, method, Keep::new().final_state())?;
    let cases = cases(&make(), parameters, count)?;
    let mut study = Study::new(make, cases, task)
        .progress(false)
        .parallelism(Parallelism::Serial);
    let (mut alone, mut lockstep) = (vec![], vec![]);
    for _ in 0..rounds {
        let mut timed = |on: bool| -> Result<_, Box<dyn Error>> {
            study.set_lockstep(on);
            let start = Instant::now();
            let results = study.run_cases(0..count)?;
            Ok((count as f64 / start.elapsed().as_secs_f64(), results))
        };
        let (a, ra) = timed(false)?;
        let (b, rb) = timed(true)?;
        assert!(ra == rb, "lockstep changed the results");
        assert_eq!(ra.failures(), 0);
        alone.push(a);
        lockstep.push(b);
    }
    Ok((median(&mut alone), median(&mut lockstep)))
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1).map(|a| a.parse::<u64>());
    let rounds = args.next().transpose()?.unwrap_or(5) as usize;
    let count = args.next().transpose()?.unwrap_or(2_000);
    println!("{count} chain-spatial-10 runs (0.5 s each), serial, median of {rounds}:");
    let dopri = Method::DormandPrince {
        rtol: 1e-6,
        atol: 1e-9,
    };
    let methods = [
        ("RK4", Method::Rk4),
        ("ABM4", Method::AdamsBashforthMoulton(AbmOrder::Four)),
        ("Dormand-Prince 1e-6", dopri),
    ];
    for ((label, method), parameters) in methods
        .into_iter()
        .flat_map(|m| [false, true].map(|p| (m, p)))
    {
        let what = match parameters {
            false => "initial states",
            true => "parameters too",
        };
        println!("{label}, random {what}:");
        let task = (method, parameters);
        for (name, (a, b)) in [
            (
                "lanes = true",
                measure(
                    lanes::chain_spatial10::ChainSpatial10::new,
                    task,
                    rounds,
                    count,
                )?,
            ),
            (
                "plain",
                measure(
                    plain::chain_spatial10::ChainSpatial10::new,
                    task,
                    rounds,
                    count,
                )?,
            ),
        ] {
            println!(
                "  {name:<13} one at a time {a:>7.0} cases/s, lockstep {b:>7.0} cases/s ({:.2}x)",
                b / a
            );
        }
    }
    Ok(())
}
