//! The work–precision studies: each model's reference final state, and
//! every method swept over its steps (or tolerances) in `f64` and `f32`,
//! one [`Row`] per run.

use std::time::Instant;

use autosim::runtime::Model;

use crate::figure8::Figure8;
use crate::method::{Method, integrate, reference, short};
use crate::report::{print_header, print_row};
use crate::{Chain5, Chain5F32, Sat, SatEvents, SatF32, Small, SmallF32, Stiff, StiffF32};

/// Runs costing more evaluations than this are skipped.
const MAX_EVALUATIONS: f64 = 1e6;
/// A run that ends finite but this far (rad) from the reference diverged.
const DIVERGED: f64 = 1.0;
/// Wall time is the median of this many runs.
pub(crate) const REPEATS: usize = 3;

/// End time of the satellite studies (s).
const T_SAT: f64 = 15.0;
/// End time of chain-spatial-5 (s).
const T_CHAIN: f64 = 5.0;
/// End time of the stiff chain (s).
const T_STIFF: f64 = 1.0;

/// One study: a model in one float type, and how its runs are measured.
struct Study<'a> {
    name: &'static str,
    float: &'static str,
    t_end: f64,
    /// Step counts n (h = t_end / n) of the fixed-step methods.
    steps: &'a [u64],
    /// Tolerances of Dormand–Prince.
    tolerances: &'a [f64],
    /// The reference final state (f64) the error is measured against (for a
    /// small-variable model: the full model's).
    reference: &'a [f64],
    /// The model's own reference, when `reference` is another model's: the
    /// error against it is the integration error alone.
    own_reference: Option<&'a [f64]>,
    /// Error of a final state against a reference.
    measure: fn(&[f64], &[f64]) -> f64,
}

/// What one run gave.
#[derive(Clone, Debug)]
pub(crate) struct Row {
    pub(crate) study: &'static str,
    pub(crate) float: &'static str,
    pub(crate) method: Method,
    /// h (fixed step) or tol (Dormand–Prince).
    pub(crate) setting: f64,
    pub(crate) steps: u64,
    pub(crate) rejected: u64,
    pub(crate) evaluations: u64,
    pub(crate) wall_s: f64,
    /// Error against the study's reference (NaN if the run failed).
    pub(crate) error: f64,
    /// Error against the model's own reference, when the study's reference
    /// is another model's (NaN otherwise, or if the run failed).
    pub(crate) integration_error: f64,
    pub(crate) status: String,
}

/// Every method over every setting of `study`.
fn sweep<M, const N: usize>(
    study: &Study<'_>,
    make: &dyn Fn() -> M,
    x0: [M::Float; N],
    rows: &mut Vec<Row>,
) where
    M: Model<State = [<M as Model>::Float; N]>,
{
    for method in Method::ALL {
        let settings: Vec<(f64, f64)> = if method == Method::Dopri {
            study.tolerances.iter().map(|&tol| (tol, 0.0)).collect()
        } else {
            study
                .steps
                .iter()
                .map(|&n| (study.t_end / n as f64, n as f64))
                .collect()
        };
        for (setting, n) in settings {
            if method != Method::Dopri && n * method.evaluations_per_step(N) > MAX_EVALUATIONS {
                continue;
            }
            let mut walls = Vec::with_capacity(REPEATS);
            let mut last = None;
            for _ in 0..REPEATS {
                let mut model = make();
                let start = Instant::now();
                let out = integrate(&mut model, method, setting, x0, study.t_end);
                walls.push(start.elapsed().as_secs_f64());
                let failed = out.failure.is_some();
                last = Some(out);
                if failed {
                    break;
                }
            }
            let out = last.expect("at least one run");
            walls.sort_by(f64::total_cmp);
            let wall_s = walls[walls.len() / 2];
            let (error, integration_error, status) = match out.failure {
                None => (
                    (study.measure)(&out.x, study.reference),
                    study
                        .own_reference
                        .map_or(f64::NAN, |r| (study.measure)(&out.x, r)),
                    "ok".to_string(),
                ),
                Some(e) => (f64::NAN, f64::NAN, short(&e)),
            };
            let status = if error > DIVERGED {
                "diverged (finite)".to_string()
            } else {
                status
            };
            let row = Row {
                study: study.name,
                float: study.float,
                method,
                setting,
                steps: out.steps,
                rejected: out.rejected,
                evaluations: out.evaluations,
                wall_s,
                error,
                integration_error,
                status,
            };
            print_row(&row);
            rows.push(row);
            // Tighter tolerances only cost more.
            if method == Method::Dopri && out.evaluations as f64 > MAX_EVALUATIONS {
                break;
            }
        }
    }
}

/// Largest |x_i - r_i| over the bus attitude q4, q5, q6.
fn attitude_error(x: &[f64], r: &[f64]) -> f64 {
    (3..6).map(|i| (x[i] - r[i]).abs()).fold(0.0, f64::max)
}

/// Largest |x_i - r_i| over the coordinates (the first half of the state).
fn coordinate_error(x: &[f64], r: &[f64]) -> f64 {
    (0..r.len() / 2)
        .map(|i| (x[i] - r[i]).abs())
        .fold(0.0, f64::max)
}

/// One study of a model generated in `f64` and again in `f32` (`study`
/// takes the float's name), from the same initial state.
fn sweep_in_both_floats<'a, M64, M32, const N: usize>(
    study: &dyn Fn(&'static str) -> Study<'a>,
    (f64_model, f32_model): (impl Fn() -> M64, impl Fn() -> M32),
    x0: [f64; N],
    rows: &mut Vec<Row>,
) where
    M64: Model<Float = f64, State = [f64; N]>,
    M32: Model<Float = f32, State = [f32; N]>,
{
    sweep(&study("f64"), &f64_model, x0, rows);
    sweep(&study("f32"), &f32_model, to_f32(x0), rows);
}

fn to_f32<const N: usize>(x: [f64; N]) -> [f32; N] {
    x.map(|v| v as f32)
}

/// The initial state of chain-spatial-5 (released at rest).
fn chain5_x0() -> [f64; 10] {
    let mut x = [0.0; 10];
    x[..5].copy_from_slice(&[0.6, -0.5, 0.4, 0.7, -0.3]);
    x
}

/// The initial state of the stiff chain: the first joint deflected.
fn stiff_x0() -> [f64; 6] {
    [0.1, 0.0, 0.0, 0.0, 0.0, 0.0]
}

/// The initial state of the satellite (thrusters off; the state is the same
/// with them on).
fn sat_x0() -> <Sat as Model>::State {
    Sat::new(Figure8::commands_only()).initial_state()
}

/// The satellite with its thrusters as events, all pairs off (the
/// discrete variables' initial values).
fn sat_events() -> SatEvents {
    SatEvents::new(Figure8::commands_only())
}

/// The initial state of the small-variable satellite.
fn small_x0() -> <Small as Model>::State {
    Small::new(Figure8::commands_only()).initial_state()
}

/// The reference final states of the studies, and what they are worth.
pub(crate) struct References {
    /// The satellite, thrusters off.
    sat: Vec<f64>,
    /// The small-variable satellite, thrusters off.
    small: Vec<f64>,
    /// chain-spatial-5.
    chain: Vec<f64>,
    /// The stiff chain.
    stiff: Vec<f64>,
    /// The satellite with the thrusters on (RK4 at 10 µs).
    thrust: Vec<f64>,
    /// The satellite with the thrusters as events.
    events: Vec<f64>,
    /// Each reference's own error (against a second, tighter run).
    pub(crate) notes: Vec<(&'static str, f64)>,
    /// The small-variable satellite against the full model at 15 s,
    /// thrusters off (rad).
    pub(crate) small_model_error: f64,
}

/// Computes (and prints) the references of every study and their own errors.
pub(crate) fn references() -> References {
    let quiet = Figure8::commands_only;
    let (sat_x0, small_x0) = (sat_x0(), small_x0());
    println!("References (Dormand-Prince, rtol = atol = 1e-12, f64; own error against 1e-13):");
    let mut reference_notes = Vec::new();
    let mut refs =
        |label: &'static str, a: Vec<f64>, b: Vec<f64>, measure: fn(&[f64], &[f64]) -> f64| {
            let e = measure(&a, &b);
            println!("  {label:<22} {e:.1e}");
            reference_notes.push((label, e));
            a
        };
    let sat_ref = refs(
        "satellite",
        reference(Sat::new(quiet()), sat_x0, T_SAT, 1e-12),
        reference(Sat::new(quiet()), sat_x0, T_SAT, 1e-13),
        attitude_error,
    );
    let small_ref = refs(
        "satellite-small",
        reference(Small::new(quiet()), small_x0, T_SAT, 1e-12),
        reference(Small::new(quiet()), small_x0, T_SAT, 1e-13),
        attitude_error,
    );
    let chain_ref = refs(
        "chain-spatial-5",
        reference(Chain5::new(), chain5_x0(), T_CHAIN, 1e-12),
        reference(Chain5::new(), chain5_x0(), T_CHAIN, 1e-13),
        coordinate_error,
    );
    let stiff_ref = refs(
        "chain-spatial-3-stiff",
        reference(Stiff::new(), stiff_x0(), T_STIFF, 1e-12),
        reference(Stiff::new(), stiff_x0(), T_STIFF, 1e-13),
        coordinate_error,
    );
    // With the thrusters on: RK4 at 10 µs (and 20 µs for its own error).
    let thrust_ref = {
        let run_rk4 = |n: u64| {
            let mut m = Sat::new(Figure8::new());
            integrate(&mut m, Method::Rk4, T_SAT / n as f64, sat_x0, T_SAT).x
        };
        refs(
            "satellite-thrusters",
            run_rk4(1_500_000),
            run_rk4(750_000),
            attitude_error,
        )
    };
    let events_x0 = sat_events().initial_state();
    let events_ref = refs(
        "satellite-events",
        reference(sat_events(), events_x0, T_SAT, 1e-12),
        reference(sat_events(), events_x0, T_SAT, 1e-13),
        attitude_error,
    );
    let small_model_error = attitude_error(&small_ref, &sat_ref);
    println!("  small-variable model vs full at 15 s (thrusters off): {small_model_error:.2e} rad");
    References {
        sat: sat_ref,
        small: small_ref,
        chain: chain_ref,
        stiff: stiff_ref,
        thrust: thrust_ref,
        events: events_ref,
        notes: reference_notes,
        small_model_error,
    }
}

/// Every study: each method over its settings, in `f64` and `f32` (the
/// table printed as it goes).
pub(crate) fn sweeps(refs: &References) -> Vec<Row> {
    let quiet = Figure8::commands_only;
    let (sat_x0, small_x0) = (sat_x0(), small_x0());
    let sat_steps: &[u64] = &[
        150, 300, 750, 1_500, 3_000, 7_500, 15_000, 30_000, 75_000, 150_000, 300_000, 750_000,
        1_500_000,
    ];
    let chain_steps: &[u64] = &[
        50, 100, 250, 500, 1_000, 2_500, 5_000, 10_000, 25_000, 50_000, 100_000, 250_000, 500_000,
    ];
    let stiff_steps: &[u64] = &[
        10, 20, 50, 100, 200, 500, 1_000, 2_000, 5_000, 10_000, 20_000, 50_000, 100_000, 200_000,
        500_000,
    ];
    let tolerances: &[f64] = &[1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11];
    let mut rows = Vec::new();
    println!();
    print_header();

    let study = |name, float, t_end, steps, reference, own_reference, measure| Study {
        name,
        float,
        t_end,
        steps,
        tolerances,
        reference,
        own_reference,
        measure,
    };
    // Both satellite models are measured against the full model's reference.
    let on_satellite_reference = |name, own_reference, float| {
        study(
            name,
            float,
            T_SAT,
            sat_steps,
            &refs.sat[..],
            own_reference,
            attitude_error as fn(&[f64], &[f64]) -> f64,
        )
    };
    let sat = |float| on_satellite_reference("satellite", None, float);
    let models = (|| Sat::new(quiet()), || SatF32::new(quiet()));
    sweep_in_both_floats(&sat, models, sat_x0, &mut rows);
    // The small model against the full model's reference: what a user gets.
    let small = |float| on_satellite_reference("satellite-small", Some(&refs.small[..]), float);
    let models = (|| Small::new(quiet()), || SmallF32::new(quiet()));
    sweep_in_both_floats(&small, models, small_x0, &mut rows);
    let thrust = study(
        "satellite-thrusters",
        "f64",
        T_SAT,
        sat_steps,
        &refs.thrust[..],
        None,
        attitude_error,
    );
    sweep(&thrust, &|| Sat::new(Figure8::new()), sat_x0, &mut rows);
    let events = study(
        "satellite-events",
        "f64",
        T_SAT,
        sat_steps,
        &refs.events[..],
        None,
        attitude_error,
    );
    sweep(
        &events,
        &sat_events,
        sat_events().initial_state(),
        &mut rows,
    );
    // The chains are measured on their coordinates, each against its own
    // reference.
    let on_coordinates = |(name, t_end, steps, reference), float| {
        let measure = coordinate_error as fn(&[f64], &[f64]) -> f64;
        study(name, float, t_end, steps, reference, None, measure)
    };
    let chain = ("chain-spatial-5", T_CHAIN, chain_steps, &refs.chain[..]);
    let (models, x0) = ((Chain5::new, Chain5F32::new), chain5_x0());
    sweep_in_both_floats(&|f| on_coordinates(chain, f), models, x0, &mut rows);
    let stiff = (
        "chain-spatial-3-stiff",
        T_STIFF,
        stiff_steps,
        &refs.stiff[..],
    );
    let (models, x0) = ((Stiff::new, StiffF32::new), stiff_x0());
    sweep_in_both_floats(&|f| on_coordinates(stiff, f), models, x0, &mut rows);
    rows
}

/// With the thrusters on, how far apart RK4 runs at h <= 10 ms land (printed).
pub(crate) fn thruster_chatter(rows: &[Row]) -> f64 {
    let chatter = rows
        .iter()
        .filter(|r| r.study == "satellite-thrusters" && r.method == Method::Rk4)
        .filter(|r| r.status == "ok" && r.setting <= 0.01 * (1.0 + 1e-9))
        .map(|r| r.error)
        .fold(0.0, f64::max);
    println!();
    println!(
        "Thrusters on: RK4 runs at h <= 10 ms end up to {chatter:.1e} rad from RK4 at h = 10 us"
    );
    chatter
}
