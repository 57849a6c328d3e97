//! Criterion benchmarks of generated `derivatives()` (the same models as
//! `examples/perf.rs`): `cargo bench --bench derivatives`.

use autosim::runtime::Model;
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

#[path = "../examples/common/perf_models.rs"]
mod perf_models;
use perf_models::{Quiet, models};

fn bench_model<M: Model<Float = f64, State = [f64; N]>, const N: usize>(
    c: &mut Criterion,
    name: &str,
    mut model: M,
) {
    // A fixed, generic state: every angle and speed non-zero.
    let mut x = [0.0; N];
    for (i, v) in x.iter_mut().enumerate() {
        *v = 0.3 + 0.07 * i as f64;
    }
    let mut dx = [0.0; N];
    c.bench_function(name, |b| {
        b.iter(|| {
            let r = model.derivatives(0.0, black_box(&x), &mut dx);
            black_box(&mut dx);
            r
        })
    });
}

fn derivatives(c: &mut Criterion) {
    use models::*;
    bench_model(c, "chain-spatial-1", chain_spatial1::ChainSpatial1::new());
    bench_model(c, "chain-spatial-3", chain_spatial3::ChainSpatial3::new());
    bench_model(c, "chain-spatial-5", chain_spatial5::ChainSpatial5::new());
    bench_model(
        c,
        "chain-spatial-10",
        chain_spatial10::ChainSpatial10::new(),
    );
    bench_model(
        c,
        "chain-spatial-20",
        chain_spatial20::ChainSpatial20::new(),
    );
    bench_model(c, "chain-planar-10", chain_planar10::ChainPlanar10::new());
    bench_model(c, "satellite", satellite::Satellite::new(Quiet));
    bench_model(
        c,
        "satellite-small",
        satellite_small::SatelliteSmall::new(Quiet),
    );
}

criterion_group!(benches, derivatives);
criterion_main!(benches);
