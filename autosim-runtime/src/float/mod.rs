//! The float types models compute in, and the math functions generated code calls.

use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

pub(crate) mod dispatch;
#[cfg(feature = "std")]
pub mod fused;
pub(crate) mod lanes;
mod straight_sin;
mod straight_sin_cos;

/// A float type a model can compute in: `f32` or `f64`.
pub trait Float:
    Copy
    + Default
    + PartialEq
    + PartialOrd
    + core::fmt::Debug
    + core::fmt::Display
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
    + 'static
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// Machine epsilon.
    const EPSILON: Self;
    /// Converts from `f64` (rounding for `f32`).
    fn from_f64(x: f64) -> Self;
    /// Converts to `f64`.
    fn to_f64(self) -> f64;
    /// `true` unless NaN or infinite.
    fn is_finite(self) -> bool;
    /// Absolute value.
    fn abs(self) -> Self;
    /// Square root.
    fn sqrt(self) -> Self;
    /// Sine.
    fn sin(self) -> Self;
    /// Cosine.
    fn cos(self) -> Self;
    /// Sine and cosine together (cheaper than both separately).
    fn sin_cos(self) -> (Self, Self);
    /// Sine and cosine together without branches on the angle (a fixed
    /// sequence of operations inlined where it is called; within one unit
    /// in the last place of [`Float::sin_cos`] up to 10 rad, two up to
    /// 1e6): for big functions, where a mispredicted branch costs most.
    fn sin_cos_inline(self) -> (Self, Self);
    /// [`Float::sin_cos_inline`] of `N` angles at once, the same values,
    /// in vector instructions where the target has them.
    fn sin_cos_inline_lanes<const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]);
    /// Sine without branches on the angle (a fixed sequence of operations
    /// inlined where it is called, computed in `f64`; within two units in
    /// the last place of [`Float::sin`] up to 1e6 rad): what generated
    /// `f64` code computes for an angle whose cosine it does not need.
    fn sin_inline(self) -> Self;
    /// Cosine without branches on the angle, as [`Float::sin_inline`].
    fn cos_inline(self) -> Self;
    /// Tangent.
    fn tan(self) -> Self;
    /// Arc sine.
    fn asin(self) -> Self;
    /// Arc cosine.
    fn acos(self) -> Self;
    /// Arc tangent of `self / x` with the quadrant of `(x, self)`.
    fn atan2(self, x: Self) -> Self;
    /// e^self.
    fn exp(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// self^e for a float exponent.
    fn powf(self, e: Self) -> Self;
    /// self^n for an integer exponent.
    fn powi(self, n: i32) -> Self;
    /// The larger of two values (NaN-ignoring like `f64::max`).
    fn max(self, other: Self) -> Self;
    /// The smaller of two values.
    fn min(self, other: Self) -> Self;
}

/// Functions that only pass their arguments on: each line
/// `fn name(args) -> R => target;` becomes an `#[inline(always)]` function
/// calling `target(args)`. Methods take `self` first; free functions take a
/// visibility (`pub fn`).
macro_rules! forward {
    ($(fn $name:ident(self $(, $arg:ident: $ty:ty)*) -> $ret:ty => $($target:ident)::+;)+) => {
        $(
            #[inline(always)]
            fn $name(self $(, $arg: $ty)*) -> $ret {
                $($target)::+(self $(, $arg)*)
            }
        )+
    };
    ($(pub fn $name:ident($($arg:ident: $ty:ty),+) -> $ret:ty => $($target:ident)::+;)+) => {
        $(
            #[inline(always)]
            pub fn $name($($arg: $ty),+) -> $ret {
                $($target)::+($($arg),+)
            }
        )+
    };
}

/// [`Float`] for `f32` or `f64`: the basic operations from `core`, the math
/// functions from `imp` (std or libm).
macro_rules! impl_float {
    ($t:ident) => {
        impl Float for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const EPSILON: Self = $t::EPSILON;
            #[inline(always)]
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            #[inline(always)]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline(always)]
            fn sin_cos_inline_lanes<const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]) {
                imp::$t::sin_cos_inline_lanes(x)
            }
            forward! {
                fn is_finite(self) -> bool => $t::is_finite;
                fn abs(self) -> Self => $t::abs;
                fn sqrt(self) -> Self => imp::$t::sqrt;
                fn sin(self) -> Self => imp::$t::sin;
                fn cos(self) -> Self => imp::$t::cos;
                fn sin_cos(self) -> (Self, Self) => imp::$t::sin_cos;
                fn sin_cos_inline(self) -> (Self, Self) => imp::$t::sin_cos_inline;
                fn sin_inline(self) -> Self => imp::$t::sin_inline;
                fn cos_inline(self) -> Self => imp::$t::cos_inline;
                fn tan(self) -> Self => imp::$t::tan;
                fn asin(self) -> Self => imp::$t::asin;
                fn acos(self) -> Self => imp::$t::acos;
                fn atan2(self, x: Self) -> Self => imp::$t::atan2;
                fn exp(self) -> Self => imp::$t::exp;
                fn ln(self) -> Self => imp::$t::ln;
                fn powf(self, e: Self) -> Self => imp::$t::powf;
                fn powi(self, n: i32) -> Self => imp::$t::powi;
                fn max(self, other: Self) -> Self => $t::max;
                fn min(self, other: Self) -> Self => $t::min;
            }
        }
    };
}

impl_float!(f64);
impl_float!(f32);

/// Sums of products for generated code: `acc.add_mul(a, b)` is
/// `acc + a * b`, `acc.sub_mul(a, b)` is `acc - a * b`. Each is one fused
/// multiply-add (a single rounding) where the target has the instruction
/// and `std` provides it (`-C target-cpu=native` on current x86-64, every
/// 64-bit Arm); otherwise exactly the bits of the plain expression. The
/// decision is the crate's target features: the x86-64-v3 and x86-64-v4
/// copies a default build adds of generated `derivatives`
/// (`dispatch.rs`) use `fused::MulAdd` instead, which always fuses (the
/// bits of a build with FMA), so they differ from the baseline copy in
/// the last bits.
pub trait MulAdd: Sized {
    /// `self + a * b`.
    fn add_mul(self, a: Self, b: Self) -> Self;
    /// `self - a * b`.
    fn sub_mul(self, a: Self, b: Self) -> Self;
}

/// Whether [`MulAdd`] fuses: `std`'s `mul_add` compiles to one instruction
/// (and the `libm` feature does not ask for the bits without `std`).
macro_rules! fused {
    ($fused:expr, $plain:expr) => {{
        #[cfg(all(
            feature = "std",
            not(feature = "libm"),
            any(target_feature = "fma", target_arch = "aarch64")
        ))]
        return $fused;
        #[cfg(not(all(
            feature = "std",
            not(feature = "libm"),
            any(target_feature = "fma", target_arch = "aarch64")
        )))]
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

/// The math functions of [`Float`] as free functions `imp::f64::sin`, … .
///
/// The trigonometric functions and their inverses come from `libm` (musl's
/// algorithms, errors below one unit in the last place) on every target:
/// measured on x86-64 against glibc (`cargo bench -p autosim-runtime
/// --bench math`) they are 1.1 to 1.5 times faster (a sine and cosine pair
/// 7.6 ns against 11.6), and they give the same bits with and without
/// `std`. `sqrt`, `exp`, `ln`, `powf` and `powi` come from `std` where
/// there is one (as fast or faster there), from `libm` otherwise, and with
/// the `libm` feature always (so that a model computes the same bits with
/// and without `std`).
mod imp {
    macro_rules! math {
        (
            $t:ident,
            trig: $sin:ident, $cos:ident, $sincos:ident, $tan:ident, $asin:ident, $acos:ident, $atan2:ident;
            libm: $sqrt:ident, $exp:ident, $ln:ident, $pow:ident
        ) => {
            pub mod $t {
                forward! {
                    pub fn sin(x: $t) -> $t => libm::$sin;
                    pub fn cos(x: $t) -> $t => libm::$cos;
                    pub fn sin_cos(x: $t) -> ($t, $t) => libm::$sincos;
                    pub fn tan(x: $t) -> $t => libm::$tan;
                    pub fn asin(x: $t) -> $t => libm::$asin;
                    pub fn acos(x: $t) -> $t => libm::$acos;
                    pub fn atan2(y: $t, x: $t) -> $t => libm::$atan2;
                }
                /// Sine and cosine without branches on the angle, computed
                /// in `f64`.
                #[inline(always)]
                pub fn sin_cos_inline(x: $t) -> ($t, $t) {
                    use crate::float::Float;
                    let (s, c) = crate::float::straight_sin_cos::sin_cos(f64::from(x));
                    (<$t>::from_f64(s), <$t>::from_f64(c))
                }
                /// Sine without branches on the angle, computed in `f64`.
                #[inline(always)]
                pub fn sin_inline(x: $t) -> $t {
                    use crate::float::Float;
                    <$t>::from_f64(crate::float::straight_sin::sin(f64::from(x)))
                }
                /// Cosine without branches on the angle, computed in `f64`.
                #[inline(always)]
                pub fn cos_inline(x: $t) -> $t {
                    use crate::float::Float;
                    <$t>::from_f64(crate::float::straight_sin::cos(f64::from(x)))
                }
                /// `N` sines and cosines without branches on the angles,
                /// computed in `f64`.
                #[inline(always)]
                pub fn sin_cos_inline_lanes<const N: usize>(x: [$t; N]) -> ([$t; N], [$t; N]) {
                    use crate::float::Float;
                    let (s, c) = crate::float::straight_sin_cos::sin_cos_lanes(x.map(f64::from));
                    (s.map(<$t>::from_f64), c.map(<$t>::from_f64))
                }
                #[cfg(all(feature = "std", not(feature = "libm")))]
                forward! {
                    pub fn sqrt(x: $t) -> $t => $t::sqrt;
                    pub fn exp(x: $t) -> $t => $t::exp;
                    pub fn ln(x: $t) -> $t => $t::ln;
                    pub fn powf(x: $t, e: $t) -> $t => $t::powf;
                    pub fn powi(x: $t, n: i32) -> $t => $t::powi;
                }
                #[cfg(any(not(feature = "std"), feature = "libm"))]
                forward! {
                    pub fn sqrt(x: $t) -> $t => libm::$sqrt;
                    pub fn exp(x: $t) -> $t => libm::$exp;
                    pub fn ln(x: $t) -> $t => libm::$ln;
                    pub fn powf(x: $t, e: $t) -> $t => libm::$pow;
                }
                /// Exponentiation by squaring: exact for the small integer
                /// powers generated code uses.
                #[cfg(any(not(feature = "std"), feature = "libm"))]
                #[inline(always)]
                pub fn powi(x: $t, n: i32) -> $t {
                    let mut base = if n < 0 { 1.0 / x } else { x };
                    let mut k = n.unsigned_abs();
                    let mut acc: $t = 1.0;
                    while k > 0 {
                        if k & 1 == 1 {
                            acc *= base;
                        }
                        base *= base;
                        k >>= 1;
                    }
                    acc
                }
            }
        };
    }
    math!(f64, trig: sin, cos, sincos, tan, asin, acos, atan2; libm: sqrt, exp, log, pow);
    math!(f32, trig: sinf, cosf, sincosf, tanf, asinf, acosf, atan2f; libm: sqrtf, expf, logf, powf);
}

/// Math functions called by generated code, generic over [`Float`].
pub mod math {
    use super::Float;
    /// Sine.
    #[inline(always)]
    pub fn sin<F: Float>(x: F) -> F {
        x.sin()
    }
    /// Cosine.
    #[inline(always)]
    pub fn cos<F: Float>(x: F) -> F {
        x.cos()
    }
    /// Sine and cosine of the same angle.
    #[inline(always)]
    pub fn sin_cos<F: Float>(x: F) -> (F, F) {
        x.sin_cos()
    }
    /// Sine and cosine of the same angle without branches on it (big
    /// generated functions call this: [`Float::sin_cos_inline`]).
    #[inline(always)]
    pub fn sin_cos_inline<F: Float>(x: F) -> (F, F) {
        x.sin_cos_inline()
    }
    /// Sine without branches on the angle (generated `f64` functions call
    /// this for an angle whose cosine they do not need:
    /// [`Float::sin_inline`]).
    #[inline(always)]
    pub fn sin_inline<F: Float>(x: F) -> F {
        x.sin_inline()
    }
    /// Cosine without branches on the angle ([`Float::cos_inline`]).
    #[inline(always)]
    pub fn cos_inline<F: Float>(x: F) -> F {
        x.cos_inline()
    }
    /// Sines and cosines of `N` angles without branches on them, in vector
    /// instructions where the target has them
    /// ([`Float::sin_cos_inline_lanes`]).
    #[inline(always)]
    pub fn sin_cos_lanes<F: Float, const N: usize>(x: [F; N]) -> ([F; N], [F; N]) {
        F::sin_cos_inline_lanes(x)
    }
    /// Tangent.
    #[inline(always)]
    pub fn tan<F: Float>(x: F) -> F {
        x.tan()
    }
    /// Arc sine.
    #[inline(always)]
    pub fn asin<F: Float>(x: F) -> F {
        x.asin()
    }
    /// Arc cosine.
    #[inline(always)]
    pub fn acos<F: Float>(x: F) -> F {
        x.acos()
    }
    /// Two-argument arc tangent of `y / x`.
    #[inline(always)]
    pub fn atan2<F: Float>(y: F, x: F) -> F {
        y.atan2(x)
    }
    /// Square root.
    #[inline(always)]
    pub fn sqrt<F: Float>(x: F) -> F {
        x.sqrt()
    }
    /// Exponential.
    #[inline(always)]
    pub fn exp<F: Float>(x: F) -> F {
        x.exp()
    }
    /// Natural logarithm.
    #[inline(always)]
    pub fn ln<F: Float>(x: F) -> F {
        x.ln()
    }
    /// Absolute value.
    #[inline(always)]
    pub fn abs<F: Float>(x: F) -> F {
        x.abs()
    }
    /// Sign: -1, 0 or 1 (0 for NaN).
    #[inline(always)]
    pub fn sign<F: Float>(x: F) -> F {
        if x > F::ZERO {
            F::ONE
        } else if x < F::ZERO {
            -F::ONE
        } else {
            F::ZERO
        }
    }
    /// Minimum.
    #[inline(always)]
    pub fn min<F: Float>(a: F, b: F) -> F {
        a.min(b)
    }
    /// Maximum.
    #[inline(always)]
    pub fn max<F: Float>(a: F, b: F) -> F {
        a.max(b)
    }
    /// Float power.
    #[inline(always)]
    pub fn powf<F: Float>(x: F, e: F) -> F {
        x.powf(e)
    }
    /// Integer power.
    #[inline(always)]
    pub fn powi<F: Float>(x: F, n: i32) -> F {
        x.powi(n)
    }
    /// `true` if `x > 0` (false for NaN): the pivot test of generated solves.
    #[inline(always)]
    pub fn is_positive<F: Float>(x: F) -> bool {
        x > F::ZERO
    }
    /// `true` if `|x|` is above a few rounding errors (false for NaN and
    /// infinity): the pivot test of the generated constraint solves.
    #[inline(always)]
    pub fn is_regular<F: Float>(x: F) -> bool {
        x.is_finite() && x.abs() > F::from_f64(16.0) * F::EPSILON
    }
}

#[cfg(test)]
mod tests {
    use super::MulAdd;

    /// `(1 + ε)(1 - ε) = 1 - ε²` rounds to 1 as a product: the sum with -1
    /// is 0 unfused and -ε² fused (one rounding).
    fn rounds_once_where_fused<F: crate::Float + MulAdd>(epsilon: F, fused: bool) {
        let one = F::ONE;
        let (a, b) = (one + epsilon, one - epsilon);
        let expected = if fused { -(epsilon * epsilon) } else { F::ZERO };
        assert_eq!((-one).add_mul(a, b), expected);
        assert_eq!((-one).sub_mul(-a, b), expected);
        assert_eq!(one.sub_mul(a, b), -expected);
    }

    #[test]
    fn add_mul_rounds_once_exactly_where_it_fuses() {
        let fused = cfg!(all(
            feature = "std",
            not(feature = "libm"),
            any(target_feature = "fma", target_arch = "aarch64")
        ));
        rounds_once_where_fused(f64::EPSILON, fused);
        rounds_once_where_fused(f32::EPSILON, fused);
    }
}
