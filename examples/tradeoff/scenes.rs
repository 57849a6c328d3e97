//! The compile-time scene options on the satellite: each scene flies the
//! paper's slew (Figure 8 user code, thrusters on and off, RK4 at 1 ms), is
//! timed, and is compared with the full `f64` model.

use std::fmt::Write as _;
use std::time::Instant;

use autosim::runtime::integrate::Rk4;
use autosim::runtime::{Float, Model, OpCount, Stepper};

use crate::figure8::Figure8;
use crate::{Sat, SatF32, Small, SmallF32, scene};

/// The scene table and the size of the motion it compares.
pub(crate) struct SceneTable {
    /// The table in Markdown (also printed).
    pub(crate) markdown: String,
    /// Largest |attitude| of the full model over the slew, thrusters on (rad).
    pub(crate) peak_on: f64,
    /// The same, thrusters off.
    pub(crate) peak_off: f64,
}

/// Flies every scene, times it and compares it with the full model; prints
/// the table.
pub(crate) fn compare() -> SceneTable {
    println!();
    println!("Scene options on the satellite (slew, RK4 h = 1 ms, 15 s):");
    let mut scenes = fly_all();
    // Timing passes interleaved over the scenes, keeping each scene's best:
    // load from other processes only ever adds time.
    for _ in 0..7 {
        for s in &mut scenes {
            s.ns_per_call = s.ns_per_call.min((s.timer)());
        }
    }
    let largest_difference = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        a.iter()
            .zip(b)
            .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
            .fold(0.0, f64::max)
    };
    let full_attitude = scenes[0].attitude.clone();
    let full_quiet = scenes[0].attitude_quiet.clone();
    for s in &mut scenes {
        s.diff = largest_difference(&s.attitude, &full_attitude);
        s.diff_quiet = largest_difference(&s.attitude_quiet, &full_quiet);
    }
    let peak = |attitude: &[[f64; 3]]| {
        attitude
            .iter()
            .flat_map(|a| a.iter().map(|v| v.abs()))
            .fold(0.0, f64::max)
    };
    let (peak_on, peak_off) = (peak(&full_attitude), peak(&full_quiet));
    let mut scene_table = String::new();
    let _ = writeln!(
        scene_table,
        "| scene | float | states | `derivatives` ops (+ × ÷ fn) | `outputs` ops | ns / call | max \\|Δ attitude\\| vs full, thrusters on [rad] | thrusters off [rad] |"
    );
    let _ = writeln!(
        scene_table,
        "| --- | --- | ---: | --- | ---: | ---: | ---: | ---: |"
    );
    for s in &scenes {
        let d = s.derivative_ops;
        let diff = |v: f64| {
            if v == 0.0 {
                "0".to_string()
            } else {
                format!("{v:.1e}")
            }
        };
        let _ = writeln!(
            scene_table,
            "| `{}` | {} | {} | {} ({} + {} + {} + {}) | {} | {:.0} | {} | {} |",
            s.label,
            s.float,
            s.states,
            d.total(),
            d.adds,
            d.muls,
            d.divs,
            d.funcs,
            s.output_ops.total(),
            s.ns_per_call,
            diff(s.diff),
            diff(s.diff_quiet),
        );
    }
    print!("{scene_table}");
    println!(
        "(largest |attitude| of the full model over the slew: {peak_on:.2e} rad with the thrusters, {peak_off:.2e} rad without)"
    );
    SceneTable {
        markdown: scene_table,
        peak_on,
        peak_off,
    }
}

/// The satellite compiled with each scene's options, flown through the slew.
fn fly_all() -> Vec<SceneRun> {
    let mut scenes = vec![
        fly_scene::<_, 20>(
            "full (satellite.sim)",
            Sat::new,
            Sat::DERIVATIVE_OPS,
            Sat::OUTPUT_OPS,
        ),
        fly_scene::<_, 20>(
            "small = [B, E, F]",
            Small::new,
            Small::DERIVATIVE_OPS,
            Small::OUTPUT_OPS,
        ),
    ];
    {
        use scene::*;
        type Bus = small_bus::SmallBus<Figure8>;
        type Boom = small_boom::SmallBoom<Figure8>;
        type Angles = small_angles::SmallAngles<Figure8>;
        type T1 = small_threshold1::SmallThreshold1<Figure8>;
        type T3 = small_threshold3::SmallThreshold3<Figure8>;
        type Att = attitude::Attitude<Figure8>;
        type LockAll = rigid_boom_all::RigidBoomAll<Figure8>;
        type Lock = rigid_boom::RigidBoom<Figure8>;
        scenes.push(fly_scene::<_, 20>(
            "small = [B]",
            Bus::new,
            Bus::DERIVATIVE_OPS,
            Bus::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 20>(
            "small = [E, F]",
            Boom::new,
            Boom::DERIVATIVE_OPS,
            Boom::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 20>(
            "small = [q4, q5, q6, q9, q10]",
            Angles::new,
            Angles::DERIVATIVE_OPS,
            Angles::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 20>(
            "small = [B, E, F], threshold = 1",
            T1::new,
            T1::DERIVATIVE_OPS,
            T1::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 20>(
            "small = [B, E, F], threshold = 3",
            T3::new,
            T3::DERIVATIVE_OPS,
            T3::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 20>(
            "outputs = [roll, pitch, yaw]",
            Att::new,
            Att::DERIVATIVE_OPS,
            Att::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 16>(
            "lock = [q9, q10]",
            LockAll::new,
            LockAll::DERIVATIVE_OPS,
            LockAll::OUTPUT_OPS,
        ));
        scenes.push(fly_scene::<_, 16>(
            "lock = [q9, q10], outputs = [roll, pitch, yaw]",
            Lock::new,
            Lock::DERIVATIVE_OPS,
            Lock::OUTPUT_OPS,
        ));
    }
    scenes.push(fly_scene::<_, 20>(
        "float = f32",
        SatF32::new,
        SatF32::DERIVATIVE_OPS,
        SatF32::OUTPUT_OPS,
    ));
    scenes.push(fly_scene::<_, 20>(
        "small = [B, E, F], float = f32",
        SmallF32::new,
        SmallF32::DERIVATIVE_OPS,
        SmallF32::OUTPUT_OPS,
    ));
    scenes
}

/// What flying the slew with one scene gave.
struct SceneRun {
    label: &'static str,
    float: &'static str,
    states: usize,
    derivative_ops: OpCount,
    output_ops: OpCount,
    /// Times `derivatives()` (median ns per call over 101 rounds) at 500
    /// states of the scene's slew.
    timer: Box<dyn FnMut() -> f64>,
    /// The best of several timing passes, interleaved with the other scenes.
    ns_per_call: f64,
    /// q4..q6 after every step, thrusters on.
    attitude: Vec<[f64; 3]>,
    /// q4..q6 after every step, thrusters off.
    attitude_quiet: Vec<[f64; 3]>,
    /// Largest |Δ q4..q6| from the full f64 model over the slew, thrusters on.
    diff: f64,
    /// The same, thrusters off.
    diff_quiet: f64,
}

/// Flies the slew (Figure 8) with RK4 at 1 ms, thrusters on and off;
/// records the attitude after every step and keeps 500 of the trajectory's
/// states to time `derivatives()` at.
fn fly_scene<M, const N: usize>(
    label: &'static str,
    make: impl Fn(Figure8) -> M,
    derivative_ops: OpCount,
    output_ops: OpCount,
) -> SceneRun
where
    M: Model<State = [<M as Model>::Float; N]> + 'static,
{
    let (attitude, samples) = slew(label, &mut make(Figure8::new()));
    let (attitude_quiet, _) = slew(label, &mut make(Figure8::commands_only()));
    let mut model = make(Figure8::new());
    let timer = Box::new(move || time_derivatives(&mut model, &samples));
    SceneRun {
        label,
        float: if M::Float::EPSILON.to_f64() > 1e-10 {
            "f32"
        } else {
            "f64"
        },
        states: N,
        derivative_ops,
        output_ops,
        timer,
        ns_per_call: f64::INFINITY,
        attitude,
        attitude_quiet,
        diff: 0.0,
        diff_quiet: 0.0,
    }
}

/// The slew with RK4 at 1 ms: q4..q6 after every step, and every 30th state.
#[allow(clippy::type_complexity)]
fn slew<M, const N: usize>(label: &str, model: &mut M) -> (Vec<[f64; 3]>, Vec<[M::Float; N]>)
where
    M: Model<State = [<M as Model>::Float; N]>,
{
    let f = <M::Float as Float>::from_f64;
    let h = 1e-3;
    let steps = 15_000;
    let mut rk4 = Rk4::new();
    let mut x = model.initial_state();
    let mut attitude = Vec::with_capacity(steps + 1);
    let mut samples = Vec::with_capacity(steps / 30 + 1);
    let angles = |x: &[M::Float; N]| [x[3].to_f64(), x[4].to_f64(), x[5].to_f64()];
    attitude.push(angles(&x));
    for n in 0..steps {
        if let Err(e) = rk4.step(model, f(n as f64 * h), &mut x, f(h)) {
            panic!("{label}: the slew failed: {e}");
        }
        attitude.push(angles(&x));
        if n % 30 == 0 {
            samples.push(x);
        }
    }
    (attitude, samples)
}

/// Median nanoseconds per `derivatives()` call over 101 rounds at `states`
/// (as `examples/perf.rs`).
fn time_derivatives<M, const N: usize>(model: &mut M, states: &[[M::Float; N]]) -> f64
where
    M: Model<State = [<M as Model>::Float; N]>,
{
    use std::hint::black_box;
    let mut dx = [M::Float::ZERO; N];
    let t = <M::Float as Float>::from_f64(5.0);
    for x in states {
        let _ = model.derivatives(t, black_box(x), &mut dx);
    }
    let rounds = 101;
    let mut per_call = Vec::with_capacity(rounds);
    for _ in 0..rounds {
        let start = Instant::now();
        for x in states {
            let _ = black_box(model.derivatives(t, black_box(x), &mut dx));
            black_box(&mut dx);
        }
        per_call.push(start.elapsed().as_nanos() as f64 / states.len() as f64);
    }
    per_call.sort_by(f64::total_cmp);
    per_call[rounds / 2]
}
