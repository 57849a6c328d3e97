//! Many states per call: `L` values of `f64` computed together, one per
//! state (struct of arrays), for generated `derivatives_lanes`.
//!
//! Generated code prints the same block for one state and for `L`; in the
//! lanes function every value is a [`Lanes`], the operators work lane by
//! lane (plain loops over `[f64; L]` that the compiler turns into vector
//! instructions: 2 doubles per SSE2 register, 4 per AVX2 register), and
//! [`math`] holds the runtime's math functions lane by lane. Each lane
//! computes exactly what one call computes for its state, in the same
//! order, with the same fusing of [`MulAdd`]: the results are the same
//! bits as `L` single calls on the same instruction set.
//!
//! Every operation here is `#[inline(always)]` in builds without debug
//! assertions and a plain `#[inline]` (so a call, at `opt-level = 0`) in
//! debug builds: inlined unoptimized into a lanes function of thousands
//! of operations, each operation's locals got their own stack slots
//! (chain-spatial-20's `derivatives_lanes` had a 1.3 MB frame, more than
//! a thread's default stack with the fast copy's on top; 350 KB with the
//! calls). The operations and their order are the same either way.

use super::MulAdd;
use crate::model::{Model, ModelError};
use core::ops::{Add, Div, Mul, Neg, Sub};

/// One `f64` per state, for `L` states.
///
/// ```
/// use autosim_runtime::Lanes;
/// let a = Lanes([1.0, 2.0, 3.0, 4.0]);
/// let b = Lanes::splat(0.5);
/// assert_eq!((a * b + b).0, [1.0, 1.5, 2.0, 2.5]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub struct Lanes<const L: usize>(pub [f64; L]);

impl<const L: usize> Lanes<L> {
    /// Every lane zero.
    pub const ZERO: Self = Lanes([0.0; L]);

    /// The same value in every lane.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub const fn splat(x: f64) -> Self {
        Lanes([x; L])
    }

    /// `f` of each lane.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn map(self, mut f: impl FnMut(f64) -> f64) -> Self {
        let mut out = self;
        for l in 0..L {
            out.0[l] = f(self.0[l]);
        }
        out
    }

    /// `f` of each lane of `self` and `other`.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn zip(self, other: Self, mut f: impl FnMut(f64, f64) -> f64) -> Self {
        let mut out = self;
        for l in 0..L {
            out.0[l] = f(self.0[l], other.0[l]);
        }
        out
    }

    /// Whether `test` holds in every lane (no early exit: a vectorizable
    /// AND).
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn all(self, mut test: impl FnMut(f64) -> bool) -> bool {
        let mut all = true;
        for l in 0..L {
            all &= test(self.0[l]);
        }
        all
    }
}

/// Binary operators lane by lane.
macro_rules! lane_op {
    ($($trait:ident $method:ident $op:tt),+) => {
        $(
            impl<const L: usize> $trait for Lanes<L> {
                type Output = Self;
                #[cfg_attr(debug_assertions, inline)]
                #[cfg_attr(not(debug_assertions), inline(always))]
                fn $method(self, other: Self) -> Self {
                    self.zip(other, |a, b| a $op b)
                }
            }
        )+
    };
}

lane_op!(Add add +, Sub sub -, Mul mul *, Div div /);

impl<const L: usize> Neg for Lanes<L> {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn neg(self) -> Self {
        self.map(|a| -a)
    }
}

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

/// The result of a user function called once per lane, `f` taking the
/// lanes' arguments: generated code calls user code lane by lane.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn call_each<const A: usize, const L: usize>(
    args: [Lanes<L>; A],
    mut f: impl FnMut([f64; A]) -> f64,
) -> Lanes<L> {
    Lanes(core::array::from_fn(|l| f(args.map(|a| a.0[l]))))
}

/// The results of a user subroutine called once per lane (`K` results).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn call_each_sub<const A: usize, const K: usize, const L: usize>(
    args: [Lanes<L>; A],
    mut f: impl FnMut([f64; A]) -> [f64; K],
) -> [Lanes<L>; K] {
    let mut out = [Lanes::ZERO; K];
    for l in 0..L {
        let results = f(args.map(|a| a.0[l]));
        for (o, r) in out.iter_mut().zip(results) {
            o.0[l] = r;
        }
    }
    out
}

/// [`check_user_result`](crate::check_user_result) for every lane.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn check_user_result_lanes<const L: usize>(
    value: Lanes<L>,
    function: &'static str,
) -> Result<Lanes<L>, ModelError> {
    crate::check_user_results(value.0, function).map(Lanes)
}

/// [`check_user_results`](crate::check_user_results) for every lane.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn check_user_results_lanes<const K: usize, const L: usize>(
    values: [Lanes<L>; K],
    function: &'static str,
) -> Result<[Lanes<L>; K], ModelError> {
    match values
        .iter()
        .fold(true, |all, v| all & v.all(f64::is_finite))
    {
        true => Ok(values),
        false => Err(ModelError::NonFiniteUserResult { function }),
    }
}

/// [`check_derivatives`](crate::check_derivatives) for `L` states at once:
/// `Ok` if every lane of every derivative is finite, else the error of the
/// first state (in state order) with a non-finite lane.
#[inline]
pub fn check_derivatives_lanes<M: Model + ?Sized, const L: usize>(
    dx: &[Lanes<L>],
) -> Result<(), ModelError> {
    // Lane by lane, the same test as `first_non_finite` on one state.
    let finite = dx.iter().fold(true, |all, d| all & d.all(f64::is_finite));
    if finite {
        return Ok(());
    }
    let index = dx.iter().position(|d| !d.all(f64::is_finite)).unwrap_or(0);
    let name = M::STATE_NAMES.get(index).copied().unwrap_or("?");
    Err(ModelError::NonFiniteDerivative { index, name })
}

/// The runtime's math functions lane by lane, under the names of
/// [`float::math`](super::math): generated lanes functions import this
/// module as `math`, so they call what a single call calls, per lane.
pub mod math {
    use super::Lanes;
    use crate::float::math as one;

    /// Functions of one argument, lane by lane.
    macro_rules! unary {
        ($($name:ident),+) => {
            $(
                #[doc = concat!("[`", stringify!($name), "`](crate::float::math::", stringify!($name), ") lane by lane.")]
                #[cfg_attr(debug_assertions, inline)]
                #[cfg_attr(not(debug_assertions), inline(always))]
                pub fn $name<const L: usize>(x: Lanes<L>) -> Lanes<L> {
                    x.map(one::$name)
                }
            )+
        };
    }

    /// Functions of two arguments, lane by lane.
    macro_rules! binary {
        ($($name:ident),+) => {
            $(
                #[doc = concat!("[`", stringify!($name), "`](crate::float::math::", stringify!($name), ") lane by lane.")]
                #[cfg_attr(debug_assertions, inline)]
                #[cfg_attr(not(debug_assertions), inline(always))]
                pub fn $name<const L: usize>(a: Lanes<L>, b: Lanes<L>) -> Lanes<L> {
                    a.zip(b, one::$name)
                }
            )+
        };
    }

    unary!(
        sin, cos, sin_inline, cos_inline, tan, asin, acos, sqrt, exp, ln, abs, sign
    );
    binary!(atan2, min, max, powf);

    /// [`powi`](crate::float::math::powi) lane by lane.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn powi<const L: usize>(x: Lanes<L>, n: i32) -> Lanes<L> {
        x.map(|v| one::powi(v, n))
    }

    /// [`sin_cos`](crate::float::math::sin_cos) (libm's) lane by lane.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn sin_cos<const L: usize>(x: Lanes<L>) -> (Lanes<L>, Lanes<L>) {
        let (mut s, mut c) = (Lanes::ZERO, Lanes::ZERO);
        for l in 0..L {
            (s.0[l], c.0[l]) = one::sin_cos(x.0[l]);
        }
        (s, c)
    }

    /// [`sin_cos_inline`](crate::float::math::sin_cos_inline) of every
    /// lane at once (the branch-free kernel, whose lanes are independent).
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn sin_cos_inline<const L: usize>(x: Lanes<L>) -> (Lanes<L>, Lanes<L>) {
        let (s, c) = one::sin_cos_lanes(x.0);
        (Lanes(s), Lanes(c))
    }

    /// [`sin_cos_lanes`](crate::float::math::sin_cos_lanes) of `N` angles
    /// in `L` lanes: each angle's lanes through the branch-free kernel.
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

    /// [`is_positive`](crate::float::math::is_positive) in every lane.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn is_positive<const L: usize>(x: Lanes<L>) -> bool {
        x.all(one::is_positive)
    }

    /// [`is_regular`](crate::float::math::is_regular) in every lane.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn is_regular<const L: usize>(x: Lanes<L>) -> bool {
        x.all(one::is_regular)
    }
}
