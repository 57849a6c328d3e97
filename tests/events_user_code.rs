//! Events that call user code (`extern fn`): a ball whose floor height and
//! speed-dependent restitution are Rust functions, read by the event's
//! indicator and its reset. Checked against the exact free-fall answer
//! (each flight a parabola, the rebound speed the law's), the law called
//! once per bounce and never by the other event, and a law that returns
//! NaN ending the run with `ModelError::NonFiniteUserResult`.

use autosim::runtime::integrate::{DopriSettings, DormandPrince};
use autosim::runtime::io::Recording;
use autosim::runtime::{IntegrationError, Model, ModelError, RunError, RunSettings, run};

autosim::model! {
    /// A ball bouncing on a floor at the height `floor(t)` with the
    /// restitution `restitution(impact speed)`, both user code.
    model LawBall;
    parameters { g = 9.81 [m/s^2] }
    extern fn restitution(speed [m/s]);
    extern fn floor(t [s]) -> [m];
    body Ball { translate: 3, q: [h], u: [v], mass: 1, inertia: 0, initial: [1] }
    gravity = -g*n3;
    event bounce [m] { indicator: h - floor(t), direction: falling, reset: { v: -restitution(-v)*v } }
    event apex [m/s] { indicator: v, direction: falling }
}

use law_ball::{Externs, LawBall};

const G: f64 = 9.81;
const H0: f64 = 1.0;
const FLOOR: f64 = 0.2;

/// The restitution law: 0.9 for slow impacts, less for fast ones.
fn law(speed: f64) -> f64 {
    0.9 - 0.1 * speed
}

/// The user code: the law (NaN from the impact `nan_at` on, counting
/// calls) and a level floor.
struct Laws {
    calls: usize,
    nan_at: usize,
}

impl Externs for Laws {
    fn restitution(&mut self, speed: f64) -> f64 {
        self.calls += 1;
        match self.calls >= self.nan_at {
            true => f64::NAN,
            false => law(speed),
        }
    }
    fn floor(&mut self, _t: f64) -> f64 {
        FLOOR
    }
}

/// The exact bounces: `(time, rebound speed)` of each, from rest at `H0`
/// over the floor at `FLOOR` (fall `sqrt(2 d/g)`, impact speed `sqrt(2 g
/// d)`, each flight `2 r/g` for rebound speed `r`, the next impact at `r`).
fn exact_bounces(n: usize) -> Vec<(f64, f64)> {
    let d = H0 - FLOOR;
    let (mut t, mut impact) = ((2.0 * d / G).sqrt(), (2.0 * G * d).sqrt());
    let mut out = Vec::new();
    for _ in 0..n {
        let rebound = law(impact) * impact;
        out.push((t, rebound));
        t += 2.0 * rebound / G;
        impact = rebound;
    }
    out
}

/// Runs the ball to `stop` with Dormand-Prince at 1e-12.
fn bounce(
    ball: &mut LawBall<Laws>,
    stop: f64,
) -> Result<Recording<LawBall<Laws>>, RunError<std::convert::Infallible>> {
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-12, 1e-12)).unwrap();
    let mut x = ball.initial_state();
    let settings = RunSettings::new(0.0, stop, 1e-3, stop / 10.0);
    let mut recording = Recording::new();
    run(ball, &mut dopri, &mut x, &settings, &mut recording)?;
    Ok(recording)
}

#[test]
fn user_code_in_an_event_gives_the_exact_bounces() {
    let exact = exact_bounces(11);
    let mut ball = LawBall::new(Laws {
        calls: 0,
        nan_at: usize::MAX,
    });
    // Up to just before bounce 11: ten bounces and ten apexes.
    let recording = bounce(&mut ball, exact[10].0 - 1e-3).unwrap();
    let named = |name: &str| -> Vec<_> {
        let events = recording.events().iter().filter(|ev| ev.name == name);
        events.cloned().collect()
    };
    let (bounces, apexes) = (named("bounce"), named("apex"));
    assert_eq!((bounces.len(), apexes.len()), (10, 10));
    let mut worst: f64 = 0.0;
    for (k, (b, a)) in bounces.iter().zip(&apexes).enumerate() {
        let (t, rebound) = exact[k];
        // At the impact: the time, the floor's height, the law's rebound.
        worst = worst.max((b.t - t).abs()).max((b.before[0] - FLOOR).abs());
        worst = worst.max((b.after[1] - rebound).abs());
        // At the apex: `r/g` after the impact, `r^2/(2 g)` above the floor.
        worst = worst.max((a.t - (t + rebound / G)).abs());
        worst = worst.max((a.before[0] - (FLOOR + rebound * rebound / (2.0 * G))).abs());
    }
    println!("user code in events, Dormand-Prince at 1e-12: worst error {worst:.1e}");
    assert!(worst < 1e-10, "{worst:e}");
    // The law is computed only when the bounce fires (not at the apexes).
    assert_eq!(ball.externs.calls, 10);
}

#[test]
fn a_non_finite_result_of_user_code_in_an_event_stops_the_run() {
    let mut ball = LawBall::new(Laws {
        calls: 0,
        nan_at: 3,
    });
    match bounce(&mut ball, 5.0) {
        Err(RunError::Integration(IntegrationError::Model { t, error })) => {
            assert_eq!(
                error,
                ModelError::NonFiniteUserResult {
                    function: "restitution"
                }
            );
            // At the third impact.
            assert!((t - exact_bounces(3)[2].0).abs() < 1e-9, "{t}");
        }
        other => panic!("expected NonFiniteUserResult, got {:?}", other.map(|_| ())),
    }
}
