//! The simulation task: run each case from its initial state to the stop
//! time and keep what [`Keep`] asks for.

use core::marker::PhantomData;
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use super::StudyError;
use super::lockstep::{self, adams_step, runge_kutta_step};
use super::method::Method;
use super::task::{CaseError, Field, Task};
use crate::batch::LANES;
use crate::event::MAX_DISCRETE;
use crate::integrate::{AbmHistory, DopriSettings, EULER, HEUN, RK4};
use crate::run::Observer;
use crate::run::counts::rounding;
use crate::{Float, IntegrationError, Lanes, Model, RunSettings, run};

/// A summary statistic of a quantity over a run's output times (the
/// samples the observer sees every `output_interval`, the start and the
/// stop included; not every integration step).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Statistic {
    /// The smallest sample.
    Min,
    /// The largest sample.
    Max,
    /// The mean of the samples.
    Mean,
    /// The root mean square of the samples.
    Rms,
    /// The largest absolute value.
    MaxAbs,
}

impl Statistic {
    fn label(self) -> &'static str {
        match self {
            Statistic::Min => "min",
            Statistic::Max => "max",
            Statistic::Mean => "mean",
            Statistic::Rms => "rms",
            Statistic::MaxAbs => "maxabs",
        }
    }
}

/// What a simulation study keeps of each run, by the name of a state, an
/// output or a discrete variable (its value at each output time).
/// Each item is one [`Field`] of the results, named as shown.
///
/// ```
/// use autosim_runtime::study::{Keep, Statistic};
/// let keep = Keep::new()
///     .final_state()                      // `final:<state>` for every state
///     .at(&[0.5, 1.0], &["energy"])       // `energy@0.5`, `energy@1`
///     .statistic("energy", Statistic::Max) // `max:energy`
///     .history(&["x"]);                   // `history:x`, one value per output time
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Keep {
    final_state: bool,
    at: Vec<(f64, String)>,
    statistics: Vec<(String, Statistic)>,
    history: Vec<String>,
}

impl Keep {
    /// Nothing kept (add what you need).
    pub fn new() -> Keep {
        Keep::default()
    }

    /// Keep the final state: a field `final:<state>` per state.
    pub fn final_state(mut self) -> Keep {
        self.final_state = true;
        self
    }

    /// Keep `quantities` (states, outputs or discrete variables) at each
    /// of `times`, which must be output times of the run (the start, the
    /// stop, or `start + k·output_interval`): a field `<quantity>@<time>`
    /// each.
    pub fn at(mut self, times: &[f64], quantities: &[&str]) -> Keep {
        for t in times {
            for q in quantities {
                self.at.push((*t, q.to_string()));
            }
        }
        self
    }

    /// Keep a statistic of a state, output or discrete variable over the
    /// output times: a field `<statistic>:<quantity>` (`min`, `max`,
    /// `mean`, `rms`, `maxabs`).
    pub fn statistic(mut self, quantity: &str, statistic: Statistic) -> Keep {
        self.statistics.push((quantity.to_string(), statistic));
        self
    }

    /// Keep the whole time history of `quantities`: a field
    /// `history:<quantity>` with one value per output time
    /// ([`Simulate::output_times`]).
    pub fn history(mut self, quantities: &[&str]) -> Keep {
        self.history
            .extend(quantities.iter().map(|q| q.to_string()));
        self
    }
}

/// A state, an output or a discrete variable, by index.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Quantity {
    State(usize),
    Output(usize),
    Discrete(usize),
}

impl Quantity {
    fn of<M: Model>(name: &str) -> Result<Quantity, StudyError> {
        // The run driver reports the first `MAX_DISCRETE` discrete variables.
        let discrete = &M::DISCRETE_NAMES[..M::DISCRETE_NAMES.len().min(MAX_DISCRETE)];
        if let Some(k) = M::STATE_NAMES.iter().position(|n| *n == name) {
            Ok(Quantity::State(k))
        } else if let Some(k) = M::OUTPUT_NAMES.iter().position(|n| *n == name) {
            Ok(Quantity::Output(k))
        } else if let Some(k) = discrete.iter().position(|n| *n == name) {
            Ok(Quantity::Discrete(k))
        } else {
            Err(StudyError::UnknownQuantity {
                name: name.to_string(),
                model: M::NAME,
                known: M::STATE_NAMES
                    .iter()
                    .chain(M::OUTPUT_NAMES)
                    .chain(discrete)
                    .map(|s| s.to_string())
                    .collect(),
            })
        }
    }

    /// The value in state `x`, outputs `y` and discrete variables `d`.
    fn value<M: Model>(self, x: &M::State, y: &M::Outputs, d: &[f64]) -> f64 {
        match self {
            Quantity::State(k) => x.as_ref()[k].to_f64(),
            Quantity::Output(k) => y.as_ref()[k].to_f64(),
            Quantity::Discrete(k) => d[k],
        }
    }
}

/// [`Keep`] resolved against a model: slots in a case's row.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Plan {
    fields: Vec<Field>,
    /// Slot of the first final state, if kept.
    final_state: Option<usize>,
    /// (output index, quantity, slot), sorted by output index.
    at: Vec<(u64, Quantity, usize)>,
    /// (quantity, statistic, slot).
    statistics: Vec<(Quantity, Statistic, usize)>,
    /// (quantity, first slot).
    history: Vec<(Quantity, usize)>,
    /// Outputs of a run to its stop (the start included).
    pub(super) samples: u64,
}

/// The simulation task: each case runs with [`run`] from `settings.start`
/// to `settings.stop` with a fresh stepper of `method` (so no case
/// inherits step sizes or derivative history from the one before), and
/// the kept values are written as the run goes: no allocation per case.
pub struct Simulate<M: Model> {
    pub(super) settings: RunSettings<M::Float>,
    method: Method,
    pub(super) plan: Plan,
    keep: Keep,
    model: PhantomData<fn() -> M>,
}

impl<M: Model> Simulate<M> {
    /// The task: `settings` (start, stop, step, output interval), the
    /// integration `method`, and what to `keep`.
    ///
    /// # Errors
    /// [`StudyError::InvalidSettings`] for bad settings or tolerances,
    /// [`StudyError::UnknownQuantity`] for a name that is neither a state
    /// nor an output, [`StudyError::NotAnOutputTime`] for a time of
    /// [`Keep::at`] that the run does not report.
    pub fn new(
        settings: RunSettings<M::Float>,
        method: Method,
        keep: Keep,
    ) -> Result<Simulate<M>, StudyError> {
        settings.validate()?;
        method.validate()?;
        let plan = plan::<M>(&settings, &keep)?;
        Ok(Simulate {
            settings,
            method,
            plan,
            keep,
            model: PhantomData,
        })
    }

    /// The output times of every run (the samples of a history).
    pub fn output_times(&self) -> Vec<f64> {
        (0..self.plan.samples)
            .map(|k| output_time(&self.settings, k))
            .collect()
    }
}

/// Output `k` (0 is the start) of a run.
fn output_time<F: Float>(settings: &RunSettings<F>, k: u64) -> f64 {
    if k == 0 {
        settings.start.to_f64()
    } else {
        settings.output_time(k).to_f64()
    }
}

fn plan<M: Model>(settings: &RunSettings<M::Float>, keep: &Keep) -> Result<Plan, StudyError> {
    let samples = settings.output_count() + 1;
    let mut fields = Vec::new();
    let add = |fields: &mut Vec<Field>, name: String, len: usize| {
        let first: usize = fields.iter().map(|f: &Field| f.len).sum();
        fields.push(Field { name, len });
        first
    };
    let final_state = if keep.final_state {
        let first: usize = fields.iter().map(|f: &Field| f.len).sum();
        for name in M::STATE_NAMES {
            add(&mut fields, format!("final:{name}"), 1);
        }
        Some(first)
    } else {
        None
    };
    let mut at = Vec::with_capacity(keep.at.len());
    for (t, name) in &keep.at {
        let q = Quantity::of::<M>(name)?;
        let k = (0..samples)
            .find(|k| output_time(settings, *k) == *t)
            .ok_or(StudyError::NotAnOutputTime { t: *t })?;
        at.push((k, q, add(&mut fields, format!("{name}@{t}"), 1)));
    }
    at.sort_by_key(|a| a.0);
    let mut statistics = Vec::with_capacity(keep.statistics.len());
    for (name, s) in &keep.statistics {
        let q = Quantity::of::<M>(name)?;
        statistics.push((q, *s, add(&mut fields, format!("{}:{name}", s.label()), 1)));
    }
    let mut history = Vec::with_capacity(keep.history.len());
    for name in &keep.history {
        let q = Quantity::of::<M>(name)?;
        let len = usize::try_from(samples)
            .map_err(|_| StudyError::InvalidCases("history too long".into()))?;
        history.push((q, add(&mut fields, format!("history:{name}"), len)));
    }
    Ok(Plan {
        fields,
        final_state,
        at,
        statistics,
        history,
        samples,
    })
}

/// The observer of one run: writes kept samples into the case's row.
struct Recorder<'a, M: Model> {
    plan: &'a Plan,
    settings: &'a RunSettings<M::Float>,
    out: &'a mut [f64],
    /// The discrete variables at the output being observed.
    discrete: [f64; MAX_DISCRETE],
    /// Output index of the next call.
    k: u64,
    /// Next entry of `plan.at`.
    next_at: usize,
    model: PhantomData<fn() -> M>,
}

impl<M: Model> Observer<M> for Recorder<'_, M> {
    type Error = core::convert::Infallible;

    fn observe_discrete(&mut self, values: &[M::Float]) -> Result<(), Self::Error> {
        for (d, v) in self.discrete.iter_mut().zip(values) {
            *d = v.to_f64();
        }
        Ok(())
    }

    /// Records output `k`; the stop of a terminal event between output
    /// times is not one (its state is the case's final state).
    fn observe(&mut self, t: M::Float, x: &M::State, y: &M::Outputs) -> Result<(), Self::Error> {
        let settings = self.settings;
        let due = match self.k {
            0 => settings.start,
            k => settings.output_time(k),
        };
        // The driver's output times are the plan's up to rounding (a
        // whole number of steps); a terminal event's stop comes earlier.
        let early = t < due - rounding(due.abs().max(t.abs()), settings.step);
        if self.k >= self.plan.samples || early {
            return Ok(());
        }
        let d = &self.discrete[..M::DISCRETE_NAMES.len().min(MAX_DISCRETE)];
        self.next_at = self
            .plan
            .record::<M>(self.k, self.next_at, self.out, (x, y, d));
        self.k += 1;
        Ok(())
    }
}

impl Plan {
    /// Starts a case's row: the statistics' initial values.
    pub(super) fn begin(&self, out: &mut [f64]) {
        for (_, s, slot) in &self.statistics {
            out[*slot] = match s {
                Statistic::Min => f64::INFINITY,
                Statistic::Max => f64::NEG_INFINITY,
                Statistic::MaxAbs | Statistic::Mean | Statistic::Rms => 0.0,
            };
        }
    }

    /// Records output `k` (the state `x`, the outputs `y`, the discrete
    /// variables `d`) in a case's row; `next_at` is the first entry of
    /// `at` not yet written. Returns the next one.
    pub(super) fn record<M: Model>(
        &self,
        k: u64,
        mut next_at: usize,
        out: &mut [f64],
        (x, y, d): (&M::State, &M::Outputs, &[f64]),
    ) -> usize {
        while let Some((at_k, q, slot)) = self.at.get(next_at) {
            if *at_k != k {
                break;
            }
            out[*slot] = q.value::<M>(x, y, d);
            next_at += 1;
        }
        for (q, s, slot) in &self.statistics {
            let v = q.value::<M>(x, y, d);
            let o = &mut out[*slot];
            *o = match s {
                Statistic::Min => o.min(v),
                Statistic::Max => o.max(v),
                Statistic::MaxAbs => o.max(v.abs()),
                Statistic::Mean => *o + v,
                Statistic::Rms => *o + v * v,
            };
        }
        for (q, first) in &self.history {
            out[*first + k as usize] = q.value::<M>(x, y, d);
        }
        next_at
    }

    /// Ends a case's row: the means and RMS values over the `recorded`
    /// outputs (fewer than the plan's when a terminal event ended the
    /// run), the final state `x`.
    pub(super) fn end<M: Model>(&self, out: &mut [f64], x: &M::State, recorded: u64) {
        let n = recorded.max(1) as f64;
        for (_, s, slot) in &self.statistics {
            match s {
                Statistic::Mean => out[*slot] /= n,
                Statistic::Rms => out[*slot] = (out[*slot] / n).sqrt(),
                _ => {}
            }
        }
        if let Some(first) = self.final_state {
            for (o, v) in out[first..].iter_mut().zip(x.as_ref()) {
                *o = v.to_f64();
            }
        }
    }
}

impl<M: Model> Task<M> for Simulate<M>
where
    M::Float: Sync,
{
    fn fields(&self) -> Vec<Field> {
        self.plan.fields.clone()
    }

    fn run(&self, model: &mut M, x: &mut M::State, out: &mut [f64]) -> Result<(), CaseError> {
        let plan = &self.plan;
        plan.begin(out);
        let mut stepper = self.method.stepper::<M>()?;
        let mut recorder = Recorder {
            plan,
            settings: &self.settings,
            out: &mut *out,
            discrete: [0.0; MAX_DISCRETE],
            k: 0,
            next_at: 0,
            model: PhantomData,
        };
        run(model, &mut stepper, x, &self.settings, &mut recorder)
            .map_err(|e| CaseError::Run(IntegrationError::from(e)))?;
        let recorded = recorder.k;
        plan.end::<M>(out, x, recorded);
        Ok(())
    }

    /// Every method, for a model without events or discrete variables
    /// (see [the study docs](super#lockstep)).
    fn runs_in_lockstep(&self) -> bool {
        M::EVENT_INDICATORS.is_empty() && M::DISCRETE_NAMES.is_empty()
    }

    fn run_group(
        &self,
        models: &mut [M],
        values: &mut [Lanes<LANES>],
        xs: &[M::State],
        outs: &mut [&mut [f64]],
        done: &mut [bool],
    ) {
        if !self.runs_in_lockstep() {
            return;
        }
        let (settings, plan) = (&self.settings, &self.plan);
        let group = (models, values);
        match self.method {
            Method::Euler => {
                let euler = |lanes: &mut _, t, h| runge_kutta_step(lanes, &EULER, t, h);
                lockstep::simulate(group, ((), euler), settings, plan, xs, outs, done)
            }
            Method::Heun => {
                let heun = |lanes: &mut _, t, h| runge_kutta_step(lanes, &HEUN, t, h);
                lockstep::simulate(group, ((), heun), settings, plan, xs, outs, done)
            }
            Method::Rk4 => {
                let rk4 = |lanes: &mut _, t, h| runge_kutta_step(lanes, &RK4, t, h);
                lockstep::simulate(group, ((), rk4), settings, plan, xs, outs, done)
            }
            Method::AdamsBashforthMoulton(order) => {
                let adams = |lanes: &mut _, t, h| adams_step(lanes, order, t, h);
                let method = (AbmHistory::new(), adams);
                lockstep::simulate(group, method, settings, plan, xs, outs, done)
            }
            Method::DormandPrince { rtol, atol } => {
                let dopri = DopriSettings::new(M::Float::from_f64(rtol), M::Float::from_f64(atol));
                lockstep::simulate_adaptive(group, dopri, settings, plan, xs, outs, done)
            }
        }
    }

    fn describe(&self) -> String {
        format!(
            "simulate {} {:?} {:?} {:?}",
            M::NAME,
            self.settings,
            self.method,
            self.keep
        )
    }
}
