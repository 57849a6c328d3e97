//! One FMU instance: the model, its time and state, the mode of the
//! standard's state machine, and reading and writing variables by value
//! reference.

use crate::Export;
use crate::ffi::{CallbackFunctions, FmuType, Status};
use crate::layout::{DEFAULT_STEP, DEFAULT_TOLERANCE, Layout, Method, Setting, Variable};
use crate::log::Log;
use autosim_runtime::{Model, ModelError, StateArray, Stepper};

/// Corrections of the dependent coordinates below this (relative to
/// `1 + |q|`) are rounding, not drift: the state is left as it is.
pub const PROJECTION_TOLERANCE: f64 = 1e-14;

/// The states of FMI 2.0's state machines (Model Exchange and
/// Co-Simulation share the first two and the last three).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// After `fmi2Instantiate`: parameters and start values may be set.
    Instantiated,
    /// Between `fmi2EnterInitializationMode` and its exit.
    Initialization,
    /// Model Exchange: event mode.
    Event,
    /// Model Exchange: continuous-time mode.
    Continuous,
    /// Co-Simulation: between steps.
    StepComplete,
    /// After `fmi2Terminate`.
    Terminated,
    /// A call returned `fmi2Error`: values may be read, `fmi2Reset` or a
    /// saved state brings the instance back.
    Error,
    /// A call returned `fmi2Fatal` (a panic): only `fmi2FreeInstance`.
    Fatal,
}

impl Mode {
    /// Every mode but `Fatal`, in the order of the standard's state
    /// machine.
    pub const ALIVE: [Mode; 7] = {
        use Mode::*;
        [
            Instantiated,
            Initialization,
            Event,
            Continuous,
            StepComplete,
            Terminated,
            Error,
        ]
    };
}

/// Why a call failed: the status to return and the message to log.
#[derive(Clone, Debug, PartialEq)]
pub struct Fail {
    /// `Error` or `Discard`.
    pub status: Status,
    /// What went wrong, for the logger.
    pub message: String,
}

impl Fail {
    /// An `fmi2Error` with this message.
    pub fn error(message: impl Into<String>) -> Fail {
        Fail {
            status: Status::Error,
            message: message.into(),
        }
    }
}

impl From<ModelError> for Fail {
    fn from(e: ModelError) -> Fail {
        Fail::error(format!("the model cannot be evaluated: {e}"))
    }
}

/// What a call returns inside the crate.
pub type Outcome<T = ()> = Result<T, Fail>;

/// A model's state vector.
type State<E> = <<E as Export>::Model as Model>::State;
/// A model's output vector.
type Outputs<E> = <<E as Export>::Model as Model>::Outputs;

/// The Co-Simulation settings' values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// `cs.method`.
    pub method: Method,
    /// `cs.tolerance`.
    pub tolerance: f64,
    /// `cs.step` (s).
    pub step: f64,
}

/// One instance of the FMU.
pub struct Instance<E: Export> {
    /// The instance name given to `fmi2Instantiate`.
    pub(crate) log: Log,
    /// Model Exchange or Co-Simulation.
    pub(crate) kind: FmuType,
    /// Where the instance is in the standard's state machine.
    pub(crate) mode: Mode,
    pub(crate) model: E::Model,
    pub(crate) layout: Layout,
    /// State-vector positions of the FMU's states.
    pub(crate) independent: Vec<usize>,
    pub(crate) t: f64,
    /// The model's whole state vector (dependent coordinates included).
    pub(crate) x: State<E>,
    /// Which FMU states were given a start value by the importer.
    pub(crate) started: Vec<bool>,
    /// The dependent coordinates are solved for the current state.
    pub(crate) assembled: bool,
    /// They were solved once since the start values were set: later
    /// solutions start from the last one (a projection, which leaves a
    /// state that satisfies the constraints bit for bit as it is).
    pub(crate) solved_once: bool,
    /// Derivatives and outputs at the current time, state and inputs.
    pub(crate) cache: Option<(State<E>, Outputs<E>)>,
    pub(crate) settings: Settings,
    /// Co-Simulation: the integrator (made at the end of initialization).
    pub(crate) stepper: Option<Box<dyn Stepper<E::Model>>>,
    /// Co-Simulation: the step Dormand–Prince suggests next.
    pub(crate) h_next: f64,
    /// The last known sign of every event indicator (0: not known yet).
    pub(crate) signs: Vec<i8>,
    /// A terminal event fired: the model asks to end the simulation.
    pub(crate) terminated: bool,
}

impl<E: Export> Instance<E> {
    /// A new instance in `Instantiated` mode, the model at its defaults.
    pub fn new(name: String, kind: FmuType, callbacks: CallbackFunctions, logging: bool) -> Self {
        let model = E::new();
        let layout = E::layout();
        let x = model.initial_state();
        let n = <<E::Model as Model>::State as StateArray<f64>>::LEN;
        let independent: Vec<usize> = (0..n).filter(|i| !E::DEPENDENT.contains(i)).collect();
        Instance {
            log: Log::new(name, callbacks, logging),
            kind,
            mode: Mode::Instantiated,
            model,
            layout,
            started: vec![false; independent.len()],
            independent,
            t: 0.0,
            x,
            assembled: E::DEPENDENT.is_empty(),
            solved_once: false,
            cache: None,
            settings: Settings {
                method: Method::DormandPrince,
                tolerance: DEFAULT_TOLERANCE,
                step: DEFAULT_STEP,
            },
            stepper: None,
            h_next: 0.0,
            signs: vec![0; E::Model::EVENT_INDICATORS.len()],
            terminated: false,
        }
    }

    /// Fails unless the instance is in one of `modes` (and of the kind
    /// `kind`, when given): the standard's state machine.
    pub fn require(&self, what: &str, modes: &[Mode], kind: Option<FmuType>) -> Outcome {
        if let Some(k) = kind
            && k != self.kind
        {
            return Err(Fail::error(format!(
                "{what} is a {} function; this instance is {}",
                kind_name(k),
                kind_name(self.kind)
            )));
        }
        if modes.contains(&self.mode) {
            return Ok(());
        }
        Err(Fail::error(format!(
            "{what} is not allowed in {:?} mode (allowed: {modes:?})",
            self.mode
        )))
    }

    /// Something changed that the cached derivatives and outputs read.
    pub(crate) fn touch(&mut self) {
        self.cache = None;
    }

    /// The state changed: the dependent coordinates need solving again.
    pub(crate) fn touch_state(&mut self) {
        self.cache = None;
        self.assembled = E::DEPENDENT.is_empty();
    }

    /// Solves the position constraints for the dependent coordinates
    /// (Newton's method from their current values), if needed: by
    /// projection with [`PROJECTION_TOLERANCE`] (so that a new speed or a
    /// rounding-level change leaves them as they are), by assembly the
    /// first time and when the projection refuses a large move.
    pub(crate) fn assemble(&mut self) -> Outcome {
        if !self.assembled {
            let mut x = self.x;
            let projected = self.solved_once
                && self
                    .model
                    .project(self.t, &mut x, PROJECTION_TOLERANCE)
                    .is_ok();
            if !projected {
                // First, or a jump larger than drift (an importer's trial
                // state far from the last one): Newton's method without
                // the projection's limit on how far it may move.
                x = self.x;
                self.model.assemble(self.t, &mut x)?;
            }
            self.x = x;
            self.assembled = true;
            self.solved_once = true;
        }
        Ok(())
    }

    /// Derivatives and outputs at the current point (computed once).
    pub(crate) fn evaluate(&mut self) -> Outcome<(State<E>, Outputs<E>)> {
        if let Some(c) = self.cache {
            return Ok(c);
        }
        self.assemble()?;
        let mut dx = State::<E>::zeros();
        let mut y = Outputs::<E>::zeros();
        self.model.derivatives(self.t, &self.x, &mut dx)?;
        self.model.outputs(self.t, &self.x, &mut y)?;
        let finite = dx.as_ref().iter().chain(y.as_ref()).all(|v| v.is_finite());
        if !finite {
            return Err(Fail::error(format!(
                "the derivatives or outputs are not finite at t = {}",
                self.t
            )));
        }
        self.cache = Some((dx, y));
        Ok((dx, y))
    }

    /// The start values of the states not given by the importer, from the
    /// current parameters (the model's `initial` values may depend on
    /// them).
    pub(crate) fn fill_initial_state(&mut self) {
        let x0 = self.model.initial_state();
        for (k, &slot) in self.independent.iter().enumerate() {
            if !self.started[k] {
                self.x.as_mut()[slot] = x0.as_ref()[slot];
            }
        }
        for &slot in E::DEPENDENT {
            self.x.as_mut()[slot] = x0.as_ref()[slot];
        }
        self.solved_once = false;
        self.touch_state();
    }

    /// The value of a Real variable.
    pub fn get_real(&mut self, vr: u32) -> Outcome<f64> {
        let variable = self.variable(vr)?;
        let needs_values = matches!(
            variable,
            Variable::Derivative(_) | Variable::Output(_) | Variable::Dependent(_)
        );
        if needs_values && self.mode == Mode::Error {
            return Err(Fail::error(format!(
                "value reference {vr} cannot be computed after an error"
            )));
        }
        Ok(match variable {
            Variable::Time => self.t,
            Variable::Parameter(k) => {
                let mut p = vec![0.0; self.layout.parameters];
                self.model.parameter_values(&mut p);
                p[k]
            }
            Variable::Setting(Setting::Tolerance) => self.settings.tolerance,
            Variable::Setting(Setting::Step) => self.settings.step,
            Variable::Setting(Setting::Method) => return Err(not_real(vr)),
            Variable::Input(k) => {
                let mut w = vec![0.0; self.layout.inputs];
                self.model.input_values(&mut w);
                w[k]
            }
            Variable::State(k) => self.x.as_ref()[self.independent[k]],
            Variable::Derivative(k) => self.evaluate()?.0.as_ref()[self.independent[k]],
            Variable::Output(k) => self.evaluate()?.1.as_ref()[k],
            Variable::Dependent(k) => {
                self.assemble()?;
                self.x.as_ref()[E::DEPENDENT[k]]
            }
            Variable::Discrete(k) => {
                let mut d = vec![0.0; self.layout.discrete];
                self.model.discrete_values(&mut d);
                d[k]
            }
        })
    }

    /// Sets a Real variable, where the standard allows it in this mode.
    pub fn set_real(&mut self, vr: u32, value: f64) -> Outcome {
        let variable = self.variable(vr)?;
        let before_start = matches!(self.mode, Mode::Instantiated | Mode::Initialization);
        match variable {
            Variable::Parameter(k) if before_start => {
                let mut p = vec![0.0; self.layout.parameters];
                self.model.parameter_values(&mut p);
                p[k] = value;
                self.model.set_parameter_values(&p);
                self.fill_initial_state();
            }
            Variable::Setting(Setting::Tolerance) if before_start => {
                if !(value > 0.0 && value.is_finite()) {
                    return Err(Fail::error(format!(
                        "cs.tolerance must be positive, not {value}"
                    )));
                }
                self.settings.tolerance = value;
            }
            Variable::Setting(Setting::Step) if before_start => {
                if !(value > 0.0 && value.is_finite()) {
                    return Err(Fail::error(format!(
                        "cs.step must be positive, not {value}"
                    )));
                }
                self.settings.step = value;
            }
            Variable::Input(k) => {
                let mut w = vec![0.0; self.layout.inputs];
                self.model.input_values(&mut w);
                w[k] = value;
                self.model.set_input_values(&w);
                self.touch();
            }
            Variable::Discrete(k) if before_start => {
                let mut d = vec![0.0; self.layout.discrete];
                self.model.discrete_values(&mut d);
                d[k] = value;
                self.model.set_discrete_values(&d);
                self.touch();
            }
            Variable::State(k) if before_start => {
                self.x.as_mut()[self.independent[k]] = value;
                self.started[k] = true;
                self.solved_once = false;
                self.touch_state();
            }
            Variable::Setting(Setting::Method) => return Err(not_real(vr)),
            other => {
                return Err(Fail::error(format!(
                    "value reference {vr} ({other:?}) cannot be set in {:?} mode",
                    self.mode
                )));
            }
        }
        Ok(())
    }

    /// The value of an Integer variable (`cs.method` is the only one).
    pub fn get_integer(&mut self, vr: u32) -> Outcome<i32> {
        match self.variable(vr)? {
            Variable::Setting(Setting::Method) => Ok(self.settings.method as i32),
            _ => Err(Fail::error(format!(
                "value reference {vr} is not an Integer variable"
            ))),
        }
    }

    /// Sets an Integer variable (`cs.method`, before the start).
    pub fn set_integer(&mut self, vr: u32, value: i32) -> Outcome {
        let before_start = matches!(self.mode, Mode::Instantiated | Mode::Initialization);
        match self.variable(vr)? {
            Variable::Setting(Setting::Method) if before_start => {
                self.settings.method = Method::from_value(value).ok_or_else(|| {
                    Fail::error(format!(
                        "cs.method {value} is not one of {:?}",
                        Method::ALL.map(|m| (m as i32, m.name()))
                    ))
                })?;
                Ok(())
            }
            _ => Err(Fail::error(format!(
                "value reference {vr} is not an Integer variable settable in {:?} mode",
                self.mode
            ))),
        }
    }

    /// The variable of a value reference, or an error naming it.
    fn variable(&self, vr: u32) -> Outcome<Variable> {
        self.layout
            .variable(vr)
            .ok_or_else(|| Fail::error(format!("unknown value reference {vr}")))
    }

    /// Writes the FMU's continuous states into `out`.
    pub fn continuous_states(&self, out: &mut [f64]) -> Outcome {
        self.check_len(out.len())?;
        for (o, &slot) in out.iter_mut().zip(&self.independent) {
            *o = self.x.as_ref()[slot];
        }
        Ok(())
    }

    /// Sets the FMU's continuous states (Model Exchange); the dependent
    /// coordinates are solved again when next needed.
    pub fn set_continuous_states(&mut self, values: &[f64]) -> Outcome {
        self.check_len(values.len())?;
        for (v, &slot) in values.iter().zip(&self.independent) {
            self.x.as_mut()[slot] = *v;
        }
        self.touch_state();
        Ok(())
    }

    /// The derivatives of the FMU's continuous states.
    pub fn derivatives(&mut self, out: &mut [f64]) -> Outcome {
        self.check_len(out.len())?;
        let (dx, _) = self.evaluate()?;
        for (o, &slot) in out.iter_mut().zip(&self.independent) {
            *o = dx.as_ref()[slot];
        }
        Ok(())
    }

    fn check_len(&self, n: usize) -> Outcome {
        if n != self.independent.len() {
            return Err(Fail::error(format!(
                "the FMU has {} continuous states, not {n}",
                self.independent.len()
            )));
        }
        Ok(())
    }
}

fn not_real(vr: u32) -> Fail {
    Fail::error(format!(
        "value reference {vr} is cs.method, an Integer variable"
    ))
}

fn kind_name(kind: FmuType) -> &'static str {
    match kind {
        FmuType::ModelExchange => "Model Exchange",
        FmuType::CoSimulation => "Co-Simulation",
    }
}
