//! What the x86-64-v3 and x86-64-v4 copies of generated code compute
//! with: a [`MulAdd`] that always fuses (one rounding per `add_mul` and
//! `sub_mul`), and the math functions whose implementation uses it (the
//! branch-free sines and cosines) fused the same way; the others are the
//! plain ones.
//!
//! [`fast_path!`](crate::fast_path) imports these by name into the module
//! of each fast copy, where they shadow the model module's plain imports:
//! a fast copy then computes exactly what a build whose target has FMA
//! computes (`-C target-cpu=x86-64-v3` or `native` on such a processor),
//! `f64::mul_add` becoming one `vfmadd` in a function compiled with the
//! `fma` feature. With the `libm` feature, which asks for the bits of a
//! `no_std` build, nothing fuses here either.

use super::Float;
use super::lanes::Lanes;
use super::straight_sin::{cos_with, sin_with};
use super::straight_sin_cos::{Rounding, sin_cos_lanes_with};

/// `acc + a b` and `acc - a b`, each with one rounding (without the
/// `libm` feature): [`super::MulAdd`] as a target with FMA computes it.
pub trait MulAdd: Sized {
    /// `self + a * b`.
    fn add_mul(self, a: Self, b: Self) -> Self;
    /// `self - a * b`.
    fn sub_mul(self, a: Self, b: Self) -> Self;
}

/// The fused expression, or the plain one with the `libm` feature.
macro_rules! fused {
    ($fused:expr, $plain:expr) => {{
        #[cfg(not(feature = "libm"))]
        return $fused;
        #[cfg(feature = "libm")]
        return $plain;
    }};
}

macro_rules! impl_mul_add {
    ($t:ident) => {
        impl MulAdd for $t {
            #[inline(always)]
            fn add_mul(self, a: Self, b: Self) -> Self {
                fused!($t::mul_add(a, b, self), self + a * b)
            }
            #[inline(always)]
            fn sub_mul(self, a: Self, b: Self) -> Self {
                fused!($t::mul_add(-a, b, self), self - a * b)
            }
        }
    };
}

impl_mul_add!(f64);
impl_mul_add!(f32);

impl<const L: usize> MulAdd for Lanes<L> {
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add_mul(self, a: Self, b: Self) -> Self {
        let mut out = self;
        for l in 0..L {
            out.0[l] = self.0[l].add_mul(a.0[l], b.0[l]);
        }
        out
    }
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sub_mul(self, a: Self, b: Self) -> Self {
        let mut out = self;
        for l in 0..L {
            out.0[l] = self.0[l].sub_mul(a.0[l], b.0[l]);
        }
        out
    }
}

/// [`Rounding`] by this module's [`MulAdd`].
pub(crate) struct Always;

impl Rounding for Always {
    #[inline(always)]
    fn add_mul(acc: f64, a: f64, b: f64) -> f64 {
        MulAdd::add_mul(acc, a, b)
    }
    #[inline(always)]
    fn sub_mul(acc: f64, a: f64, b: f64) -> f64 {
        MulAdd::sub_mul(acc, a, b)
    }
}

/// The branch-free sines and cosines of `N` angles, fused, computed in
/// `f64` (as `Float::sin_cos_inline_lanes`).
#[inline(always)]
fn sin_cos_fused<F: Float, const N: usize>(x: [F; N]) -> ([F; N], [F; N]) {
    let (s, c) = sin_cos_lanes_with::<Always, N>(x.map(F::to_f64));
    (s.map(F::from_f64), c.map(F::from_f64))
}

/// [`float::math`](super::math) with the branch-free sines and cosines
/// fused.
pub mod math {
    pub use crate::float::math::*;

    /// [`sin_inline`](crate::float::math::sin_inline), fused.
    #[inline(always)]
    pub fn sin_inline<F: super::Float>(x: F) -> F {
        F::from_f64(super::sin_with::<super::Always>(x.to_f64()))
    }

    /// [`cos_inline`](crate::float::math::cos_inline), fused.
    #[inline(always)]
    pub fn cos_inline<F: super::Float>(x: F) -> F {
        F::from_f64(super::cos_with::<super::Always>(x.to_f64()))
    }

    /// [`sin_cos_inline`](crate::float::math::sin_cos_inline), fused.
    #[inline(always)]
    pub fn sin_cos_inline<F: super::Float>(x: F) -> (F, F) {
        let ([s], [c]) = super::sin_cos_fused([x]);
        (s, c)
    }

    /// [`sin_cos_lanes`](crate::float::math::sin_cos_lanes), fused.
    #[inline(always)]
    pub fn sin_cos_lanes<F: super::Float, const N: usize>(x: [F; N]) -> ([F; N], [F; N]) {
        super::sin_cos_fused(x)
    }
}

/// [`lanes::math`](super::lanes::math) with the branch-free sines and
/// cosines fused.
pub mod lanes_math {
    use crate::float::lanes::Lanes;
    pub use crate::float::lanes::math::*;

    /// [`sin_inline`](crate::float::lanes::math::sin_inline), fused.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn sin_inline<const L: usize>(x: Lanes<L>) -> Lanes<L> {
        x.map(super::math::sin_inline)
    }

    /// [`cos_inline`](crate::float::lanes::math::cos_inline), fused.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn cos_inline<const L: usize>(x: Lanes<L>) -> Lanes<L> {
        x.map(super::math::cos_inline)
    }

    /// [`sin_cos_inline`](crate::float::lanes::math::sin_cos_inline), fused.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn sin_cos_inline<const L: usize>(x: Lanes<L>) -> (Lanes<L>, Lanes<L>) {
        let (s, c) = super::sin_cos_fused(x.0);
        (Lanes(s), Lanes(c))
    }

    /// [`sin_cos_lanes`](crate::float::lanes::math::sin_cos_lanes), fused.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn sin_cos_lanes<const N: usize, const L: usize>(
        x: [Lanes<L>; N],
    ) -> ([Lanes<L>; N], [Lanes<L>; N]) {
        let (mut s, mut c) = ([Lanes::ZERO; N], [Lanes::ZERO; N]);
        for k in 0..N {
            (s[k], c[k]) = sin_cos_inline(x[k]);
        }
        (s, c)
    }
}

#[cfg(test)]
mod tests {
    use super::{Lanes, MulAdd, lanes_math, math};

    /// Random doubles over many binades, both signs (a fixed sequence).
    fn values(n: usize) -> impl Iterator<Item = f64> {
        let mut s: u64 = 0x9e37_79b9_7f4a_7c15;
        (0..n).map(move |_| {
            s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let mantissa = (s >> 11) as f64 / (1u64 << 53) as f64;
            let exponent = ((s >> 3) % 16) as i32 - 8;
            let sign = if s & 1 == 0 { 1.0 } else { -1.0 };
            sign * (1.0 + mantissa) * 2f64.powi(exponent)
        })
    }

    /// `add_mul` and `sub_mul` give the bits of `mul_add` (one rounding),
    /// for `f64`, `f32` and every lane of `Lanes`: `(1 + ε)(1 - ε) - 1` is
    /// `-ε²`, not the 0 of two roundings. With the `libm` feature nothing
    /// fuses.
    #[test]
    fn add_mul_is_mul_add() {
        let fused = !cfg!(feature = "libm");
        let e = f64::EPSILON;
        let expected = if fused { -(e * e) } else { 0.0 };
        assert_eq!((-1.0f64).add_mul(1.0 + e, 1.0 - e), expected);
        let e32 = f32::EPSILON;
        let expected32 = if fused { -(e32 * e32) } else { 0.0 };
        assert_eq!((-1.0f32).add_mul(1.0 + e32, 1.0 - e32), expected32);
        let mut v = values(3000);
        while let (Some(a), Some(b), Some(c)) = (v.next(), v.next(), v.next()) {
            let (add, sub) = if fused {
                (a.mul_add(b, c), (-a).mul_add(b, c))
            } else {
                (c + a * b, c - a * b)
            };
            assert_eq!(c.add_mul(a, b).to_bits(), add.to_bits());
            assert_eq!(c.sub_mul(a, b).to_bits(), sub.to_bits());
            let lanes = Lanes([c, a, b, c]).add_mul(Lanes([a, b, c, a]), Lanes([b, c, a, b]));
            assert_eq!(lanes.0[0].to_bits(), add.to_bits());
            let (a, b, c) = (a as f32, b as f32, c as f32);
            let add = if fused { a.mul_add(b, c) } else { c + a * b };
            assert_eq!(c.add_mul(a, b).to_bits(), add.to_bits());
        }
    }

    /// The fused sines and cosines: within an ulp of libm's up to 10 rad;
    /// in a build whose target has FMA, the bits of the crate's own
    /// (which fuse there), which is what the fast copies of a default
    /// build must give; lanes and single angles the same bits.
    #[test]
    fn fused_sines_are_the_fma_builds() {
        let fma_build = cfg!(all(target_feature = "fma", not(feature = "libm")));
        for x in values(4000).map(|x| x * 1.2) {
            let (s, c) = math::sin_cos_inline(x);
            let ulp = |v: f64| f64::EPSILON * v.abs().max(f64::MIN_POSITIVE);
            assert!((s - libm::sin(x)).abs() <= ulp(s), "sin {x}");
            assert!((c - libm::cos(x)).abs() <= ulp(c), "cos {x}");
            if fma_build {
                let plain = crate::float::math::sin_cos_inline(x);
                assert_eq!(
                    (s.to_bits(), c.to_bits()),
                    (plain.0.to_bits(), plain.1.to_bits())
                );
            }
            let ([s2, _], [c2, _]) = math::sin_cos_lanes([x, 0.5]);
            assert_eq!((s2.to_bits(), c2.to_bits()), (s.to_bits(), c.to_bits()));
            let (ls, lc) = lanes_math::sin_cos_inline(Lanes([0.25, x, 1.0, -x]));
            assert_eq!(
                (ls.0[1].to_bits(), lc.0[1].to_bits()),
                (s.to_bits(), c.to_bits())
            );
            let x32 = x as f32;
            let (s64, c64) = math::sin_cos_inline(f64::from(x32));
            assert_eq!(math::sin_cos_inline(x32), (s64 as f32, c64 as f32));
        }
    }

    /// The fused lone sine and cosine: within `2ε` of libm's relative to
    /// the value (`tests/straight_sin_cos.rs` counts units in the last
    /// place) at angles over sixteen binades, up to about 300 rad; in a build
    /// whose target has FMA, the bits of the crate's own; lane by lane the
    /// same bits.
    #[test]
    fn fused_lone_sines_are_the_fma_builds() {
        let fma_build = cfg!(all(target_feature = "fma", not(feature = "libm")));
        for x in values(4000).map(|x| x * 1.2) {
            let (s, c) = (math::sin_inline(x), math::cos_inline(x));
            let two_ulps = |v: f64| 2.0 * f64::EPSILON * v.abs().max(f64::MIN_POSITIVE);
            assert!((s - libm::sin(x)).abs() <= two_ulps(s), "sin {x}");
            assert!((c - libm::cos(x)).abs() <= two_ulps(c), "cos {x}");
            if fma_build {
                let plain = (
                    crate::float::math::sin_inline(x),
                    crate::float::math::cos_inline(x),
                );
                assert_eq!(
                    (s.to_bits(), c.to_bits()),
                    (plain.0.to_bits(), plain.1.to_bits())
                );
            }
            let lanes = Lanes([0.25, x, 1.0, -x]);
            let (ls, lc) = (lanes_math::sin_inline(lanes), lanes_math::cos_inline(lanes));
            assert_eq!(
                (ls.0[1].to_bits(), lc.0[1].to_bits()),
                (s.to_bits(), c.to_bits())
            );
        }
    }
}
