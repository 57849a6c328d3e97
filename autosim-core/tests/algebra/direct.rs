//! The independent truth of the algebra's property tests: a tree evaluated
//! directly in f64, with no simplification, and a running error bound.

use proptest::prelude::*;

use super::{EPS, T};

/// Value `v`; magnitude bound `s` (the tree evaluated with absolute values,
/// ordinary symbols at least 1 in magnitude); first-order error bound `e`:
/// the output's change when every intermediate result is perturbed by a
/// relative amount of its magnitude bound (a sum by the sum of its terms'
/// magnitudes), in units of that relative amount.
#[derive(Clone, Copy, Debug)]
pub struct V {
    pub v: f64,
    pub s: f64,
    pub e: f64,
}

pub fn direct(t: &T, vals: &[f64], small: &[usize]) -> V {
    let d = |a: &T| direct(a, vals, small);
    match t {
        T::Sym(i) => {
            let v = vals[*i];
            let s = if small.contains(i) {
                v.abs()
            } else {
                v.abs().max(1.0)
            };
            V { v, s, e: 0.0 }
        }
        T::Int(n) => num(*n as f64),
        T::Rat(n, dd) => num(*n as f64 / *dd as f64),
        T::Flt(v) => num(*v),
        T::Add(a, b) | T::Sub(a, b) => {
            let (a, b) = (d(a), d(b));
            let v = if matches!(t, T::Add(..)) {
                a.v + b.v
            } else {
                a.v - b.v
            };
            let s = a.s + b.s;
            V {
                v,
                s,
                e: a.e + b.e + s,
            }
        }
        T::Mul(a, b) => {
            let (a, b) = (d(a), d(b));
            let s = a.s * b.s;
            V {
                v: a.v * b.v,
                s,
                e: b.v.abs() * a.e + a.v.abs() * b.e + s,
            }
        }
        T::Div(a, b) => {
            let (a, b) = (d(a), d(b));
            let s = a.s / b.v.abs();
            V {
                v: a.v / b.v,
                s,
                e: a.e / b.v.abs() + a.v.abs() * b.e / (b.v * b.v) + s,
            }
        }
        T::Neg(a) => {
            let a = d(a);
            V { v: -a.v, ..a }
        }
        T::PowI(a, n) => {
            let a = d(a);
            let v = a.v.powi(*n as i32);
            let s = if *n > 0 { a.s.powi(*n as i32) } else { v.abs() };
            let dv = (*n as f64).abs() * a.v.abs().powi(*n as i32 - 1);
            V {
                v,
                s,
                e: dv * a.e + s,
            }
        }
        T::Sin(a) => {
            let a = d(a);
            let v = a.v.sin();
            V {
                v,
                s: v.abs().max(a.s.min(1.0)),
                e: a.v.cos().abs() * a.e + a.s + v.abs(),
            }
        }
        T::Cos(a) => {
            let a = d(a);
            let v = a.v.cos();
            V {
                v,
                s: 1.0,
                e: a.v.sin().abs() * a.e + 1.0 + a.s,
            }
        }
        T::Exp(a) => {
            let a = d(a);
            let v = a.v.exp();
            V {
                v,
                s: v,
                e: v * a.e + v * (1.0 + a.s),
            }
        }
        T::Atan2(y, x) => {
            let (y, x) = (d(y), d(x));
            // On the branch cut (y = 0 within rounding, x < 0) the value
            // is ±π depending on the sign of a zero, and at the origin
            // (x = ±0 too: the algebra writes `-0` as `0`) it is 0 or ±π:
            // no reference value.
            let on_cut = x.v <= 0.0 && y.v.abs() <= 64.0 * EPS * y.e;
            let v = if on_cut { f64::NAN } else { y.v.atan2(x.v) };
            let r2 = x.v * x.v + y.v * y.v;
            V {
                v,
                s: v.abs(),
                e: (x.v.abs() * y.e + y.v.abs() * x.e) / r2 + v.abs(),
            }
        }
        T::Sqrt(a) => {
            let a = d(a);
            let v = a.v.sqrt();
            V {
                v,
                s: a.s.sqrt(),
                e: a.e / (2.0 * v) + v,
            }
        }
    }
}

fn num(v: f64) -> V {
    V {
        v,
        s: v.abs(),
        e: 0.0,
    }
}

/// Asserts `got` matches the direct evaluation `want` to relative 1e-9 plus
/// the rounding allowance; skips non-finite reference values.
pub fn close(got: f64, want: V) -> Result<(), TestCaseError> {
    if !want.v.is_finite() || !want.e.is_finite() {
        return Ok(());
    }
    let tol = 1e-9 * want.v.abs() + 64.0 * EPS * want.e;
    prop_assert!(
        (got - want.v).abs() <= tol,
        "constructed {got} vs direct {} (tolerance {tol:e})",
        want.v
    );
    Ok(())
}
