//! Element-wise helpers on state arrays, shared by the integrators.
//!
//! All of them work in place on fixed arrays and never allocate.

use crate::{Float, IntegrationError, Model, StateArray, check_finite};

/// `out = x + h · Σ cᵢ·kᵢ`.
#[inline]
pub(crate) fn combine<F: Float, S: StateArray<F>>(out: &mut S, x: &S, h: F, terms: &[(F, &S)]) {
    combine_terms(out, x, h, terms.iter().copied());
}

/// `out = x + h · Σⱼ wⱼ·kⱼ` for one row `w` of a Butcher tableau (as many
/// terms as the shorter of `w` and `k`). Zero weights are left out, not
/// multiplied (`0·∞` would be NaN), so a row with zeros computes what the
/// list of its non-zero terms computes with [`combine`].
#[inline]
pub(crate) fn combine_row<F: Float, S: StateArray<F>>(
    out: &mut S,
    x: &S,
    h: F,
    weights: &[f64],
    k: &[S],
) {
    let terms = weights
        .iter()
        .zip(k)
        .filter(|(w, _)| **w != 0.0)
        .map(|(w, kj)| (F::from_f64(*w), kj));
    combine_terms(out, x, h, terms);
}

/// [`combine_row`] for one lane of stages kept lane by lane (`k[j][lane]`
/// is stage `j` of that lane, as a study's lockstep groups keep them):
/// `out = x + h·Σⱼ wⱼ·k[j][lane]`, the same terms summed in the same
/// order, so the same bits.
#[cfg(feature = "study")]
#[inline]
pub(crate) fn combine_lane<F: Float, S: StateArray<F>, const G: usize>(
    out: &mut S,
    x: &S,
    h: F,
    weights: &[f64],
    k: &[[S; G]],
    lane: usize,
) {
    let terms = weights
        .iter()
        .zip(k)
        .filter(|(w, _)| **w != 0.0)
        .map(|(w, kj)| (F::from_f64(*w), &kj[lane]));
    combine_terms(out, x, h, terms);
}

/// `out = x + h · Σ cᵢ·kᵢ` over `terms`, summed in their order.
#[inline]
fn combine_terms<'k, F, S>(
    out: &mut S,
    x: &S,
    h: F,
    terms: impl Iterator<Item = (F, &'k S)> + Clone,
) where
    F: Float,
    S: StateArray<F> + 'k,
{
    for (i, (o, xi)) in out.as_mut().iter_mut().zip(x.as_ref()).enumerate() {
        let mut sum = F::ZERO;
        for (c, k) in terms.clone() {
            if let Some(v) = k.as_ref().get(i) {
                sum += c * *v;
            }
        }
        *o = *xi + h * sum;
    }
}

/// The derivative evaluations since `before` (the counter's value when the
/// step began), saturated to `u32` for [`StepInfo::evaluations`](super::StepInfo).
#[inline]
pub(crate) fn evaluations_since(before: u64, now: u64) -> u32 {
    u32::try_from(now - before).unwrap_or(u32::MAX)
}

/// Root-mean-square of `errᵢ / (atol + rtol·max(|aᵢ|, |bᵢ|))`: the error
/// measure of adaptive methods (≤ 1 means "within tolerance").
#[inline]
pub(crate) fn weighted_rms<F: Float, S: StateArray<F>>(
    err: &S,
    a: &S,
    b: &S,
    rtol: F,
    atol: F,
) -> F {
    let mut sum = F::ZERO;
    for ((e, ai), bi) in err.as_ref().iter().zip(a.as_ref()).zip(b.as_ref()) {
        let scale = atol + rtol * ai.abs().max(bi.abs());
        let r = *e / scale;
        sum += r * r;
    }
    let n = S::LEN.max(1);
    (sum / F::from_f64(n as f64)).sqrt()
}

/// `true` if both arrays hold the same values (NaN never matches).
#[inline]
pub(crate) fn same<F: Float, S: StateArray<F>>(a: &S, b: &S) -> bool {
    a.as_ref() == b.as_ref()
}

/// Evaluates the model's derivatives, counting the call and turning a
/// [`ModelError`](crate::ModelError) into an [`IntegrationError`].
///
/// A model that fails at a state holding a NaN or an infinity (a stage of a
/// step that overflowed: a generated model then sees a NaN pivot and reports
/// a singular mass matrix) is reported as [`IntegrationError::NonFinite`]
/// naming that state: the overflow is the cause, not the mass matrix.
#[inline]
pub(crate) fn eval<M: Model>(
    model: &mut M,
    t: M::Float,
    x: &M::State,
    dx: &mut M::State,
    evaluations: &mut u64,
) -> Result<(), IntegrationError> {
    *evaluations += 1;
    model
        .derivatives(t, x, dx)
        .map_err(|error| evaluation_error::<M>(t, x, error))
}

/// What [`eval`] reports when the model fails with `error` at `(t, x)`:
/// [`IntegrationError::NonFinite`] naming the state if `x` is not finite
/// (the cause), [`IntegrationError::Model`] otherwise.
#[inline]
pub(crate) fn evaluation_error<M: Model>(
    t: M::Float,
    x: &M::State,
    error: crate::ModelError,
) -> IntegrationError {
    check_finite::<M>(t, x)
        .err()
        .unwrap_or(IntegrationError::Model {
            t: t.to_f64(),
            error,
        })
}

/// Rejects a step that is zero, NaN or infinite.
#[inline]
pub(crate) fn check_step<F: Float>(h: F) -> Result<(), IntegrationError> {
    if h.is_finite() && h != F::ZERO {
        Ok(())
    } else {
        Err(IntegrationError::InvalidSettings {
            reason: "the step must be finite and non-zero",
        })
    }
}
