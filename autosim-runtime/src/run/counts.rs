//! Counting fixed steps and outputs between two times, forgiving what
//! rounding the model's float type puts into the times: the one place
//! where the driver (`advance_fixed`), the lockstep ticks (`grid.rs`) and
//! the output count decide how many steps a span holds and whether two
//! times are the same.
//!
//! The allowance is 64 ε relative to the times' size, but never more than
//! 1/64 of the step: in `f32` 64 ε of a time `2^17` steps from zero is a
//! whole step, and a larger allowance skipped steps (a sampled run at
//! 1 kHz stopped integrating after 131 s and still ended `Ok`).

use crate::Float;

/// The difference between two times of size `scale` that is rounding
/// for a run of fixed `step`: `min(64 ε scale, |step| / 64)`.
pub(crate) fn rounding<F: Float>(scale: F, step: F) -> F {
    let relative = F::from_f64(64.0) * F::EPSILON * scale.abs();
    let cap = step.abs() / F::from_f64(64.0);
    if relative < cap { relative } else { cap }
}

/// ⌈span / step⌉ as a count: a quotient above an integer by no more than
/// the [`rounding`] of times of size `scale` (in steps), or by 1e-9
/// relative, is that integer.
pub(super) fn step_count<F: Float>(span: F, step: F, scale: F) -> u64 {
    let steps = span.to_f64() / step.to_f64();
    let forgiven = (rounding(scale, step) / step.abs()).to_f64();
    ceil_count(steps, forgiven)
}

/// ⌈v⌉ as a count, treating values within `forgiven` or 1e-9 (relative)
/// above an integer as that integer (so 1.0000000000002 intervals are 1,
/// not 2). Zero for non-positive or NaN values; saturates for huge ones.
fn ceil_count(v: f64, forgiven: f64) -> u64 {
    if v.is_nan() || v <= 0.0 {
        return 0;
    }
    let v = v - (1e-9 * v.max(1.0)).max(forgiven);
    if v.is_nan() || v <= 0.0 {
        return 0;
    }
    // `as` saturates; the comparison rounds up a fractional part.
    let i = v as u64;
    if (i as f64) < v {
        i.saturating_add(1)
    } else {
        i
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ceil_count_rounds_up_but_forgives_rounding_noise() {
        assert_eq!(ceil_count(0.0, 0.0), 0);
        assert_eq!(ceil_count(-3.0, 0.0), 0);
        assert_eq!(ceil_count(f64::NAN, 0.0), 0);
        assert_eq!(ceil_count(1.0, 0.0), 1);
        assert_eq!(ceil_count(1.0 + 1e-13, 0.0), 1);
        assert_eq!(ceil_count(1.01, 0.0), 2);
        assert_eq!(ceil_count(10.0 / 0.1, 0.0), 100);
        assert_eq!(ceil_count(2.5, 0.0), 3);
        assert_eq!(ceil_count(1e300, 0.0), u64::MAX);
        assert_eq!(ceil_count(7.001, 0.01), 7);
    }

    /// In `f32`, sample instants `j · 1 ms` past `2^17` are a rounding
    /// apart from the grid, never a whole step.
    #[test]
    fn f32_times_far_from_zero_count_their_steps() {
        let step = 1e-3f32;
        for j in [131_072u32, 131_073, 200_000] {
            let t = j as f32 * step;
            assert_eq!(step_count(t, step, t), u64::from(j), "at {t}");
            assert!(rounding(t, step) <= step / 64.0);
            // Three tenths of a step more is one step more.
            assert_eq!(step_count(t + 0.3 * step, step, t), u64::from(j) + 1);
        }
        // f64 keeps its allowance far below a step.
        assert_eq!(rounding(1e3, 1e-3f64), 64.0 * f64::EPSILON * 1e3);
    }
}
