//! Speed of the compiler itself: building and deriving chain-spatial-n.
//! Run with `cargo bench -p autosim-core --bench derive`.

use autosim_core::expr::ExprId;
use autosim_core::mech::{Axis, BodyId, BodySpec, Rotation, System};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

/// chain-spatial-n of reference-models.md (parameter values irrelevant here).
pub fn chain_spatial(n: usize) -> System {
    let mut sys = System::new("ChainSpatial");
    let par = |sys: &mut System, name: &str, v: f64| -> ExprId {
        let s = sys.add_parameter(name, v, None).expect("new parameter");
        sys.arena.sym(s)
    };
    let k = par(&mut sys, "k", 2.0);
    let c = par(&mut sys, "c", 0.1);
    let g = par(&mut sys, "g", 9.81);
    let p = par(&mut sys, "P", 0.0005);
    let zero = sys.arena.zero();
    let mut prev_len: Option<ExprId> = None;
    for i in 1..=n {
        let m = par(&mut sys, &format!("m{i}"), 1.0);
        let l = par(&mut sys, &format!("L{i}"), 0.4);
        let ixx = par(&mut sys, &format!("Ixx{i}"), 0.01);
        let iyy = par(&mut sys, &format!("Iyy{i}"), 0.01);
        let izz = par(&mut sys, &format!("Izz{i}"), 0.002);
        let parent = if i == 1 {
            "N".to_string()
        } else {
            format!("B{}", i - 1)
        };
        let mut spec = BodySpec::new(&format!("B{i}"), &parent);
        if let Some(pl) = prev_len {
            spec.joint_point = Some([zero, zero, sys.arena.neg(pl)]);
        }
        let axis = ((i - 1) % 3) as i64 + 1;
        spec.joint.rotation = Rotation::Simple(Axis::number(axis).unwrap());
        spec.mass = Some(m);
        let half = sys.arena.rational(-1, 2);
        spec.cm = Some([zero, zero, sys.arena.mul(half, l)]);
        spec.inertia = Some([[ixx, p, zero], [p, iyy, zero], [zero, zero, izz]]);
        let b = sys.add_body(spec).expect("valid body");
        let q = sys.arena.sym(sys.coordinates()[i - 1].q);
        let u = sys.arena.sym(sys.coordinates()[i - 1].u);
        let kq = sys.arena.mul(k, q);
        let cu = sys.arena.mul(c, u);
        let s = sys.arena.add(kq, cu);
        let mag = sys.arena.neg(s);
        let parent_id = sys.body_named(&parent).expect("parent");
        let axis_v = sys.unit_vector(parent_id, Axis::number(axis).unwrap());
        let v = axis_v.scale(&mut sys.arena, mag);
        sys.add_moment(&format!("spring{i}"), b, Some(parent_id), v)
            .expect("moment");
        prev_len = Some(l);
    }
    let n3 = sys.unit_vector(BodyId::N, Axis::A3);
    let mg = sys.arena.neg(g);
    let gv = n3.scale(&mut sys.arena, mg);
    sys.set_gravity(gv);
    sys
}

fn derive(c: &mut Criterion) {
    let mut group = c.benchmark_group("derive");
    group.sample_size(10);
    for n in [10usize, 50] {
        group.bench_function(format!("chain-spatial-{n}"), |b| {
            b.iter(|| {
                let mut sys = chain_spatial(black_box(n));
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
