//! The bouncing ball of the FMU event checks (`tests/fmi.rs`): the
//! generated falling ball (`tests/fmi/ball.sim`) with its impacts added
//! through the `Model` trait's event interface, which is all the FMU reads
//! of events; a model whose events are generated gets the same.
//!
//! | event | indicator, direction | action |
//! | --- | --- | --- |
//! | `bounce` | `z`, falling | `v := -RESTITUTION·v`, `bounces += 1` |
//! | `apex` | `v`, falling | none (marks the tops) |
//! | `stop` | `t - STOP`, rising | ends the run |

include!(concat!(env!("OUT_DIR"), "/ball.rs"));
include!(concat!(env!("OUT_DIR"), "/ball_fmu.rs"));

use autosim_runtime::{EventIndicator, EventOutcome, Linearize, Model, ModelError};

/// Coefficient of restitution of the impacts.
pub const RESTITUTION: f64 = 0.8;
/// The time of the terminal event `stop` (s): between the checks'
/// communication points, so that both interfaces must locate it.
pub const STOP: f64 = 2.505;

/// The falling ball with impacts on the floor.
#[derive(Clone, Debug)]
pub struct Bouncing {
    /// The generated continuous model.
    pub ball: ball::Ball,
    /// Impacts so far: the discrete variable.
    pub bounces: f64,
}

impl Bouncing {
    /// At rest 1 m above the floor, no impact yet.
    pub fn new() -> Self {
        Bouncing {
            ball: ball::Ball::new(),
            bounces: 0.0,
        }
    }
}

impl Default for Bouncing {
    fn default() -> Self {
        Self::new()
    }
}

type State = <ball::Ball as Model>::State;
type Outputs = <ball::Ball as Model>::Outputs;

impl Model for Bouncing {
    type Float = f64;
    type State = State;
    type Outputs = Outputs;
    const NAME: &'static str = ball::Ball::NAME;
    const STATE_NAMES: &'static [&'static str] = ball::Ball::STATE_NAMES;
    const STATE_UNITS: &'static [&'static str] = ball::Ball::STATE_UNITS;
    const PARAMETER_NAMES: &'static [&'static str] = ball::Ball::PARAMETER_NAMES;
    const PARAMETER_UNITS: &'static [&'static str] = ball::Ball::PARAMETER_UNITS;
    const OUTPUT_NAMES: &'static [&'static str] = ball::Ball::OUTPUT_NAMES;
    const OUTPUT_UNITS: &'static [&'static str] = ball::Ball::OUTPUT_UNITS;
    const EVENT_INDICATORS: &'static [EventIndicator] = &[
        EventIndicator::falling("bounce"),
        EventIndicator::falling("apex"),
        EventIndicator::rising("stop"),
    ];
    const DISCRETE_NAMES: &'static [&'static str] = &["bounces"];
    const DISCRETE_UNITS: &'static [&'static str] = &["1"];

    fn derivatives(&mut self, t: f64, x: &State, dx: &mut State) -> Result<(), ModelError> {
        self.ball.derivatives(t, x, dx)
    }

    fn outputs(&mut self, t: f64, x: &State, y: &mut Outputs) -> Result<(), ModelError> {
        self.ball.outputs(t, x, y)
    }

    fn parameter_values(&self, values: &mut [f64]) {
        self.ball.parameter_values(values);
    }

    fn set_parameter_values(&mut self, values: &[f64]) {
        self.ball.set_parameter_values(values);
    }

    fn initial_state(&self) -> State {
        self.ball.initial_state()
    }

    fn event_indicators(&mut self, t: f64, x: &State, g: &mut [f64]) -> Result<(), ModelError> {
        g[0] = x[0];
        g[1] = x[1];
        g[2] = t - STOP;
        Ok(())
    }

    fn event(&mut self, index: usize, _t: f64, x: &mut State) -> Result<EventOutcome, ModelError> {
        match index {
            0 => {
                x[1] *= -RESTITUTION;
                self.bounces += 1.0;
                Ok(EventOutcome::Continue)
            }
            2 => Ok(EventOutcome::Stop),
            _ => Ok(EventOutcome::Continue),
        }
    }

    fn discrete_values(&self, values: &mut [f64]) {
        if let Some(v) = values.first_mut() {
            *v = self.bounces;
        }
    }

    fn set_discrete_values(&mut self, values: &[f64]) {
        if let Some(&v) = values.first() {
            self.bounces = v;
        }
    }
}

impl Linearize for Bouncing {
    const LINEAR_STATES: &'static [usize] = <ball::Ball as Linearize>::LINEAR_STATES;

    fn linearize_into(
        &mut self,
        t: f64,
        x: &State,
        a: &mut [f64],
        b: &mut [f64],
        c: &mut [f64],
        d: &mut [f64],
    ) -> Result<(), ModelError> {
        self.ball.linearize_into(t, x, a, b, c, d)
    }
}

autosim_fmi::export_fmi2! {
    model: Bouncing,
    new: Bouncing::new(),
    guid: ball_fmu::GUID,
    dependent: ball_fmu::DEPENDENT,
    linearize: true,
}
