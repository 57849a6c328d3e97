//! Where the math functions of generated code come from: the standard
//! library (the platform's libm, glibc on Linux) against the `libm` crate,
//! per function, on 1000 arguments in the range generated code sees
//! (angles in ±2 rad; positive values for the logarithm, powers and roots).
//!
//! `cargo bench -p autosim-runtime --bench math`

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

/// 1000 values spread over `[lo, hi)`, the same every run.
fn arguments(lo: f64, hi: f64) -> Vec<f64> {
    let mut rng = autosim_test_support::Rng::new(0x5eed_ca11);
    (0..1000).map(|_| rng.uniform(lo, hi)).collect()
}

/// One function from each source, on the same arguments.
fn pair(c: &mut Criterion, name: &str, xs: &[f64], std: fn(f64) -> f64, libm: fn(f64) -> f64) {
    let mut group = c.benchmark_group(name);
    let mut out = vec![0.0; xs.len()];
    for (source, f) in [("std", std), ("libm", libm)] {
        group.bench_function(source, |b| {
            b.iter(|| {
                for (o, x) in out.iter_mut().zip(black_box(xs)) {
                    *o = f(*x);
                }
                black_box(&out);
            })
        });
    }
    group.finish();
}

fn math(c: &mut Criterion) {
    let angles = arguments(-2.0, 2.0);
    let small = arguments(-0.9, 0.9);
    let positive = arguments(0.1, 2.1);
    pair(c, "sin", &angles, f64::sin, libm::sin);
    pair(c, "cos", &angles, f64::cos, libm::cos);
    let std_pair = |x: f64| {
        let (s, c) = x.sin_cos();
        s + c
    };
    let libm_pair = |x: f64| {
        let (s, c) = libm::sincos(x);
        s + c
    };
    pair(c, "sin_cos", &angles, std_pair, libm_pair);
    pair(c, "tan", &small, f64::tan, libm::tan);
    pair(c, "asin", &small, f64::asin, libm::asin);
    pair(c, "acos", &small, f64::acos, libm::acos);
    pair(
        c,
        "atan2",
        &angles,
        |y| y.atan2(0.7),
        |y| libm::atan2(y, 0.7),
    );
    pair(c, "exp", &angles, f64::exp, libm::exp);
    pair(c, "ln", &positive, f64::ln, libm::log);
    pair(c, "powf", &positive, |x| x.powf(1.7), |x| libm::pow(x, 1.7));
    pair(c, "sqrt", &positive, f64::sqrt, libm::sqrt);
}

criterion_group!(benches, math);
criterion_main!(benches);
