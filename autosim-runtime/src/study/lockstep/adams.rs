//! One Adams–Bashforth–Moulton step for every lane of a group: what
//! [`AdamsBashforthMoulton`](crate::integrate::AdamsBashforthMoulton)
//! does to one state, with each lane's own derivative history.
//!
//! Every lane steps at the same times by the same steps, so the history
//! of every lane is usually in the same condition (empty at the start,
//! filling for the first steps, full after): then every evaluation is
//! one call for all lanes. A lane whose state changed outside the step
//! (a projection onto its constraints) loses its history alone and takes
//! RK4 start-up steps while the others predict and correct: the
//! evaluations only it needs are one call for it alone; the two at the
//! end of the step (RK4's last stage or the corrector's evaluation at the
//! predicted state, then the derivative at the new state) are one call
//! for all lanes either way.

use crate::integrate::{AbmHistory, AbmOrder, RK4, check_step, combine_lane};
use crate::{Float, Model};

use super::{GROUP, Lanes, Source};

/// The lanes of an Adams–Bashforth–Moulton group: RK4's four stage
/// workspaces (for start-up steps), each lane's history.
pub(in crate::study) type AdamsLanes<'m, M> = Lanes<'m, M, 4, AbmHistory<M>>;

/// One step of the `order` pair from `t` by `h` for every lane, each
/// from its own history.
pub(in crate::study) fn adams_step<M: Model>(
    lanes: &mut AdamsLanes<'_, M>,
    order: AbmOrder,
    t: M::Float,
    h: M::Float,
) {
    if check_step(h).is_err() {
        lanes.n = 0;
        return;
    }
    for l in 0..lanes.n {
        lanes.carry[l].validate(t, &lanes.x[l], h);
    }
    // The derivative at the start, for the lanes that have none.
    let empty = core::array::from_fn(|l| lanes.carry[l].is_empty());
    lanes.evaluate_some(t, Source::Start, 0, empty);
    for l in 0..lanes.n {
        let history = &mut lanes.carry[l];
        if history.is_empty() {
            history.begin(&lanes.k[0][l]);
        }
        lanes.k[0][l] = *history.newest();
    }
    // RK4's middle stages, for the lanes starting up.
    for i in 1..3 {
        let starts: [bool; GROUP] = core::array::from_fn(|l| lanes.carry[l].starts_up(order));
        for l in (0..lanes.n).filter(|&l| starts[l]) {
            combine_lane(&mut lanes.stage[l], &lanes.x[l], h, RK4.a[i], &lanes.k, l);
        }
        let t_stage = t + M::Float::from_f64(RK4.c[i]) * h;
        lanes.evaluate_some(t_stage, Source::Stage, i, starts);
    }
    // At the end of the step, for every lane: RK4's last stage, or the
    // Adams–Bashforth prediction.
    for l in 0..lanes.n {
        if lanes.carry[l].starts_up(order) {
            combine_lane(&mut lanes.stage[l], &lanes.x[l], h, RK4.a[3], &lanes.k, l);
        } else {
            lanes.carry[l].predict(order, &mut lanes.stage[l], &lanes.x[l], h);
        }
    }
    // RK4's `c` is 1 there: `t + 1·h` is `t + h` to the bit.
    lanes.evaluate(t + h, Source::Stage, 3);
    for l in 0..lanes.n {
        if lanes.carry[l].starts_up(order) {
            combine_lane(&mut lanes.stage[l], &lanes.x[l], h, &RK4.b, &lanes.k, l);
        } else {
            let fp = lanes.k[3][l];
            lanes.carry[l].correct(order, &mut lanes.stage[l], &lanes.x[l], h, &fp);
        }
    }
    lanes.accept(t + h);
    // The derivative at the new state, for the history.
    lanes.evaluate(t + h, Source::Start, 0);
    for l in 0..lanes.n {
        let (x, f) = (lanes.x[l], lanes.k[0][l]);
        lanes.carry[l].accept(t, h, &x, &f);
    }
}
