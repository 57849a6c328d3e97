//! The two copies of generated `derivatives` (the target's baseline and
//! x86-64-v3, `autosim::runtime`'s `float/dispatch.rs`) give the same
//! bits: every state derivative and every error, at random states, for
//! models that take each kind of generated code (the mass matrix's LDLᵀ,
//! the articulated-body recursion, constraint solves, `f32`), each big
//! enough to have two (200 operations or more).
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
    // 200 operations has one: `emit/model/versions.rs`).
    autosim::model!(
        file = "examples/models/chain_planar_5.sim",
        name = ChainPlanar5F32,
        float = f32
    );
    autosim::model!(file = "examples/models/rolling_disc.sim");
    autosim::model!(file = "examples/models/bicycle.sim");
}

/// `derivatives` at `states` random states near the model's initial
/// state (coordinates ±π, speeds ±3 around it), with the baseline copy
/// forced, then with the copy detection picks: the bits of each result.
fn both_paths<M: Model>(mut model: M, seed: u64) -> usize
where
    M::State: core::fmt::Debug,
{
    let mut rng = Rng::new(seed);
    let x0 = model.initial_state();
    let mut compared = 0;
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
        let bits = |dx: &M::State| {
            dx.as_ref()
                .iter()
                .map(|v| v.to_f64().to_bits())
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&base_dx), bits(&fast_dx), "{} at {x:?}", M::NAME);
        compared += 1;
    }
    compared
}

#[test]
fn baseline_and_v3_copies_give_the_same_bits() {
    if !autosim::runtime::__private::has_v3() {
        println!("SKIPPED: this processor has no x86-64-v3: both calls take the baseline copy");
    } else if cfg!(all(target_feature = "avx2", target_feature = "fma")) {
        println!("SKIPPED: this build's target has AVX2 and FMA: it keeps one copy");
    }
    let compared = both_paths(models::chain_planar5::ChainPlanar5::new(), 1)
        + both_paths(models::chain_spatial7::ChainSpatial7::new(), 2)
        + both_paths(models::chain_planar5_f32::ChainPlanar5F32::new(), 3)
        + both_paths(models::bicycle::Bicycle::new(), 4)
        + both_paths(models::rolling_disc::RollingDisc::new(), 5);
    autosim::runtime::__private::allow_fast_path(true);
    assert_eq!(compared, 1000);
}
