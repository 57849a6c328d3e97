//! Running a range of cases into [`Results`]: one case after the other, or
//! on rayon's workers (each with its own scratch space for setting a
//! case, reused from case to case); cases one at a time, or in groups of
//! [`GROUP`] that run in lockstep (see [the study docs](super#lockstep)).

use core::ops::Range;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::string::{String, ToString};
use std::vec::Vec;

use indicatif::ProgressBar;
use rayon::prelude::*;

use super::lockstep::GROUP;
use super::targets::{Setter, Target, resolve};
use super::{CaseError, Parallelism, Results, Study, StudyError, Task, progress};
use crate::{Model, StateArray};

/// A case's row of the results: its table values, kept values, error.
type Row<'a> = (&'a mut [f64], &'a mut [f64], &'a mut Option<String>);

/// Where cases run during one call: the pool, if any, and the bar.
pub(super) struct Runner {
    pool: Option<rayon::ThreadPool>,
    serial: bool,
    pub(super) bar: ProgressBar,
}

impl Runner {
    pub(super) fn new(
        parallelism: Parallelism,
        progress: bool,
        total: u64,
    ) -> Result<Runner, StudyError> {
        let pool = match parallelism {
            Parallelism::Threads(n) => Some(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n.max(1))
                    .build()
                    .map_err(|e| StudyError::ThreadPool(e.to_string()))?,
            ),
            Parallelism::Serial | Parallelism::AllCores => None,
        };
        Ok(Runner {
            pool,
            serial: parallelism == Parallelism::Serial,
            bar: progress::bar(progress, total),
        })
    }
}

impl<M, F, T> Study<M, F, T>
where
    M: Model,
    F: Fn() -> M + Sync,
    T: Task<M>,
{
    /// Runs cases `range` (indices into the table) and returns their
    /// results in memory: what a chunk of a distributed study runs.
    ///
    /// # Errors
    /// [`StudyError::OutOfRange`], a column that sets nothing, or a thread
    /// pool that cannot be made. Failed cases are not errors: see
    /// [`Results::errors`].
    pub fn run_cases(&self, range: Range<u64>) -> Result<Results, StudyError> {
        let runner = Runner::new(
            self.parallelism,
            self.progress,
            range.end.saturating_sub(range.start),
        )?;
        let results = self.execute(range, &runner)?;
        runner.bar.finish_and_clear();
        Ok(results)
    }

    pub(super) fn targets(&self) -> Result<Vec<Target>, StudyError> {
        resolve::<M>(self.cases.names(), &self.setup_columns)
    }

    /// Runs `range` with `runner`'s threads, ticking its bar; no case
    /// starts once the study is cancelled (then the results are dropped:
    /// [`StudyError::Cancelled`]).
    pub(super) fn execute(
        &self,
        range: Range<u64>,
        runner: &Runner,
    ) -> Result<Results, StudyError> {
        let len = self.cases.len();
        if range.start > range.end || range.end > len {
            return Err(StudyError::OutOfRange {
                start: range.start,
                end: range.end,
                len,
            });
        }
        let targets = self.targets()?;
        let count = usize::try_from(range.end - range.start)
            .map_err(|_| StudyError::InvalidCases("too many cases for one chunk".into()))?;
        let mut results = Results::blank(self.layout(), range.start, count);
        let mut rows = results.rows_mut();
        // A worker's scratch space: the parameter, input and setup vectors.
        let worker = || Setter::<M::Float>::new::<M>(self.setup_columns.len());
        let size = if self.in_lockstep() { GROUP } else { 1 };
        let first = |g: usize| range.start + (g * size) as u64;
        let group = |w: &mut Setter<M::Float>, (g, rows): (usize, &mut [Row<'_>])| {
            if self.cancelled() {
                return;
            }
            match rows {
                [(case, out, error)] => **error = self.run_case(&targets, w, first(g), case, out),
                _ => self.run_group(&targets, w, first(g), rows),
            }
            runner.bar.inc(rows.len() as u64);
        };
        if runner.serial {
            let mut w = worker();
            rows.chunks_mut(size)
                .enumerate()
                .for_each(|g| group(&mut w, g));
        } else {
            let mut all = || {
                rows.par_chunks_mut(size)
                    .enumerate()
                    .for_each_init(worker, group)
            };
            match &runner.pool {
                Some(pool) => pool.install(all),
                None => all(),
            }
        }
        if self.cancelled() {
            return Err(StudyError::Cancelled);
        }
        Ok(results)
    }

    /// Whether the study runs groups of cases in lockstep.
    fn in_lockstep(&self) -> bool {
        self.lockstep && M::LOCKSTEP && self.setup.is_none() && self.task.runs_in_lockstep()
    }

    /// Runs the group of cases `first..` (`rows`, at most [`GROUP`]) in
    /// lockstep, each on its own model; those that do not finish there,
    /// one at a time.
    fn run_group(
        &self,
        targets: &[Target],
        setter: &mut Setter<M::Float>,
        first: u64,
        rows: &mut [Row<'_>],
    ) {
        for (i, (case, _, _)) in rows.iter_mut().enumerate() {
            self.cases.case(first + i as u64, case);
        }
        let done = catch_unwind(AssertUnwindSafe(|| {
            self.run_together(targets, setter, rows)
        }))
        .unwrap_or([false; GROUP]);
        for (i, (case, out, error)) in rows.iter_mut().enumerate() {
            **error = match done[i] {
                true => None,
                false => self.run_case(targets, setter, first + i as u64, case, out),
            };
        }
    }

    /// Runs the cases of `rows` together ([`Task::run_group`]), each on a
    /// model of its own, set as `run_case` sets it; returns which
    /// finished.
    fn run_together(
        &self,
        targets: &[Target],
        setter: &mut Setter<M::Float>,
        rows: &mut [Row<'_>],
    ) -> [bool; GROUP] {
        let n = rows.len().min(GROUP);
        let mut models: [M; GROUP] = core::array::from_fn(|_| (self.make_model)());
        let mut xs = [M::State::zeros(); GROUP];
        let mut outs: [&mut [f64]; GROUP] = Default::default();
        for (i, (case, out, _)) in rows.iter_mut().enumerate().take(n) {
            xs[i] = setter.apply(targets, case, &mut models[i]);
            outs[i] = &mut **out;
        }
        M::lane_values(&models[..n], &mut setter.lane_values);
        let mut done = [false; GROUP];
        self.task.run_group(
            &mut models[..n],
            &mut setter.lane_values,
            &xs[..n],
            &mut outs[..n],
            &mut done[..n],
        );
        done
    }

    /// Runs case `index`: its table values into `case`, its kept values
    /// into `out` (NaN if it fails); returns its error.
    fn run_case(
        &self,
        targets: &[Target],
        setter: &mut Setter<M::Float>,
        index: u64,
        case: &mut [f64],
        out: &mut [f64],
    ) -> Option<String> {
        self.cases.case(index, case);
        let attempt = catch_unwind(AssertUnwindSafe(|| -> Result<(), CaseError> {
            let mut model = (self.make_model)();
            let mut x = setter.apply(targets, case, &mut model);
            if let Some(setup) = &self.setup {
                setup(&setter.setup, &mut model, &mut x)?;
            }
            self.task.run(&mut model, &mut x, out)
        }));
        let error = match attempt {
            Ok(Ok(())) => return None,
            Ok(Err(e)) => e,
            Err(panic) => CaseError::Panic(panic_message(panic.as_ref())),
        };
        out.fill(f64::NAN);
        Some(error.to_string())
    }
}

fn panic_message(panic: &(dyn core::any::Any + Send)) -> String {
    if let Some(s) = panic.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = panic.downcast_ref::<String>() {
        s.clone()
    } else {
        "(no message)".to_string()
    }
}
