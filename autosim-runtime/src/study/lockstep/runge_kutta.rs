//! One step of an explicit Runge–Kutta method (Euler, Heun, RK4) for
//! every lane of a group: what the fixed-step steppers do to one state.

use crate::integrate::{Tableau, check_step, combine_lane};
use crate::{Float, Model};

use super::{Lanes, Source};

/// One step of `tableau` from `t` by `h` for every lane: the step
/// checked, each stage one call for all lanes, the new state checked
/// before it replaces the old.
pub(in crate::study) fn runge_kutta_step<M: Model, const S: usize>(
    lanes: &mut Lanes<'_, M, S, ()>,
    tableau: &Tableau<S>,
    t: M::Float,
    h: M::Float,
) {
    if check_step(h).is_err() {
        lanes.n = 0;
        return;
    }
    lanes.evaluate(t, Source::Start, 0);
    for i in 1..S {
        for l in 0..lanes.n {
            combine_lane(
                &mut lanes.stage[l],
                &lanes.x[l],
                h,
                tableau.a[i],
                &lanes.k,
                l,
            );
        }
        lanes.evaluate(t + M::Float::from_f64(tableau.c[i]) * h, Source::Stage, i);
    }
    for l in 0..lanes.n {
        combine_lane(&mut lanes.stage[l], &lanes.x[l], h, &tableau.b, &lanes.k, l);
    }
    lanes.accept(t + h);
}
