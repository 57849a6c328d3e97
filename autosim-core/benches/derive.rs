//! Speed of the compiler itself: building and deriving chain-spatial-n.
//! Run with `cargo bench -p autosim-core --bench derive`.

use autosim_test_support::api::chain;
use criterion::{Criterion, criterion_group, criterion_main};
use serde_json::{Value, json};
use std::hint::black_box;

/// Parameter values for chain-spatial-n of reference-models.md (irrelevant
/// here: the benchmark times building the model and deriving it).
fn chain_spatial_parameters(n: usize) -> Value {
    let mut params = json!({"k": 2.0, "c": 0.1, "g": 9.81, "P": 0.0005});
    for i in 1..=n {
        for (name, value) in [
            ("m", 1.0),
            ("L", 0.4),
            ("Ixx", 0.01),
            ("Iyy", 0.01),
            ("Izz", 0.002),
        ] {
            params[format!("{name}{i}")] = json!(value);
        }
    }
    params
}

fn derive(c: &mut Criterion) {
    let mut group = c.benchmark_group("derive");
    group.sample_size(10);
    for n in [10usize, 50] {
        let params = chain_spatial_parameters(n);
        group.bench_function(format!("chain-spatial-{n}"), |b| {
            b.iter(|| {
                let mut sys = chain(black_box(n), true, &params);
                let eqs = sys.equations().expect("equations");
                black_box(eqs.forcing.len())
            })
        });
    }
    // The whole compiler on model files, as the macro runs it: parse,
    // resolve, derive, optimize, emit tokens (build scripts also format the
    // file with prettyplease, which costs more than all of this).
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models");
    for file in [
        "satellite.sim",
        "chain_spatial_10.sim",
        "chain_spatial_20.sim",
    ] {
        let text = std::fs::read_to_string(dir.join(file)).expect("model file");
        let src = autosim_core::diag::SourceFile::new(file, text);
        group.bench_function(format!("compile {file}"), |b| {
            b.iter(|| {
                let c = autosim_core::pipeline::compile_source(black_box(&src)).expect("compiles");
                let tokens = autosim_core::emit::model_tokens(
                    &c.program,
                    &autosim_core::emit::EmitOptions::default(),
                );
                black_box(autosim_core::emit::format_tokens(&tokens).len())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, derive);
criterion_main!(benches);
