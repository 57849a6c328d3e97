//! The paper's slew with its thruster logic in the derivatives (a stateful
//! `extern fn`, called at every evaluation) against the same logic run as
//! a 100 Hz sampled controller (`run_sampled`): the sampled form gives the
//! same attitude with RK4 at 1 ms and with Dormand–Prince at 1e-9; the
//! in-derivative form does not.

use autosim::runtime::integrate::{DormandPrince, Rk4};

#[macro_use]
#[allow(unused_macros, dead_code)]
#[path = "../examples/common/figure8.rs"]
mod figure8;
#[path = "../examples/common/slew_forms.rs"]
mod slew_forms;
use slew_forms::{STOP, distance, in_derivatives, sampled};

#[test]
fn a_sampled_controller_does_not_depend_on_the_integrator() {
    let (rk4, _) = sampled(Rk4::new(), 1e-3);
    let (dopri, _) = sampled(DormandPrince::with_tolerances(1e-9, 1e-9).unwrap(), 1e-3);
    let sampled_diff = distance(rk4, dopri);
    let (rk4_in, _) = in_derivatives(Rk4::new(), 1e-3);
    let (dopri_in, _) = in_derivatives(DormandPrince::with_tolerances(1e-9, 1e-9).unwrap(), 1e-3);
    let in_diff = distance(rk4_in, dopri_in);
    eprintln!(
        "attitude at {STOP} s, RK4 1 ms vs Dormand-Prince 1e-9: sampled {sampled_diff:.2e} rad, in the derivatives {in_diff:.2e} rad"
    );
    assert!(sampled_diff < 1e-6, "sampled: {rk4:?} vs {dopri:?}");
    assert!(
        in_diff > 10.0 * sampled_diff,
        "the in-derivative form depends on the integrator"
    );
}

mod clock {
    autosim::model! {
        /// A unit mass pushed by its input: `v = t` under a unit push.
        model Clock32;
        settings { float: f32 }
        input push [N];
        body B { translate: 1, q: [x], u: [v], mass: 1, inertia: 0 }
        force f { on: B, along: n1, magnitude: push }
    }
}

/// An `f32` run sampled at 1 kHz far past `2^17` samples keeps
/// integrating, one RK4 step a sample (it stopped after 131 s and still
/// ended `Ok`: the allowance for rounding had grown to a whole step).
#[test]
fn an_f32_sampled_run_integrates_to_its_end() {
    use autosim::runtime::{RunSettings, run_sampled};
    let (period, stop) = (1e-3f32, 200.0f32);
    let mut model = clock::clock32::Clock32::new();
    let mut x = [0.0f32; 2];
    let mut samples = 0u32;
    let mut controller = |_t: f32, _x: &[f32; 2], _y: &[f32; 0], inputs: &mut [f32]| {
        samples += 1;
        inputs[0] = 1.0;
    };
    let settings = RunSettings::new(0.0, stop, period, stop);
    let summary = run_sampled(
        &mut model,
        &mut Rk4::new(),
        &mut x,
        &settings,
        period,
        &mut controller,
        &mut |_: f32, _: &[f32; 2], _: &[f32; 0]| {},
    )
    .expect("runs");
    // 200 000 additions of 1e-3 in `f32` are 0.2 % off; stopped, 35 %.
    assert!(
        (x[1] - stop).abs() < 1e-2 * stop,
        "v = {} at t = {stop}",
        x[1]
    );
    assert_eq!(summary.steps, 200_000);
    assert_eq!(samples, 200_001);
}

mod switched {
    autosim::model! {
        /// A body at rest and a level set from outside; an event notes
        /// when the level rises through one half.
        model Level;
        input level [m];
        discrete high = 0;
        body B { translate: 1, q: [x], u: [v], mass: 1, inertia: 0 }
        event rise [m] { indicator: level - 0.5, direction: rising, set: { high: 1 } }
    }
}

/// An input that a sample changes fires, at that sample instant, the
/// event its indicator's jump crosses (the driver keeps the indicators'
/// signs across the sample).
#[test]
fn a_sampled_input_fires_the_event_it_crosses() {
    use autosim::runtime::io::Recording;
    use autosim::runtime::{RunSettings, run_sampled};
    let mut model = switched::level::Level::new();
    let mut x = [0.0; 2];
    let mut controller = |t: f64, _: &[f64; 2], _: &[f64; 0], inputs: &mut [f64]| {
        inputs[0] = if t >= 0.3 { 1.0 } else { 0.0 };
    };
    let mut recording = Recording::new();
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.1);
    run_sampled(
        &mut model,
        &mut Rk4::new(),
        &mut x,
        &settings,
        0.1,
        &mut controller,
        &mut recording,
    )
    .expect("runs");
    let events = recording.events();
    assert_eq!(events.len(), 1, "{events:?}");
    assert!((events[0].t - 0.3).abs() < 1e-12, "at {}", events[0].t);
    assert_eq!(model.discrete.high, 1.0);
}

mod pushed {
    autosim::model! {
        /// A unit mass on a unit spring, pushed by its input.
        model Pushed;
        input push [N];
        body B { translate: 1, q: [x], u: [v], mass: 1, inertia: 0 }
        force f { on: B, along: n1, magnitude: push - x as [N] }
    }
}

/// `run_sampled_at` reports at the times it is given (repeated ones too)
/// and samples as `run_sampled` does: on the times `run_sampled` reports
/// at, the same bits; on other times, the same samples and the same end.
#[test]
fn sampled_runs_report_at_given_times() {
    use autosim::runtime::io::Recording;
    use autosim::runtime::{RunSettings, run_sampled, run_sampled_at};
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.1);
    let run = |times: Option<&[f64]>| {
        let mut model = pushed::pushed::Pushed::new();
        let mut x = [0.2, 0.0];
        let mut samples = Vec::new();
        let mut controller = |t: f64, x: &[f64; 2], _: &[f64; 0], inputs: &mut [f64]| {
            samples.push(t);
            inputs[0] = -3.0 * x[0] - 2.0 * x[1];
        };
        let mut recording = Recording::new();
        let (stepper, period) = (&mut Rk4::new(), 0.1);
        match times {
            None => run_sampled(
                &mut model,
                stepper,
                &mut x,
                &settings,
                period,
                &mut controller,
                &mut recording,
            ),
            Some(times) => run_sampled_at(
                &mut model,
                stepper,
                &mut x,
                &settings,
                times,
                period,
                &mut controller,
                &mut recording,
            ),
        }
        .expect("runs");
        (recording, samples, x)
    };
    let (every, samples, end) = run(None);
    let times: Vec<f64> = every.time().to_vec();
    assert_eq!(times.len(), 11);
    let (listed, listed_samples, listed_end) = run(Some(&times));
    assert_eq!(listed.time(), &times[..]);
    let values = |r: &Recording<pushed::pushed::Pushed>| -> Vec<Vec<f64>> {
        r.columns().iter().map(|c| c.values.clone()).collect()
    };
    assert_eq!(values(&listed), values(&every));
    assert_eq!((listed_samples, listed_end), (samples.clone(), end));

    let odd = [0.05, 0.25, 0.25, 0.7];
    let (sparse, sparse_samples, sparse_end) = run(Some(&odd));
    // A fixed step's grid time stands for the time within its rounding
    // (as in every run: `7 · 0.1` is `0.7000000000000001`).
    let reported = sparse.time();
    assert_eq!(reported.len(), odd.len());
    assert!(
        reported.iter().zip(odd).all(|(a, b)| (a - b).abs() < 1e-15),
        "{reported:?}"
    );
    assert_eq!(sparse_samples, samples);
    assert!(
        (sparse_end[0] - end[0]).abs() < 1e-9 && (sparse_end[1] - end[1]).abs() < 1e-9,
        "{sparse_end:?} vs {end:?}"
    );
    let bad = run_sampled_at(
        &mut pushed::pushed::Pushed::new(),
        &mut Rk4::new(),
        &mut [0.0; 2],
        &settings,
        &[0.5, 0.4],
        0.1,
        &mut |_: f64, _: &[f64; 2], _: &[f64; 0], _: &mut [f64]| {},
        &mut Recording::new(),
    );
    assert!(bad.is_err(), "times out of order are refused");
}
