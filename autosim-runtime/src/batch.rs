//! Derivatives at many states in one call: of one model
//! ([`Model::derivatives_batch`]) or of several, each at its own time
//! and state ([`Model::derivatives_each`], a study's cases in lockstep).
//! Generated
//! `f64` models with the `lanes` option evaluate [`LANES`] states at a
//! time through their `derivatives_lanes` (struct of arrays, vector
//! instructions), the same bits as one call per state; every other model
//! loops over single calls.

use crate::float::lanes::Lanes;
use crate::model::{Model, ModelError};

/// States a generated model evaluates together in
/// [`Model::derivatives_batch`]: four `f64`, one AVX2 register per value
/// (eight measured slower on AVX2, `examples/perf.rs`).
pub const LANES: usize = 4;

/// [`Model::derivatives_batch`] through a model's lanes function `lanes`
/// (generated models' override): states in groups of `L`, transposed to
/// struct of arrays; a group in which any state fails (a singular pivot,
/// a non-finite derivative or user result) is evaluated again state by
/// state, so that each state gets exactly the result one call gives it;
/// the states left over after the last full group, one call each.
///
/// Processes as many states as the shortest of `x`, `dx`, `status` holds.
/// Public for other lane counts than [`LANES`]: with a generated model
/// `m` and its values gathered once, `let v = M::values_in_lanes([&m;
/// 8]);`, `in_lanes::<_, 8, N>(&mut m, t, &x, &mut dx, &mut status, |m, t,
/// x, dx| m.derivatives_lanes_with(&v, t, x, dx))` evaluates eight states
/// per call (`t` there is the time in every lane).
#[inline]
pub fn in_lanes<M, const L: usize, const N: usize>(
    model: &mut M,
    t: f64,
    x: &[[f64; N]],
    dx: &mut [[f64; N]],
    status: &mut [Result<(), ModelError>],
    mut lanes: impl FnMut(
        &mut M,
        Lanes<L>,
        &[Lanes<L>; N],
        &mut [Lanes<L>; N],
    ) -> Result<(), ModelError>,
) where
    M: Model<Float = f64, State = [f64; N]> + ?Sized,
{
    let count = x.len().min(dx.len()).min(status.len());
    let mut soa_dx = [Lanes::<L>::ZERO; N];
    for range in full_groups::<L>(count) {
        let soa_x = struct_of_arrays::<L, N>(&x[range.clone()]);
        match lanes(model, Lanes::splat(t), &soa_x, &mut soa_dx) {
            Ok(()) => scatter(&soa_dx, &mut dx[range.clone()], &mut status[range]),
            Err(_) => one_by_one(
                model,
                t,
                &x[range.clone()],
                &mut dx[range.clone()],
                &mut status[range],
            ),
        }
    }
    let rest = count / L * L..count;
    one_by_one(
        model,
        t,
        &x[rest.clone()],
        &mut dx[rest.clone()],
        &mut status[rest],
    );
}

/// The ranges of the full groups of `L` among `count` states.
fn full_groups<const L: usize>(count: usize) -> impl Iterator<Item = core::ops::Range<usize>> {
    (0..count / L).map(|g| g * L..(g + 1) * L)
}

/// `L` states (the first `L` of `x`) as struct of arrays: state `i` of
/// the `l`-th in lane `l` of entry `i`.
#[inline]
fn struct_of_arrays<const L: usize, const N: usize>(x: &[[f64; N]]) -> [Lanes<L>; N] {
    core::array::from_fn(|i| Lanes(core::array::from_fn(|l| x[l][i])))
}

/// [`Model::lane_values`] through a model's gather of one group, `of`
/// (generated models' override): `values[g * K..(g + 1) * K]` is
/// `of` the `g`-th full group of `L` models, as far as `values` reaches.
#[inline]
pub fn values_in_groups<M, const L: usize, const K: usize>(
    models: &[M],
    values: &mut [Lanes<L>],
    of: impl Fn([&M; L]) -> [Lanes<L>; K],
) {
    if K == 0 {
        return;
    }
    for (group, v) in models.chunks_exact(L).zip(values.chunks_exact_mut(K)) {
        v.copy_from_slice(&of(core::array::from_fn(|l| &group[l])));
    }
}

/// [`Model::derivatives_each`] through a model's lanes function `lanes`
/// (generated models' override): `models[k]` at time `t[k]` and state
/// `x[k]`, in groups of
/// `L` whose lane `l` reads the values of the group's `l`-th model
/// (`values[g * K..(g + 1) * K]`, what [`values_in_groups`] gathered)
/// while user code is called on the group's first model (what
/// [`Model::LOCKSTEP`] allows). A group whose values `values` does not
/// hold, a group in which any state fails, and the models left over after
/// the last full group are evaluated one call each, so that each state
/// gets exactly the result its model's [`Model::derivatives`] gives it.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn each_in_lanes<M, const L: usize, const K: usize, const N: usize>(
    models: &mut [M],
    values: &[Lanes<L>],
    t: &[f64],
    x: &[[f64; N]],
    dx: &mut [[f64; N]],
    status: &mut [Result<(), ModelError>],
    mut lanes: impl FnMut(
        &mut M,
        &[Lanes<L>; K],
        Lanes<L>,
        &[Lanes<L>; N],
        &mut [Lanes<L>; N],
    ) -> Result<(), ModelError>,
) where
    M: Model<Float = f64, State = [f64; N]>,
{
    let count = models.len().min(t.len()).min(x.len());
    let count = count.min(dx.len()).min(status.len());
    let mut soa_dx = [Lanes::<L>::ZERO; N];
    for (g, range) in full_groups::<L>(count).enumerate() {
        let group = &mut models[range.clone()];
        let v = values
            .get(g * K..(g + 1) * K)
            .and_then(|v| <&[Lanes<L>; K]>::try_from(v).ok());
        let soa_t = Lanes(core::array::from_fn(|l| t[range.start + l]));
        let soa_x = struct_of_arrays::<L, N>(&x[range.clone()]);
        match v.map(|v| lanes(&mut group[0], v, soa_t, &soa_x, &mut soa_dx)) {
            Some(Ok(())) => scatter(&soa_dx, &mut dx[range.clone()], &mut status[range]),
            _ => each_alone(
                group,
                &t[range.clone()],
                &x[range.clone()],
                &mut dx[range.clone()],
                &mut status[range],
            ),
        }
    }
    let rest = count / L * L..count;
    each_alone(
        &mut models[rest.clone()],
        &t[rest.clone()],
        &x[rest.clone()],
        &mut dx[rest.clone()],
        &mut status[rest],
    );
}

/// Lane `l` of the struct-of-arrays derivatives `soa_dx` into `dx[l]`, its
/// status `Ok`.
#[inline]
fn scatter<const L: usize, const N: usize>(
    soa_dx: &[Lanes<L>; N],
    dx: &mut [[f64; N]],
    status: &mut [Result<(), ModelError>],
) {
    for (l, (d, s)) in dx.iter_mut().zip(status).enumerate() {
        *d = core::array::from_fn(|i| soa_dx[i].0[l]);
        *s = Ok(());
    }
}

/// One [`Model::derivatives`] call per model, each at its time and
/// state: the default [`Model::derivatives_each`].
#[inline]
pub fn each_alone<M: Model>(
    models: &mut [M],
    t: &[M::Float],
    x: &[M::State],
    dx: &mut [M::State],
    status: &mut [Result<(), ModelError>],
) {
    for ((((m, t), x), dx), s) in models
        .iter_mut()
        .zip(t)
        .zip(x)
        .zip(dx.iter_mut())
        .zip(status.iter_mut())
    {
        *s = m.derivatives(*t, x, dx);
    }
}

/// One [`Model::derivatives`] call per state: the default
/// [`Model::derivatives_batch`].
#[inline]
pub fn one_by_one<M: Model + ?Sized>(
    model: &mut M,
    t: M::Float,
    x: &[M::State],
    dx: &mut [M::State],
    status: &mut [Result<(), ModelError>],
) {
    for ((x, dx), s) in x.iter().zip(dx.iter_mut()).zip(status.iter_mut()) {
        *s = model.derivatives(t, x, dx);
    }
}
