//! Runs recorded in memory, column by column.

use std::prelude::rust_2024::*;

use std::convert::Infallible;
use std::marker::PhantomData;

use super::error::OutputError;
use super::names::closest;
use crate::{Float, Model, Observer};

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
/// one [`Column`] per state, per input and per output (values as `f64`).
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
    model: PhantomData<fn(&M)>,
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
            columns: states.chain(inputs).chain(outputs).collect(),
            inputs: std::vec![0.0; n_inputs],
            model: PhantomData,
        }
    }

    /// The output times.
    pub fn time(&self) -> &[f64] {
        &self.time
    }

    /// All columns: states first, then inputs, then outputs.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// The column named `name` (a state, an input or an output).
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

    fn observe(&mut self, t: M::Float, x: &M::State, y: &M::Outputs) -> Result<(), Infallible> {
        self.time.push(t.to_f64());
        let values = x
            .as_ref()
            .iter()
            .map(|v| v.to_f64())
            .chain(self.inputs.iter().copied())
            .chain(y.as_ref().iter().map(|v| v.to_f64()));
        for (column, v) in self.columns.iter_mut().zip(values) {
            column.values.push(v);
        }
        Ok(())
    }
}
