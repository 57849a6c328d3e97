//! A study allocates per chunk, never per case: serially, 10 cases and
//! 1000 cases make the same number of allocations (the results' arrays and
//! the worker's scratch space), for the simulation task with every kind of
//! kept quantity and for a random table; and the same in lockstep (a
//! lanes model, initial states only).

use autosim::runtime::RunSettings;
use autosim::runtime::integrate::AbmOrder;
use autosim::runtime::study::{
    Cases, Distribution, Keep, Method, Parallelism, Simulate, Statistic, Study,
};
use autosim_test_support::alloc_count::{Counting, allocations};

#[global_allocator]
static GLOBAL: Counting = Counting;

autosim::model!(file = "examples/models/pendulum.sim");
use pendulum::Pendulum;

#[test]
fn a_study_allocates_per_chunk_not_per_case() {
    let cases = Cases::new()
        .grid("torque", &[0.0, 0.1])
        .unwrap()
        .random(500, 9, &[("q", Distribution::uniform(-1.0, 1.0))])
        .unwrap();
    let keep = Keep::new()
        .final_state()
        .at(&[0.5], &["height"])
        .statistic("u", Statistic::Rms)
        .history(&["q"]);
    for method in [
        Method::Rk4,
        Method::DormandPrince {
            rtol: 1e-8,
            atol: 1e-10,
        },
    ] {
        let task =
            Simulate::new(RunSettings::new(0.0, 1.0, 0.01, 0.1), method, keep.clone()).unwrap();
        let study = Study::new(Pendulum::new, cases.clone(), task)
            .parallelism(Parallelism::Serial)
            .progress(false);
        let run =
            |n: u64| allocations(|| drop(std::hint::black_box(study.run_cases(0..n).unwrap())));
        run(1); // anything done once
        let (few, many) = (run(10), run(1000));
        assert!(few > 0, "the counter sees the results' arrays");
        assert_eq!(
            few, many,
            "{method:?}: 10 cases made {few} allocations, 1000 made {many}"
        );
    }
}

mod lanes {
    autosim::model!(file = "examples/models/pendulum.sim", lanes = true);
}

#[test]
fn a_study_in_lockstep_allocates_per_chunk_not_per_case() {
    // A lanes model: groups of four in lockstep, with every kind of run
    // (fixed steps, Adams histories, adaptive steps).
    let u = Distribution::uniform(-1.0, 1.0);
    let columns = [("q", u), ("u", u), ("m", Distribution::uniform(1.0, 2.0))];
    let cases = Cases::new().random(1000, 9, &columns).unwrap();
    let keep = Keep::new()
        .final_state()
        .at(&[0.5], &["height"])
        .statistic("u", Statistic::Rms)
        .history(&["q"]);
    let methods = [
        Method::Rk4,
        Method::AdamsBashforthMoulton(AbmOrder::Four),
        Method::DormandPrince {
            rtol: 1e-6,
            atol: 1e-9,
        },
    ];
    for method in methods {
        let settings = RunSettings::new(0.0, 1.0, 0.01, 0.1);
        let task = Simulate::new(settings, method, keep.clone()).unwrap();
        let study = Study::new(lanes::pendulum::Pendulum::new, cases.clone(), task)
            .parallelism(Parallelism::Serial)
            .progress(false);
        let run =
            |n: u64| allocations(|| drop(std::hint::black_box(study.run_cases(0..n).unwrap())));
        run(1);
        let (few, many) = (run(10), run(1000));
        assert!(few > 0, "the counter sees the results' arrays");
        assert_eq!(
            few, many,
            "{method:?}: 10 cases made {few} allocations, 1000 made {many}"
        );
    }
}
