//! Lockstep: a simulation study integrates up to [`GROUP`] cases
//! together, each on its own model, each stage of each step evaluating
//! all of them in one [`Model::derivatives_each`] call (four states per
//! call of a generated model's `derivatives_lanes`, with the `lanes`
//! option, each lane reading its own case's parameters and inputs, at its
//! own time).
//!
//! # When
//!
//! The model must allow it: [`Model::LOCKSTEP`], which models generated
//! with the `lanes` option set (their `derivatives_each` is where the
//! time goes away, and the option already asks user code not to depend on
//! the order of calls). Other models run one case at a time: their
//! `derivatives_each` is one `derivatives` call per state, which gains
//! nothing (chain-spatial-10 without lanes ran 5 % slower in lockstep),
//! and user code that keeps state (allowed there, with fresh state per
//! case) would see the calls of four cases interleaved.
//!
//! A group is cases next to each other in the table (a chunk of
//! [`GROUP`]), whatever their parameters, inputs and initial states (a
//! parameter sweep, a Monte Carlo, a grid over initial conditions): each
//! case has its own model, set as it is when it runs alone, and the
//! lanes function reads each lane's parameters, constants and inputs from
//! its case's model (user code is called on the group's first model for
//! every lane: its results depend on its arguments alone). The study must
//! have no setup function (which may change a model in ways the lanes
//! cannot see). The task must say it can ([`Task::runs_in_lockstep`](super::Task)):
//! [`Simulate`](super::Simulate), with any method, of a model without
//! events or discrete variables (whose cases would take different steps
//! and actions at different times). Euler, Heun, RK4 and
//! Adams–Bashforth–Moulton take the same fixed steps in every case (each
//! Adams case keeps its own derivative history, see [`adams_step`]);
//! Dormand–Prince cases each take their own steps, one trial per case
//! per round, each at its own time (see [`simulate_adaptive`]).
//! [`Modes`](super::Modes) and [`Custom`](super::Custom) tasks run one
//! case at a time. [`Study::lockstep`](super::Study::lockstep) turns it
//! off.
//!
//! # Why this design
//!
//! The study already hands chunks of rows to rayon's workers, each with
//! its own scratch space; lockstep only makes the unit of work a chunk of
//! [`GROUP`] rows instead of one row, so threads, the progress bar, shards
//! and resuming are untouched, and nothing is shared between threads.
//! Each case keeps its own model, so a lane that leaves takes its model
//! with it, and the outputs, assembly and projection of each case are its
//! own model's. Each case does the arithmetic it does alone: the same
//! ticks (times and steps, [`fixed_ticks`], tested equal to the run
//! driver's; for each Dormand–Prince case, the adaptive driver's own
//! trial toward the next output time, `run::adaptive_trial`), the same
//! Runge–Kutta and Adams
//! combinations
//! ([`combine_lane`](crate::integrate::combine_lane) sums what the
//! single stepper's `combine_row` sums, in the same order; an Adams lane's
//! history is the single stepper's own type, with its own prediction,
//! correction and checks of what it still holds, and a Dormand–Prince
//! case's step-size control the stepper's
//! [`Control`](crate::integrate::Control)), and
//! `derivatives_each` gives each state the bits its model's `derivatives`
//! gives it (its contract, tested for generated models in
//! `tests/lanes.rs`). The
//! model's functions must be functions of their arguments (what
//! [`Model::LOCKSTEP`] promises).
//!
//! A case that fails any check the run driver makes (a derivative error,
//! a non-finite state or output, assembly or projection, the step limit)
//! leaves the group (the others go on, compacted, so the batch stays
//! contiguous, its lane values moved with it) and is run again alone by
//! the study: it fails exactly as it does alone, with the same error. A
//! case that finishes early (Dormand–Prince) leaves too. Two or three
//! lanes left of a full group still make one call of the lanes function
//! (see [`Lanes::evaluate_at`]); one lane, one `derivatives` call. A panic anywhere in a group runs
//! the whole group again, case by case. Nothing is allocated: the
//! workspaces are arrays of [`GROUP`] states on the worker's stack, the
//! models the study's, one per case of the group.

use crate::batch::LANES;
use crate::error::{check_finite_outputs, check_finite_parameters};
use crate::run::grid::{Tick, fixed_ticks};
use crate::{Model, ModelError, RunSettings, StateArray, check_finite};

use super::simulate::Plan;

mod adams;
mod dormand_prince;
mod runge_kutta;

pub(super) use adams::adams_step;
pub(super) use dormand_prince::simulate_adaptive;
pub(super) use runge_kutta::runge_kutta_step;

/// Cases integrated together: one batch of [`LANES`] states per stage.
pub(super) const GROUP: usize = LANES;

/// The cases of a group still running (the first `n` lanes, each with its
/// model), with the workspaces of a method of up to `S` stages and what
/// it carries from step to step for each lane (`C`: nothing for
/// Runge–Kutta methods, the derivative history for Adams methods).
pub(super) struct Lanes<'m, M: Model, const S: usize, C: Copy> {
    n: usize,
    /// The case (index into the group) each lane runs.
    case: [usize; GROUP],
    /// Each lane's model (its case's).
    models: &'m mut [M],
    /// What [`Model::lane_values`] gathered from the models, lane `l`
    /// the `l`-th model's (the lanes that leave take theirs along; the
    /// places past the lanes still running hold the first one's): valid
    /// if the group started full.
    values: &'m mut [crate::Lanes<LANES>],
    /// The group started with [`GROUP`] cases (and `values` is theirs).
    full: bool,
    x: [M::State; GROUP],
    /// `k[j][lane]`: stage `j`'s derivatives.
    k: [[M::State; GROUP]; S],
    /// The stages' states, then the new states.
    stage: [M::State; GROUP],
    status: [Result<(), ModelError>; GROUP],
    /// What each lane's method carries from step to step.
    carry: [C; GROUP],
}

/// Where [`Lanes::evaluate`] takes the states from.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Source {
    /// The lanes' states at the start of the step.
    Start,
    /// The stage states.
    Stage,
}

impl<'m, M: Model, const S: usize, C: Copy> Lanes<'m, M, S, C> {
    /// Lanes for the cases starting at `xs` on `models` (at most [`GROUP`],
    /// as many as both have), with the models' lane values, each lane
    /// carrying `carry` at first.
    fn new(
        models: &'m mut [M],
        values: &'m mut [crate::Lanes<LANES>],
        xs: &[M::State],
        carry: C,
    ) -> Lanes<'m, M, S, C> {
        let z = M::State::zeros();
        let mut x = [z; GROUP];
        let n = xs.len().min(models.len()).min(GROUP);
        x[..n].copy_from_slice(&xs[..n]);
        Lanes {
            n,
            case: core::array::from_fn(|l| l),
            models,
            values,
            full: n == GROUP,
            x,
            k: [[z; GROUP]; S],
            stage: [z; GROUP],
            status: [Ok(()); GROUP],
            carry: [carry; GROUP],
        }
    }

    /// Lane `l` leaves: the last lane takes its place (every array).
    fn remove(&mut self, l: usize) {
        let last = self.n - 1;
        self.case.swap(l, last);
        self.models.swap(l, last);
        self.x.swap(l, last);
        self.stage.swap(l, last);
        self.status.swap(l, last);
        self.carry.swap(l, last);
        for k in &mut self.k {
            k.swap(l, last);
        }
        self.n = last;
        if self.full && last > 0 {
            for v in self.values.iter_mut() {
                v.0.swap(l, last);
                // The places past the lanes running: the first lane's.
                let first = v.0[0];
                v.0[last..].fill(first);
            }
        }
    }

    /// Keeps the lanes for which `ok(self, lane)` holds.
    fn retain(&mut self, mut ok: impl FnMut(&mut Self, usize) -> bool) {
        for l in (0..self.n).rev() {
            if !ok(self, l) {
                self.remove(l);
            }
        }
    }

    /// The derivatives at time `t` of every lane's state `from` into
    /// `k[i]`, one call for all lanes; the lanes that fail leave.
    fn evaluate(&mut self, t: M::Float, from: Source, i: usize) {
        self.evaluate_some(t, from, i, [true; GROUP]);
    }

    /// [`Lanes::evaluate`] for the lanes `picked` alone.
    fn evaluate_some(&mut self, t: M::Float, from: Source, i: usize, picked: [bool; GROUP]) {
        self.evaluate_at(&[t; GROUP], from, i, picked);
        self.retain(|lanes, l| lanes.status[l].is_ok());
    }

    /// The derivatives of the lanes `picked`, each at its time `t[l]` and
    /// its state `from`, into `k[i]` and their status into `status` (`Ok`
    /// for the others; the lanes stay): one call for all if it picks
    /// every lane, one call each otherwise.
    ///
    /// A group that started full and has lost lanes still makes that one
    /// call for two or three lanes: the places of the lanes gone compute
    /// the first lane's derivative again (its values, time and state;
    /// their results are dropped), since one call for four costs less
    /// than two or three calls for one.
    fn evaluate_at(
        &mut self,
        t: &[M::Float; GROUP],
        from: Source,
        i: usize,
        picked: [bool; GROUP],
    ) {
        let n = self.n;
        self.status = [Ok(()); GROUP];
        let states = match from {
            Source::Start => &mut self.x,
            Source::Stage => &mut self.stage,
        };
        if picked[..n].iter().all(|p| *p) {
            let padded = self.full && n >= 2;
            let (m, values) = match padded {
                true => (GROUP, &*self.values),
                false => (n, &[][..]),
            };
            let mut times = *t;
            if padded {
                let (first, rest) = states.split_at_mut(n);
                rest.fill(first[0]);
                times[n..].fill(t[0]);
            }
            M::derivatives_each(
                &mut self.models[..m],
                values,
                &times[..m],
                &states[..m],
                &mut self.k[i][..m],
                &mut self.status[..m],
            );
            self.status[n..].fill(Ok(()));
            return;
        }
        for l in (0..n).filter(|&l| picked[l]) {
            M::derivatives_each(
                &mut self.models[l..=l],
                &[],
                &t[l..=l],
                &states[l..=l],
                &mut self.k[i][l..=l],
                &mut self.status[l..=l],
            );
        }
    }

    /// Each lane's new state `stage` replaces its state `x` if it is
    /// finite at `t`; the lanes whose new state is not leave.
    fn accept(&mut self, t: M::Float) {
        self.retain(|lanes, l| {
            let ok = check_finite::<M>(t, &lanes.stage[l]).is_ok();
            lanes.x[l] = lanes.stage[l];
            ok
        });
    }
}

/// What the run driver does at the start: each lane's parameters and
/// state checked, its state assembled; the lanes that fail leave.
fn begin<M: Model, const S: usize, C: Copy>(lanes: &mut Lanes<'_, M, S, C>, t: M::Float) {
    lanes.retain(|lanes, l| {
        let model = &mut lanes.models[l];
        check_finite_parameters(model, t).is_ok()
            && check_finite::<M>(t, &lanes.x[l]).is_ok()
            && model.assemble(t, &mut lanes.x[l]).is_ok()
    });
}

/// The outputs at `t` of every lane, checked and recorded as output `k`
/// of its case's row; the lanes that fail leave. Returns the next entry
/// of the plan's `at` (the same for every case).
fn emit<M: Model, const S: usize, C: Copy>(
    lanes: &mut Lanes<'_, M, S, C>,
    (plan, outs): (&Plan, &mut [&mut [f64]]),
    t: M::Float,
    (k, next_at): (u64, usize),
) -> usize {
    let mut next = next_at;
    lanes.retain(
        |lanes, l| match record(lanes, l, (plan, outs), t, (k, next_at)) {
            Some(after) => {
                next = after;
                true
            }
            None => false,
        },
    );
    next
}

/// The outputs at `t` of lane `l`, checked and recorded as output `k` of
/// its case's row (`next_at` the first entry of the plan's `at` not yet
/// written): the next entry, or `None` if the outputs failed.
fn record<M: Model, const S: usize, C: Copy>(
    lanes: &mut Lanes<'_, M, S, C>,
    l: usize,
    (plan, outs): (&Plan, &mut [&mut [f64]]),
    t: M::Float,
    (k, next_at): (u64, usize),
) -> Option<usize> {
    let mut y = M::Outputs::zeros();
    let x = &lanes.x[l];
    let ok =
        lanes.models[l].outputs(t, x, &mut y).is_ok() && check_finite_outputs::<M>(t, &y).is_ok();
    ok.then(|| plan.record::<M>(k, next_at, outs[lanes.case[l]], (x, &y, &[])))
}

/// Runs the cases starting at `xs` (at most [`GROUP`]) together, case `k`
/// on `models[k]` (whose lane values [`Model::lane_values`] gathered into
/// `values`), each lane carrying `carry` at first and stepped by `step`
/// (the lanes, the time, the step), as [`run`](crate::run()) runs each
/// with the fixed-step stepper `step` does for all; `done[k]` is set for
/// the cases that finished (their rows in `outs[k]` written). The models
/// of the cases that leave are swapped among `models`' first entries (the
/// study makes fresh ones for a case it runs again).
pub(super) fn simulate<'m, M: Model, const S: usize, C: Copy>(
    (models, values): (&'m mut [M], &'m mut [crate::Lanes<LANES>]),
    (carry, mut step): (C, impl FnMut(&mut Lanes<'m, M, S, C>, M::Float, M::Float)),
    settings: &RunSettings<M::Float>,
    plan: &Plan,
    xs: &[M::State],
    outs: &mut [&mut [f64]],
    done: &mut [bool],
) {
    let mut lanes = Lanes::<M, S, C>::new(models, values, xs, carry);
    lanes.n = lanes.n.min(outs.len()).min(done.len());
    for out in outs.iter_mut().take(lanes.n) {
        plan.begin(out);
    }
    begin(&mut lanes, settings.start);
    let (mut steps, mut k, mut next_at) = (0, 0, 0);
    let finished = fixed_ticks(settings, |tick| {
        match tick {
            Tick::Output(t) => {
                next_at = emit(&mut lanes, (plan, outs), t, (k, next_at));
                k += 1;
            }
            Tick::Step { t, h, t_end } => {
                if steps >= settings.max_steps {
                    // The step limit: every case fails alone.
                    return Err(());
                }
                step(&mut lanes, t, h);
                let tolerance = settings.projection_tolerance;
                lanes.retain(|lanes, l| {
                    lanes.models[l]
                        .project(t_end, &mut lanes.x[l], tolerance)
                        .is_ok()
                });
                steps += 1;
            }
        }
        // Nobody left: stop.
        if lanes.n == 0 { Err(()) } else { Ok(()) }
    });
    if finished.is_err() {
        return;
    }
    for l in 0..lanes.n {
        let case = lanes.case[l];
        plan.end::<M>(outs[case], &lanes.x[l], plan.samples);
        done[case] = true;
    }
}
