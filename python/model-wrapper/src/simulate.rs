//! One simulation: the integrator the caller names, the runtime's
//! `run_at` driver reporting at the requested times (events located, as
//! in every run of the runtime), and the time history — states, outputs,
//! inputs, discrete variables and the events that fired — collected into
//! flat vectors for NumPy.

use crate::Generated;
use crate::inputs::{Driven, InputSource};
use crate::interrupt::Poll;
use autosim_runtime::integrate::{
    AbmOrder, AdamsBashforthMoulton, DopriSettings, DormandPrince, Euler, Heun, Rk4, SdirkSettings,
    Stepper,
};
use autosim_runtime::run::EventSettings;
use autosim_runtime::{
    EventRecord, IntegrationError, Model, Observer, RunError, RunSettings, StateArray, run_at,
    run_sampled_at,
};
use core::convert::Infallible;

/// The integrators, by the names Python uses.
pub const METHODS: [&str; 7] = ["dopri", "rk4", "sdirk3", "abm4", "abm2", "heun", "euler"];

/// What to simulate.
pub struct Request {
    /// An entry of [`METHODS`].
    pub method: String,
    /// Start time.
    pub t0: f64,
    /// Stop time.
    pub t_end: f64,
    /// Fixed step, or the first trial step of `dopri`.
    pub h: f64,
    /// Relative tolerance (`dopri`).
    pub rtol: f64,
    /// Absolute tolerance (`dopri`).
    pub atol: f64,
    /// Output times (non-decreasing, within `[t0, t_end]`).
    pub times: Vec<f64>,
    /// Initial state.
    pub x0: Vec<f64>,
    /// Step limit.
    pub max_steps: u64,
    /// Initial values of the discrete variables (`None`: the model's own).
    pub discrete0: Option<Vec<f64>>,
    /// How events are located and when chattering stops the run.
    pub events: EventSettings<f64>,
}

/// A discrete-time controller run every `period` (guide 3's sampled
/// control): it reads the time, state and outputs at each sample instant
/// and writes the inputs held until the next.
pub trait SampledControl: Send {
    /// At sample instant `t` with state `x` and outputs `y`: the inputs
    /// (the current ones on entry) to hold.
    fn sample(&mut self, t: f64, x: &[f64], y: &[f64], inputs: &mut [f64]);
}

/// A controller with its sample period.
pub struct Sampler {
    /// The sample period (s).
    pub period: f64,
    /// The controller.
    pub control: Box<dyn SampledControl>,
}

/// Why a simulation failed.
pub enum Failure {
    /// The message (bad settings, an integration or model error).
    Message(String),
    /// Events chattered: the message, the last event's name, its time and
    /// the events in the chain.
    Zeno {
        /// The runtime's message.
        message: String,
        /// The event that fired last.
        event: &'static str,
        /// Its time.
        t: f64,
        /// Events in the chain.
        events: u32,
    },
}

impl Failure {
    /// The message.
    pub fn message(&self) -> &str {
        match self {
            Failure::Message(m) | Failure::Zeno { message: m, .. } => m,
        }
    }
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Failure::Message(message)
    }
}

/// The events of a run, in the order they fired, row-major.
#[derive(Default)]
pub struct EventLog {
    /// Their instants.
    pub t: Vec<f64>,
    /// Which indicator fired (index into the model's events).
    pub index: Vec<usize>,
    /// States before each action, one row per event.
    pub x_before: Vec<f64>,
    /// States after.
    pub x_after: Vec<f64>,
    /// Discrete variables before.
    pub d_before: Vec<f64>,
    /// Discrete variables after.
    pub d_after: Vec<f64>,
}

/// A finished simulation, row-major.
#[derive(Default)]
pub struct Trajectory {
    /// Output times.
    pub t: Vec<f64>,
    /// States, one row per time.
    pub x: Vec<f64>,
    /// Outputs, one row per time.
    pub y: Vec<f64>,
    /// Inputs, one row per time.
    pub u: Vec<f64>,
    /// Discrete variables, one row per time.
    pub d: Vec<f64>,
    /// The events that fired.
    pub events: EventLog,
    /// The terminal event that stopped the run early, if one did.
    pub terminal_event: Option<usize>,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected trial steps.
    pub rejected_steps: u64,
    /// Derivative evaluations.
    pub evaluations: u64,
}

impl<M: Model<Float = f64>> Observer<M> for Trajectory {
    type Error = Infallible;
    fn observe(&mut self, t: f64, x: &M::State, y: &M::Outputs) -> Result<(), Infallible> {
        self.t.push(t);
        self.x.extend_from_slice(x.as_ref());
        self.y.extend_from_slice(y.as_ref());
        Ok(())
    }
    fn observe_inputs(&mut self, inputs: &[f64]) -> Result<(), Infallible> {
        self.u.extend_from_slice(inputs);
        Ok(())
    }
    fn observe_discrete(&mut self, values: &[f64]) -> Result<(), Infallible> {
        self.d.extend_from_slice(values);
        Ok(())
    }
    fn observe_event(&mut self, event: &EventRecord<'_, M>) -> Result<(), Infallible> {
        let log = &mut self.events;
        log.t.push(event.t);
        log.index.push(event.index);
        log.x_before.extend_from_slice(event.before.as_ref());
        log.x_after.extend_from_slice(event.after.as_ref());
        log.d_before.extend_from_slice(event.discrete_before);
        log.d_after.extend_from_slice(event.discrete_after);
        Ok(())
    }
}

/// Runs `model` (a copy: its inputs end where the source left them) as
/// `request` says, its inputs from `source` or set by `sampler` at its
/// sample instants, until `poll` says stop.
///
/// # Errors
/// The integration error's message (it names the time, and the state or
/// speed at fault), or an unknown method; chattering events as
/// [`Failure::Zeno`].
pub fn simulate<M: Generated>(
    model: &M,
    request: &Request,
    source: Box<dyn InputSource>,
    sampler: Option<Sampler>,
    poll: Poll,
) -> Result<Trajectory, Failure> {
    let mut stepper = stepper::<M>(request)?;
    let mut driven = Driven::new(model.clone(), source, poll);
    if let Some(d0) = &request.discrete0 {
        driven.model.set_discrete_values(d0);
    }
    let mut x = M::State::zeros();
    x.as_mut().copy_from_slice(&request.x0);
    let settings = RunSettings::new(
        request.t0,
        request.t_end,
        request.h,
        request.t_end - request.t0,
    )
    .with_max_steps(request.max_steps)
    .with_events(request.events);
    let mut out = Trajectory::default();
    let summary = match sampler {
        Some(Sampler {
            period,
            mut control,
        }) => {
            let mut controller = |t: f64, x: &M::State, y: &M::Outputs, u: &mut [f64]| {
                control.sample(t, x.as_ref(), y.as_ref(), u);
            };
            run_sampled_at(
                &mut driven,
                &mut *stepper,
                &mut x,
                &settings,
                &request.times,
                period,
                &mut controller,
                &mut out,
            )
        }
        None => run_at(
            &mut driven,
            &mut *stepper,
            &mut x,
            &settings,
            &request.times,
            &mut out,
        ),
    }
    .map_err(failure)?;
    if M::INPUT_NAMES.len() > autosim_runtime::run::MAX_RECORDED_INPUTS {
        out.u.clear();
    }
    out.steps = summary.steps;
    out.rejected_steps = summary.rejected_steps;
    out.evaluations = summary.evaluations;
    out.terminal_event = summary.terminal_event;
    Ok(out)
}

fn failure(e: RunError<Infallible>) -> Failure {
    let message = e.to_string();
    match e {
        RunError::Integration(IntegrationError::Zeno {
            t, name, events, ..
        }) => Failure::Zeno {
            message,
            event: name,
            t,
            events,
        },
        _ => Failure::Message(message),
    }
}

fn stepper<M: Generated>(request: &Request) -> Result<Box<dyn Stepper<Driven<M>>>, String> {
    Ok(match request.method.as_str() {
        "dopri" => Box::new(
            DormandPrince::new(DopriSettings::new(request.rtol, request.atol))
                .map_err(|e| e.to_string())?,
        ),
        "rk4" => Box::new(Rk4::new()),
        "heun" => Box::new(Heun::new()),
        "euler" => Box::new(Euler::new()),
        "abm4" => Box::new(AdamsBashforthMoulton::new(AbmOrder::Four)),
        "abm2" => Box::new(AdamsBashforthMoulton::new(AbmOrder::Two)),
        "sdirk3" => M::sdirk3::<Driven<M>>(SdirkSettings::default()),
        other => {
            return Err(format!(
                "unknown method {other:?}: use one of {}",
                METHODS.join(", ")
            ));
        }
    })
}
