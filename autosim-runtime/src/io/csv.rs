//! CSV output of runs: one row per output time, flushed as it is written.

use std::prelude::rust_2024::*;
use std::vec;

use std::fmt::Write as _;
use std::fs::File;
use std::io::Write;
use std::marker::PhantomData;
use std::path::Path;

use super::error::OutputError;
use crate::event::MAX_DISCRETE;
use crate::{EventRecord, Float, Model, Observer};

/// An [`Observer`] that writes every output time of a run as a CSV row:
/// time, then the states, the discrete variables, the inputs and the
/// outputs, under a header of `name [unit]` columns (`time [s]` first).
/// A model with events has one more column, `event`: empty in the output
/// rows; every event adds two rows at its instant, before and after its
/// action, both naming the event (the first is the state before).
///
/// Each row is flushed when written, so a run that stops early (a
/// non-finite state, a crash) leaves every row up to the failure on disk.
/// Use it to hand results to a spreadsheet, pandas or gnuplot.
pub struct CsvWriter<M, W: Write> {
    writer: csv::Writer<W>,
    field: String,
    rows: u64,
    /// The inputs of the row being written (given by the run driver).
    inputs: Vec<f64>,
    /// The discrete variables of the row being written.
    discrete: Vec<f64>,
    model: PhantomData<fn(&M)>,
}

impl<M: Model> CsvWriter<M, File> {
    /// Creates (or truncates) the file at `path` and writes the header.
    ///
    /// # Errors
    /// [`OutputError::Io`] if the file cannot be created, or
    /// [`OutputError::Csv`] if the header cannot be written.
    pub fn create(path: impl AsRef<Path>) -> Result<Self, OutputError> {
        let path = path.as_ref();
        let file = File::create(path).map_err(|source| OutputError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Self::new(file)
    }
}

impl<M: Model, W: Write> CsvWriter<M, W> {
    /// Writes the header to `writer` and returns the observer.
    ///
    /// # Errors
    /// [`OutputError::Csv`] if the header cannot be written.
    pub fn new(writer: W) -> Result<Self, OutputError> {
        let mut writer = csv::WriterBuilder::new()
            .flexible(false)
            .from_writer(writer);
        let mut header = vec![String::from("time [s]")];
        let named = |names: &'static [&'static str], units: &'static [&'static str]| {
            names.iter().zip(units.iter().chain(std::iter::repeat(&"")))
        };
        let columns = named(M::STATE_NAMES, M::STATE_UNITS)
            .chain(named(M::DISCRETE_NAMES, M::DISCRETE_UNITS).take(MAX_DISCRETE))
            .chain(named(M::INPUT_NAMES, M::INPUT_UNITS).take(crate::run::MAX_RECORDED_INPUTS))
            .chain(named(M::OUTPUT_NAMES, M::OUTPUT_UNITS));
        header.extend(columns.map(|(name, unit)| super::names::labelled(name, unit)));
        if !M::EVENT_INDICATORS.is_empty() {
            header.push(String::from("event"));
        }
        writer.write_record(&header)?;
        writer.flush().map_err(csv::Error::from)?;
        Ok(Self {
            writer,
            field: String::new(),
            rows: 0,
            inputs: vec![0.0; M::INPUT_NAMES.len().min(crate::run::MAX_RECORDED_INPUTS)],
            discrete: vec![0.0; M::DISCRETE_NAMES.len().min(MAX_DISCRETE)],
            model: PhantomData,
        })
    }

    /// Data rows written so far.
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// Flushes and returns the underlying writer.
    ///
    /// # Errors
    /// [`OutputError::Csv`] if the final flush fails.
    pub fn into_inner(self) -> Result<W, OutputError> {
        self.writer
            .into_inner()
            .map_err(|e| OutputError::Csv(csv::Error::from(e.into_error())))
    }

    fn write_value(&mut self, v: impl std::fmt::Debug) -> Result<(), csv::Error> {
        self.field.clear();
        // Writing to a String cannot fail. `Debug` is the shortest text that
        // reads back exactly, with an exponent for very large or small values.
        let _ = write!(self.field, "{v:?}");
        self.writer.write_field(&self.field)
    }

    /// One row: time, states, discrete variables, inputs (as kept),
    /// outputs, and for a model with events the event column.
    fn write_row(
        &mut self,
        t: f64,
        x: &[M::Float],
        discrete: &[f64],
        y: &[M::Float],
        event: &str,
    ) -> Result<(), OutputError> {
        self.write_value(t)?;
        for v in x {
            self.write_value(*v)?;
        }
        for v in discrete {
            self.write_value(*v)?;
        }
        for k in 0..self.inputs.len() {
            self.write_value(self.inputs[k])?;
        }
        for v in y {
            self.write_value(*v)?;
        }
        if !M::EVENT_INDICATORS.is_empty() {
            self.writer.write_field(event)?;
        }
        self.writer.write_record(None::<&[u8]>)?;
        self.writer.flush().map_err(csv::Error::from)?;
        self.rows += 1;
        Ok(())
    }
}

impl<M: Model, W: Write> Observer<M> for CsvWriter<M, W> {
    type Error = OutputError;
    fn observe_inputs(&mut self, inputs: &[M::Float]) -> Result<(), OutputError> {
        for (kept, v) in self.inputs.iter_mut().zip(inputs) {
            *kept = v.to_f64();
        }
        Ok(())
    }

    fn observe_discrete(&mut self, values: &[M::Float]) -> Result<(), OutputError> {
        for (kept, v) in self.discrete.iter_mut().zip(values) {
            *kept = v.to_f64();
        }
        Ok(())
    }

    fn observe(&mut self, t: M::Float, x: &M::State, y: &M::Outputs) -> Result<(), OutputError> {
        let discrete = std::mem::take(&mut self.discrete);
        let written = self.write_row(t.to_f64(), x.as_ref(), &discrete, y.as_ref(), "");
        self.discrete = discrete;
        written
    }

    fn observe_event(&mut self, event: &EventRecord<'_, M>) -> Result<(), OutputError> {
        for (kept, v) in self.inputs.iter_mut().zip(event.inputs) {
            *kept = v.to_f64();
        }
        let t = event.t.to_f64();
        let before: Vec<f64> = event.discrete_before.iter().map(|v| v.to_f64()).collect();
        let after: Vec<f64> = event.discrete_after.iter().map(|v| v.to_f64()).collect();
        let (x0, y0) = (event.before.as_ref(), event.outputs_before.as_ref());
        self.write_row(t, x0, &before, y0, event.name)?;
        let (x1, y1) = (event.after.as_ref(), event.outputs_after.as_ref());
        self.write_row(t, x1, &after, y1, event.name)
    }
}
