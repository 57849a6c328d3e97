//! FMI 2.0 export (`autosim-fmu`, `autosim-fmi`) checked by FMPy, an
//! independent importer: every FMU built here from `examples/models` is
//! validated, simulated as Model Exchange (FMPy's CVode) and Co-Simulation,
//! its directional derivatives compared with central finite differences,
//! its `ModelStructure` with the dependencies found numerically; for the
//! reference models (satellite with user code, a chain, the four-bar, the
//! quarter car with its road input, the model of every language feature
//! with its user code and an input) both runs are compared with autosim's
//! own run; and on the quarter car two interleaved instances, forbidden
//! call sequences and serialized FMU states (`tests/fmi/check_fmus.py`).
//!
//! The FMUs are built once per test run into `target/fmi-test` (one cargo
//! workspace for the generated libraries, one target folder shared with
//! the satellite's user crate). Without Python or the registry the test
//! prints a `SKIPPED:` line.

use autosim::runtime::integrate::DormandPrince;
use autosim::runtime::{Model, ModelError, Stepper};
use autosim_test_support::features_user;
use autosim_test_support::python::{python_env, skip, target_dir, workspace_root};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// The FMPy release the checks were written against.
const FMPY: &str = "fmpy==0.3.32";

/// Models of `examples/models` exported as FMUs here: every model without
/// user code; the satellite from its user crate `examples/fmu_satellite`
/// and [`USER_CODE`] from theirs.
const EXPORTED: [&str; 23] = [
    "andrews",
    "bicycle",
    "bouncing_ball",
    "chain_planar_1",
    "chain_planar_10",
    "chain_planar_2",
    "chain_planar_2_f32",
    "chain_planar_3",
    "chain_planar_5",
    "chain_spatial_1",
    "chain_spatial_10",
    "chain_spatial_2",
    "chain_spatial_20",
    "chain_spatial_3",
    "chain_spatial_3_stiff",
    "chain_spatial_5",
    "chain_spatial_7",
    "four_bar",
    "pendulum",
    "pendulum_end_stop",
    "quarter_car",
    "quarter_car_bump_stop",
    "rolling_disc",
];

autosim::model!(file = "examples/models/quarter_car.sim");
autosim::model!(file = "examples/models/four_bar.sim");
autosim::model!(file = "examples/models/chain_spatial_3.sim");
// The satellite and the user code of its FMU's crate (which names the
// model's module `satellite` beside it).
autosim::model!(file = "examples/models/satellite.sim");
#[path = "../examples/fmu_satellite/src/control.rs"]
mod control;
// The model of every language feature with the user code of its FMU's
// crate (`tests/fmi/user/features`).
autosim::model!(file = "examples/models/features.sim");

/// `features.sim`'s user code as the tests run it.
struct FeaturesUser;

impl features::Externs for FeaturesUser {
    fn friction(&mut self, speed: f64, normal: f64) -> f64 {
        features_user::friction(speed, normal)
    }

    fn sensor(&mut self, t: f64, x: f64) -> [f64; 2] {
        features_user::sensor(t, x)
    }
}

/// A model whose inputs are piecewise constant in time: the value of
/// `input` at `held`, the start of the current step.
struct Driven<'a, M> {
    model: M,
    input: &'a dyn Fn(f64) -> Vec<f64>,
    held: f64,
}

impl<M: Model<Float = f64>> Driven<'_, M> {
    fn drive(&mut self) {
        let w = (self.input)(self.held);
        self.model.set_input_values(&w);
    }
}

impl<M: Model<Float = f64>> Model for Driven<'_, M> {
    type Float = f64;
    type State = M::State;
    type Outputs = M::Outputs;
    const NAME: &'static str = M::NAME;
    const STATE_NAMES: &'static [&'static str] = M::STATE_NAMES;
    const STATE_UNITS: &'static [&'static str] = M::STATE_UNITS;
    const OUTPUT_NAMES: &'static [&'static str] = M::OUTPUT_NAMES;
    const OUTPUT_UNITS: &'static [&'static str] = M::OUTPUT_UNITS;

    fn derivatives(&mut self, t: f64, x: &M::State, dx: &mut M::State) -> Result<(), ModelError> {
        self.drive();
        self.model.derivatives(t, x, dx)
    }

    fn outputs(&mut self, t: f64, x: &M::State, y: &mut M::Outputs) -> Result<(), ModelError> {
        self.drive();
        self.model.outputs(t, x, y)
    }

    fn project(&mut self, t: f64, x: &mut M::State, tolerance: f64) -> Result<bool, ModelError> {
        self.model.project(t, x, tolerance)
    }
}

/// Autosim's own run of a model: Dormand–Prince at 1e-12 from its
/// (assembled) initial state with the `start` values, landing on every output time and every time
/// in `breaks` (where the inputs change), projected onto the position
/// constraints after every step; the times and the named states and
/// outputs at each output time.
fn reference<M: Model<Float = f64>>(
    mut model: M,
    names: &[&str],
    (stop, every): (f64, f64),
    start: &[(&str, f64)],
    (input, breaks): (&dyn Fn(f64) -> Vec<f64>, &[f64]),
) -> Value {
    let mut x = model.initial_state();
    for (name, value) in start {
        let k = M::STATE_NAMES.iter().position(|s| s == name);
        x.as_mut()[k.unwrap_or_else(|| panic!("no state {name}"))] = *value;
    }
    model.assemble(0.0, &mut x).expect("assembles");
    let mut driven = Driven {
        model,
        input,
        held: 0.0,
    };
    let mut dopri = DormandPrince::<Driven<M>>::with_tolerances(1e-12, 1e-12).expect("tolerances");
    let outputs: Vec<f64> = (0..=(stop / every).round() as usize)
        .map(|k| k as f64 * every)
        .collect();
    let mut ends: Vec<f64> = outputs.iter().chain(breaks).copied().collect();
    ends.sort_by(f64::total_cmp);
    let mut samples = vec![sample(&mut driven, 0.0, &x, names)];
    let (mut t, mut h) = (0.0, every);
    for &end in ends.iter().filter(|&&e| e > 0.0) {
        driven.held = t;
        dopri.reset();
        while end - t > 1e-12 * (1.0 + end) {
            let info = dopri
                .step(&mut driven, t, &mut x, h.min(end - t))
                .expect("a step");
            t += info.h;
            h = info.h_next;
            driven.project(t, &mut x, 0.0).expect("projects");
        }
        t = end;
        if outputs.contains(&end) {
            samples.push(sample(&mut driven, end, &x, names));
        }
    }
    let mut columns: serde_json::Map<String, Value> = names
        .iter()
        .enumerate()
        .map(|(k, n)| (n.to_string(), samples.iter().map(|s| s[k]).collect()))
        .collect();
    columns.insert("time".into(), json!(outputs));
    Value::Object(columns)
}

/// The named states and outputs at `(t, x)`.
fn sample<M: Model<Float = f64>>(model: &mut M, t: f64, x: &M::State, names: &[&str]) -> Vec<f64> {
    let mut y = <M::Outputs as autosim::runtime::StateArray<f64>>::zeros();
    model.outputs(t, x, &mut y).expect("outputs");
    names
        .iter()
        .map(|n| {
            let state = M::STATE_NAMES.iter().position(|s| s == n);
            match state {
                Some(k) => x.as_ref()[k],
                None => {
                    let k = M::OUTPUT_NAMES.iter().position(|o| o == n);
                    y.as_ref()[k.unwrap_or_else(|| panic!("{n} is no state or output"))]
                }
            }
        })
        .collect()
}

/// The quarter car's road: a 5 cm step (a curb) at 0.205 s, between
/// output times. Piecewise constant because FMPy 0.3.32 sets inputs only at
/// communication points and input events (its CVode right-hand side does
/// not interpolate an input table), where a ramp would jump at every
/// output time; at the step both FMPy's runs stop and restart.
const CURB: f64 = 0.205;
const ROAD: [(f64, f64); 4] = [(0.0, 0.0), (CURB, 0.0), (CURB, 0.05), (1.0, 0.05)];

fn road(t: f64) -> Vec<f64> {
    vec![step(t, CURB, 0.05)]
}

/// The features model's actuator command: 5 N from 0.305 s (between
/// output times, for the same reason as the road's step).
const PUSH_AT: f64 = 0.305;
const PUSH: [(f64, f64); 4] = [(0.0, 0.0), (PUSH_AT, 0.0), (PUSH_AT, 5.0), (1.0, 5.0)];

fn push(t: f64) -> Vec<f64> {
    vec![step(t, PUSH_AT, 5.0)]
}

/// 0 before `at`, `height` from `at` on.
fn step(t: f64, at: f64, height: f64) -> f64 {
    if t < at { 0.0 } else { height }
}

fn no_input(_: f64) -> Vec<f64> {
    Vec::new()
}

/// The reference of a model with the bounds FMPy's runs are held to
/// (inputs piecewise constant: the same for Model Exchange and
/// Co-Simulation).
fn references<M: Model<Float = f64>>(
    model: M,
    names: &[&str],
    stop: f64,
    start: &[(&str, f64)],
    input: (&dyn Fn(f64) -> Vec<f64>, &[f64]),
) -> Value {
    let every = 0.01;
    let reference = reference(model, names, (stop, every), start, input);
    let start: serde_json::Map<String, Value> = start
        .iter()
        .map(|(n, v)| (n.to_string(), json!(v)))
        .collect();
    json!({
        "stop": stop,
        "start": start,
        "interval": every,
        // FMPy's CVode at rtol 1e-10 (atol rtol × nominal 1).
        "me_tolerance": 1e-10,
        "me_bound": 1e-6,
        // The FMU's Dormand–Prince at 1e-12 (fmi2SetupExperiment's tolerance).
        "cs_tolerance": 1e-12,
        "cs_bound": 1e-9,
        "reference": reference,
    })
}

/// Pairs (unknown, known) whose expressions read the known while the
/// value does not depend on it: `ModelStructure` lists them (FMI allows a
/// dependency that is not there, never the reverse), the numerical check
/// finds them zero at its three random points.
fn invariant(model: &str) -> Value {
    match model {
        // A level, uniform plane: nothing depends on the heading psi. The
        // spin rate u5's equation reads the lean phi and u5 itself in
        // terms that cancel; the centre's speed |vel(D)| reads the angles
        // through the dependent speeds the rolling constraints solve.
        "RollingDisc" => json!([
            ["der(u4)", "psi"],
            ["der(u5)", "psi"],
            ["der(u6)", "psi"],
            ["energy", "psi"],
            ["speed", "psi"],
            ["der(u5)", "phi"],
            ["der(u5)", "u5"],
            ["speed", "phi"],
        ]),
        // The Whipple bicycle on a level plane: nothing depends on the
        // heading psi or on the wheels' rotation angles thetaR and thetaF
        // (the equations read them through the frames the contact points'
        // velocities are written in; the terms cancel), and the front
        // wheel's rate (a dependent speed) reads the lean rate u_phi in
        // terms that cancel: the FMU's exact directional derivatives of
        // these pairs are below 1e-15 at random states.
        "Bicycle" => {
            let mut pairs: Vec<[&str; 2]> = [
                "der(x)",
                "der(y)",
                "der(psi)",
                "der(thetaF)",
                "der(u_phi)",
                "der(u_thetaR)",
                "der(u_delta)",
            ]
            .into_iter()
            .flat_map(|d| [[d, "thetaR"], [d, "thetaF"]])
            .collect();
            pairs.extend(
                [
                    "der(psi)",
                    "der(thetaF)",
                    "der(u_phi)",
                    "der(u_thetaR)",
                    "der(u_delta)",
                ]
                .map(|d| [d, "psi"]),
            );
            pairs.push(["der(thetaF)", "u_phi"]);
            json!(pairs)
        }
        // As the satellite's (its spec): camera_rate = |rot(D)| reads the
        // camera's angle q8 through D's axes; a rotation keeps a length.
        "SatelliteSmall" => json!([["camera_rate", "q8"]]),
        // With its thrusters as inputs (SatelliteSampled) or discrete
        // modes that only events change (SatelliteEvents: the attitude
        // error enters the event indicators, not the equations), moments
        // about the bus's own axes, and no gravity, no force depends on the
        // bus's attitude q4..q6: the equations read it through the frames
        // they are written in.
        "SatelliteSampled" | "SatelliteEvents" => {
            let mut pairs = vec![json!(["camera_rate", "q8"]), json!(["der(u1)", "q4"])];
            for d in 4..=10 {
                for q in ["q4", "q5", "q6"] {
                    pairs.push(json!([format!("der(u{d})"), q]));
                }
            }
            json!(pairs)
        }
        _ => json!([]),
    }
}

/// The features model's gyro (`Gyro`, inertia diag(0.1, 0.2, 0.3), its
/// mass centre at its fixed point) carries a massless hinge turning freely
/// about the gyro's axis 2: nothing exerts a moment about that axis on the
/// gyro, so Euler's equation for it is the torque-free one,
/// `I2 der(u5) = (I3 - I1) u4 u6`, whatever the hinge's and arm's angles
/// and rates. The equations read the gyro's and the arm's coordinates
/// (the coupled mass matrix and forcing the accelerations are solved
/// from), the value does not: [`gyro_spin_identity`] checks the identity
/// itself at random states.
fn gyro_spin_invariant() -> Value {
    json!(["q5", "q6", "q7", "q8", "u5", "u7", "u8"].map(|k| ["der(u5)", k]))
}

/// `der(u5) = (I3 - I1)/I2 u4 u6` (see [`gyro_spin_invariant`]), checked
/// with the bead's small variables small (the model keeps their first
/// order only: the spring's length, 0.7 - 0.8 s m at theta = 0, reaches
/// zero at s = 0.875 and its direction divides by it).
fn gyro_spin_identity() -> Value {
    json!({
        "unknown": "der(u5)",
        "coefficient": (0.3 - 0.1) / 0.2,
        "factors": ["u4", "u6"],
        "small": ["s", "sdot"],
    })
}

/// Adds `fields` to a JSON object.
fn merge(mut a: Value, fields: Value) -> Value {
    if let (Some(a), Value::Object(b)) = (a.as_object_mut(), fields) {
        a.extend(b);
    }
    a
}

/// The event checks of a bouncing ball (`check_events` in
/// `tests/fmi/check_fmus.py`) dropped from rest at 1 m with restitution
/// 0.8 under g = 9.81, run to 3 s; `model` adds what is the FMU's own (its
/// variables' names, its event indicators, an impact counter, a terminal
/// event).
fn ball_events(model: Value) -> Value {
    merge(
        json!({
            "g": 9.81, "restitution": 0.8, "h0": 1.0, "speed": "v",
            "stop": 3.0, "interval": 0.01,
            // CVode at rtol 1e-10 locating the zero crossings: impact
            // times and the state after them to 1e-7.
            "me_tolerance": 1e-10, "me_time_bound": 1e-7, "me_bound": 1e-7,
            // Dormand–Prince at 1e-12 with the run driver's event location
            // (to the rounding of the time on its interpolant).
            "cs_tolerance": 1e-12, "cs_time_bound": 1e-9, "cs_bound": 1e-9,
        }),
        model,
    )
}

/// The other models with user code, each built from its crate in
/// `tests/fmi/user/<model>`.
const USER_CODE: [&str; 4] = [
    "features",
    "satellite_events",
    "satellite_sampled",
    "satellite_small",
];

/// The largest models, whose libraries are built at `opt-level` 0 here:
/// the same numbers as a release build (no optimization level changes a
/// floating-point result in Rust), built in a fraction of the time (the
/// guide's FMI chapter has the figures).
const UNOPTIMIZED: [&str; 4] = [
    "bicycle",
    "chain_planar_10",
    "chain_spatial_10",
    "chain_spatial_20",
];

fn build_fmus(out: &Path) -> Vec<PathBuf> {
    let root = workspace_root();
    let models = root.join("examples/models");
    let mut fmus: Vec<autosim_fmu::Fmu> = EXPORTED
        .iter()
        .map(|m| {
            let fmu = autosim_fmu::Fmu::new(models.join(format!("{m}.sim")))
                .out_dir(out)
                .work_dir(out.join("build"));
            if UNOPTIMIZED.contains(m) {
                fmu.opt_level(0)
            } else {
                fmu
            }
        })
        .collect();
    fmus.push(
        autosim_fmu::Fmu::new(models.join("satellite.sim"))
            .out_dir(out)
            .work_dir(out.join("build"))
            .user_crate(root.join("examples/fmu_satellite")),
    );
    // The other models with user code, from their crates in `tests/fmi/user`.
    for m in USER_CODE {
        fmus.push(
            autosim_fmu::Fmu::new(models.join(format!("{m}.sim")))
                .out_dir(out)
                .work_dir(out.join("build"))
                .user_crate(root.join("tests/fmi/user").join(m)),
        );
    }
    fmus.push(
        autosim_fmu::Fmu::new(root.join("tests/fmi/pressed_cart.sim"))
            .out_dir(out)
            .work_dir(out.join("build")),
    );
    // Another default experiment than its crate's build script knows: the
    // GUIDs must still agree (FMPy refused to instantiate such an FMU).
    let experiment = autosim_fmu::Experiment {
        stop: 3.0,
        step: 0.005,
        ..autosim_fmu::Experiment::default()
    };
    fmus.push(
        autosim_fmu::Fmu::new(root.join("tests/fmi/ball.sim"))
            .out_dir(out)
            .work_dir(out.join("build"))
            .user_crate(root.join("tests/fmi/ball_fmu"))
            .experiment(experiment),
    );
    let built = autosim_fmu::build_all(&fmus).unwrap_or_else(|e| panic!("{e}"));
    built.into_iter().map(|b| b.fmu).collect()
}

#[test]
fn fmpy_validates_simulates_and_differentiates_every_exported_fmu() {
    let env = match python_env(&[FMPY, "numpy"]) {
        Ok(env) => env,
        Err(why) => {
            skip("the FMU checks with FMPy", &why);
            return;
        }
    };
    let out = target_dir().join("fmi-test");
    let paths = build_fmus(&out);
    let fmu = |name: &str| {
        paths
            .iter()
            .find(|p| p.file_stem().and_then(|s| s.to_str()) == Some(name))
            .unwrap_or_else(|| panic!("no FMU {name}"))
            .display()
            .to_string()
    };

    let quarter_names = ["zu", "zs", "vu", "vs", "deflection", "body_acceleration"];
    let four_names = ["q1", "u1", "q2", "q3", "energy", "loop_n2", "loop_n3"];
    let chain_names = chain_spatial3::ChainSpatial3::STATE_NAMES;
    let features_names: Vec<&str> = features::Features::<FeaturesUser>::STATE_NAMES
        .iter()
        .chain(features::Features::<FeaturesUser>::OUTPUT_NAMES)
        .copied()
        .collect();
    let sat_names = [
        "roll",
        "pitch",
        "yaw",
        "clock_angle",
        "camera_angle",
        "camera_rate",
    ];
    let mut specs: Vec<Value> = vec![
        merge(
            references(
                quarter_car::QuarterCar::new(),
                &quarter_names,
                1.0,
                &[],
                (&road, &[CURB]),
            ),
            json!({
                "name": "QuarterCar",
                "input": { "time": ROAD.map(|r| r.0), "road": ROAD.map(|r| r.1) },
                "sequence_checks": {
                    "parameter": "ms", "values": [300.0, 600.0],
                    "watch": "zs", "output": "deflection",
                },
            }),
        ),
        merge(
            references(
                four_bar::FourBar::new(),
                &four_names,
                2.0,
                &[],
                (&no_input, &[]),
            ),
            json!({ "name": "FourBar" }),
        ),
        merge(
            references(
                chain_spatial3::ChainSpatial3::new(),
                chain_names,
                2.0,
                &[("q1", 0.5), ("q2", -0.4), ("q3", 0.3), ("u3", 1.0)],
                (&no_input, &[]),
            ),
            json!({ "name": "ChainSpatial3" }),
        ),
        merge(
            references(
                satellite::Satellite::new(control::Control),
                &sat_names,
                3.0,
                &[],
                (&no_input, &[]),
            ),
            // camera_rate = |rot(D)| reads the camera's angle q8 (its
            // components in D's axes do) but a rotation keeps a vector's
            // length: numerically it does not depend on q8.
            json!({ "name": "Satellite", "invariant": [["camera_rate", "q8"]] }),
        ),
        merge(
            references(
                features::Features::new(FeaturesUser),
                &features_names,
                1.0,
                &[("u4", 1.0), ("u6", -2.0), ("u8", 0.5)],
                (&push, &[PUSH_AT]),
            ),
            json!({
                "name": "Features",
                "input": { "time": PUSH.map(|r| r.0), "push": PUSH.map(|r| r.1) },
                "invariant": gyro_spin_invariant(),
                "identities": [gyro_spin_identity()],
            }),
        ),
    ];
    // The bouncing ball of `tests/fmi/ball_fmu` (its `RESTITUTION` and
    // `STOP`, its impact counter), dropped from rest at 1 m (`ball.sim`).
    specs.push(json!({
        "name": "Ball",
        "events": ball_events(json!({
            "height": "z", "counter": "bounces", "stop_event": 2.505, "indicators": 3,
        })),
    }));
    // The language's bouncing ball (`examples/models/bouncing_ball.sim`,
    // restitution 0.8 by default; `bounce` and `apex`, no terminal event;
    // its resting mode only after 4 s).
    specs.push(json!({
        "name": "BouncingBall",
        "events": ball_events(json!({ "height": "h", "indicators": 2 })),
    }));
    // A cart pressed against an end stop by a spring (`pressed_cart.sim`):
    // bounces ever smaller, their impacts in closed form; to 2 s, before
    // the bounces accumulate at 2.075 s. CVode locating the crossings at
    // rtol 1e-10 from x0 = 0 and 1e-8 from x0 = -0.2 (the initial position
    // a parameter the FMU's `x` is computed from).
    specs.push(json!({
        "name": "PressedCart",
        "pressed": {
            "parameters": { "M": 1.0, "k": 4.0, "x_rest": 1.0, "x_stop": 0.5, "e": 0.5 },
            "stop": 2.0, "interval": 0.01,
            "starts": [0.0, -0.2],
            "me_bounds": [[1e-10, 1e-7], [1e-8, 1e-6]], "past_bound": 1e-12,
        },
    }));
    let with_reference: Vec<String> = specs
        .iter()
        .map(|s| s["name"].as_str().unwrap_or_default().to_string())
        .collect();
    for path in &paths {
        let name = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or_default()
            .to_string();
        if !with_reference.contains(&name) {
            // Andrews' mechanism turns in milliseconds (the test set's run is 30 ms).
            let stop = if name == "Andrews" { 0.03 } else { 1.0 };
            specs.push(json!({
                "name": name, "stop": stop, "interval": stop / 100.0,
                "invariant": invariant(&name),
            }));
        }
    }
    for spec in &mut specs {
        let name = spec["name"].as_str().unwrap_or_default().to_string();
        spec["fmu"] = json!(fmu(&name));
    }
    let manifest = out.join("manifest.json");
    std::fs::write(&manifest, json!({ "fmus": specs }).to_string()).expect("manifest");
    let script = workspace_root().join("tests/fmi/check_fmus.py");
    let run = env
        .command()
        .arg(&script)
        .arg(&manifest)
        .output()
        .expect("python runs");
    let stdout = String::from_utf8_lossy(&run.stdout);
    println!("{stdout}");
    eprintln!("{}", String::from_utf8_lossy(&run.stderr));
    assert!(run.status.success(), "FMU checks failed:\n{stdout}");
    assert!(stdout.contains("all FMU checks passed"));
}
