//! Events written in the model language (`discrete` and `event` items),
//! checked against known answers: the bouncing ball's analytic bounce
//! times and apex heights, its Zeno limit ending with the typed error, and
//! its resting mode (`examples/models/bouncing_ball.sim`).

use autosim::runtime::integrate::{DopriSettings, DormandPrince, Rk4};
use autosim::runtime::io::Recording;
use autosim::runtime::{IntegrationError, Model, RunError, RunSettings, Stepper, run};

autosim::model!(file = "examples/models/bouncing_ball.sim");

use bouncing_ball::{BouncingBall, Parameters};

const G: f64 = 9.81;
const H0: f64 = 1.0;

/// The analytic instant of bounce `k` (1-based) from rest at `H0`: the
/// first fall takes `t1 = sqrt(2 H0/g)`, the flight after bounce `j` takes
/// `2 e^j t1`.
fn bounce_time(e: f64, k: i32) -> f64 {
    let t1 = (2.0 * H0 / G).sqrt();
    t1 + (1..k).map(|j| 2.0 * e.powi(j) * t1).sum::<f64>()
}

/// The analytic apex after bounce `k`: `e^(2k) H0`, at `e^k t1` after it.
fn apex(e: f64, k: i32) -> (f64, f64) {
    let t1 = (2.0 * H0 / G).sqrt();
    (bounce_time(e, k) + e.powi(k) * t1, e.powi(2 * k) * H0)
}

/// Runs the ball with restitution `e` to `stop`; the events recorded.
fn bounce<S: Stepper<BouncingBall>>(
    stepper: &mut S,
    e: f64,
    v_min: f64,
    step: f64,
    stop: f64,
) -> Result<(Recording<BouncingBall>, BouncingBall), RunError<std::convert::Infallible>> {
    let parameters = Parameters {
        e,
        v_min,
        ..Parameters::default()
    };
    let mut ball = BouncingBall::with_parameters(parameters);
    let mut x = ball.initial_state();
    let settings = RunSettings::new(0.0, stop, step, stop / 10.0);
    let mut recording = Recording::new();
    run(&mut ball, stepper, &mut x, &settings, &mut recording)?;
    Ok((recording, ball))
}

/// The worst error of the first ten bounce times and apex heights (and
/// apex times) against the analytic values.
fn worst_error(recording: &Recording<BouncingBall>, e: f64) -> f64 {
    let named = |name: &str| -> Vec<(f64, f64)> {
        let events = recording.events().iter().filter(|ev| ev.name == name);
        events.map(|ev| (ev.t, ev.before[0])).collect()
    };
    let (bounces, apexes) = (named("bounce"), named("apex"));
    assert!(
        bounces.len() >= 10 && apexes.len() >= 10,
        "{} bounces",
        bounces.len()
    );
    let mut worst: f64 = 0.0;
    for k in 1..=10 {
        let (t, h) = bounces[k as usize - 1];
        worst = worst.max((t - bounce_time(e, k)).abs()).max(h.abs());
        let (ta, ha) = apex(e, k);
        let (t, h) = apexes[k as usize - 1];
        worst = worst.max((t - ta).abs()).max((h - ha).abs());
    }
    worst
}

#[test]
fn bounce_times_and_apex_heights_match_the_analytic_ones() {
    let e = 0.8;
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let (recording, ball) = bounce(&mut dopri, e, 0.01, 1e-3, 3.7).unwrap();
    let worst = worst_error(&recording, e);
    println!("Dormand-Prince at 1e-12: worst error of 10 bounces and apexes {worst:.1e}");
    assert!(worst < 1e-10, "{worst:e}");
    // The reset is the language's `v: -e*v`, exactly.
    let first = &recording.events()[0];
    assert_eq!(first.name, "bounce");
    assert_eq!(first.after[1], -e * first.before[1]);
    assert_eq!(ball.discrete.resting, 0.0);
    // RK4 integrates free fall (a quadratic) exactly and the event is
    // located on the cubic Hermite interpolant, exact for it too: the
    // accuracy its step allows is rounding, at any step.
    for h in [1e-2, 1e-3] {
        let (recording, _) = bounce(&mut Rk4::new(), e, 0.01, h, 3.7).unwrap();
        let worst = worst_error(&recording, e);
        println!("RK4 h = {h}: worst error {worst:.1e}");
        assert!(worst < 1e-11, "h = {h}: {worst:e}");
    }
}

/// A coarse `time_tolerance` locates each bounce to that width (the
/// state moved to the far end of the bracket, inside the floor by up to
/// the speed times the width) and goes on bouncing.
#[test]
fn a_coarse_time_tolerance_locates_bounces_to_its_width() {
    use autosim::runtime::run::EventSettings;
    for tolerance in [1e-3, 1e-5] {
        let mut ball = BouncingBall::with_parameters(Parameters {
            e: 0.8,
            v_min: 0.01,
            ..Parameters::default()
        });
        let mut x = ball.initial_state();
        let events = EventSettings {
            time_tolerance: tolerance,
            ..EventSettings::default()
        };
        let settings = RunSettings::new(0.0, 3.7, 1e-3, 0.37).with_events(events);
        let mut recording = Recording::new();
        let mut dopri = DormandPrince::new(DopriSettings::new(1e-10, 1e-10)).unwrap();
        run(&mut ball, &mut dopri, &mut x, &settings, &mut recording).unwrap();
        let bounces: Vec<f64> = recording
            .events()
            .iter()
            .filter(|e| e.name == "bounce")
            .map(|e| e.t)
            .collect();
        assert!(bounces.len() >= 10, "{tolerance}: {bounces:?}");
        for (k, t) in bounces.iter().take(10).enumerate() {
            let exact = bounce_time(0.8, k as i32 + 1);
            // Each bounce's bracket is at most the tolerance wide, and the
            // instants after it inherit the earlier ones' offsets.
            assert!(
                (t - exact).abs() < 10.0 * tolerance,
                "{tolerance}: bounce {k} at {t}, exact {exact}"
            );
        }
    }
}

#[test]
fn a_ball_without_a_minimum_rebound_speed_ends_with_the_zeno_error() {
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-10, 1e-10)).unwrap();
    // e = 0.9 from 1 m: infinitely many bounces before t1 (1 + 2e/(1-e)).
    let limit = (2.0 * H0 / G).sqrt() * (1.0 + 2.0 * 0.9 / 0.1);
    match bounce(&mut dopri, 0.9, 0.0, 1e-3, 20.0) {
        Err(RunError::Integration(IntegrationError::Zeno {
            t, name, events, ..
        })) => {
            println!("Zeno at {t} s (limit {limit} s) after {events} events of `{name}`");
            assert_eq!(name, "bounce");
            assert!(t < limit && t > 7.0, "{t} against {limit}");
        }
        other => panic!("expected the Zeno error, got {:?}", other.map(|_| ())),
    }
}

#[test]
fn the_resting_mode_ends_the_bounces() {
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-10, 1e-10)).unwrap();
    let (recording, ball) = bounce(&mut dopri, 0.8, 0.5, 1e-3, 6.0).unwrap();
    // Rebounds 0.8^k 4.43 m/s fall below 0.5 m/s after bounce 10.
    let bounces = recording.events().iter().filter(|e| e.name == "bounce");
    assert_eq!(bounces.count(), 10);
    assert_eq!(ball.discrete.resting, 1.0);
    let mut values = [0.0];
    ball.discrete_values(&mut values);
    assert_eq!(values, [1.0]);
    assert_eq!(BouncingBall::DISCRETE_NAMES, ["resting"]);
    assert_eq!(BouncingBall::EVENT_INDICATORS.len(), 2);
}

/// A study's columns set the discrete variables' initial values (a mode
/// to start in) and its `Keep` reads them at the output times, as the
/// events leave them. Checked against free fall: from rest at `H0`,
/// `h(t) = H0 - g t²/2` before the first bounce at `t1 = sqrt(2 H0/g)`;
/// resting from the start, `h = H0` throughout; with `v_min` above the
/// impact speed, the first bounce leaves the ball resting.
#[test]
fn a_study_sets_and_keeps_the_discrete_variables() {
    use autosim::runtime::study::{Cases, Keep, Method, Simulate, Statistic, Study};
    let cases = Cases::new()
        .grid("resting", &[0.0, 1.0])
        .unwrap()
        .grid("v_min", &[0.01, 10.0])
        .unwrap();
    let keep = Keep::new()
        .at(&[0.3], &["h"])
        .statistic("resting", Statistic::Max)
        .history(&["resting"]);
    let settings = RunSettings::new(0.0, 0.6, 1e-3, 0.15);
    let method = Method::DormandPrince {
        rtol: 1e-12,
        atol: 1e-12,
    };
    let task = Simulate::new(settings, method, keep).unwrap();
    let results = Study::new(BouncingBall::new, cases, task)
        .progress(false)
        .run_cases(0..4)
        .unwrap();
    assert_eq!(results.failures(), 0);
    let (h, most, history) = (
        results.field("h@0.3").unwrap(),
        results.field("max:resting").unwrap(),
        results.field("history:resting").unwrap(),
    );
    let falling = H0 - G * 0.3 * 0.3 / 2.0;
    let t1 = (2.0 * H0 / G).sqrt();
    assert!((0.45..0.6).contains(&t1));
    // Cases: (resting 0, v_min 0.01), (0, 10), (1, 0.01), (1, 10).
    assert!((h[0] - falling).abs() < 1e-12 && (h[1] - falling).abs() < 1e-12);
    assert_eq!((h[2], h[3]), (H0, H0));
    // Outputs at 0, 0.15, 0.3, 0.45 (before t1) and 0.6 (after).
    assert_eq!(&history[..5], &[0.0; 5], "bouncing on at 0.01 m/s");
    assert_eq!(&history[5..10], &[0.0, 0.0, 0.0, 0.0, 1.0]);
    assert_eq!(&history[10..], &[1.0; 10]);
    assert_eq!(most, [0.0, 1.0, 1.0, 1.0]);
}

mod spring {
    autosim::model! {
        /// A unit mass on a unit spring, `x = sin t`, that notes when it
        /// first passes `x = 1/2` (at `t = π/6`).
        model Oscillator;
        parameters { k = 1 [N/m], m = 1 [kg] }
        discrete t_half [s] = 0;
        body Mass { translate: 1, q: [x], u: [v], mass: m, inertia: 0, initial_speeds: [1] }
        force spring { on: Mass.cm, vector: -k*x*n1 }
        event half [m] { indicator: x - 0.5, direction: rising, set: { t_half: t } }
    }
}

/// A study locates events as a run does with the same method: on
/// Dormand–Prince's own continuous extension (it used the Hermite cubic
/// of the step's ends, 100 times less accurate, until its stepper
/// passed the extension on). Checked against the exact instant `π/6`
/// and, bit for bit, against the run made by hand.
#[test]
fn a_study_locates_events_on_the_methods_continuous_extension() {
    use autosim::runtime::study::{Cases, Keep, Method, Simulate, Study};
    use spring::oscillator::Oscillator;
    let (rtol, atol) = (1e-10, 1e-12);
    let settings = RunSettings::new(0.0, 1.0, 1e-3, 1.0);
    let keep = Keep::new().at(&[1.0], &["t_half", "x"]);
    let task = Simulate::new(settings, Method::DormandPrince { rtol, atol }, keep).unwrap();
    let results = Study::new(
        Oscillator::new,
        Cases::new().grid("k", &[1.0]).unwrap(),
        task,
    )
    .progress(false)
    .run_cases(0..1)
    .unwrap();
    let (t_half, x) = (results.values()[0], results.values()[1]);
    let exact = std::f64::consts::FRAC_PI_6;
    assert!((t_half - exact).abs() < 1e-10, "{t_half} against {exact}");

    let mut model = Oscillator::new();
    let mut state = model.initial_state();
    let mut dopri = DormandPrince::new(DopriSettings::new(rtol, atol)).unwrap();
    run(
        &mut model,
        &mut dopri,
        &mut state,
        &settings,
        &mut |_, _: &_, _: &_| {},
    )
    .unwrap();
    assert_eq!(t_half.to_bits(), model.discrete.t_half.to_bits());
    assert_eq!(x.to_bits(), state[0].to_bits());
}

mod end_stop {
    autosim::model! {
        /// A unit mass pushed from rest by a constant force `F`, its run
        /// ended when it reaches `x = 1` (at `t = √(2/F)`).
        model Pushed;
        parameters { m = 1 [kg] }
        input F [N] = 2;
        body Mass { translate: 1, q: [x], u: [v], mass: m, inertia: 0 }
        force push { on: Mass, along: n1, magnitude: F }
        event end [m] { indicator: x - 1, direction: rising, stop: true }
    }
}

/// A case a terminal event ends between output times keeps its outputs
/// before the event, NaN after it (the event's state went into the next
/// output's slot), and its mean over the outputs it had; checked against
/// `x = F t²/2`.
#[test]
fn a_terminal_event_leaves_the_outputs_after_it_empty() {
    use autosim::runtime::study::{Cases, Keep, Method, Simulate, Statistic, Study};
    use end_stop::pushed::Pushed;
    // Stops at 0.79 and 1.25 s, between output times.
    let settings = RunSettings::new(0.0, 2.0, 1e-3, 0.5);
    let keep = Keep::new()
        .at(&[1.5], &["x"])
        .history(&["x"])
        .statistic("x", Statistic::Mean)
        .final_state();
    let task = Simulate::new(settings, Method::Rk4, keep).unwrap();
    let results = Study::new(
        Pushed::new,
        Cases::new().grid("F", &[3.2, 1.28]).unwrap(),
        task,
    )
    .progress(false)
    .run_cases(0..2)
    .unwrap();
    assert_eq!(results.failures(), 0);
    let field = |name: &str| results.field(name).unwrap();
    let (at, history, mean, last) = (
        field("x@1.5"),
        field("history:x"),
        field("mean:x"),
        field("final:x"),
    );
    let x = |f: f64, t: f64| f * t * t / 2.0;
    for (case, f) in [3.2f64, 1.28].into_iter().enumerate() {
        let row = &history[case * 5..case * 5 + 5];
        let stop = (2.0 / f).sqrt();
        let kept: Vec<f64> = (0..5)
            .map(|k| 0.5 * k as f64)
            .filter(|t| *t <= stop)
            .collect();
        for (k, t) in kept.iter().enumerate() {
            assert!((row[k] - x(f, *t)).abs() < 1e-12, "case {case}: {row:?}");
        }
        assert!(
            row[kept.len()..].iter().all(|v| v.is_nan()),
            "case {case}: {row:?}"
        );
        assert!(at[case].is_nan(), "x@1.5 after the stop: {}", at[case]);
        let want = kept.iter().map(|t| x(f, *t)).sum::<f64>() / kept.len() as f64;
        assert!(
            (mean[case] - want).abs() < 1e-12,
            "mean {} against {want}",
            mean[case]
        );
        assert!((last[case] - 1.0).abs() < 1e-9, "final x {}", last[case]);
    }
}
