//! Runs recorded in memory, column by column.

use std::prelude::rust_2024::*;

use std::convert::Infallible;
use std::marker::PhantomData;

use super::error::OutputError;
use super::names::closest;
use crate::event::MAX_DISCRETE;
use crate::{EventRecord, Float, Model, Observer};

/// One recorded column: a state or an output, with its unit.
#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    /// The state's or output's name.
    pub name: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// One value per output time.
    pub values: Vec<f64>,
}

/// An [`Observer`] that keeps every output time in memory: the times, then
/// one [`Column`] per state, per discrete variable, per input and per
/// output (values as `f64`). Each event adds two rows at its instant
/// (before and after its action, so plots show the jump) and an entry in
/// [`Recording::events`].
///
/// Use it to inspect or plot a run afterwards
/// ([`Recording::plot_svg`] with feature `plot`); for long runs prefer
/// [`CsvWriter`](super::CsvWriter), which keeps nothing in memory.
#[derive(Clone, Debug)]
pub struct Recording<M> {
    time: Vec<f64>,
    columns: Vec<Column>,
    /// The inputs of the row being recorded (given by the run driver).
    inputs: Vec<f64>,
    /// The discrete variables of the row being recorded.
    discrete: Vec<f64>,
    events: Vec<LoggedEvent>,
    model: PhantomData<fn(&M)>,
}

/// One event of a recorded run.
#[derive(Clone, Debug, PartialEq)]
pub struct LoggedEvent {
    /// Its instant.
    pub t: f64,
    /// The event's name.
    pub name: &'static str,
    /// The state before the action.
    pub before: Vec<f64>,
    /// The state after the action.
    pub after: Vec<f64>,
    /// The discrete variables before the action.
    pub discrete_before: Vec<f64>,
    /// The discrete variables after the action.
    pub discrete_after: Vec<f64>,
}

impl<M: Model> Recording<M> {
    /// An empty recording with a column for every state and output of `M`.
    pub fn new() -> Self {
        let unit = |units: &'static [&'static str], i: usize| units.get(i).copied().unwrap_or("");
        let states = M::STATE_NAMES.iter().enumerate().map(|(i, name)| Column {
            name,
            unit: unit(M::STATE_UNITS, i),
            values: Vec::new(),
        });
        let n_discrete = M::DISCRETE_NAMES.len().min(MAX_DISCRETE);
        let discrete = M::DISCRETE_NAMES[..n_discrete]
            .iter()
            .enumerate()
            .map(|(i, name)| Column {
                name,
                unit: unit(M::DISCRETE_UNITS, i),
                values: Vec::new(),
            });
        let n_inputs = M::INPUT_NAMES.len().min(crate::run::MAX_RECORDED_INPUTS);
        let inputs = M::INPUT_NAMES[..n_inputs]
            .iter()
            .enumerate()
            .map(|(i, name)| Column {
                name,
                unit: unit(M::INPUT_UNITS, i),
                values: Vec::new(),
            });
        let outputs = M::OUTPUT_NAMES.iter().enumerate().map(|(i, name)| Column {
            name,
            unit: unit(M::OUTPUT_UNITS, i),
            values: Vec::new(),
        });
        Self {
            time: Vec::new(),
            columns: states
                .chain(discrete)
                .chain(inputs)
                .chain(outputs)
                .collect(),
            inputs: std::vec![0.0; n_inputs],
            discrete: std::vec![0.0; n_discrete],
            events: Vec::new(),
            model: PhantomData,
        }
    }

    /// The output times.
    pub fn time(&self) -> &[f64] {
        &self.time
    }

    /// The events of the run, in time order.
    pub fn events(&self) -> &[LoggedEvent] {
        &self.events
    }

    /// All columns: states first, then discrete variables, inputs and
    /// outputs.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// The column named `name` (a state, a discrete variable, an input or
    /// an output).
    ///
    /// # Errors
    /// [`OutputError::UnknownColumn`] naming the closest column, if any.
    pub fn column(&self, name: &str) -> Result<&Column, OutputError> {
        self.columns.iter().find(|c| c.name == name).ok_or_else(|| {
            let names: Vec<&'static str> = self.columns.iter().map(|c| c.name).collect();
            OutputError::UnknownColumn {
                name: name.to_string(),
                suggestion: closest(name, &names),
            }
        })
    }
}

impl<M: Model> Recording<M> {
    /// Appends one row: time, states, discrete variables, the inputs as
    /// kept, outputs.
    fn push_row(&mut self, t: f64, x: &[M::Float], discrete: &[f64], y: &[M::Float]) {
        self.time.push(t);
        let values = x
            .iter()
            .map(|v| v.to_f64())
            .chain(discrete.iter().copied())
            .chain(self.inputs.iter().copied())
            .chain(y.iter().map(|v| v.to_f64()));
        for (column, v) in self.columns.iter_mut().zip(values) {
            column.values.push(v);
        }
    }
}

impl<M: Model> Default for Recording<M> {
    fn default() -> Self {
        Self::new()
    }
}

impl<M: Model> Observer<M> for Recording<M> {
    type Error = Infallible;
    fn observe_inputs(&mut self, inputs: &[M::Float]) -> Result<(), Infallible> {
        for (kept, v) in self.inputs.iter_mut().zip(inputs) {
            *kept = v.to_f64();
        }
        Ok(())
    }

    fn observe_discrete(&mut self, values: &[M::Float]) -> Result<(), Infallible> {
        for (kept, v) in self.discrete.iter_mut().zip(values) {
            *kept = v.to_f64();
        }
        Ok(())
    }

    fn observe(&mut self, t: M::Float, x: &M::State, y: &M::Outputs) -> Result<(), Infallible> {
        let discrete = std::mem::take(&mut self.discrete);
        self.push_row(t.to_f64(), x.as_ref(), &discrete, y.as_ref());
        self.discrete = discrete;
        Ok(())
    }

    fn observe_event(&mut self, event: &EventRecord<'_, M>) -> Result<(), Infallible> {
        for (kept, v) in self.inputs.iter_mut().zip(event.inputs) {
            *kept = v.to_f64();
        }
        let f64s = |values: &[M::Float]| values.iter().map(|v| v.to_f64()).collect::<Vec<_>>();
        let logged = LoggedEvent {
            t: event.t.to_f64(),
            name: event.name,
            before: f64s(event.before.as_ref()),
            after: f64s(event.after.as_ref()),
            discrete_before: f64s(event.discrete_before),
            discrete_after: f64s(event.discrete_after),
        };
        let t = logged.t;
        self.push_row(
            t,
            event.before.as_ref(),
            &logged.discrete_before,
            event.outputs_before.as_ref(),
        );
        self.push_row(
            t,
            event.after.as_ref(),
            &logged.discrete_after,
            event.outputs_after.as_ref(),
        );
        self.events.push(logged);
        Ok(())
    }
}
