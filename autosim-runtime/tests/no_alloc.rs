//! Steppers and the run driver never allocate: counted by a global
//! allocator (per thread, so parallel tests do not interfere).

mod common;

use autosim_test_support::alloc_count::{Counting, allocations};

use autosim_runtime::integrate::{
    AbmOrder, AdamsBashforthMoulton, DopriSettings, DormandPrince, Euler, Heun, Rk4, Sdirk3,
    SdirkSettings,
};
use autosim_runtime::{Float, Model, RunSettings, Stepper, run};
use common::{Ball, Oscillator, StiffLinear, VanDerPol};

#[global_allocator]
static GLOBAL: Counting = Counting;

fn run_quietly<M: Model, S: Stepper<M>>(mut model: M, mut stepper: S, step: M::Float) {
    let mut x = model.initial_state();
    let mut sink = M::Float::ZERO;
    let f = M::Float::from_f64;
    let settings = RunSettings::new(f(0.0), f(200.0) * step, step, f(10.0) * step);
    let summary = run(
        &mut model,
        &mut stepper,
        &mut x,
        &settings,
        &mut |t, _: &M::State, _: &M::Outputs| {
            sink = t;
        },
    );
    assert!(summary.is_ok());
}

#[test]
fn steppers_and_driver_do_not_allocate() {
    // The counter sees allocations at all.
    assert!(allocations(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
    // Construction, stepping, the driver and the closure observer: none.
    let n = allocations(|| {
        run_quietly(Oscillator::default(), Euler::new(), 0.01);
        run_quietly(Oscillator::default(), Heun::new(), 0.01);
        run_quietly(Oscillator::default(), Rk4::new(), 0.01);
        run_quietly(
            Oscillator::default(),
            AdamsBashforthMoulton::new(AbmOrder::Four),
            0.01,
        );
        run_quietly(
            Oscillator::default(),
            DormandPrince::new(DopriSettings::new(1e-8, 1e-8)).unwrap(),
            0.01,
        );
        run_quietly(
            StiffLinear::default(),
            Sdirk3::new(SdirkSettings::default()),
            0.01,
        );
        run_quietly(
            VanDerPol::with_mu(100.0),
            Sdirk3::new(SdirkSettings::default()),
            0.01,
        );
    });
    assert_eq!(n, 0, "allocations during stepping");
}

#[test]
fn events_do_not_allocate() {
    // A ball that bounces and comes to rest: located crossings, actions,
    // restarts, with and without dense output.
    let ball = || Ball::new(0.8, 0.5);
    let n = allocations(|| {
        run_quietly(ball(), Rk4::new(), 0.01);
        run_quietly(ball(), AdamsBashforthMoulton::new(AbmOrder::Four), 0.01);
        run_quietly(
            ball(),
            DormandPrince::new(DopriSettings::new(1e-8, 1e-8)).unwrap(),
            0.01,
        );
    });
    assert_eq!(n, 0, "allocations while handling events");
}
