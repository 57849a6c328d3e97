//! The copies of generated `derivatives` (the target's baseline,
//! x86-64-v3 and x86-64-v4, `autosim::runtime`'s `float/dispatch.rs`)
//! agree: the same errors, and every state derivative within a few
//! rounding errors of the baseline's, at random states, for models that
//! take each kind of generated code (the mass matrix's LDLᵀ, the
//! articulated-body recursion, constraint solves, `f32`), each big enough
//! to have fast copies (40 operations or more). The fast copies fuse each
//! `add_mul` (one rounding), the baseline does not: where they run, some
//! derivatives differ from the baseline's in their last bits, which shows
//! that the fast copies fuse; the x86-64-v3 and x86-64-v4 copies fuse the
//! same products and give the same bits. That they fuse exactly as a
//! build whose target has FMA (the same bits) is tested on the runtime's
//! fused `MulAdd` and sines (`float/fused.rs`), against `mul_add` and the
//! crate's own functions in such a build; and
//! `tests/models/tests/lanes.rs` checks that single calls and lanes fuse
//! alike, on each copy.
//! On a processor without x86-64-v3 (or v4), or in a build that keeps one
//! copy (the target already has AVX2 and FMA, or not x86-64), calls take
//! the most capable copy there is and the test says so.
#![cfg(target_arch = "x86_64")]

use autosim::runtime::__private::{Path, limit_path, path};
use autosim::runtime::{Float, Model, StateArray};
use autosim_test_support::Rng;

mod models {
    autosim::model!(file = "examples/models/chain_planar_5.sim");
    autosim::model!(file = "examples/models/chain_spatial_7.sim");
    // In `f32`, at a size that keeps fast copies (a function of fewer than
    // 40 operations has one copy: `emit/model/versions.rs`).
    autosim::model!(
        file = "examples/models/chain_planar_5.sim",
        name = ChainPlanar5F32,
        float = f32
    );
    autosim::model!(file = "examples/models/rolling_disc.sim");
    autosim::model!(file = "examples/models/bicycle.sim");
}

/// What [`every_path`] found: states compared, and states where some
/// derivative's bits differ between the baseline and the x86-64-v3 copy,
/// and between the x86-64-v3 and the x86-64-v4 copies.
#[derive(Default)]
struct Compared {
    states: usize,
    baseline_differs: usize,
    v4_differs: usize,
}

/// What `derivatives` gives at `x` on the copy `limit` allows.
fn on_path<M: Model>(
    model: &mut M,
    x: &M::State,
    limit: Path,
) -> (Result<(), autosim::runtime::ModelError>, M::State) {
    limit_path(limit);
    let mut dx = M::State::zeros();
    let result = model.derivatives(M::Float::from_f64(0.3), x, &mut dx);
    (result, dx)
}

fn bits<F: Float>(dx: &[F]) -> Vec<u64> {
    dx.iter().map(|v| v.to_f64().to_bits()).collect()
}

/// `derivatives` at 200 random states near the model's initial state
/// (coordinates ±π, speeds ±3 around it) on the baseline copy, the
/// x86-64-v3 copy and the most capable copy: the same result, derivatives
/// within `sqrt(ε)` (relative to the largest) of the baseline's, and the
/// x86-64-v4 copy's bits those of the x86-64-v3 copy.
fn every_path<M: Model>(mut model: M, seed: u64, compared: &mut Compared)
where
    M::State: core::fmt::Debug,
{
    let mut rng = Rng::new(seed);
    let x0 = model.initial_state();
    for _ in 0..200 {
        let mut x = x0;
        for v in x.as_mut() {
            let delta = M::Float::from_f64(rng.uniform(-3.0, 3.0));
            *v += delta;
        }
        let (base_result, base_dx) = on_path(&mut model, &x, Path::Baseline);
        let (v3_result, v3_dx) = on_path(&mut model, &x, Path::V3);
        let (v4_result, v4_dx) = on_path(&mut model, &x, Path::V4);
        assert_eq!(base_result, v3_result, "{} at {x:?}", M::NAME);
        assert_eq!(v3_result, v4_result, "{} at {x:?}", M::NAME);
        let (base, fast) = (base_dx.as_ref(), v3_dx.as_ref());
        let scale = base.iter().fold(1.0, |m: f64, v| m.max(v.to_f64().abs()));
        let tolerance = M::Float::EPSILON.to_f64().sqrt() * scale;
        for (b, f) in base.iter().zip(fast) {
            let (b, f) = (b.to_f64(), f.to_f64());
            let close = (b - f).abs() <= tolerance || (b.is_nan() && f.is_nan());
            assert!(close, "{} at {x:?}: {b} and {f}", M::NAME);
        }
        compared.baseline_differs += usize::from(bits(base) != bits(fast));
        compared.v4_differs += usize::from(bits(fast) != bits(v4_dx.as_ref()));
        compared.states += 1;
    }
}

#[test]
fn the_copies_agree_and_the_fast_copies_fuse_alike() {
    limit_path(Path::V4);
    let fastest = path();
    let has_copies =
        !cfg!(all(target_feature = "avx2", target_feature = "fma")) && !cfg!(feature = "libm");
    if !has_copies {
        println!("SKIPPED: this build keeps one copy, or fuses in none (libm)");
    } else if fastest < Path::V3 {
        println!("SKIPPED: this processor has no x86-64-v3: every call takes the baseline copy");
    } else if fastest < Path::V4 {
        println!("SKIPPED: this processor has no x86-64-v4: its copy is not compared");
    }
    let mut compared = Compared::default();
    every_path(models::chain_planar5::ChainPlanar5::new(), 1, &mut compared);
    every_path(
        models::chain_spatial7::ChainSpatial7::new(),
        2,
        &mut compared,
    );
    every_path(
        models::chain_planar5_f32::ChainPlanar5F32::new(),
        3,
        &mut compared,
    );
    every_path(models::bicycle::Bicycle::new(), 4, &mut compared);
    every_path(models::rolling_disc::RollingDisc::new(), 5, &mut compared);
    limit_path(Path::V4);
    assert_eq!(compared.states, 1000);
    assert_eq!(
        compared.v4_differs, 0,
        "the x86-64-v4 copy fuses differently"
    );
    if has_copies && fastest >= Path::V3 {
        assert!(compared.baseline_differs > 0, "the fast copies do not fuse");
    } else {
        assert_eq!(compared.baseline_differs, 0);
    }
}
