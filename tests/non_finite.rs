//! Non-finite values are never silent at run time: a derivative that is NaN
//! or infinite at a finite state is `ModelError::NonFiniteDerivative` from
//! generated `derivatives` itself, a non-finite output stops a run with
//! `IntegrationError::NonFiniteOutput`, a user function's NaN or infinity
//! is `ModelError::NonFiniteUserResult` naming the function, and a state
//! that overflows is `IntegrationError::NonFinite`; each names the first
//! value and the time.

use autosim::runtime::integrate::{DopriSettings, DormandPrince, Rk4};
use autosim::runtime::{IntegrationError, Model, ModelError, RunError, RunSettings, run};

autosim::model! {
    /// A particle pulled toward the origin by `k/x^2`: singular at x = 0.
    model Attract;
    parameters { k = 1 [N m^2] }
    body P { translate: 1, q: [x], u: [v], mass: 1, inertia: 0 }
    force pull { on: P, vector: -k/x^2*n1 }
    output closeness = 1/(1 + x^2);
}

autosim::model! {
    /// An output with no real value below x = 2.
    model Root;
    parameters { m = 2 [kg] }
    body P { translate: 1, q: [x], mass: m, inertia: 0, initial: [1] }
    output root = sqrt(x - 2);
}

autosim::model! {
    /// A drag law and a sensor written in Rust, which go wrong past x = 1.
    model Dragged;
    extern fn drag(speed [m/s]) -> [N];
    body P { translate: 1, q: [x], u: [v], mass: 1, inertia: 0 }
    extern sub sensor(x) -> (reading [m], health);
    force resist { on: P, along: n1, magnitude: drag(v) }
    output position [m] = reading;
    output sensor_health = health;
}

use attract::Attract;

/// A drag law that divides by `1 - x` (infinite at x = 1), and a sensor
/// whose health is NaN beyond x = 2.
struct Faulty {
    x: f64,
}

impl dragged::Externs for Faulty {
    fn drag(&mut self, speed: f64) -> f64 {
        -speed / (1.0 - self.x)
    }
    fn sensor(&mut self, position: f64) -> [f64; 2] {
        self.x = position;
        let health = if position > 2.0 { f64::NAN } else { 1.0 };
        [position, health]
    }
}

/// Runs `model` from `x` with RK4, ignoring the outputs.
fn run_rk4<M: Model<Float = f64>>(
    model: &mut M,
    x: &mut M::State,
    settings: &RunSettings<f64>,
) -> Result<autosim::runtime::RunSummary<f64>, RunError<std::convert::Infallible>> {
    run(
        model,
        &mut Rk4::new(),
        x,
        settings,
        &mut |_, _: &_, _: &_| {},
    )
}

#[test]
fn an_infinite_derivative_is_an_error_not_ok() {
    let mut model = Attract::new();
    let mut dx = [0.0; 2];
    let r = model.derivatives(0.0, &[0.0, 0.0], &mut dx);
    assert_eq!(
        r,
        Err(ModelError::NonFiniteDerivative {
            index: 1,
            name: "v"
        })
    );
    let text = r.unwrap_err().to_string();
    assert!(
        text.contains("derivative of state v (#1) is not finite"),
        "{text}"
    );
    assert_eq!(model.derivatives(0.0, &[1.0, 0.0], &mut dx), Ok(()));
    assert_eq!(dx, [0.0, -1.0]);
}

#[test]
fn rk4_started_at_the_singularity_stops_with_the_typed_error() {
    let mut model = Attract::new();
    let mut x = [0.0, 0.0];
    let settings = RunSettings::new(0.0, 1.0, 1e-3, 0.1);
    let r = run_rk4(&mut model, &mut x, &settings);
    let Err(RunError::Integration(e)) = r else {
        panic!("expected an integration error, got {r:?}");
    };
    assert_eq!(
        e,
        IntegrationError::Model {
            t: 0.0,
            error: ModelError::NonFiniteDerivative {
                index: 1,
                name: "v"
            }
        }
    );
    assert_eq!(x, [0.0, 0.0], "the state is left as it was");
}

#[test]
fn a_fixed_step_cannot_see_the_singularity_between_steps_an_adaptive_one_stops_there() {
    // Released at x = 1 the particle reaches x = 0 at t = pi/(2 sqrt 2)
    // = 1.1107 s with an infinite speed. RK4's steps never land on x = 0:
    // every value it computes is finite, and it steps past the collision
    // (nothing non-finite to report; the limitation is the fixed step's).
    let settings = RunSettings::new(0.0, 3.0, 1e-3, 0.1);
    let mut x = [1.0, 0.0];
    let r = run_rk4(&mut Attract::new(), &mut x, &settings);
    assert!(r.is_ok() && x[0] < 0.0, "{r:?} {x:?}");
    // Dormand-Prince's error control shrinks the step toward the
    // singularity and stops there with a typed error.
    let mut x = [1.0, 0.0];
    let mut dopri = DormandPrince::new(DopriSettings::new(1e-8, 1e-8)).expect("valid tolerances");
    let r = run(
        &mut Attract::new(),
        &mut dopri,
        &mut x,
        &settings,
        &mut |_, _: &_, _: &_| {},
    );
    let Err(RunError::Integration(e)) = r else {
        panic!("expected an integration error, got {r:?}");
    };
    let t = e.time().unwrap_or(f64::NAN);
    assert!((t - 1.1107).abs() < 1e-3, "{e}");
}

#[test]
fn a_non_finite_output_stops_the_run_naming_it() {
    let mut model = root::Root::new();
    let mut x = model.initial_state();
    let settings = RunSettings::new(0.0, 1.0, 1e-2, 0.1);
    let mut rows = 0;
    let r = run(
        &mut model,
        &mut Rk4::new(),
        &mut x,
        &settings,
        &mut |_, _: &_, _: &_| rows += 1,
    );
    assert_eq!(
        r,
        Err(RunError::Integration(IntegrationError::NonFiniteOutput {
            t: 0.0,
            index: 0,
            name: "root"
        }))
    );
    assert_eq!(rows, 0, "nothing was written");
}

#[test]
fn a_nan_parameter_is_named_before_the_first_step() {
    // A NaN mass made the mass matrix's pivot NaN, reported as a singular
    // mass matrix; the run driver now names the parameter.
    let mut model = Attract::new();
    model.set_parameter_values(&[f64::NAN]);
    let mut x = [1.0, 0.0];
    let settings = RunSettings::new(0.0, 1.0, 1e-2, 0.1);
    let r = run_rk4(&mut model, &mut x, &settings);
    let expected = IntegrationError::NonFiniteParameter {
        t: 0.0,
        name: "k",
        input: false,
    };
    assert_eq!(r, Err(RunError::Integration(expected)));
    assert_eq!(
        expected.to_string(),
        "parameter k is not finite at t = 0: set it to a finite value"
    );
}

#[test]
fn a_nan_mass_is_named_and_a_nan_pivot_says_so() {
    let mut model = root::Root::new();
    model.set_parameter_values(&[f64::NAN]);
    let mut x = [3.0, 0.0];
    let settings = RunSettings::new(0.0, 1.0, 1e-2, 0.1);
    let r = run_rk4(&mut model, &mut x, &settings);
    assert!(
        matches!(
            r,
            Err(RunError::Integration(
                IntegrationError::NonFiniteParameter { name: "m", .. }
            ))
        ),
        "{r:?}"
    );
    // Called directly, derivatives reports the pivot, and says NaN is a cause.
    let mut dx = [0.0; 2];
    let e = model.derivatives(0.0, &x, &mut dx).unwrap_err().to_string();
    assert!(e.contains("or is NaN"), "{e}");
}

#[test]
fn a_user_functions_nan_or_infinity_is_named() {
    let mut model = dragged::Dragged::new(Faulty { x: 1.0 });
    let mut dx = [0.0; 2];
    let r = model.derivatives(0.0, &[1.0, 1.0], &mut dx);
    assert_eq!(r, Err(ModelError::NonFiniteUserResult { function: "drag" }));
    assert_eq!(
        r.unwrap_err().to_string(),
        "the user function drag returned NaN or infinity at this state (check its arguments' range and its divisions)"
    );
    model.externs.x = 0.0;
    assert_eq!(model.derivatives(0.0, &[1.0, 1.0], &mut dx), Ok(()));
    let mut y = [0.0; 2];
    assert_eq!(model.outputs(0.0, &[1.5, 0.0], &mut y), Ok(()));
    assert_eq!(y, [1.5, 1.0]);
    let r = model.outputs(0.0, &[2.5, 0.0], &mut y);
    assert_eq!(
        r,
        Err(ModelError::NonFiniteUserResult { function: "sensor" })
    );
}
