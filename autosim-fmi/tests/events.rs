//! Events through the FMI functions' bodies on a hand-written bouncing
//! ball, without an importer: the indicators, the event iteration of
//! `fmi2NewDiscreteStates` (a reset reported, the discrete variable, an
//! indicator landing exactly on zero, a terminal event), and
//! Co-Simulation locating an impact and stopping at a terminal event.
//! (FMPy runs a real FMU with events in the workspace's `tests/fmi.rs`.)

use autosim_fmi::entry;
use autosim_fmi::ffi::{
    CallbackFunctions, Component, EventInfo, FALSE, FmuType, LAST_SUCCESSFUL_TIME, Status,
    TERMINATED, TRUE,
};
use autosim_fmi::{Export, Variable};
use autosim_runtime::{EventIndicator, EventOutcome, Model, ModelError};
use std::ffi::CString;

const G: f64 = 9.81;
const E: f64 = 0.5;
/// The terminal event's time (s).
const STOP: f64 = 1.0;

/// z'' = -g; `bounce` (z falling through 0): v := -e·v, bounces += 1;
/// `stop` (t - STOP rising) ends the run.
#[derive(Default)]
struct Ball {
    bounces: f64,
}

impl Model for Ball {
    type Float = f64;
    type State = [f64; 2];
    type Outputs = [f64; 0];
    const NAME: &'static str = "Ball";
    const STATE_NAMES: &'static [&'static str] = &["z", "v"];
    const STATE_UNITS: &'static [&'static str] = &["m", "m/s"];
    const EVENT_INDICATORS: &'static [EventIndicator] = &[
        EventIndicator::falling("bounce"),
        EventIndicator::rising("stop"),
    ];
    const DISCRETE_NAMES: &'static [&'static str] = &["bounces"];
    const DISCRETE_UNITS: &'static [&'static str] = &["1"];

    fn derivatives(&mut self, _: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        dx[0] = x[1];
        dx[1] = -G;
        Ok(())
    }
    fn event_indicators(&mut self, t: f64, x: &[f64; 2], g: &mut [f64]) -> Result<(), ModelError> {
        g[0] = x[0];
        g[1] = t - STOP;
        Ok(())
    }
    fn event(&mut self, k: usize, _: f64, x: &mut [f64; 2]) -> Result<EventOutcome, ModelError> {
        if k == 1 {
            return Ok(EventOutcome::Stop);
        }
        x[1] *= -E;
        self.bounces += 1.0;
        Ok(EventOutcome::Continue)
    }
    fn discrete_values(&self, values: &mut [f64]) {
        values[0] = self.bounces;
    }
    fn set_discrete_values(&mut self, values: &[f64]) {
        self.bounces = values[0];
    }
    fn initial_state(&self) -> [f64; 2] {
        [1.0, 0.0]
    }
}

struct Bouncing;
impl Export for Bouncing {
    type Model = Ball;
    const GUID: &'static str = "{ball}";
    const DEPENDENT: &'static [usize] = &[];
    fn new() -> Ball {
        Ball::default()
    }
}

fn start(kind: FmuType) -> Component {
    let name = CString::new("ball").unwrap();
    let guid = CString::new(Bouncing::GUID).unwrap();
    let callbacks = CallbackFunctions::none();
    let c = unsafe {
        entry::instantiate::<Bouncing>(
            name.as_ptr(),
            kind,
            guid.as_ptr(),
            std::ptr::null(),
            &callbacks,
            0,
            0,
        )
    };
    assert!(!c.is_null());
    unsafe {
        assert_eq!(
            entry::setup_experiment::<Bouncing>(c, 0, 0.0, 0.0, 0, 0.0),
            Status::Ok
        );
        assert_eq!(entry::enter_initialization_mode::<Bouncing>(c), Status::Ok);
        assert_eq!(entry::exit_initialization_mode::<Bouncing>(c), Status::Ok);
    }
    c
}

fn new_discrete_states(c: Component) -> EventInfo {
    let mut info = EventInfo {
        new_discrete_states_needed: TRUE,
        terminate_simulation: TRUE,
        nominals_of_continuous_states_changed: TRUE,
        values_of_continuous_states_changed: TRUE,
        next_event_time_defined: TRUE,
        next_event_time: -1.0,
    };
    let status = unsafe { entry::new_discrete_states::<Bouncing>(c, &mut info) };
    assert_eq!(status, Status::Ok);
    assert_eq!(info.new_discrete_states_needed, FALSE);
    info
}

/// Continuous-time mode at `(t, x)`; then event mode there.
fn stop_at(c: Component, t: f64, x: [f64; 2]) -> EventInfo {
    unsafe {
        assert_eq!(entry::enter_continuous_time_mode::<Bouncing>(c), Status::Ok);
        assert_eq!(entry::set_time::<Bouncing>(c, t), Status::Ok);
        assert_eq!(
            entry::set_continuous_states::<Bouncing>(c, x.as_ptr(), 2),
            Status::Ok
        );
        assert_eq!(entry::enter_event_mode::<Bouncing>(c), Status::Ok);
    }
    new_discrete_states(c)
}

fn states(c: Component) -> [f64; 2] {
    let mut x = [f64::NAN; 2];
    let status = unsafe { entry::get_continuous_states::<Bouncing>(c, x.as_mut_ptr(), 2) };
    assert_eq!(status, Status::Ok);
    x
}

fn bounces(c: Component) -> f64 {
    let r = Bouncing::layout().reference(Variable::Discrete(0));
    let mut out = f64::NAN;
    assert_eq!(
        unsafe { entry::get_real::<Bouncing>(c, &r, 1, &mut out) },
        Status::Ok
    );
    out
}

#[test]
fn model_exchange_fires_in_the_indicators_direction_and_reports_resets_and_stops() {
    let c = start(FmuType::ModelExchange);
    // The first event iteration learns the signs: nothing fires.
    let info = new_discrete_states(c);
    assert_eq!(info.values_of_continuous_states_changed, FALSE);
    let mut g = [f64::NAN; 2];
    let n = g.len();
    assert_eq!(
        unsafe { entry::get_event_indicators::<Bouncing>(c, g.as_mut_ptr(), n) },
        Status::Ok
    );
    assert_eq!(g, [1.0, -STOP]);
    assert_eq!(
        unsafe { entry::get_event_indicators::<Bouncing>(c, g.as_mut_ptr(), 1) },
        Status::Error,
        "a wrong number of indicators is an error"
    );
    unsafe { entry::free_instance::<Bouncing>(c) };
    let c = start(FmuType::ModelExchange);
    new_discrete_states(c);

    // Just past the floor, falling: the impact resets the speed.
    let info = stop_at(c, 0.45, [-1e-9, -4.0]);
    assert_eq!(info.values_of_continuous_states_changed, TRUE);
    assert_eq!(info.terminate_simulation, FALSE);
    assert_eq!(states(c), [-1e-9, 2.0]);
    assert_eq!(bounces(c), 1.0);
    // Rising through the floor again is not an impact (falling only).
    let info = stop_at(c, 0.46, [1e-9, 1.9]);
    assert_eq!(info.values_of_continuous_states_changed, FALSE);
    assert_eq!(bounces(c), 1.0);
    // Landing exactly on the floor counts as the crossing.
    let info = stop_at(c, 0.8, [0.0, -1.0]);
    assert_eq!(info.values_of_continuous_states_changed, TRUE);
    assert_eq!((states(c), bounces(c)), ([0.0, 0.5], 2.0));
    // The terminal event exactly at its time ends the simulation.
    let info = stop_at(c, STOP, [0.1, 0.2]);
    assert_eq!(info.terminate_simulation, TRUE);
    assert_eq!(info.values_of_continuous_states_changed, FALSE);
    unsafe { entry::free_instance::<Bouncing>(c) };
}

#[test]
fn co_simulation_locates_the_impact_and_stops_at_the_terminal_event() {
    let c = start(FmuType::CoSimulation);
    // The first impact at t1 = sqrt(2/g) (0.4515 s), inside this step.
    let t1 = (2.0 / G).sqrt();
    assert_eq!(
        unsafe { entry::do_step::<Bouncing>(c, 0.0, 0.5, TRUE) },
        Status::Ok
    );
    let s = 0.5 - t1;
    let v1 = E * G * t1;
    let exact = [v1 * s - 0.5 * G * s * s, v1 - G * s];
    let x = states_cs(c);
    assert!(
        (x[0] - exact[0]).abs() < 1e-7 && (x[1] - exact[1]).abs() < 1e-6,
        "{x:?} vs {exact:?}"
    );
    assert_eq!(bounces(c), 1.0);
    // The step over STOP ends at STOP with fmi2Discard and the status says
    // why; another step is an error.
    assert_eq!(
        unsafe { entry::do_step::<Bouncing>(c, 0.5, 0.75, TRUE) },
        Status::Discard
    );
    let mut terminated = FALSE;
    let mut last = f64::NAN;
    unsafe {
        assert_eq!(
            entry::get_boolean_status::<Bouncing>(c, TERMINATED, &mut terminated),
            Status::Ok
        );
        assert_eq!(
            entry::get_real_status::<Bouncing>(c, LAST_SUCCESSFUL_TIME, &mut last),
            Status::Ok
        );
    }
    assert_eq!(terminated, TRUE);
    assert!((last - STOP).abs() < 1e-12, "stopped at {last}");
    assert_eq!(
        unsafe { entry::do_step::<Bouncing>(c, last, 0.1, TRUE) },
        Status::Error
    );
    unsafe { entry::free_instance::<Bouncing>(c) };
}

/// The continuous states through `fmi2GetReal` (a Co-Simulation instance
/// has no `fmi2GetContinuousStates`).
fn states_cs(c: Component) -> [f64; 2] {
    let layout = Bouncing::layout();
    let refs = [
        layout.reference(Variable::State(0)),
        layout.reference(Variable::State(1)),
    ];
    let mut x = [f64::NAN; 2];
    let status = unsafe { entry::get_real::<Bouncing>(c, refs.as_ptr(), 2, x.as_mut_ptr()) };
    assert_eq!(status, Status::Ok);
    x
}
