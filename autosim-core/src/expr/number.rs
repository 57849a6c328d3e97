//! Exact rational numbers, with a float form only where the user wrote one.
//!
//! Arithmetic on two rationals stays exact while it fits in `i128`; on
//! overflow (which real models do not reach) it degrades to a float rather
//! than failing. A float operand makes the result a float.

use core::cmp::Ordering;
use core::fmt;
use core::ops::{Add, Mul, Neg, Sub};

/// A number in an expression: an exact rational `num/den` (`den > 0`, lowest
/// terms) or a float written by the user.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Number {
    /// An exact rational number.
    Rational {
        /// Numerator.
        num: i128,
        /// Denominator, always positive.
        den: i128,
    },
    /// A float (stored by its bits so it can be hashed; never NaN, never -0.0).
    Float(u64),
}

fn gcd(mut a: i128, mut b: i128) -> i128 {
    a = a.abs();
    b = b.abs();
    while b != 0 {
        let t = a % b;
        a = b;
        b = t;
    }
    a
}

impl Number {
    /// Zero.
    pub const ZERO: Number = Number::Rational { num: 0, den: 1 };
    /// One.
    pub const ONE: Number = Number::Rational { num: 1, den: 1 };
    /// Minus one.
    pub const MINUS_ONE: Number = Number::Rational { num: -1, den: 1 };

    /// An integer.
    pub fn int(n: i64) -> Number {
        Number::Rational {
            num: n as i128,
            den: 1,
        }
    }

    /// The rational `num/den` in lowest terms; `None` if `den == 0`.
    pub fn rational(num: i128, den: i128) -> Option<Number> {
        if den == 0 {
            return None;
        }
        let g = gcd(num, den);
        let (mut n, mut d) = (num / g, den / g);
        if d < 0 {
            n = n.checked_neg()?;
            d = d.checked_neg()?;
        }
        Some(Number::Rational { num: n, den: d })
    }

    /// A float; NaN is not representable and gives `None`; -0.0 becomes 0.0.
    pub fn float(x: f64) -> Option<Number> {
        if x.is_nan() {
            return None;
        }
        let x = if x == 0.0 { 0.0 } else { x };
        Some(Number::Float(x.to_bits()))
    }

    /// Parses a decimal literal such as `12`, `0.0025`, `1.5e3` or `2E-4`
    /// exactly into a rational. Returns `None` if it is not a plain decimal
    /// literal or does not fit.
    pub fn parse_decimal(text: &str) -> Option<Number> {
        let text = text.trim().replace('_', "");
        let (mantissa, exponent) = match text.find(['e', 'E']) {
            Some(i) => (&text[..i], text[i + 1..].parse::<i32>().ok()?),
            None => (&text[..], 0),
        };
        let (int_part, frac_part) = match mantissa.find('.') {
            Some(i) => (&mantissa[..i], &mantissa[i + 1..]),
            None => (mantissa, ""),
        };
        if int_part.is_empty() && frac_part.is_empty() {
            return None;
        }
        if !int_part.chars().all(|c| c.is_ascii_digit())
            || !frac_part.chars().all(|c| c.is_ascii_digit())
        {
            return None;
        }
        let digits = format!("{int_part}{frac_part}");
        let digits = digits.trim_start_matches('0');
        let mut num: i128 = if digits.is_empty() {
            0
        } else {
            digits.parse().ok()?
        };
        let scale = exponent.checked_sub(frac_part.len() as i32)?;
        let mut den: i128 = 1;
        if scale >= 0 {
            num = num.checked_mul(10i128.checked_pow(scale as u32)?)?;
        } else {
            den = 10i128.checked_pow(scale.unsigned_abs())?;
        }
        Number::rational(num, den)
    }

    /// The value as `f64`.
    pub fn to_f64(self) -> f64 {
        match self {
            Number::Rational { num, den } => num as f64 / den as f64,
            Number::Float(bits) => f64::from_bits(bits),
        }
    }

    /// `true` for exactly zero (a float 0.0 counts).
    pub fn is_zero(self) -> bool {
        match self {
            Number::Rational { num, .. } => num == 0,
            Number::Float(bits) => f64::from_bits(bits) == 0.0,
        }
    }

    /// `true` for exactly one.
    pub fn is_one(self) -> bool {
        match self {
            Number::Rational { num, den } => num == 1 && den == 1,
            Number::Float(bits) => f64::from_bits(bits) == 1.0,
        }
    }

    /// `true` if negative.
    pub fn is_negative(self) -> bool {
        self.to_f64() < 0.0
    }

    /// `true` for an exact rational.
    pub fn is_exact(self) -> bool {
        matches!(self, Number::Rational { .. })
    }

    /// The value as an integer, if it is an exact integer.
    pub fn as_integer(self) -> Option<i128> {
        match self {
            Number::Rational { num, den: 1 } => Some(num),
            _ => None,
        }
    }

    fn from_f64_result(x: f64) -> Number {
        // NaN can only come from inf-inf or 0*inf of float operands; keep a
        // defined value rather than failing (the evaluator reports non-finite
        // results where they matter).
        Number::float(x).unwrap_or(Number::Float(f64::INFINITY.to_bits()))
    }

    /// Reciprocal; `None` for zero.
    pub fn recip(self) -> Option<Number> {
        if self.is_zero() {
            return None;
        }
        match self {
            Number::Rational { num, den } => {
                Number::rational(den, num).or_else(|| Number::float(1.0 / self.to_f64()))
            }
            Number::Float(bits) => Number::float(1.0 / f64::from_bits(bits)),
        }
    }

    /// Quotient; `None` when dividing by zero.
    pub fn checked_div(self, other: Number) -> Option<Number> {
        Some(self * other.recip()?)
    }

    /// Integer power; `None` for `0^negative`.
    pub fn powi(self, n: i128) -> Option<Number> {
        if n < 0 {
            return self.recip()?.powi(-n);
        }
        if let Number::Rational { num, den } = self
            && let Ok(e) = u32::try_from(n)
            && let (Some(a), Some(b)) = (num.checked_pow(e), den.checked_pow(e))
        {
            return Number::rational(a, b);
        }
        let e = i32::try_from(n).ok()?;
        Number::float(self.to_f64().powi(e))
    }

    /// Exact square root of a rational that is a perfect square, if any.
    pub fn exact_sqrt(self) -> Option<Number> {
        match self {
            Number::Rational { num, den } if num >= 0 => {
                let a = isqrt(num)?;
                let b = isqrt(den)?;
                Number::rational(a, b)
            }
            _ => None,
        }
    }

    /// Greatest common divisor of two rationals (positive): gcd of numerators
    /// over lcm of denominators. Floats have no common factor but 1.
    pub fn gcd(self, other: Number) -> Number {
        match (self, other) {
            (Number::Rational { num: a, den: b }, Number::Rational { num: c, den: d }) => {
                let n = gcd(a, c);
                if n == 0 {
                    return Number::ONE;
                }
                let g = gcd(b, d);
                match (b / g).checked_mul(d) {
                    Some(l) => Number::rational(n, l).unwrap_or(Number::ONE),
                    None => Number::ONE,
                }
            }
            _ => Number::ONE,
        }
    }

    /// Absolute value.
    pub fn abs(self) -> Number {
        if self.is_negative() { -self } else { self }
    }

    /// Total order by value (for sorting numbers).
    pub fn cmp_value(self, other: Number) -> Ordering {
        self.to_f64()
            .partial_cmp(&other.to_f64())
            .unwrap_or(Ordering::Equal)
    }
}

fn isqrt(n: i128) -> Option<i128> {
    if n < 0 {
        return None;
    }
    let mut r = (n as f64).sqrt() as i128;
    while r > 0 && r.checked_mul(r)? > n {
        r -= 1;
    }
    while (r + 1).checked_mul(r + 1)? <= n {
        r += 1;
    }
    (r * r == n).then_some(r)
}

/// `a/b + c/d` exactly, if it fits.
fn rational_sum((a, b): (i128, i128), (c, d): (i128, i128)) -> Option<Number> {
    let g = gcd(b, d);
    let lcm = (b / g).checked_mul(d)?;
    let n = a
        .checked_mul(lcm / b)?
        .checked_add(c.checked_mul(lcm / d)?)?;
    Number::rational(n, lcm)
}

/// `a/b · c/d` exactly, if it fits.
fn rational_product((a, b): (i128, i128), (c, d): (i128, i128)) -> Option<Number> {
    let g1 = gcd(a, d).max(1);
    let g2 = gcd(c, b).max(1);
    let n = (a / g1).checked_mul(c / g2)?;
    let m = (b / g2).checked_mul(d / g1)?;
    Number::rational(n, m)
}

/// Both as `(numerator, denominator)`, if both are rational.
fn rationals(x: Number, y: Number) -> Option<((i128, i128), (i128, i128))> {
    match (x, y) {
        (Number::Rational { num: a, den: b }, Number::Rational { num: c, den: d }) => {
            Some(((a, b), (c, d)))
        }
        _ => None,
    }
}

/// Sum: exact for rationals that fit, a float otherwise.
impl Add for Number {
    type Output = Number;

    fn add(self, other: Number) -> Number {
        rationals(self, other)
            .and_then(|(x, y)| rational_sum(x, y))
            .unwrap_or_else(|| Number::from_f64_result(self.to_f64() + other.to_f64()))
    }
}

/// Negation.
impl Neg for Number {
    type Output = Number;

    fn neg(self) -> Number {
        match self {
            Number::Rational { num, den } => match num.checked_neg() {
                Some(n) => Number::Rational { num: n, den },
                None => Number::from_f64_result(-self.to_f64()),
            },
            Number::Float(bits) => Number::from_f64_result(-f64::from_bits(bits)),
        }
    }
}

/// Difference.
impl Sub for Number {
    type Output = Number;

    fn sub(self, other: Number) -> Number {
        self + -other
    }
}

/// Product: exact for rationals that fit, a float otherwise.
impl Mul for Number {
    type Output = Number;

    fn mul(self, other: Number) -> Number {
        rationals(self, other)
            .and_then(|(x, y)| rational_product(x, y))
            .unwrap_or_else(|| Number::from_f64_result(self.to_f64() * other.to_f64()))
    }
}

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Number::Rational { num, den: 1 } => write!(f, "{num}"),
            Number::Rational { num, den } => write!(f, "{num}/{den}"),
            Number::Float(bits) => {
                let x = f64::from_bits(bits);
                if x.is_finite() && x == x.trunc() && x.abs() < 1e15 {
                    write!(f, "{x:.1}")
                } else {
                    write!(f, "{x:?}")
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_literals_are_exact() {
        assert_eq!(Number::parse_decimal("0.0025"), Number::rational(1, 400));
        assert_eq!(Number::parse_decimal("1.5e3"), Some(Number::int(1500)));
        assert_eq!(Number::parse_decimal("2E-4"), Number::rational(1, 5000));
        assert_eq!(
            Number::parse_decimal("3.1415926"),
            Number::rational(15707963, 5000000)
        );
        assert_eq!(Number::parse_decimal("abc"), None);
        assert_eq!(Number::parse_decimal("."), None);
    }

    #[test]
    fn arithmetic_is_exact_and_overflow_degrades_to_float() {
        let a = Number::rational(1, 3).unwrap();
        let b = Number::rational(1, 6).unwrap();
        assert_eq!(a + b, Number::rational(1, 2).unwrap());
        assert_eq!(a * b, Number::rational(1, 18).unwrap());
        assert_eq!(a.checked_div(b), Some(Number::int(2)));
        assert_eq!(Number::ZERO.recip(), None);
        let big = Number::Rational {
            num: i128::MAX,
            den: 1,
        };
        assert!(matches!(big + big, Number::Float(_)));
        assert!(matches!(big * big, Number::Float(_)));
        assert_eq!(
            Number::rational(9, 4).unwrap().exact_sqrt(),
            Number::rational(3, 2)
        );
        assert_eq!(Number::int(2).exact_sqrt(), None);
        assert_eq!(Number::int(2).powi(-2), Number::rational(1, 4));
        assert_eq!(Number::ZERO.powi(-1), None);
    }
}
