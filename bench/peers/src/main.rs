//! `autosim_bench bench ROUNDS`: every chain model's generated
//! `derivatives()` timed exactly as the peers' `pin_bench bench` and
//! `cas_bench bench` time theirs (1000 random states, q in [-π, π], speeds
//! in [-1, 1]; batches of 1000 calls, about 0.04 s of batches per model and
//! round), printing the same JSON lines with method `autosim`. Then the
//! satellite (kind `satellite`; no peer has it), timed the same way, so
//! its time is measured in the same run as the chains.

use autosim::runtime::Model;
use std::hint::black_box;
use std::time::Instant;

macro_rules! models {
    ($($module:ident :: $ty:ident => $kind:literal, $n:literal;)+) => {
        $(autosim::include_model!($module);)+
        fn run_all(rounds: usize, rng: &mut Rng, out: &mut Vec<(String, u32, Vec<f64>)>) {
            $(out.push(($kind.to_string(), $n, time($module::$ty::new(), rounds, rng)));)+
        }
    };
}

models! {
    chain_planar1::ChainPlanar1 => "planar", 1;
    chain_planar2::ChainPlanar2 => "planar", 2;
    chain_planar3::ChainPlanar3 => "planar", 3;
    chain_planar5::ChainPlanar5 => "planar", 5;
    chain_planar7::ChainPlanar7 => "planar", 7;
    chain_planar10::ChainPlanar10 => "planar", 10;
    chain_planar20::ChainPlanar20 => "planar", 20;
    chain_planar50::ChainPlanar50 => "planar", 50;
    chain_spatial1::ChainSpatial1 => "spatial", 1;
    chain_spatial2::ChainSpatial2 => "spatial", 2;
    chain_spatial3::ChainSpatial3 => "spatial", 3;
    chain_spatial5::ChainSpatial5 => "spatial", 5;
    chain_spatial7::ChainSpatial7 => "spatial", 7;
    chain_spatial10::ChainSpatial10 => "spatial", 10;
    chain_spatial20::ChainSpatial20 => "spatial", 20;
    chain_spatial50::ChainSpatial50 => "spatial", 50;
}

autosim::include_model!(satellite);

// The satellite's user code: `Quiet`, as `examples/perf.rs` times it.
include!("../../../examples/common/quiet.rs");
quiet!(satellite::Externs);

/// SplitMix64, uniform in [lo, hi).
struct Rng(u64);
impl Rng {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        lo + (hi - lo) * ((z >> 11) as f64 / (1u64 << 53) as f64)
    }
}

const STATES: usize = 1000;

/// Per-batch ns per call of `model` over `rounds` rounds.
fn time<M: Model<Float = f64, State = [f64; N]>, const N: usize>(
    mut model: M,
    rounds: usize,
    rng: &mut Rng,
) -> Vec<f64> {
    let n = N / 2;
    let states: Vec<[f64; N]> = (0..STATES)
        .map(|_| {
            std::array::from_fn(|i| {
                if i < n {
                    rng.uniform(-std::f64::consts::PI, std::f64::consts::PI)
                } else {
                    rng.uniform(-1.0, 1.0)
                }
            })
        })
        .collect();
    let mut dx = [0.0; N];
    let mut pass = |m: &mut M| {
        let start = Instant::now();
        for x in &states {
            let _ = black_box(m.derivatives(0.0, black_box(x), &mut dx));
        }
        start.elapsed().as_nanos() as f64 / STATES as f64
    };
    let one = pass(&mut model); // warm-up and calibration, as the peers
    let batches = (0.04e9 / one.max(1.0)).clamp(7.0, 601.0) as usize;
    (0..rounds * batches).map(|_| pass(&mut model)).collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(String::as_str) != Some("bench") {
        eprintln!("usage: autosim_bench bench [ROUNDS]");
        std::process::exit(2);
    }
    let rounds: usize = args.get(2).and_then(|r| r.parse().ok()).unwrap_or(1);
    let mut rng = Rng(12345);
    let mut out = Vec::new();
    run_all(rounds, &mut rng, &mut out);
    let satellite = satellite::Satellite::new(Quiet);
    out.push((
        "satellite".to_string(),
        10,
        time(satellite, rounds, &mut rng),
    ));
    for (kind, n, batches) in out {
        let list: Vec<String> = batches.iter().map(|b| format!("{b:.3}")).collect();
        println!(
            "{{\"kind\": \"{kind}\", \"n\": {n}, \"method\": \"autosim\", \"calls_per_batch\": {STATES}, \"batches_ns\": [{}]}}",
            list.join(", ")
        );
    }
}
