//! Inputs over time during a simulation: held, a table interpolated
//! linearly in time, or a Python callable (in `native`), applied by
//! [`Driven`], the model seen by the integrators, which sets the inputs at
//! each evaluation's time (and forwards the model's events and discrete
//! variables).

use autosim_runtime::{EventIndicator, EventOutcome, Model, ModelError};

use crate::interrupt::Poll;

/// Where a simulation's inputs come from.
pub trait InputSource: Send {
    /// Writes the inputs at time `t` into `u`; `false` leaves the model's
    /// current inputs untouched (a held source).
    fn at(&mut self, t: f64, u: &mut [f64]) -> bool;
}

/// The model's current inputs, held for the whole run.
pub struct Held;

impl InputSource for Held {
    fn at(&mut self, _: f64, _: &mut [f64]) -> bool {
        false
    }
}

/// Inputs sampled at increasing times, linearly interpolated between them
/// and held beyond the ends.
pub struct Table {
    times: Vec<f64>,
    /// Row-major, one row of `width` per time.
    values: Vec<f64>,
    width: usize,
}

impl Table {
    /// A table of `values` (one row per time, `width` columns).
    ///
    /// # Errors
    /// A sentence when the times are not increasing and finite or the
    /// sizes disagree.
    pub fn new(times: Vec<f64>, values: Vec<f64>, width: usize) -> Result<Table, String> {
        if times.is_empty() || values.len() != times.len() * width {
            return Err(format!(
                "the input table has {} times and {} values in all: it needs one row of {width} values per time ({} values)",
                times.len(),
                values.len(),
                times.len() * width
            ));
        }
        if !times.iter().all(|t| t.is_finite()) || !times.windows(2).all(|w| w[0] < w[1]) {
            return Err("the input table's times must be finite and increasing".to_string());
        }
        Ok(Table {
            times,
            values,
            width,
        })
    }
}

impl InputSource for Table {
    fn at(&mut self, t: f64, u: &mut [f64]) -> bool {
        let w = self.width;
        let row = |k: usize| &self.values[k * w..(k + 1) * w];
        let last = self.times.len() - 1;
        let k = self.times.partition_point(|&tk| tk <= t);
        if k == 0 {
            u.copy_from_slice(row(0));
        } else if k > last {
            u.copy_from_slice(row(last));
        } else {
            let (t0, t1) = (self.times[k - 1], self.times[k]);
            let s = (t - t0) / (t1 - t0);
            for ((ui, a), b) in u.iter_mut().zip(row(k - 1)).zip(row(k)) {
                *ui = a + s * (b - a);
            }
        }
        true
    }
}

/// A model whose inputs follow a source: every evaluation first sets the
/// inputs at its time. Its derivatives fail once `poll` says stop (Ctrl-C:
/// see [`crate::interrupt`]), which ends the run.
pub struct Driven<M> {
    /// The model.
    pub model: M,
    /// The inputs' source.
    pub source: Box<dyn InputSource>,
    buffer: Vec<f64>,
    poll: Poll,
}

impl<M: Model<Float = f64>> Driven<M> {
    /// `model` driven by `source`, stopped by `poll`.
    pub fn new(model: M, source: Box<dyn InputSource>, poll: Poll) -> Self {
        Driven {
            model,
            source,
            buffer: vec![0.0; M::INPUT_NAMES.len()],
            poll,
        }
    }

    fn apply(&mut self, t: f64) {
        if self.source.at(t, &mut self.buffer) {
            self.model.set_input_values(&self.buffer);
        }
    }
}

impl<M: Model<Float = f64>> Model for Driven<M> {
    type Float = f64;
    type State = M::State;
    type Outputs = M::Outputs;
    const NAME: &'static str = M::NAME;
    const STATE_NAMES: &'static [&'static str] = M::STATE_NAMES;
    const STATE_UNITS: &'static [&'static str] = M::STATE_UNITS;
    const PARAMETER_NAMES: &'static [&'static str] = M::PARAMETER_NAMES;
    const PARAMETER_UNITS: &'static [&'static str] = M::PARAMETER_UNITS;
    const INPUT_NAMES: &'static [&'static str] = M::INPUT_NAMES;
    const INPUT_UNITS: &'static [&'static str] = M::INPUT_UNITS;
    const OUTPUT_NAMES: &'static [&'static str] = M::OUTPUT_NAMES;
    const OUTPUT_UNITS: &'static [&'static str] = M::OUTPUT_UNITS;
    const EVENT_INDICATORS: &'static [EventIndicator] = M::EVENT_INDICATORS;
    const DISCRETE_NAMES: &'static [&'static str] = M::DISCRETE_NAMES;
    const DISCRETE_UNITS: &'static [&'static str] = M::DISCRETE_UNITS;

    fn derivatives(&mut self, t: f64, x: &M::State, dx: &mut M::State) -> Result<(), ModelError> {
        if self.poll.stopped() {
            // Any error ends the run; the caller raises what stopped it.
            return Err(ModelError::NonFiniteUserResult {
                function: "(interrupted)",
            });
        }
        self.apply(t);
        self.model.derivatives(t, x, dx)
    }

    fn outputs(&mut self, t: f64, x: &M::State, y: &mut M::Outputs) -> Result<(), ModelError> {
        self.apply(t);
        self.model.outputs(t, x, y)
    }

    fn parameter_values(&self, values: &mut [f64]) {
        self.model.parameter_values(values);
    }

    fn set_parameter_values(&mut self, values: &[f64]) {
        self.model.set_parameter_values(values);
    }

    fn assemble(&mut self, t: f64, x: &mut M::State) -> Result<(), ModelError> {
        self.apply(t);
        self.model.assemble(t, x)
    }

    fn input_values(&self, values: &mut [f64]) {
        self.model.input_values(values);
    }

    fn set_input_values(&mut self, values: &[f64]) {
        self.model.set_input_values(values);
    }

    fn project(&mut self, t: f64, x: &mut M::State, tolerance: f64) -> Result<bool, ModelError> {
        self.apply(t);
        self.model.project(t, x, tolerance)
    }

    fn initial_state(&self) -> M::State {
        self.model.initial_state()
    }

    fn event_indicators(&mut self, t: f64, x: &M::State, g: &mut [f64]) -> Result<(), ModelError> {
        self.apply(t);
        self.model.event_indicators(t, x, g)
    }

    fn event(
        &mut self,
        index: usize,
        t: f64,
        x: &mut M::State,
    ) -> Result<EventOutcome, ModelError> {
        self.apply(t);
        self.model.event(index, t, x)
    }

    fn discrete_values(&self, values: &mut [f64]) {
        self.model.discrete_values(values);
    }

    fn set_discrete_values(&mut self, values: &[f64]) {
        self.model.set_discrete_values(values);
    }
}
