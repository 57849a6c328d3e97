//! The two copies of generated `derivatives` (the target's baseline and
//! x86-64-v3, `autosim::runtime`'s `float/dispatch.rs`) agree: the same
//! errors, and every state derivative within a few rounding errors of the
//! other's, at random states, for models that take each kind of generated
//! code (the mass matrix's LDLᵀ, the articulated-body recursion,
//! constraint solves, `f32`), each big enough to have two (40 operations
//! or more). The x86-64-v3 copy fuses each `add_mul` (one rounding), the
//! baseline does not: where both copies run, some derivatives differ in
//! their last bits, which shows that the fast copy fuses. That it fuses
//! exactly as a build whose target has FMA (the same bits) is tested on
//! the runtime's fused `MulAdd` and sines (`float/fused.rs`), against
//! `mul_add` and the crate's own functions in such a build; and
//! `tests/models/tests/lanes.rs` checks that single calls and lanes fuse
//! alike, on each copy.
//! On a processor without x86-64-v3, or in a build that keeps one copy
//! (the target already has AVX2 and FMA, or not x86-64), both calls take
//! the same copy and the test says so.
#![cfg(target_arch = "x86_64")]

use autosim::runtime::{Float, Model, StateArray};
use autosim_test_support::Rng;

mod models {
    autosim::model!(file = "examples/models/chain_planar_5.sim");
    autosim::model!(file = "examples/models/chain_spatial_7.sim");
    // In `f32`, at a size that keeps two copies (a function of fewer than
    // 40 operations has one: `emit/model/versions.rs`).
    autosim::model!(
        file = "examples/models/chain_planar_5.sim",
        name = ChainPlanar5F32,
        float = f32
    );
    autosim::model!(file = "examples/models/rolling_disc.sim");
    autosim::model!(file = "examples/models/bicycle.sim");
}

/// What [`both_paths`] found: states compared, and states where some
/// derivative's bits differ between the copies.
#[derive(Default)]
struct Compared {
    states: usize,
    differing: usize,
}

/// `derivatives` at 200 random states near the model's initial state
/// (coordinates ±π, speeds ±3 around it), with the baseline copy forced,
/// then with the copy detection picks: the same result, and derivatives
/// within `sqrt(ε)` (relative to the largest) of each other.
fn both_paths<M: Model>(mut model: M, seed: u64, compared: &mut Compared)
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
        let run = |model: &mut M, fast: bool| {
            autosim::runtime::__private::allow_fast_path(fast);
            let mut dx = M::State::zeros();
            let result = model.derivatives(M::Float::from_f64(0.3), &x, &mut dx);
            (result, dx)
        };
        let (base_result, base_dx) = run(&mut model, false);
        let (fast_result, fast_dx) = run(&mut model, true);
        assert_eq!(base_result, fast_result, "{} at {x:?}", M::NAME);
        let (base, fast) = (base_dx.as_ref(), fast_dx.as_ref());
        let scale = base.iter().fold(1.0, |m: f64, v| m.max(v.to_f64().abs()));
        let tolerance = M::Float::EPSILON.to_f64().sqrt() * scale;
        for (b, f) in base.iter().zip(fast) {
            let (b, f) = (b.to_f64(), f.to_f64());
            let close = (b - f).abs() <= tolerance || (b.is_nan() && f.is_nan());
            assert!(close, "{} at {x:?}: {b} and {f}", M::NAME);
        }
        let bits = |dx: &[M::Float]| dx.iter().map(|v| v.to_f64().to_bits()).collect::<Vec<_>>();
        compared.differing += usize::from(bits(base) != bits(fast));
        compared.states += 1;
    }
}

#[test]
fn baseline_and_v3_copies_agree_and_the_v3_copy_fuses() {
    let two_copies = autosim::runtime::__private::has_v3()
        && !cfg!(all(target_feature = "avx2", target_feature = "fma"))
        && !cfg!(feature = "libm");
    if !autosim::runtime::__private::has_v3() {
        println!("SKIPPED: this processor has no x86-64-v3: both calls take the baseline copy");
    } else if !two_copies {
        println!("SKIPPED: this build keeps one copy, or fuses in neither (libm)");
    }
    let mut compared = Compared::default();
    both_paths(models::chain_planar5::ChainPlanar5::new(), 1, &mut compared);
    both_paths(
        models::chain_spatial7::ChainSpatial7::new(),
        2,
        &mut compared,
    );
    both_paths(
        models::chain_planar5_f32::ChainPlanar5F32::new(),
        3,
        &mut compared,
    );
    both_paths(models::bicycle::Bicycle::new(), 4, &mut compared);
    both_paths(models::rolling_disc::RollingDisc::new(), 5, &mut compared);
    autosim::runtime::__private::allow_fast_path(true);
    assert_eq!(compared.states, 1000);
    if two_copies {
        assert!(compared.differing > 0, "the x86-64-v3 copy does not fuse");
    } else {
        assert_eq!(compared.differing, 0);
    }
}
