//! A sine or a cosine alone in a fixed sequence of operations: what
//! generated `f64` code computes for an angle whose sine or cosine it
//! needs but not both (`Float::sin_inline`, `Float::cos_inline`).
//!
//! libm's `sin` branches on the size of the argument and on its quadrant;
//! at random angles those branches are mispredicted often, and a
//! mispredicted branch discards everything the processor had in flight.
//! Here the argument is reduced by the nearest multiple of π (not π/2, as
//! the pair kernel in `straight_sin_cos.rs` does): the remainder's sine
//! is one odd polynomial on `[-π/2, π/2]` whatever the quadrant, and the
//! multiple's parity only flips the sign bit, so a lone sine or cosine is
//! half the pair kernel's work and has no branch on the angle between
//! 1e-9 and 1e6 in size (libm takes the rest, which keeps `sin(-0) = -0`,
//! NaN and infinities, and exact reductions of huge arguments). The
//! cosine is the sine of `x - (n + 1/2) π`, the same reduction by an odd
//! multiple of π/2.
//!
//! Accuracy: the reduction subtracts the multiple in three parts, the
//! first two products exact while the multiple of π/2 is below 2^20
//! (angles up to 1.6e6); the polynomial is the
//! minimax odd polynomial of degree 17 for the relative error of
//! `sin r` on `|r| ≤ π/2` (fitted by the Remez exchange in 60-digit
//! arithmetic: error 2.8e-19 before its coefficients are rounded),
//! evaluated by Estrin's scheme for a short dependency chain. Near
//! `|r| = π/2` the polynomial's terms are of the result's size, so their
//! roundings add up: within two units in the last place of libm's values
//! up to 1e6 rad (`tests/straight_sin_cos.rs`), against one for the pair
//! kernel, whose remainders are within π/4 (from the exact values,
//! measured once with 50-digit arithmetic over 60 000 angles up to 1e6:
//! 2.2 units at most, libm's 0.74).

use super::straight_sin_cos::{AsTarget, PI_2_HI, PI_2_LO, PI_2_MID, ROUNDING, Rounding, in_range};

/// `sin r = r + r z Σ ODD[k] z^k` with `z = r²`, `|r| ≤ π/2`.
const ODD: [f64; 8] = [
    -0.166_666_666_666_666_66,
    0.008_333_333_333_333_194,
    -0.000_198_412_698_412_092_18,
    2.755_731_921_113_729e-6,
    -2.505_210_687_280_364_6e-8,
    1.605_893_970_596_475e-10,
    -7.642_991_491_042_833e-13,
    2.721_174_980_538_557_2e-15,
];

/// The sine of `x`, fused where the target has FMA (the crate's
/// `MulAdd`).
#[inline(always)]
pub(crate) fn sin(x: f64) -> f64 {
    sin_with::<AsTarget>(x)
}

/// The cosine of `x`, fused where the target has FMA.
#[inline(always)]
pub(crate) fn cos(x: f64) -> f64 {
    cos_with::<AsTarget>(x)
}

/// The sine of `x`, rounding as `R` says.
#[inline(always)]
pub(crate) fn sin_with<R: Rounding>(x: f64) -> f64 {
    if !in_range(x) {
        return elsewhere(x, libm::sin);
    }
    // `1.5 · 2^52 + n` for the nearest multiple `n π`: its low bit is
    // `n`'s parity.
    let shifted = R::add_mul(ROUNDING, x, core::f64::consts::FRAC_1_PI);
    let n = shifted - ROUNDING;
    let negate = (shifted.to_bits() & 1) << 63;
    f64::from_bits(near_zero::<R>(reduce::<R>(x, n)).to_bits() ^ negate)
}

/// The cosine of `x`, rounding as `R` says: `(-1)^(n+1) sin(x - (n + 1/2) π)`
/// for the nearest such `n`.
#[inline(always)]
pub(crate) fn cos_with<R: Rounding>(x: f64) -> f64 {
    if !in_range(x) {
        return elsewhere(x, libm::cos);
    }
    let shifted = R::add_mul(-0.5, x, core::f64::consts::FRAC_1_PI) + ROUNDING;
    let n = shifted - ROUNDING;
    let negate = (shifted.to_bits().wrapping_add(1) & 1) << 63;
    f64::from_bits(near_zero::<R>(reduce::<R>(x, n + 0.5)).to_bits() ^ negate)
}

/// `x - m π` for a multiple `m` of 1/2 below 2^19 in size, in three
/// parts: `π/2`'s doubled, so that `m π` is `2m π/2`, the same products
/// and the same bits as the pair kernel's reduction, without the
/// doubling's latency.
#[inline(always)]
fn reduce<R: Rounding>(x: f64, m: f64) -> f64 {
    R::sub_mul(
        R::sub_mul(R::sub_mul(x, m, 2.0 * PI_2_HI), m, 2.0 * PI_2_MID),
        m,
        2.0 * PI_2_LO,
    )
}

/// The sine of `|r| ≤ π/2`.
#[inline(always)]
fn near_zero<R: Rounding>(r: f64) -> f64 {
    let z = r * r;
    let z2 = z * z;
    let z4 = z2 * z2;
    let pair = |a: f64, b: f64| R::add_mul(a, b, z);
    let high = R::add_mul(pair(ODD[4], ODD[5]), z2, pair(ODD[6], ODD[7]));
    let low = R::add_mul(pair(ODD[0], ODD[1]), z2, pair(ODD[2], ODD[3]));
    R::add_mul(r, r * z, R::add_mul(low, z4, high))
}

/// A tiny, huge or non-finite angle: libm's function.
#[cold]
#[inline(never)]
fn elsewhere(x: f64, libm: fn(f64) -> f64) -> f64 {
    libm(x)
}
