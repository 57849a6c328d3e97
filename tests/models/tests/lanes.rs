//! Many states per call give the same bits as one call per state:
//! `Model::derivatives_batch` (generated models: `derivatives_lanes`, four
//! states at a time) against `derivatives` at each state, and
//! `Model::derivatives_each` (a model per state, each with its own
//! parameters and inputs, as a study's cases in lockstep) against each
//! model's `derivatives`, every
//! derivative's bits and every error, at random states (with states that
//! make a derivative or a user result non-finite, and state counts that
//! leave a partial group), on each instruction-set copy, for models
//! that take each kind of generated code: sines in pairs (the chains),
//! the articulated-body recursion, the mass matrix's LDLᵀ and constraint
//! solves (the four-bar, the rolling disc), the common block
//! (chain-spatial-20), user functions and subroutines (the satellite),
//! inputs and discrete variables, and an `f32` model (the default batch).

use autosim::runtime::__private::{Path, limit_path};
use autosim::runtime::batch::LANES;
use autosim::runtime::{Float, Lanes, Model, ModelError, StateArray};
use autosim_models_check::lanes as models;
use autosim_test_support::Rng;

/// What `derivatives` gives at `x`: the error, or the derivatives' bits.
type Outcome = Result<Vec<u64>, ModelError>;

fn bits<F: Float>(dx: &[F]) -> Vec<u64> {
    dx.iter().map(|v| v.to_f64().to_bits()).collect()
}

/// `count` states near the initial state (coordinates and speeds moved
/// by up to ±3); every 37th has a NaN entry and every 41st a huge one, so
/// that some groups fail and are evaluated again state by state.
fn states<M: Model>(model: &M, rng: &mut Rng, count: usize) -> Vec<M::State> {
    let x0 = model.initial_state();
    (0..count)
        .map(|k| {
            let mut x = x0;
            for v in x.as_mut() {
                *v += M::Float::from_f64(rng.uniform(-3.0, 3.0));
            }
            let n = x.as_ref().len();
            if k % 37 == 5 {
                x.as_mut()[k % n] = M::Float::from_f64(f64::NAN);
            }
            if k % 41 == 7 {
                x.as_mut()[(k + 1) % n] = M::Float::from_f64(1e300);
            }
            x
        })
        .collect()
}

/// The outcomes of a batch: each state's error or derivatives' bits.
fn outcomes<M: Model>(status: &[Result<(), ModelError>], dx: &[M::State]) -> Vec<Outcome> {
    status
        .iter()
        .zip(dx)
        .map(|(s, d)| s.map(|()| bits(d.as_ref())))
        .collect()
}

/// `make()` with every parameter and input scaled by a random factor in
/// [0.8, 1.2].
fn varied<M: Model>(make: &impl Fn() -> M, rng: &mut Rng) -> M {
    let mut model = make();
    let mut vary = |values: &mut [M::Float]| {
        for v in values {
            *v = M::Float::from_f64(v.to_f64() * rng.uniform(0.8, 1.2));
        }
    };
    let mut p = vec![M::Float::ZERO; M::PARAMETER_NAMES.len()];
    model.parameter_values(&mut p);
    vary(&mut p);
    model.set_parameter_values(&p);
    let mut u = vec![M::Float::ZERO; M::INPUT_NAMES.len()];
    model.input_values(&mut u);
    vary(&mut u);
    model.set_input_values(&u);
    model
}

/// Compares the batch with single calls on `make()` at `count` states, and
/// `derivatives_each` with single calls on `count` models of varied
/// parameters and inputs, with calls limited to the copy `path` (or the
/// most capable the processor has, if less); returns (states, errors)
/// compared.
fn compare<M: Model>(make: &impl Fn() -> M, seed: u64, count: usize, path: Path) -> (usize, usize) {
    limit_path(path);
    let mut rng = Rng::new(seed);
    let mut model = make();
    let xs = states(&model, &mut rng, count);
    let t = M::Float::from_f64(0.3);
    let one = |model: &mut M, x: &M::State| {
        let mut dx = M::State::zeros();
        model.derivatives(t, x, &mut dx).map(|()| bits(dx.as_ref()))
    };
    let single: Vec<Outcome> = xs.iter().map(|x| one(&mut model, x)).collect();
    let mut dx = vec![M::State::zeros(); count];
    let mut status = vec![Ok(()); count];
    model.derivatives_batch(t, &xs, &mut dx, &mut status);
    for (k, (one, many)) in single.iter().zip(outcomes::<M>(&status, &dx)).enumerate() {
        assert_eq!(*one, many, "{} state {k} ({:?})", M::NAME, xs[k].as_ref());
    }
    let mut models: Vec<M> = (0..count).map(|_| varied(make, &mut rng)).collect();
    // Each model at its own time too.
    let times: Vec<M::Float> = (0..count)
        .map(|k| M::Float::from_f64(0.3 + 0.01 * k as f64))
        .collect();
    let alone: Vec<Outcome> = (models.iter_mut().zip(&times).zip(&xs))
        .map(|((m, t), x)| {
            let mut dx = M::State::zeros();
            m.derivatives(*t, x, &mut dx).map(|()| bits(dx.as_ref()))
        })
        .collect();
    // With every group's values, with the first group's only (the others
    // one call per model), with none.
    let mut values = vec![Lanes::ZERO; M::LANE_VALUES * (count / LANES)];
    M::lane_values(&models, &mut values);
    let first = values.len().min(M::LANE_VALUES);
    for values in [&values[..], &values[..first], &[]] {
        M::derivatives_each(&mut models, values, &times, &xs, &mut dx, &mut status);
        for (k, (one, each)) in alone.iter().zip(outcomes::<M>(&status, &dx)).enumerate() {
            let at = xs[k].as_ref();
            assert_eq!(*one, each, "{} model and state {k} ({at:?})", M::NAME);
        }
    }
    // Each varied model computes other derivatives than the batch's one
    // (where both are finite; the satellite's user code gives NaN at most
    // of its states).
    let both = |(a, b): (&Outcome, &Outcome)| a.is_ok() && b.is_ok();
    let comparable = single.iter().zip(&alone).filter(|p| both(*p)).count();
    let differ = single
        .iter()
        .zip(&alone)
        .filter(|p| both(*p) && p.0 != p.1)
        .count();
    assert!(
        differ == comparable || M::PARAMETER_NAMES.is_empty(),
        "{}: {differ} of {comparable} differ",
        M::NAME
    );
    let errors = single.iter().filter(|o| o.is_err()).count();
    (count, errors)
}

/// [`compare`] on every copy and at two counts (a multiple of four and
/// not); returns the states and errors compared.
fn every_copy<M: Model>(make: impl Fn() -> M, seed: u64) -> (usize, usize) {
    let mut total = (0, 0);
    let cases = [
        (Path::Baseline, 200),
        (Path::V3, 203),
        (Path::V4, 203),
        (Path::V4, 3),
    ];
    for (path, count) in cases {
        let (n, e) = compare(&make, seed, count, path);
        total = (total.0 + n, total.1 + e);
    }
    limit_path(Path::V4);
    total
}

/// User code: a thruster on a dead band, NaN for a large error (so that
/// some states fail with `NonFiniteUserResult`), fixed commands.
struct Thrusters;

impl models::satellite::Externs for Thrusters {
    fn thrust(&mut self, _t: f64, axis: f64, error: f64) -> f64 {
        match error {
            e if e.abs() > 2.5 => f64::NAN,
            e if e > 0.0025 => -axis,
            e if e < -0.0025 => axis,
            _ => 0.0,
        }
    }
    fn cmd(&mut self, t: f64) -> [f64; 2] {
        [0.8 + t, -0.45]
    }
}

/// Runs `f` on a thread with the stack `std` gives a spawned thread by
/// default (2 MiB): in an unoptimized (test) build every temporary of a
/// lanes function has its own stack slot, and the biggest model here
/// (chain-spatial-20, about 350 KB then) must still fit where user code
/// calls it, as a test thread or a study's worker.
fn default_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(f)
        .expect("a thread")
        .join()
        .expect("the test passes");
}

#[test]
fn batch_gives_the_bits_and_errors_of_single_calls() {
    default_stack(batch_matches_single_calls);
}

fn batch_matches_single_calls() {
    let runs = [
        every_copy(models::chain_spatial7::ChainSpatial7::new, 1),
        every_copy(models::chain_spatial10::ChainSpatial10::new, 2),
        every_copy(models::chain_spatial20::ChainSpatial20::new, 3),
        every_copy(models::chain_planar10::ChainPlanar10::new, 4),
        every_copy(models::four_bar::FourBar::new, 5),
        every_copy(models::rolling_disc::RollingDisc::new, 6),
        every_copy(models::bicycle::Bicycle::new, 7),
        every_copy(|| models::satellite::Satellite::new(Thrusters), 8),
        every_copy(models::quarter_car_bump_stop::QuarterCarBumpStop::new, 9),
        every_copy(models::chain_planar2_f32::ChainPlanar2F32::new, 10),
        every_copy(models::driven_pendulum::DrivenPendulum::new, 11),
    ];
    for (k, (states, errors)) in runs.iter().enumerate() {
        assert_eq!(*states, 609, "model #{k}");
        // Every model meets the NaN and huge states: the error path is
        // compared too, not only the finite one.
        assert!(*errors >= 10, "model #{k}: only {errors} errors compared");
    }
}

#[test]
fn eight_lanes_give_the_bits_of_single_calls() {
    default_stack(eight_lanes);
}

fn eight_lanes() {
    let mut model = models::chain_spatial10::ChainSpatial10::new();
    let mut rng = Rng::new(12);
    let xs = states(&model, &mut rng, 8);
    let x8: [autosim::runtime::Lanes<8>; 20] =
        core::array::from_fn(|i| autosim::runtime::Lanes(core::array::from_fn(|k| xs[k][i])));
    let mut d8 = [autosim::runtime::Lanes::<8>::ZERO; 20];
    // States 5 and 7 are the NaN and the huge one: the call fails.
    assert!(model.derivatives_lanes(0.1, &x8, &mut d8).is_err());
    // Finite states only: Ok, and the same bits lane by lane.
    let finite: Vec<[f64; 20]> = xs
        .iter()
        .map(|x| x.map(|v| if v.is_nan() { 0.0 } else { v.clamp(-3.0, 3.0) }))
        .collect();
    let x8: [autosim::runtime::Lanes<8>; 20] =
        core::array::from_fn(|i| autosim::runtime::Lanes(core::array::from_fn(|k| finite[k][i])));
    assert_eq!(model.derivatives_lanes(0.1, &x8, &mut d8), Ok(()));
    for (k, x) in finite.iter().enumerate() {
        let mut dx = [0.0; 20];
        model.derivatives(0.1, x, &mut dx).expect("finite state");
        let lane: Vec<u64> = d8.iter().map(|d| d.0[k].to_bits()).collect();
        assert_eq!(lane, bits(&dx), "state {k}");
    }
}
