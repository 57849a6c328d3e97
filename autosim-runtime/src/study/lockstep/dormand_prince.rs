//! Dormand–Prince in lockstep: each case of a group runs as the run
//! driver runs it alone with [`DormandPrince`](crate::integrate::DormandPrince)
//! (its own step sizes, rejections and times, landing on the output
//! times), and every round each case takes one trial step: the six stages
//! of the four trials are six calls for the four states, each lane at its
//! own time. The first stage of a step is the last of the step before
//! (first same as last); the cases without it (all at the first step, a
//! case whose projection changed its state) evaluate it first, in one
//! call if all of them need it, alone otherwise.
//!
//! Each case's step-size control is the stepper's own
//! ([`Control`]): the same trials, the same acceptances, the same next
//! steps, so the same bits as the case run alone.

use crate::integrate::{
    Control, DOPRI5, DopriSettings, ERROR, check_trial_step, combine_lane, ends_at,
    evaluation_error,
};
use crate::run::{AdaptiveTrial, adaptive_trial};
use crate::{Float, Model, RunSettings, StateArray, StepInfo};

use super::super::simulate::Plan;
use super::{GROUP, LANES, Lanes, Source, begin, record};

/// What one case of a Dormand–Prince group carries from round to round:
/// where the run driver is (time, next trial step, steps, next output)
/// and the stepper's state (its step-size control, where its last step
/// ended).
pub(in crate::study) struct Adaptive<M: Model> {
    control: Control<M::Float>,
    /// The time reached.
    t: M::Float,
    /// The run driver's next trial step.
    h: M::Float,
    /// Steps accepted.
    steps: u64,
    /// The next output (0 is the start) and its first entry of the plan's
    /// `at` not yet written.
    output: u64,
    next_at: usize,
    /// The step in progress (its trials go on), as the run driver began
    /// it.
    stepping: Option<AdaptiveTrial<M::Float>>,
    /// The step needs its first stage evaluated.
    first_stage: bool,
    /// Every stage of this round's trial was evaluated: it is judged.
    evaluated: bool,
    /// `k[0]` holds the derivative where the last step ended, `(t_end,
    /// x_end)` (first same as last).
    fsal: bool,
    t_end: M::Float,
    x_end: M::State,
}

impl<M: Model> Clone for Adaptive<M> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M: Model> Copy for Adaptive<M> {}

impl<M: Model> Adaptive<M> {
    /// A case at the start of `settings` with the stepper `dopri`.
    fn new(dopri: DopriSettings<M::Float>, settings: &RunSettings<M::Float>) -> Self {
        Adaptive {
            control: Control::new(dopri),
            t: settings.start,
            h: settings.step,
            steps: 0,
            output: 0,
            next_at: 0,
            stepping: None,
            first_stage: false,
            evaluated: false,
            fsal: false,
            t_end: M::Float::ZERO,
            x_end: M::State::zeros(),
        }
    }
}

/// The lanes of a Dormand–Prince group: the seven stages, each case's
/// run.
type AdaptiveLanes<'m, M> = Lanes<'m, M, 7, Adaptive<M>>;

/// Runs the cases starting at `xs` (at most [`GROUP`]) together, case `k`
/// on `models[k]` (whose lane values are `values`), each as
/// [`run`](crate::run()) runs it with a fresh
/// [`DormandPrince`](crate::integrate::DormandPrince) of `dopri`;
/// `done[k]` is set for the cases that finished (their rows in `outs[k]`
/// written).
pub(in crate::study) fn simulate_adaptive<M: Model>(
    (models, values): (&mut [M], &mut [crate::Lanes<LANES>]),
    dopri: DopriSettings<M::Float>,
    settings: &RunSettings<M::Float>,
    plan: &Plan,
    xs: &[M::State],
    outs: &mut [&mut [f64]],
    done: &mut [bool],
) {
    let case = Adaptive::new(dopri, settings);
    let mut lanes = AdaptiveLanes::<M>::new(models, values, xs, case);
    lanes.n = lanes.n.min(outs.len()).min(done.len());
    for out in outs.iter_mut().take(lanes.n) {
        plan.begin(out);
    }
    begin(&mut lanes, settings.start);
    lanes.retain(|lanes, l| emit(lanes, l, (plan, outs)));
    loop {
        lanes.retain(|lanes, l| next_step(lanes, l, settings, (plan, outs), done));
        if lanes.n == 0 {
            return;
        }
        trial(&mut lanes);
        lanes.retain(|lanes, l| judge(lanes, l, settings, (plan, outs)));
    }
}

/// Output `output` of lane `l` at its time, recorded; `false` if the
/// outputs failed.
fn emit<M: Model>(
    lanes: &mut AdaptiveLanes<'_, M>,
    l: usize,
    (plan, outs): (&Plan, &mut [&mut [f64]]),
) -> bool {
    let c = lanes.carry[l];
    match record(lanes, l, (plan, outs), c.t, (c.output, c.next_at)) {
        Some(next_at) => {
            let c = &mut lanes.carry[l];
            c.next_at = next_at;
            c.output += 1;
            true
        }
        None => false,
    }
}

/// What the run driver does for lane `l` before a step: the outputs the
/// lane has reached, then the next step begun (its trial landing on the
/// next output time if it nearly reaches it). `false` if the lane leaves:
/// finished (its row ended, `done` set), or failed (the step limit, an
/// output).
fn next_step<M: Model>(
    lanes: &mut AdaptiveLanes<'_, M>,
    l: usize,
    settings: &RunSettings<M::Float>,
    (plan, outs): (&Plan, &mut [&mut [f64]]),
    done: &mut [bool],
) -> bool {
    if lanes.carry[l].stepping.is_some() {
        return true;
    }
    loop {
        let c = &mut lanes.carry[l];
        if c.output > settings.output_count() {
            let case = lanes.case[l];
            plan.end::<M>(outs[case], &lanes.x[l], plan.samples);
            done[case] = true;
            return false;
        }
        let t_out = settings.output_time(c.output);
        let Some(trial) = adaptive_trial(c.t, t_out, c.h) else {
            // Rounding only: there.
            c.t = t_out;
            if !emit(lanes, l, (plan, outs)) {
                return false;
            }
            continue;
        };
        if c.steps >= settings.max_steps || check_trial_step(trial.h).is_err() {
            return false;
        }
        let reuse = c.fsal && ends_at::<M>(c.t, &lanes.x[l], c.t_end, &c.x_end);
        c.fsal = false;
        c.first_stage = !reuse;
        c.control.begin(trial.h);
        c.stepping = Some(trial);
        return true;
    }
}

/// One trial of every lane: the first stage where it is needed (the
/// lanes whose model fails there leave), the lanes whose trial underflows
/// leave, then the six stages, each one call for the lanes whose trial no
/// stage has failed yet (a lane whose stage fails has its next trial
/// smaller, as the stepper does).
fn trial<M: Model>(lanes: &mut AdaptiveLanes<'_, M>) {
    let times = core::array::from_fn(|l| lanes.carry[l].t);
    let first: [bool; GROUP] = core::array::from_fn(|l| lanes.carry[l].first_stage);
    lanes.evaluate_at(&times, Source::Start, 0, first);
    lanes.retain(|lanes, l| {
        lanes.carry[l].first_stage = false;
        lanes.status[l].is_ok()
    });
    lanes.retain(|lanes, l| {
        let c = &lanes.carry[l];
        !c.control.underflows(c.t)
    });
    let n = lanes.n;
    let mut going = [true; GROUP];
    for i in 1..=6 {
        let mut times = [M::Float::ZERO; GROUP];
        for l in (0..n).filter(|&l| going[l]) {
            let (t, h) = (lanes.carry[l].t, lanes.carry[l].control.h);
            if i < 6 {
                combine_lane(
                    &mut lanes.stage[l],
                    &lanes.x[l],
                    h,
                    DOPRI5.a[i],
                    &lanes.k,
                    l,
                );
                times[l] = t + M::Float::from_f64(DOPRI5.c[i]) * h;
            } else {
                // The new state (fifth order); its derivative is the last
                // stage and the next step's first.
                combine_lane(&mut lanes.stage[l], &lanes.x[l], h, &DOPRI5.b, &lanes.k, l);
                times[l] = t + h;
            }
        }
        lanes.evaluate_at(&times, Source::Stage, i, going);
        for l in 0..n {
            if let (true, Err(error)) = (going[l], lanes.status[l]) {
                let e = evaluation_error::<M>(times[l], &lanes.stage[l], error);
                lanes.carry[l].control.stage_failed(e);
                going[l] = false;
            }
        }
    }
    for (case, evaluated) in lanes.carry[..n].iter_mut().zip(going) {
        case.evaluated = evaluated;
        if evaluated {
            case.control.stages_done();
        }
    }
}

/// The judgement of lane `l`'s trial (if all its stages were evaluated):
/// rejected, the lane tries again next round; accepted, the run driver's
/// bookkeeping after a step (the time, the next trial step, the
/// projection, the output it landed on). `false` if the lane leaves (the
/// projection or the outputs failed).
fn judge<M: Model>(
    lanes: &mut AdaptiveLanes<'_, M>,
    l: usize,
    settings: &RunSettings<M::Float>,
    (plan, outs): (&Plan, &mut [&mut [f64]]),
) -> bool {
    if !lanes.carry[l].evaluated {
        // A stage failed: the next trial is already set.
        return true;
    }
    let zeros = M::State::zeros();
    let mut err = zeros;
    let c = &mut lanes.carry[l];
    let (h, rejected) = (c.control.h, c.control.rejected);
    combine_lane(&mut err, &zeros, h, &ERROR, &lanes.k, l);
    let (x, x_new) = (&lanes.x[l], &lanes.stage[l]);
    let Some(h_next) = c.control.judge(c.t, x, x_new, &err, &lanes.k[6][l]) else {
        return true;
    };
    lanes.x[l] = *x_new;
    lanes.k[0][l] = lanes.k[6][l];
    (c.fsal, c.t_end, c.x_end) = (true, c.t + h, *x_new);
    let Some(trial) = c.stepping.take() else {
        return false;
    };
    // What the stepper reports for the step (`rejected`: this step's).
    let info = StepInfo {
        h,
        h_next,
        rejected,
        evaluations: 0,
    };
    let landed;
    (c.t, c.h, landed) = trial.accepted(c.t, c.h, &info);
    c.steps += 1;
    let tolerance = settings.projection_tolerance;
    let projected = lanes.models[l].project(c.t, &mut lanes.x[l], tolerance);
    projected.is_ok() && (!landed || emit(lanes, l, (plan, outs)))
}
