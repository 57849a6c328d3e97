//! Speed of generated code: median nanoseconds per `derivatives()` call at
//! random states, one JSON object per line.
//!
//! `cargo run --release --example perf`

use autosim::runtime::{Model, OpCount};
use autosim_test_support::Rng;
use std::hint::black_box;
use std::time::Instant;

#[path = "common/perf_models.rs"]
mod perf_models;
use perf_models::{Quiet, models};

/// Median ns per call over `rounds` rounds of calls at `states`.
fn measure<M: Model<Float = f64, State = [f64; N]>, const N: usize>(
    model: &mut M,
    states: &[[f64; N]],
) -> f64 {
    let mut dx = [0.0; N];
    // Warm up.
    for x in states {
        let _ = model.derivatives(0.0, black_box(x), &mut dx);
    }
    let rounds = 201;
    let mut per_call: Vec<f64> = Vec::with_capacity(rounds);
    for _ in 0..rounds {
        let start = Instant::now();
        for x in states {
            let _ = black_box(model.derivatives(0.0, black_box(x), &mut dx));
            black_box(&mut dx);
        }
        per_call.push(start.elapsed().as_nanos() as f64 / states.len() as f64);
    }
    per_call.sort_by(f64::total_cmp);
    per_call[rounds / 2]
}

fn states<const N: usize>(
    rng: &mut Rng,
    count: usize,
    scale_small: Option<&[usize]>,
) -> Vec<[f64; N]> {
    let n = N / 2;
    (0..count)
        .map(|_| {
            let mut x = [0.0; N];
            for (i, v) in x.iter_mut().enumerate() {
                *v = if i < n {
                    rng.uniform(-std::f64::consts::PI, std::f64::consts::PI)
                } else {
                    rng.uniform(-2.0, 2.0)
                };
                if scale_small.is_some_and(|s| s.contains(&(i % n))) {
                    *v *= 1e-3;
                }
            }
            x
        })
        .collect()
}

fn report<M: Model<Float = f64, State = [f64; N]>, const N: usize>(
    name: &str,
    mut model: M,
    ops: OpCount,
    rng: &mut Rng,
    small: Option<&[usize]>,
) {
    let xs = states::<N>(rng, 512, small);
    let ns = measure(&mut model, &xs);
    println!(
        "{{\"model\": \"{name}\", \"n_states\": {N}, \"ns_per_call\": {ns:.1}, \"ops\": {}, \"adds\": {}, \"muls\": {}, \"divs\": {}, \"funcs\": {}}}",
        ops.total(),
        ops.adds,
        ops.muls,
        ops.divs,
        ops.funcs
    );
}

fn main() {
    use models::*;
    let mut rng = Rng::new(0x2545_f491_4f6c_dd1d);
    macro_rules! chain {
        ($name:literal, $m:ident :: $t:ident) => {
            report($name, $m::$t::new(), $m::$t::DERIVATIVE_OPS, &mut rng, None)
        };
    }
    chain!("chain-spatial-1", chain_spatial1::ChainSpatial1);
    chain!("chain-spatial-2", chain_spatial2::ChainSpatial2);
    chain!("chain-spatial-3", chain_spatial3::ChainSpatial3);
    chain!("chain-spatial-5", chain_spatial5::ChainSpatial5);
    chain!("chain-spatial-7", chain_spatial7::ChainSpatial7);
    chain!("chain-spatial-10", chain_spatial10::ChainSpatial10);
    chain!("chain-spatial-20", chain_spatial20::ChainSpatial20);
    chain!("chain-planar-10", chain_planar10::ChainPlanar10);
    type Full = satellite::Satellite<Quiet>;
    report(
        "satellite",
        Full::new(Quiet),
        Full::DERIVATIVE_OPS,
        &mut rng,
        None,
    );
    type Small = satellite_small::SatelliteSmall<Quiet>;
    // Small-variable states: the bus motion and boom angles are small.
    let small = [0, 1, 2, 3, 4, 5, 8, 9];
    report(
        "satellite-small",
        Small::new(Quiet),
        Small::DERIVATIVE_OPS,
        &mut rng,
        Some(&small),
    );
}
