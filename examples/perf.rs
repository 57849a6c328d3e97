//! Speed of generated code: median nanoseconds per `derivatives()` call at
//! random states, one JSON object per line; at the end, many states per
//! call (`derivatives_lanes`, 4 and 8 lanes) against one call per state.
//!
//! `cargo run --release --example perf`

use autosim::runtime::batch::in_lanes;
use autosim::runtime::integrate::Rk4;
use autosim::runtime::{Lanes, Model, ModelError, OpCount, RunSettings, run};
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

/// 512 states along a run from `x0` (for constrained models, whose states
/// must satisfy the constraints).
fn along_run<M: Model<Float = f64, State = [f64; N]>, const N: usize>(
    model: &mut M,
    x0: [f64; N],
    stop: f64,
) -> Vec<[f64; N]> {
    let mut x = x0;
    let mut out = Vec::with_capacity(512);
    let settings = RunSettings::new(0.0, stop, stop / 4096.0, stop / 511.0);
    run(
        model,
        &mut Rk4::new(),
        &mut x,
        &settings,
        &mut |_t, x: &[f64; N], _y: &M::Outputs| out.push(*x),
    )
    .expect("the run succeeds");
    out
}

fn report<M: Model<Float = f64, State = [f64; N]>, const N: usize>(
    name: &str,
    model: M,
    ops: OpCount,
    rng: &mut Rng,
    small: Option<&[usize]>,
) {
    let xs = states::<N>(rng, 512, small);
    report_at(name, model, ops, &xs);
}

fn report_at<M: Model<Float = f64, State = [f64; N]>, const N: usize>(
    name: &str,
    mut model: M,
    ops: OpCount,
    xs: &[[f64; N]],
) {
    let ns = measure(&mut model, xs);
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
    constrained();
    linearization(&mut rng);
    many_states(&mut rng);
}

/// Median ns per state of `derivatives_batch`-style evaluation of `xs`
/// with `L` lanes per call (`in_lanes`), after checking that it gives the
/// bits of single calls.
fn batch_ns<M, const L: usize, const N: usize>(
    model: &mut M,
    xs: &[[f64; N]],
    lanes: impl Fn(&mut M, Lanes<L>, &[Lanes<L>; N], &mut [Lanes<L>; N]) -> Result<(), ModelError>
    + Copy,
) -> f64
where
    M: Model<Float = f64, State = [f64; N]>,
{
    let mut dx = vec![[0.0; N]; xs.len()];
    let mut status = vec![Ok(()); xs.len()];
    in_lanes(model, 0.0, xs, &mut dx, &mut status, lanes);
    for (x, (d, s)) in xs.iter().zip(dx.iter().zip(&status)) {
        let mut one = [0.0; N];
        assert_eq!(model.derivatives(0.0, x, &mut one), *s);
        assert_eq!(one.map(f64::to_bits), d.map(f64::to_bits), "lanes differ");
    }
    let rounds = 201;
    let mut per_state: Vec<f64> = Vec::with_capacity(rounds);
    for _ in 0..rounds {
        let start = Instant::now();
        in_lanes(model, 0.0, black_box(xs), &mut dx, &mut status, lanes);
        black_box((&mut dx, &mut status));
        per_state.push(start.elapsed().as_nanos() as f64 / xs.len() as f64);
    }
    per_state.sort_by(f64::total_cmp);
    per_state[rounds / 2]
}

/// Many states per call: ns per state and states per second of one call
/// per state, of `derivatives_batch` (4 lanes) and of 8 lanes, for
/// chain-spatial-10 and the satellite, with the floating-point operations
/// per second those rates mean (`DERIVATIVE_OPS`' adds, multiplies and
/// divides, the functions not counted).
fn many_states(rng: &mut Rng) {
    use models::*;
    macro_rules! lanes {
        ($name:literal, $model:expr, $ty:ty, $n:literal) => {{
            let mut m = $model;
            let xs = states::<$n>(rng, 512, None);
            let single = measure(&mut m, &xs);
            let (v4, v8) = (<$ty>::values_in_lanes([&m; 4]), <$ty>::values_in_lanes([&m; 8]));
            let four = batch_ns::<_, 4, $n>(&mut m, &xs, |m, t, x, dx| m.derivatives_lanes_with(&v4, t, x, dx));
            let eight = batch_ns::<_, 8, $n>(&mut m, &xs, |m, t, x, dx| m.derivatives_lanes_with(&v8, t, x, dx));
            let ops = <$ty>::DERIVATIVE_OPS;
            let flop = (ops.adds + ops.muls + ops.divs) as f64;
            println!(
                "{{\"model\": \"{}\", \"flop_per_state\": {flop}, \"single_ns\": {single:.1}, \"lanes4_ns\": {four:.1}, \"lanes8_ns\": {eight:.1}, \"single_states_per_s\": {:.3e}, \"lanes4_states_per_s\": {:.3e}, \"lanes8_states_per_s\": {:.3e}, \"single_gflops\": {:.2}, \"lanes4_gflops\": {:.2}, \"lanes8_gflops\": {:.2}}}",
                $name,
                1e9 / single,
                1e9 / four,
                1e9 / eight,
                flop / single,
                flop / four,
                flop / eight,
            );
        }};
    }
    lanes!(
        "chain-spatial-10",
        chain_spatial10_lanes::ChainSpatial10Lanes::new(),
        chain_spatial10_lanes::ChainSpatial10Lanes,
        20
    );
    lanes!(
        "satellite",
        satellite_lanes::SatelliteLanes::new(Quiet),
        satellite_lanes::SatelliteLanes<Quiet>,
        20
    );
}

/// Median ns of `f` over rounds of `states`.
fn median_ns<S>(states: &[S], mut f: impl FnMut(&S)) -> f64 {
    for x in states {
        f(x);
    }
    let rounds = 51;
    let mut per_call: Vec<f64> = Vec::with_capacity(rounds);
    for _ in 0..rounds {
        let start = Instant::now();
        for x in states {
            f(black_box(x));
        }
        per_call.push(start.elapsed().as_nanos() as f64 / states.len() as f64);
    }
    per_call.sort_by(f64::total_cmp);
    per_call[rounds / 2]
}

/// `linearize` against central differences of `derivatives` (2 evaluations
/// per state), at random states (the bicycle: at states along a run, which
/// satisfy its constraints).
fn linearization(rng: &mut Rng) {
    use models::*;
    macro_rules! compare {
        ($name:literal, $model:expr, $ty:ty, $n:literal, $states:expr) => {{
            let mut m = $model;
            let xs: Vec<[f64; $n]> = $states(&mut m);
            let lin = median_ns(&xs, |x| {
                let _ = black_box(m.linearize(0.0, x));
            });
            let mut dx = [0.0; $n];
            let eval = median_ns(&xs, |x| {
                let _ = black_box(m.derivatives(0.0, x, &mut dx));
            });
            let ops = <$ty>::LINEARIZE_OPS;
            println!(
                "{{\"model\": \"{}\", \"linearize_ns\": {lin:.1}, \"linearize_ops\": {}, \"central_differences_ns\": {:.1}, \"ratio\": {:.2}}}",
                $name,
                ops.total(),
                2.0 * $n as f64 * eval,
                lin / (2.0 * $n as f64 * eval)
            );
        }};
    }
    compare!(
        "chain-spatial-10",
        chain_spatial10_linear::ChainSpatial10Linear::new(),
        chain_spatial10_linear::ChainSpatial10Linear,
        20,
        |_: &mut _| states::<20>(rng, 64, None)
    );
    compare!(
        "satellite",
        satellite_linear::SatelliteLinear::new(Quiet),
        satellite_linear::SatelliteLinear<Quiet>,
        20,
        |_: &mut _| states::<20>(rng, 64, None)
    );
    compare!(
        "bicycle",
        bicycle_linear::BicycleLinear::new(),
        bicycle_linear::BicycleLinear,
        11,
        |m: &mut bicycle_linear::BicycleLinear| {
            let mut x0 = m.initial_state();
            // Rolling at 5 m/s with a roll perturbation (as `constrained`).
            x0[3] = 0.05;
            x0[9] = 5.0 / 0.3;
            along_run(m, x0, 5.0).into_iter().step_by(8).collect()
        }
    );
}

/// The constrained models, at states along their own runs.
fn constrained() {
    use models::*;
    let mut four_bar = four_bar::FourBar::new();
    let x0 = four_bar.initial_state();
    let xs = along_run(&mut four_bar, x0, 5.0);
    report_at("four-bar", four_bar, four_bar::FourBar::DERIVATIVE_OPS, &xs);
    let mut andrews = andrews::Andrews::new();
    let x0 = andrews.initial_state();
    let xs = along_run(&mut andrews, x0, 0.03);
    report_at("andrews", andrews, andrews::Andrews::DERIVATIVE_OPS, &xs);
    let mut bicycle = bicycle::Bicycle::new();
    let mut x0 = bicycle.initial_state();
    // Rolling at 5 m/s with a roll perturbation.
    x0[3] = 0.05;
    x0[9] = 5.0 / 0.3;
    let xs = along_run(&mut bicycle, x0, 5.0);
    report_at("bicycle", bicycle, bicycle::Bicycle::DERIVATIVE_OPS, &xs);
}
