//! The FMI functions' bodies on hand-written models, without an importer:
//! the state machine, values by reference, a panic becoming `fmi2Fatal`,
//! Co-Simulation against the exact solution, FMU states. (FMPy runs the
//! real shared libraries in the workspace's `tests/fmi.rs`.)

use autosim_fmi::entry;
use autosim_fmi::ffi::{CallbackFunctions, Component, FmuType, Status};
use autosim_fmi::{Export, Layout, Variable};
use autosim_runtime::{Model, ModelError};
use std::ffi::CString;

/// `x'' = -omega² x + force`: states x, v; parameter omega; input force;
/// output the energy.
struct Oscillator {
    omega: f64,
    force: f64,
    panics: bool,
}

impl Model for Oscillator {
    type Float = f64;
    type State = [f64; 2];
    type Outputs = [f64; 1];
    const NAME: &'static str = "Oscillator";
    const STATE_NAMES: &'static [&'static str] = &["x", "v"];
    const STATE_UNITS: &'static [&'static str] = &["m", "m/s"];
    const PARAMETER_NAMES: &'static [&'static str] = &["omega"];
    const PARAMETER_UNITS: &'static [&'static str] = &["rad/s"];
    const INPUT_NAMES: &'static [&'static str] = &["force"];
    const INPUT_UNITS: &'static [&'static str] = &["m/s^2"];
    const OUTPUT_NAMES: &'static [&'static str] = &["energy"];
    const OUTPUT_UNITS: &'static [&'static str] = &["J/kg"];

    fn derivatives(&mut self, _: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        assert!(!self.panics, "a bug in user code");
        dx[0] = x[1];
        dx[1] = -self.omega * self.omega * x[0] + self.force;
        Ok(())
    }
    fn outputs(&mut self, _: f64, x: &[f64; 2], y: &mut [f64; 1]) -> Result<(), ModelError> {
        y[0] = 0.5 * (x[1] * x[1] + self.omega * self.omega * x[0] * x[0]);
        Ok(())
    }
    fn parameter_values(&self, values: &mut [f64]) {
        values[0] = self.omega;
    }
    fn set_parameter_values(&mut self, values: &[f64]) {
        self.omega = values[0];
    }
    fn input_values(&self, values: &mut [f64]) {
        values[0] = self.force;
    }
    fn set_input_values(&mut self, values: &[f64]) {
        self.force = values[0];
    }
    fn initial_state(&self) -> [f64; 2] {
        [1.0, 0.0]
    }
}

struct Fine;
impl Export for Fine {
    type Model = Oscillator;
    const GUID: &'static str = "{oscillator}";
    const DEPENDENT: &'static [usize] = &[];
    fn new() -> Oscillator {
        Oscillator {
            omega: 2.0,
            force: 0.0,
            panics: false,
        }
    }
}

struct Buggy;
impl Export for Buggy {
    type Model = Oscillator;
    const GUID: &'static str = "{buggy}";
    const DEPENDENT: &'static [usize] = &[];
    fn new() -> Oscillator {
        Oscillator {
            panics: true,
            ..Fine::new()
        }
    }
}

fn instantiate<E: Export>(kind: FmuType, guid: &str) -> Component {
    let name = CString::new("test").unwrap();
    let guid = CString::new(guid).unwrap();
    let callbacks = CallbackFunctions::none();
    unsafe {
        entry::instantiate::<E>(
            name.as_ptr(),
            kind,
            guid.as_ptr(),
            std::ptr::null(),
            &callbacks,
            0,
            0,
        )
    }
}

fn vr(v: Variable) -> u32 {
    Fine::layout().reference(v)
}

fn get<E: Export>(c: Component, v: Variable) -> (Status, f64) {
    let r = vr(v);
    let mut out = f64::NAN;
    let status = unsafe { entry::get_real::<E>(c, &r, 1, &mut out) };
    (status, out)
}

fn set<E: Export>(c: Component, v: Variable, value: f64) -> Status {
    let r = vr(v);
    unsafe { entry::set_real::<E>(c, &r, 1, &value) }
}

fn initialize<E: Export>(c: Component) {
    unsafe {
        assert_eq!(
            entry::setup_experiment::<E>(c, 0, 0.0, 0.0, 0, 0.0),
            Status::Ok
        );
        assert_eq!(entry::enter_initialization_mode::<E>(c), Status::Ok);
        assert_eq!(entry::exit_initialization_mode::<E>(c), Status::Ok);
    }
}

#[test]
fn the_layout_numbers_every_variable() {
    let layout: Layout = Fine::layout();
    assert_eq!(
        (
            layout.parameters,
            layout.inputs,
            layout.states,
            layout.outputs
        ),
        (1, 1, 2, 1)
    );
    assert_eq!(layout.variable(0), Some(Variable::Time));
    assert_eq!(layout.variable(1), Some(Variable::Parameter(0)));
}

#[test]
fn a_wrong_guid_or_no_callbacks_give_no_instance() {
    assert!(instantiate::<Fine>(FmuType::ModelExchange, "{another}").is_null());
    let name = CString::new("x").unwrap();
    let guid = CString::new(Fine::GUID).unwrap();
    let c = unsafe {
        entry::instantiate::<Fine>(
            name.as_ptr(),
            FmuType::ModelExchange,
            guid.as_ptr(),
            std::ptr::null(),
            std::ptr::null(),
            0,
            0,
        )
    };
    assert!(c.is_null());
}

#[test]
fn the_state_machine_refuses_and_reset_recovers() {
    let c = instantiate::<Fine>(FmuType::ModelExchange, Fine::GUID);
    assert!(!c.is_null());
    // Parameters before initialization; no values yet.
    assert_eq!(set::<Fine>(c, Variable::Parameter(0), 3.0), Status::Ok);
    assert_eq!(get::<Fine>(c, Variable::State(0)).0, Status::Error);
    // The instance is in Error mode now: only reset helps.
    assert_eq!(
        unsafe { entry::enter_initialization_mode::<Fine>(c) },
        Status::Error
    );
    assert_eq!(unsafe { entry::reset::<Fine>(c) }, Status::Ok);
    initialize::<Fine>(c);
    // Reset restored the default parameter.
    assert_eq!(get::<Fine>(c, Variable::Parameter(0)), (Status::Ok, 2.0));
    assert_eq!(get::<Fine>(c, Variable::Output(0)), (Status::Ok, 2.0));
    // Parameters are fixed after initialization; outputs never settable.
    assert_eq!(set::<Fine>(c, Variable::Parameter(0), 3.0), Status::Error);
    unsafe { entry::reset::<Fine>(c) };
    initialize::<Fine>(c);
    assert_eq!(set::<Fine>(c, Variable::Output(0), 3.0), Status::Error);
    unsafe { entry::reset::<Fine>(c) };
    initialize::<Fine>(c);
    // A Co-Simulation function on a Model Exchange instance.
    assert_eq!(
        unsafe { entry::do_step::<Fine>(c, 0.0, 0.1, 1) },
        Status::Error
    );
    unsafe { entry::free_instance::<Fine>(c) };
}

#[test]
fn a_panic_is_fatal_not_an_unwind_into_c() {
    let c = instantiate::<Buggy>(FmuType::ModelExchange, Buggy::GUID);
    unsafe {
        assert_eq!(
            entry::setup_experiment::<Buggy>(c, 0, 0.0, 0.0, 0, 0.0),
            Status::Ok
        );
        assert_eq!(entry::enter_initialization_mode::<Buggy>(c), Status::Ok);
        // Exit evaluates the model, whose derivatives panic.
        assert_eq!(entry::exit_initialization_mode::<Buggy>(c), Status::Fatal);
        // Fatal is final.
        assert_eq!(entry::reset::<Buggy>(c), Status::Fatal);
        entry::free_instance::<Buggy>(c);
    }
}

#[test]
fn co_simulation_follows_the_exact_solution_and_fmu_states_restore_it() {
    let c = instantiate::<Fine>(FmuType::CoSimulation, Fine::GUID);
    unsafe {
        assert_eq!(
            entry::setup_experiment::<Fine>(c, 1, 1e-12, 0.0, 0, 0.0),
            Status::Ok
        );
        assert_eq!(entry::enter_initialization_mode::<Fine>(c), Status::Ok);
        assert_eq!(entry::exit_initialization_mode::<Fine>(c), Status::Ok);
    }
    let h = 0.1;
    let mut saved = std::ptr::null_mut();
    for k in 0..20 {
        if k == 10 {
            assert_eq!(
                unsafe { entry::get_fmu_state::<Fine>(c, &mut saved) },
                Status::Ok
            );
        }
        assert_eq!(
            unsafe { entry::do_step::<Fine>(c, k as f64 * h, h, 1) },
            Status::Ok
        );
    }
    // x = cos(2 t) from x = 1, v = 0.
    let (_, x) = get::<Fine>(c, Variable::State(0));
    assert!((x - (2.0f64 * 2.0).cos()).abs() < 1e-10, "{x}");
    // Back to t = 1 through the serialized bytes, and the same way on.
    let mut size = 0usize;
    unsafe {
        assert_eq!(
            entry::serialized_size::<Fine>(c, saved, &mut size),
            Status::Ok
        );
        let mut bytes = vec![0 as std::ffi::c_char; size];
        assert_eq!(
            entry::serialize::<Fine>(c, saved, bytes.as_mut_ptr(), size),
            Status::Ok
        );
        entry::free_fmu_state::<Fine>(c, &mut saved);
        let mut restored = std::ptr::null_mut();
        assert_eq!(
            entry::deserialize::<Fine>(c, bytes.as_ptr(), size, &mut restored),
            Status::Ok
        );
        assert_eq!(entry::set_fmu_state::<Fine>(c, restored), Status::Ok);
        entry::free_fmu_state::<Fine>(c, &mut restored);
    }
    assert_eq!(get::<Fine>(c, Variable::Time).1, 1.0);
    for k in 10..20 {
        assert_eq!(
            unsafe { entry::do_step::<Fine>(c, k as f64 * h, h, 1) },
            Status::Ok
        );
    }
    assert_eq!(get::<Fine>(c, Variable::State(0)).1, x);
    unsafe { entry::free_instance::<Fine>(c) };
}
