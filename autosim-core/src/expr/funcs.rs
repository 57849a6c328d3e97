//! Function constructors: evaluation of exact cases, odd/even symmetry,
//! inverse-function cancellation, atan2 common factors, and truncated Taylor
//! series of small arguments (the paper's Table 5, first two rows).

use super::arena::{Arena, ExprId, Func, Meta, Node};
use super::number::Number;

/// Taylor coefficients (degree, numerator, denominator) of functions that
/// vanish at 0, for small arguments.
const SIN_SERIES: &[(i64, i64, i64)] = &[(1, 1, 1), (3, -1, 6), (5, 1, 120), (7, -1, 5040)];
const TAN_SERIES: &[(i64, i64, i64)] = &[(1, 1, 1), (3, 1, 3), (5, 2, 15), (7, 17, 315)];
const ASIN_SERIES: &[(i64, i64, i64)] = &[(1, 1, 1), (3, 1, 6), (5, 3, 40), (7, 5, 112)];
const COS_SERIES: &[(i64, i64, i64)] = &[
    (0, 1, 1),
    (2, -1, 2),
    (4, 1, 24),
    (6, -1, 720),
    (8, 1, 40320),
];
const EXP_SERIES: &[(i64, i64, i64)] = &[
    (0, 1, 1),
    (1, 1, 1),
    (2, 1, 2),
    (3, 1, 6),
    (4, 1, 24),
    (5, 1, 120),
    (6, 1, 720),
];

impl Arena {
    /// `f(args)`, simplified. The caller guarantees the argument count
    /// (built-in arity or the user function's declared arity); a wrong count
    /// still gives a node, never a panic.
    pub fn func(&mut self, f: Func, args: &[ExprId]) -> ExprId {
        if args.len() == 1 {
            if let Some(e) = self.simplify_unary(f, args[0]) {
                return e;
            }
        } else if args.len() == 2
            && let Some(e) = self.simplify_binary(f, args[0], args[1])
        {
            return e;
        }
        let constant = !matches!(f, Func::User(_)) && args.iter().all(|a| self.is_constant(*a));
        let order = match f {
            Func::Abs if args.len() == 1 => self.order(args[0]),
            _ => 0,
        };
        self.intern(Node::Func(f, args.into()), Meta { constant, order })
    }

    /// `sin(x)`.
    pub fn sin(&mut self, x: ExprId) -> ExprId {
        self.func(Func::Sin, &[x])
    }

    /// `cos(x)`.
    pub fn cos(&mut self, x: ExprId) -> ExprId {
        self.func(Func::Cos, &[x])
    }

    /// Splits `e` into (is negative, absolute expression) by its leading sign.
    pub fn split_sign(&mut self, e: ExprId) -> (bool, ExprId) {
        match self.node(e).clone() {
            Node::Num(n) if n.is_negative() => (true, self.num(-n)),
            Node::Prod(c, fs) if c.is_negative() => (true, self.product_with(-c, &fs)),
            _ => (false, e),
        }
    }

    fn simplify_unary(&mut self, f: Func, x: ExprId) -> Option<ExprId> {
        // Exact values at 0 and inverse-function cancellation.
        let is_zero = self.is_zero(x);
        match f {
            Func::Sin | Func::Tan | Func::Asin | Func::Abs | Func::Sign if is_zero => {
                return Some(self.zero());
            }
            Func::Cos | Func::Exp if is_zero => return Some(self.one()),
            Func::Ln if x == self.one() => return Some(self.zero()),
            _ => {}
        }
        if let Node::Func(g, inner) = self.node(x).clone() {
            if inner.len() == 1 {
                let cancels = matches!(
                    (f, g),
                    (Func::Sin, Func::Asin) | (Func::Cos, Func::Acos) | (Func::Exp, Func::Ln)
                );
                if cancels {
                    return Some(inner[0]);
                }
                if f == Func::Abs && g == Func::Abs {
                    return Some(x);
                }
            }
            if inner.len() == 2 && g == Func::Atan2 && f == Func::Tan {
                return Some(self.div(inner[0], inner[1]));
            }
        }
        // Floats the user wrote are evaluated.
        if let Some(Number::Float(bits)) = self.as_number(x) {
            let v = f64::from_bits(bits);
            let r = match f {
                Func::Sin => v.sin(),
                Func::Cos => v.cos(),
                Func::Tan => v.tan(),
                Func::Asin => v.asin(),
                Func::Acos => v.acos(),
                Func::Exp => v.exp(),
                Func::Ln => v.ln(),
                Func::Abs => v.abs(),
                Func::Sign => v.signum(),
                _ => f64::NAN,
            };
            if r.is_finite()
                && let Some(n) = Number::float(r)
            {
                return Some(self.num(n));
            }
        }
        if let (Func::Abs, Some(n)) = (f, self.as_number(x)) {
            return Some(self.num(n.abs()));
        }
        if let (Func::Sign, Some(n)) = (f, self.as_number(x)) {
            let s = if n.is_negative() { -1 } else { 1 };
            return Some(self.int(s));
        }
        // Symmetry: odd and even functions of a negated argument.
        let (negative, ax) = self.split_sign(x);
        if negative {
            match f {
                Func::Sin | Func::Tan | Func::Asin | Func::Sign => {
                    let inner = self.func(f, &[ax]);
                    return Some(self.neg(inner));
                }
                Func::Cos | Func::Abs => return Some(self.func(f, &[ax])),
                _ => {}
            }
        }
        // Truncated Taylor series of small arguments.
        let order = self.order(x);
        if order > 0 {
            let series = match f {
                Func::Sin => Some(SIN_SERIES),
                Func::Cos => Some(COS_SERIES),
                Func::Tan => Some(TAN_SERIES),
                Func::Asin => Some(ASIN_SERIES),
                Func::Atan2 => None,
                Func::Exp => Some(EXP_SERIES),
                _ => None,
            };
            if let Some(series) = series {
                return Some(self.taylor(x, series));
            }
        }
        None
    }

    /// Sum of `c_k x^k` over a series table; the sum constructor drops the
    /// terms that are small relative to the leading one.
    fn taylor(&mut self, x: ExprId, series: &[(i64, i64, i64)]) -> ExprId {
        let mut terms = Vec::with_capacity(series.len());
        for &(k, n, d) in series {
            let xk = self.powi(x, k);
            let c = Number::rational(n as i128, d as i128).unwrap_or(Number::ZERO);
            terms.push(self.scale(c, xk));
        }
        self.sum(&terms)
    }

    fn simplify_binary(&mut self, f: Func, a: ExprId, b: ExprId) -> Option<ExprId> {
        match f {
            Func::Atan2 => {
                // atan2(k y, k x) = atan2(y, x) for a common factor k > 0:
                // positive numbers and even powers only (a negative factor
                // would change the quadrant).
                let (ca, fa) = self.coefficient_and_factors(a);
                let (cb, fb) = self.coefficient_and_factors(b);
                let g = ca.gcd(cb);
                let mut common: Vec<ExprId> = Vec::new();
                for f in &fa {
                    if fb.contains(f) && self.is_even_power(*f) {
                        common.push(*f);
                    }
                }
                if !g.is_one() || !common.is_empty() {
                    let gi = g.recip()?;
                    let k = self.product(&common);
                    let a2 = self.div(a, k);
                    let b2 = self.div(b, k);
                    let a2 = self.scale(gi, a2);
                    let b2 = self.scale(gi, b2);
                    return Some(self.func(Func::Atan2, &[a2, b2]));
                }
                None
            }
            Func::Min | Func::Max => {
                if a == b {
                    return Some(a);
                }
                let (na, nb) = (self.as_number(a)?, self.as_number(b)?);
                let pick_a = match f {
                    Func::Min => na.cmp_value(nb).is_le(),
                    _ => na.cmp_value(nb).is_ge(),
                };
                Some(if pick_a { a } else { b })
            }
            _ => None,
        }
    }

    /// `true` if `e` is `x^k` for an even integer `k`.
    pub(super) fn is_even_power(&self, e: ExprId) -> bool {
        match self.node(e) {
            Node::Pow(_, x) => self
                .as_number(*x)
                .and_then(|n| n.as_integer())
                .is_some_and(|k| k % 2 == 0),
            _ => false,
        }
    }

    /// The numeric coefficient and the factors of an expression.
    pub(crate) fn coefficient_and_factors(&self, e: ExprId) -> (Number, Vec<ExprId>) {
        match self.node(e) {
            Node::Num(n) => (*n, Vec::new()),
            Node::Prod(c, fs) => (*c, fs.to_vec()),
            _ => (Number::ONE, vec![e]),
        }
    }
}
