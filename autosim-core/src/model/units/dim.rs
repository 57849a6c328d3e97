//! The algebra of physical dimensions: a dimension is a vector of rational
//! exponents over the seven SI base units (kg, m, s, A, K, mol, cd) plus the
//! radian, which SI counts as dimensionless (rad = m/m) but which is kept
//! here so that units read as written (`N m/rad`).
//!
//! Two dimensions are *compatible* when they agree on the seven SI bases:
//! the radian's exponent is carried along for display and never makes a
//! mismatch (an angle is a dimensionless number, as in SI).

use std::fmt;

/// A rational exponent, in lowest terms with a positive denominator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Ratio {
    num: i64,
    den: i64,
}

/// The largest numerator or denominator an exponent may reach; beyond it
/// an operation gives `None` (the dimension is then not tracked).
const MAX_TERM: i64 = 1 << 40;

impl Ratio {
    /// Zero.
    pub const ZERO: Ratio = Ratio { num: 0, den: 1 };
    /// One.
    pub const ONE: Ratio = Ratio { num: 1, den: 1 };

    /// `num/den` in lowest terms, or `None` if `den` is zero or a term is
    /// out of range.
    pub fn new(num: i64, den: i64) -> Option<Ratio> {
        if den == 0 {
            return None;
        }
        let g = gcd(num.unsigned_abs(), den.unsigned_abs()).max(1) as i64;
        let sign = if den < 0 { -1 } else { 1 };
        let (num, den) = (sign * num / g, sign * den / g);
        (num.abs() <= MAX_TERM && den <= MAX_TERM).then_some(Ratio { num, den })
    }

    /// The integer `n`.
    pub fn int(n: i64) -> Ratio {
        Ratio { num: n, den: 1 }
    }

    /// Numerator (carries the sign).
    pub fn num(self) -> i64 {
        self.num
    }

    /// Denominator (positive).
    pub fn den(self) -> i64 {
        self.den
    }

    /// True for zero.
    pub fn is_zero(self) -> bool {
        self.num == 0
    }

    /// `self + other`.
    pub fn plus(self, other: Ratio) -> Option<Ratio> {
        let num = self
            .num
            .checked_mul(other.den)?
            .checked_add(other.num.checked_mul(self.den)?)?;
        Ratio::new(num, self.den.checked_mul(other.den)?)
    }

    /// `self * other`.
    pub fn times(self, other: Ratio) -> Option<Ratio> {
        Ratio::new(
            self.num.checked_mul(other.num)?,
            self.den.checked_mul(other.den)?,
        )
    }

    /// `-self`.
    pub fn negated(self) -> Ratio {
        Ratio {
            num: -self.num,
            den: self.den,
        }
    }

    /// `1/self`, `None` for zero.
    pub fn recip(self) -> Option<Ratio> {
        Ratio::new(self.den, self.num)
    }
}

fn gcd(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

impl fmt::Display for Ratio {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.den {
            1 => write!(f, "{}", self.num),
            _ => write!(f, "({}/{})", self.num, self.den),
        }
    }
}

/// The base units, in the order of a [`Dim`]'s exponents.
pub const BASES: [&str; 8] = ["kg", "m", "s", "A", "K", "mol", "cd", "rad"];

/// The index of the radian among the [`BASES`].
pub const RAD: usize = 7;

/// A physical dimension: exponents over [`BASES`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Dim(pub [Ratio; 8]);

impl Dim {
    /// A dimensionless number.
    pub const ONE: Dim = Dim([Ratio::ZERO; 8]);

    /// The base unit number `k` of [`BASES`].
    pub fn base(k: usize) -> Dim {
        let mut d = Dim::ONE;
        d.0[k] = Ratio::ONE;
        d
    }

    /// The dimension with these integer exponents over [`BASES`].
    pub fn of(exponents: [i64; 8]) -> Dim {
        Dim(exponents.map(Ratio::int))
    }

    /// `self * other` (exponents add).
    pub fn times(self, other: Dim) -> Option<Dim> {
        self.zip(other, Ratio::plus)
    }

    /// `self / other`.
    pub fn over(self, other: Dim) -> Option<Dim> {
        self.times(other.recip())
    }

    /// `1/self`.
    pub fn recip(self) -> Dim {
        Dim(self.0.map(Ratio::negated))
    }

    /// `self^p` for a rational power `p`.
    pub fn pow(self, p: Ratio) -> Option<Dim> {
        let mut out = Dim::ONE;
        for (o, e) in out.0.iter_mut().zip(self.0) {
            *o = e.times(p)?;
        }
        Some(out)
    }

    fn zip(self, other: Dim, f: fn(Ratio, Ratio) -> Option<Ratio>) -> Option<Dim> {
        let mut out = Dim::ONE;
        for k in 0..8 {
            out.0[k] = f(self.0[k], other.0[k])?;
        }
        Some(out)
    }

    /// True when the seven SI exponents are zero (an angle is
    /// dimensionless).
    pub fn is_dimensionless(self) -> bool {
        self.0[..RAD].iter().all(|e| e.is_zero())
    }

    /// True when `self` and `other` agree on the seven SI bases.
    pub fn compatible(self, other: Dim) -> bool {
        self.0[..RAD] == other.0[..RAD]
    }

    /// True when every exponent is zero, the radian's included.
    pub fn is_one(self) -> bool {
        self == Dim::ONE
    }
}

/// Newton, in base units (kg m/s^2), used to read dimensions back as
/// mechanics writes them (`N m`, `N/m`, `N s/m`).
const NEWTON: [i64; 8] = [1, 1, -2, 0, 0, 0, 0, 0];

/// Prints a dimension as a unit: newtons where the exponent of kg is 1
/// and that of s negative (`N m/rad`, `N s/m`), the base units otherwise
/// (`kg m^2`, `m/s^2`); `1` for a dimensionless number.
impl fmt::Display for Dim {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut d = *self;
        let mut newtons = false;
        if d.0[0] == Ratio::ONE
            && d.0[2].num() < 0
            && let Some(rest) = d.over(Dim::of(NEWTON))
        {
            d = rest;
            newtons = true;
        }
        let mut up: Vec<String> = Vec::new();
        let mut down: Vec<String> = Vec::new();
        if newtons {
            up.push("N".to_string());
        }
        for (k, e) in d.0.iter().enumerate() {
            if e.is_zero() {
                continue;
            }
            let (list, e) = if e.num() > 0 {
                (&mut up, *e)
            } else {
                (&mut down, e.negated())
            };
            list.push(match e == Ratio::ONE {
                true => BASES[k].to_string(),
                false => format!("{}^{e}", BASES[k]),
            });
        }
        let up = if up.is_empty() {
            "1".to_string()
        } else {
            up.join(" ")
        };
        match down.len() {
            0 => f.write_str(&up),
            1 => write!(f, "{up}/{}", down[0]),
            _ => write!(f, "{up}/({})", down.join(" ")),
        }
    }
}
