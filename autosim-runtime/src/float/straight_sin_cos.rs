//! Sines and cosines in a fixed sequence of operations: pairs of angles
//! for every `f64` generated function (`Float::sin_cos_inline_lanes`),
//! single angles for the big ones (`Float::sin_cos_inline`).
//!
//! libm's `sincos` branches on the argument: on its size (up to π/4 it
//! skips the reduction) and on the quadrant (which of sine and cosine to
//! negate and swap). At random angles those branches are mispredicted
//! often, and in a function of thousands of straight-line operations a
//! mispredicted branch discards everything the processor had in flight.
//! Here the argument is reduced by the nearest multiple of π/2, the
//! polynomials of both are evaluated, and the quadrant swaps and negates
//! them with selects and sign bits: no branch depends on the angle
//! between 1e-9 and 1e6 in size (libm's `sincos` takes the rest, which
//! keeps `sin(-0) = -0`, NaN and infinities, and exact reductions of huge
//! arguments). Measured on the chains of `bench/peers`: chain-spatial-50
//! 2 773 → 2 468 ns, chain-planar-50 1 590 → 1 330 ns; for one angle in a
//! small function, whose time is its critical path, libm's shorter fast
//! path wins (chain-planar-5 87.5 ns with libm against 99.8), so generated
//! code calls the one-angle form only from big blocks; two angles at once
//! ([`sin_cos_lanes`]) beat two libm calls in every block.
//!
//! Accuracy: the reduction subtracts `k π/2` in three parts, the first two
//! exact for `|k| < 2^20`; the polynomials are the Taylor series to the
//! 17th and 18th powers (remainders under 1e-19 on `|r| ≤ π/4`), evaluated
//! by Estrin's scheme for a short dependency chain, with fused
//! multiply-adds where the target has them (`MulAdd`: the same bits as
//! the plain expressions elsewhere; chain-planar-20 and chain-planar-50
//! 5-6 % faster with them on an Intel Xeon), or always (the fast
//! copies of a default build, through [`Rounding`]). Against libm's and
//! the platform's values: within one unit in the last place up to 10 rad,
//! two up to 1e6 rad (`tests/straight_sin_cos.rs`).

use super::MulAdd;

/// How the kernel rounds `acc + a b` and `acc - a b`: [`AsTarget`] as the
/// crate's [`MulAdd`] does (fused where the target has FMA), or always
/// fused (`fused::Always`, for the fast copies of generated code).
pub(crate) trait Rounding {
    /// `acc + a b`.
    fn add_mul(acc: f64, a: f64, b: f64) -> f64;
    /// `acc - a b`.
    fn sub_mul(acc: f64, a: f64, b: f64) -> f64;
}

/// [`Rounding`] by the crate's [`MulAdd`].
pub(crate) struct AsTarget;

impl Rounding for AsTarget {
    #[inline(always)]
    fn add_mul(acc: f64, a: f64, b: f64) -> f64 {
        acc.add_mul(a, b)
    }
    #[inline(always)]
    fn sub_mul(acc: f64, a: f64, b: f64) -> f64 {
        acc.sub_mul(a, b)
    }
}

/// `1.5 · 2^52`: adding and subtracting it rounds to an integer.
pub(super) const ROUNDING: f64 = 6_755_399_441_055_744.0;
/// π/2 in three parts: the first 33 bits, the next 33, the rest.
pub(super) const PI_2_HI: f64 = 1.570_796_326_734_125_6;
pub(super) const PI_2_MID: f64 = 6.077_100_506_303_966e-11;
pub(super) const PI_2_LO: f64 = 2.022_266_248_795_950_6e-21;
/// `(-1)^k / (2k + 3)!` for `k = 0..8`: `sin r = r + r z Σ S[k] z^k`.
const S: [f64; 8] = [
    -1.0 / 6.0,
    1.0 / 120.0,
    -1.0 / 5_040.0,
    1.0 / 362_880.0,
    -1.0 / 39_916_800.0,
    1.0 / 6_227_020_800.0,
    -1.0 / 1_307_674_368_000.0,
    1.0 / 355_687_428_096_000.0,
];
/// `(-1)^k / (2k + 4)!` for `k = 0..8`: `cos r = 1 - z/2 + z² Σ C[k] z^k`.
const C: [f64; 8] = [
    1.0 / 24.0,
    -1.0 / 720.0,
    1.0 / 40_320.0,
    -1.0 / 3_628_800.0,
    1.0 / 479_001_600.0,
    -1.0 / 87_178_291_200.0,
    1.0 / 20_922_789_888_000.0,
    -1.0 / 6_402_373_705_728_000.0,
];

/// Sine and cosine of `x` (see the module documentation).
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    let ([sin], [cos]) = sin_cos_lanes_with::<AsTarget, 1>([x]);
    (sin, cos)
}

/// Sines and cosines of `N` angles, lane by lane the same operations, in
/// one loop over the lanes without branches (the quadrant from the rounded
/// value's low bits, the swap and signs by bit masks), which the compiler
/// turns into vector instructions where the target has them.
#[inline(always)]
pub fn sin_cos_lanes<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
    sin_cos_lanes_with::<AsTarget, N>(x)
}

/// [`sin_cos_lanes`] rounding as `R` says.
#[inline(always)]
pub(crate) fn sin_cos_lanes_with<R: Rounding, const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
    // Every lane compared, then one branch (`&`, not `&&`).
    if !x.iter().fold(true, |all, &x| all & in_range(x)) {
        return elsewhere::<R, N>(x);
    }
    let (mut sin, mut cos) = ([0.0; N], [0.0; N]);
    for lane in 0..N {
        (sin[lane], cos[lane]) = reduced::<R>(x[lane]);
    }
    (sin, cos)
}

/// Whether `x` takes the branch-free path.
#[inline(always)]
pub(super) fn in_range(x: f64) -> bool {
    (x.abs() >= 1.0e-9) & (x.abs() <= 1.0e6)
}

/// Sine and cosine of an angle [`in_range`], by its nearest multiple of
/// π/2 and the remainder.
#[inline(always)]
fn reduced<R: Rounding>(x: f64) -> (f64, f64) {
    // `1.5 · 2^52 + k`: its low bits are `k`'s (two's complement).
    let shifted = R::add_mul(ROUNDING, x, core::f64::consts::FRAC_2_PI);
    let k = shifted - ROUNDING;
    let r = R::sub_mul(
        R::sub_mul(R::sub_mul(x, k, PI_2_HI), k, PI_2_MID),
        k,
        PI_2_LO,
    );
    let (s, c) = near_zero::<R>(r);
    let quadrant = shifted.to_bits();
    let swap = 0u64.wrapping_sub(quadrant & 1);
    let (s, c) = (s.to_bits(), c.to_bits());
    let (s, c) = ((s & !swap) | (c & swap), (c & !swap) | (s & swap));
    (
        f64::from_bits(s ^ ((quadrant & 2) << 62)),
        f64::from_bits(c ^ ((quadrant.wrapping_add(1) & 2) << 62)),
    )
}

/// Sine and cosine of `|r| ≤ π/4`.
#[inline(always)]
fn near_zero<R: Rounding>(r: f64) -> (f64, f64) {
    let z = r * r;
    let z2 = z * z;
    let z4 = z2 * z2;
    let estrin = |p: &[f64; 8]| {
        let pair = |a: f64, b: f64| R::add_mul(a, b, z);
        let high = R::add_mul(pair(p[4], p[5]), z2, pair(p[6], p[7]));
        let low = R::add_mul(pair(p[0], p[1]), z2, pair(p[2], p[3]));
        R::add_mul(low, z4, high)
    };
    let sin = R::add_mul(r, r * z, estrin(&S));
    // 1 - z/2 rounded, then what that rounding lost, as in fdlibm.
    let half = 0.5 * z;
    let w = 1.0 - half;
    let cos = w + R::add_mul((1.0 - w) - half, z2, estrin(&C));
    (sin, cos)
}

/// [`sin_cos_lanes`] with a tiny, huge or non-finite angle: lane by lane,
/// libm's `sincos` for those (which keeps `sin(-0) = -0`, NaN and
/// infinities, and reduces huge angles exactly).
#[cold]
#[inline(never)]
fn elsewhere<R: Rounding, const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
    let pairs = x.map(|x| {
        if in_range(x) {
            reduced::<R>(x)
        } else {
            libm::sincos(x)
        }
    });
    (pairs.map(|p| p.0), pairs.map(|p| p.1))
}
