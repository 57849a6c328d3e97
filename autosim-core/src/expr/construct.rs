//! Constructors that simplify as they build (the paper's Table 5).
//!
//! Every constructor returns a canonical node: nested sums and products are
//! flattened, numbers folded, like terms and like powers combined, terms and
//! factors sorted by id, a sum's leading term is never negative (`-(a + b)`
//! instead of `-a - b`), `sin² + cos²` collapses (and any sum of products of
//! sines and cosines that is identically a number, `trigpoly.rs`),
//! `sin a cos b + cos a sin b` is `sin(a + b)` (and the like, `angle_sum.rs`), inverse
//! functions cancel, and terms that are small relative to the rest of their
//! sum are dropped.

use super::arena::{Arena, ExprId, Func, Meta, Node};
use super::number::Number;

impl Arena {
    // ----- numbers -----

    /// The expression for a number.
    pub fn num(&mut self, n: Number) -> ExprId {
        self.intern(
            Node::Num(n),
            Meta {
                constant: true,
                order: 0,
            },
        )
    }

    /// The expression for an integer.
    pub fn int(&mut self, n: i64) -> ExprId {
        self.num(Number::int(n))
    }

    /// The expression for the rational `num/den`; a zero denominator gives
    /// 0 rather than a panic.
    pub fn rational(&mut self, num: i64, den: i64) -> ExprId {
        let n = Number::rational(num as i128, den as i128).unwrap_or(Number::ZERO);
        self.num(n)
    }

    // ----- arithmetic -----

    /// `a + b`. Common symbolic factors are pulled out
    /// (`gcf(a, b) (a/gcf + b/gcf)`, the paper's `add`; see [`Arena::sum`]).
    pub fn add(&mut self, a: ExprId, b: ExprId) -> ExprId {
        if self.is_zero(a) {
            return b;
        }
        if self.is_zero(b) {
            return a;
        }
        self.sum(&[a, b])
    }

    /// `a - b`.
    pub fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let nb = self.neg(b);
        self.add(a, nb)
    }

    /// `-a`.
    pub fn neg(&mut self, a: ExprId) -> ExprId {
        self.scale(Number::MINUS_ONE, a)
    }

    /// `c a` for a number `c`.
    pub fn scale(&mut self, c: Number, a: ExprId) -> ExprId {
        self.product_with(c, &[a])
    }

    /// `a b`.
    pub fn mul(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.product_with(Number::ONE, &[a, b])
    }

    /// `a / b`.
    pub fn div(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let inv = self.inv(b);
        self.mul(a, inv)
    }

    /// `1 / a`.
    pub fn inv(&mut self, a: ExprId) -> ExprId {
        let m1 = self.num(Number::MINUS_ONE);
        self.pow(a, m1)
    }

    /// `a ^ n` for an integer `n`.
    pub fn powi(&mut self, a: ExprId, n: i64) -> ExprId {
        let e = self.int(n);
        self.pow(a, e)
    }

    /// `sqrt(a)`, represented as `a ^ (1/2)`.
    pub fn sqrt(&mut self, a: ExprId) -> ExprId {
        let half = self.rational(1, 2);
        self.pow(a, half)
    }

    /// The sum of any number of expressions.
    pub fn sum(&mut self, items: &[ExprId]) -> ExprId {
        let mut constant = Number::ZERO;
        let mut terms: Vec<(ExprId, Number)> = Vec::with_capacity(items.len());
        for &it in items {
            self.collect_term(it, Number::ONE, &mut constant, &mut terms);
        }
        self.finish_sum(constant, terms, None)
    }

    /// The product of any number of expressions.
    pub fn product(&mut self, items: &[ExprId]) -> ExprId {
        self.product_with(Number::ONE, items)
    }

    /// Splits a term of a sum into (monomial with coefficient 1, coefficient),
    /// flattening nested sums (a numeric multiple of a sum is distributed, so
    /// `-(a + b)` and `a + b` cancel).
    pub(super) fn collect_term(
        &mut self,
        e: ExprId,
        scale: Number,
        constant: &mut Number,
        terms: &mut Vec<(ExprId, Number)>,
    ) {
        match self.node(e).clone() {
            Node::Num(n) => *constant = *constant + scale * n,
            Node::Sum(ts) => {
                for t in ts.iter() {
                    self.collect_term(*t, scale, constant, terms);
                }
            }
            Node::Prod(c, fs) => {
                if fs.len() == 1 && matches!(self.node(fs[0]), Node::Sum(_)) {
                    self.collect_term(fs[0], scale * c, constant, terms);
                } else {
                    let mono = self.monomial(&fs);
                    terms.push((mono, scale * c));
                }
            }
            _ => terms.push((e, scale)),
        }
    }

    /// The product of sorted, already-canonical factors with coefficient 1.
    fn monomial(&mut self, factors: &[ExprId]) -> ExprId {
        match factors.len() {
            0 => self.one(),
            1 => factors[0],
            _ => {
                let meta = self.prod_meta(factors);
                self.intern(Node::Prod(Number::ONE, factors.into()), meta)
            }
        }
    }

    /// Like `monomial` but never creates a node.
    pub(super) fn find_monomial(&self, factors: &[ExprId]) -> Option<ExprId> {
        match factors.len() {
            0 => Some(self.one()),
            1 => Some(factors[0]),
            _ => self.find(&Node::Prod(Number::ONE, factors.into())),
        }
    }

    fn prod_meta(&self, factors: &[ExprId]) -> Meta {
        let mut constant = true;
        let mut order: i32 = 0;
        for f in factors {
            let m = self.meta(*f);
            constant &= m.constant;
            order += i32::from(m.order);
        }
        Meta {
            constant,
            order: order.clamp(i16::MIN as i32, i16::MAX as i32) as i16,
        }
    }

    /// The factors of a monomial (coefficient 1).
    pub(super) fn monomial_factors(&self, mono: ExprId) -> Vec<ExprId> {
        match self.node(mono) {
            Node::Prod(c, fs) if c.is_one() => fs.to_vec(),
            _ => vec![mono],
        }
    }

    /// `c * mono` as a canonical node.
    fn make_term(&mut self, c: Number, mono: ExprId) -> ExprId {
        if c.is_zero() {
            return self.zero();
        }
        if c.is_one() {
            return mono;
        }
        let factors = self.monomial_factors(mono);
        if factors.len() == 1 && factors[0] == self.one() {
            return self.num(c);
        }
        let meta = self.prod_meta(&factors);
        self.intern(Node::Prod(c, factors.into()), meta)
    }

    /// The canonical sum of `constant` and `terms`, the quotient of a sum by
    /// its common factor `pulled` if any.
    fn finish_sum(
        &mut self,
        mut constant: Number,
        mut terms: Vec<(ExprId, Number)>,
        pulled: Option<ExprId>,
    ) -> ExprId {
        // Combine like terms.
        terms.sort_by_key(|t| t.0);
        let mut merged: Vec<(ExprId, Number)> = Vec::with_capacity(terms.len());
        for (m, c) in terms {
            match merged.last_mut() {
                Some(last) if last.0 == m => last.1 = last.1 + c,
                _ => merged.push((m, c)),
            }
        }
        merged.retain(|t| !t.1.is_zero());
        // A monomial can be the number 1 (e.g. from the trig identity).
        let one = self.one();
        if let Some(pos) = merged.iter().position(|t| t.0 == one) {
            constant = constant + merged[pos].1;
            merged.remove(pos);
        }

        if !merged.is_empty() && self.apply_trig_identity(&mut merged, &mut constant) {
            let terms = merged;
            return self.finish_sum(constant, terms, pulled);
        }
        // Sines and cosines of angle sums (`angle_sum.rs`).
        if merged.len() >= 2 && self.apply_angle_sum(&mut merged, &mut constant) {
            let terms = merged;
            return self.finish_sum(constant, terms, pulled);
        }

        // Drop terms that are small relative to the rest.
        if merged.iter().any(|t| self.order(t.0) != 0) {
            let mut min_order = if constant.is_zero() { i16::MAX } else { 0 };
            for t in &merged {
                min_order = min_order.min(self.order(t.0));
            }
            let threshold = i32::from(self.threshold);
            merged.retain(|t| i32::from(self.order(t.0)) - i32::from(min_order) < threshold);
        }

        if merged.is_empty() {
            return self.num(constant);
        }
        // Sums of squared direction cosines (1), products of two rows (0),
        // products in disguise (one term).
        if merged.len() + usize::from(!constant.is_zero()) >= 2
            && let Some(e) = self.sum_collapsed(constant, &merged)
        {
            return e;
        }

        // Pull out a symbolic factor common to every term.
        // Never the factor just pulled out again: that is a division that did
        // not cancel, and pulling it forever overflowed the stack.
        if constant.is_zero()
            && merged.len() >= 2
            && let Some(g) = self.common_factor(&merged)
            && Some(g) != pulled
        {
            let inv = self.inv(g);
            let parts: Vec<ExprId> = merged
                .iter()
                .map(|&(m, c)| self.product_with(c, &[m, inv]))
                .collect();
            let mut inner_terms = Vec::with_capacity(parts.len());
            let mut inner_constant = Number::ZERO;
            for part in parts {
                self.collect_term(part, Number::ONE, &mut inner_constant, &mut inner_terms);
            }
            let inner = self.finish_sum(inner_constant, inner_terms, Some(g));
            return self.mul(g, inner);
        }

        if merged.len() == 1 && constant.is_zero() {
            let (m, c) = merged[0];
            return self.make_term(c, m);
        }
        // Sign convention: the leading (lowest-id) term is never negative.
        let negate = merged[0].1.is_negative();
        if negate {
            constant = -constant;
            for t in merged.iter_mut() {
                t.1 = -t.1;
            }
        }
        let mut items: Vec<ExprId> = Vec::with_capacity(merged.len() + 1);
        if !constant.is_zero() {
            items.push(self.num(constant));
        }
        for (m, c) in merged {
            items.push(self.make_term(c, m));
        }
        items.sort();
        let mut meta = Meta {
            constant: true,
            order: i16::MAX,
        };
        for it in &items {
            let m = self.meta(*it);
            meta.constant &= m.constant;
            meta.order = meta.order.min(m.order);
        }
        let s = self.intern(Node::Sum(items.into()), meta);
        if negate {
            let meta = Meta {
                constant: meta.constant,
                order: meta.order,
            };
            self.intern(Node::Prod(Number::MINUS_ONE, Box::new([s])), meta)
        } else {
            s
        }
    }

    /// The product of the factors (with the smallest numeric exponent) that
    /// every monomial of a sum has, if any.
    fn common_factor(&mut self, terms: &[(ExprId, Number)]) -> Option<ExprId> {
        let powers = |arena: &Arena, m: ExprId| -> Vec<(ExprId, Number)> {
            arena
                .monomial_factors(m)
                .into_iter()
                .filter(|f| *f != arena.one())
                .map(|f| match arena.node(f) {
                    Node::Pow(b, x) => match arena.as_number(*x) {
                        Some(n) => (*b, n),
                        None => (f, Number::ONE),
                    },
                    _ => (f, Number::ONE),
                })
                .collect()
        };
        let mut common = powers(self, terms[0].0);
        for &(m, _) in &terms[1..] {
            if common.is_empty() {
                return None;
            }
            let other = powers(self, m);
            common.retain_mut(|(base, e)| match other.iter().find(|(b, _)| b == base) {
                Some((_, e2)) if e.is_negative() == e2.is_negative() => {
                    let smaller = if e.is_negative() {
                        e.cmp_value(*e2).is_ge()
                    } else {
                        e.cmp_value(*e2).is_le()
                    };
                    if !smaller {
                        *e = *e2;
                    }
                    true
                }
                _ => false,
            });
        }
        if common.is_empty() {
            return None;
        }
        let factors: Vec<ExprId> = common
            .into_iter()
            .map(|(b, e)| {
                let en = self.num(e);
                self.pow(b, en)
            })
            .collect();
        Some(self.product(&factors))
    }

    /// Finds `c M sin²x + c M cos²x` (→ `c M`) and `c M - c M sin²x`
    /// (→ `c M cos²x`, and the same with sin and cos exchanged) in a list of
    /// combined terms. Rewrites the list and returns `true` if one was found.
    fn apply_trig_identity(
        &mut self,
        terms: &mut Vec<(ExprId, Number)>,
        constant: &mut Number,
    ) -> bool {
        for i in 0..terms.len() {
            let (mono, c) = terms[i];
            let factors = self.monomial_factors(mono);
            for (k, &f) in factors.iter().enumerate() {
                let Some((func, arg)) = self.squared_trig(f) else {
                    continue;
                };
                let other = if func == Func::Sin {
                    Func::Cos
                } else {
                    Func::Sin
                };
                let two = self.int(2);
                let other_sq = self
                    .find(&Node::Func(other, Box::new([arg])))
                    .and_then(|of| self.find(&Node::Pow(of, two)));
                let mut rest = factors.clone();
                rest.remove(k);
                // c M s² + c M c²  →  c M
                let partner_mono = other_sq.and_then(|osq| {
                    let mut partner = rest.clone();
                    partner.push(osq);
                    self.sort_factors(&mut partner);
                    self.find_monomial(&partner)
                });
                if let Some(pm) = partner_mono
                    && let Some(j) = terms.iter().position(|t| t.0 == pm && t.1 == c)
                {
                    let rest_mono = self.monomial(&rest);
                    let (a, b) = (i.max(j), i.min(j));
                    terms.remove(a);
                    terms.remove(b);
                    terms.push((rest_mono, c));
                    return true;
                }
                // c M - c M s²  →  c M c²
                let neg_c = -c;
                let rest_found = if rest.is_empty() {
                    if *constant == neg_c { Some(None) } else { None }
                } else {
                    self.find_monomial(&rest).and_then(|rm| {
                        terms
                            .iter()
                            .position(|t| t.0 == rm && t.1 == neg_c)
                            .map(Some)
                    })
                };
                if let Some(j) = rest_found {
                    let of = self.func(other, &[arg]);
                    let other_sq = self.pow(of, two);
                    let mut with_other = rest.clone();
                    with_other.push(other_sq);
                    self.sort_factors(&mut with_other);
                    let new_mono = self.monomial(&with_other);
                    match j {
                        Some(j) => {
                            let (a, b) = (i.max(j), i.min(j));
                            terms.remove(a);
                            terms.remove(b);
                        }
                        None => {
                            *constant = Number::ZERO;
                            terms.remove(i);
                        }
                    }
                    terms.push((new_mono, neg_c));
                    return true;
                }
            }
        }
        false
    }

    /// `Some((Sin|Cos, x))` if `e` is `sin(x)^2` or `cos(x)^2`.
    fn squared_trig(&self, e: ExprId) -> Option<(Func, ExprId)> {
        if let Node::Pow(b, x) = self.node(e)
            && self.as_number(*x) == Some(Number::int(2))
            && let Node::Func(f @ (Func::Sin | Func::Cos), args) = self.node(*b)
        {
            return Some((*f, args[0]));
        }
        None
    }

    /// The product `c * items`, flattened, with like powers combined.
    pub(crate) fn product_with(&mut self, c: Number, items: &[ExprId]) -> ExprId {
        let mut coef = c;
        let mut powers: Vec<(ExprId, ExprId)> = Vec::with_capacity(items.len() + 2);
        for &it in items {
            self.collect_factor(it, &mut coef, &mut powers);
        }
        if coef.is_zero() {
            return self.zero();
        }
        powers.sort_by_key(|p| p.0);
        let mut merged: Vec<(ExprId, ExprId)> = Vec::with_capacity(powers.len());
        for (b, e) in powers {
            match merged.last_mut() {
                Some(last) if last.0 == b => last.1 = self.sum(&[last.1, e]),
                _ => merged.push((b, e)),
            }
        }
        let mut reflatten = self.merge_abs_powers(&mut merged);
        let mut factors: Vec<ExprId> = Vec::with_capacity(merged.len());
        for (b, e) in merged {
            let f = if e == self.one() { b } else { self.pow(b, e) };
            match self.node(f) {
                Node::Num(n) => coef = coef * *n,
                Node::Prod(..) => {
                    reflatten = true;
                    factors.push(f);
                }
                // `abs(y)^2` is `y^2`: a power of another base, which may
                // meet a factor `y^2` it must combine with.
                Node::Pow(base, _) if *base != b => {
                    reflatten = true;
                    factors.push(f);
                }
                _ => factors.push(f),
            }
        }
        if reflatten {
            return self.product_with(coef, &factors);
        }
        if coef.is_zero() {
            return self.zero();
        }
        self.sort_factors(&mut factors);
        match factors.len() {
            0 => self.num(coef),
            1 if coef.is_one() => factors[0],
            _ => {
                let meta = self.prod_meta(&factors);
                self.intern(Node::Prod(coef, factors.into()), meta)
            }
        }
    }

    /// Combines `x^k` with `|x|^m` (integer `k`, `m`) among the merged
    /// (base, exponent) pairs of a product: `x^k = |x|^k` for even `k`,
    /// `sign(x) |x|^k` for odd `k`, so the pair is `|x|^(k+m)`, times
    /// `sign(x)` for odd `k`. `x / |x|` (a direction's sign, left by the
    /// length `|x|` of a vector `x w`) becomes `sign(x)`, `x^2 / |x|` is
    /// `|x|`: no division left to differentiate. Equal wherever the product
    /// was defined (it may add the value at `x = 0`). Returns `true` if a
    /// pair was combined (the caller flattens the product again).
    fn merge_abs_powers(&mut self, merged: &mut Vec<(ExprId, ExprId)>) -> bool {
        let integer = |a: &Arena, e: ExprId| a.as_number(e).and_then(|n| n.as_integer());
        let mut changed = false;
        let mut i = 0;
        while i < merged.len() {
            let (b, m) = merged[i];
            let inner = match self.node(b) {
                Node::Func(Func::Abs, args) if args.len() == 1 => args[0],
                _ => {
                    i += 1;
                    continue;
                }
            };
            let Some(j) = merged.iter().position(|p| p.0 == inner) else {
                i += 1;
                continue;
            };
            let (Some(_), Some(k)) = (integer(self, m), integer(self, merged[j].1)) else {
                i += 1;
                continue;
            };
            merged[i].1 = self.sum(&[m, merged[j].1]);
            if k % 2 == 0 {
                merged.remove(j);
            } else {
                merged[j] = (self.func(Func::Sign, &[inner]), self.one());
            }
            changed = true;
            i = 0;
        }
        changed
    }

    fn collect_factor(&mut self, e: ExprId, coef: &mut Number, powers: &mut Vec<(ExprId, ExprId)>) {
        match self.node(e).clone() {
            Node::Num(n) => *coef = *coef * n,
            Node::Prod(c, fs) => {
                *coef = *coef * c;
                for f in fs.iter() {
                    self.collect_factor(*f, coef, powers);
                }
            }
            Node::Pow(b, x) => powers.push((b, x)),
            _ => {
                let one = self.one();
                powers.push((e, one));
            }
        }
    }

    /// Canonical factor order: by the id of each factor's base (so `a^2*b`
    /// reads in symbol order), then by id. Bases are distinct after like
    /// powers are combined, so the order is total.
    pub(crate) fn sort_factors(&self, factors: &mut [ExprId]) {
        factors.sort_by_key(|f| match self.node(*f) {
            Node::Pow(b, _) => (*b, *f),
            _ => (*f, *f),
        });
    }

    /// `(c fs)^e` for a fractional `e` as `(x^2k)^e = |x|^(2k e)` for each
    /// factor of `fs` that is an even power, times `(c rest)^e`: the square
    /// root of a perfect square `c^2 x^2` (a squared length that simplified
    /// to one) is `|c x|`, whose derivative has no division. `None` if no
    /// factor is an even power. (The rest is not negative wherever the
    /// power was real.)
    fn pow_even_factors(&mut self, c: Number, fs: &[ExprId], e: ExprId) -> Option<ExprId> {
        if !fs.iter().any(|f| self.is_even_power(*f)) {
            return None;
        }
        let (squares, rest): (Vec<ExprId>, Vec<ExprId>) =
            fs.iter().partition(|f| self.is_even_power(**f));
        let rest = self.product_with(c, &rest);
        let mut parts: Vec<ExprId> = squares.iter().map(|f| self.pow(*f, e)).collect();
        parts.push(self.pow(rest, e));
        Some(self.product(&parts))
    }

    /// `base ^ exponent`.
    pub fn pow(&mut self, base: ExprId, exponent: ExprId) -> ExprId {
        if let Some(e) = self.as_number(exponent) {
            if e.is_zero() {
                return self.one();
            }
            if e.is_one() {
                return base;
            }
            let integer = e.as_integer();
            match self.node(base).clone() {
                Node::Num(b) => {
                    if let Some(n) = integer {
                        if let Some(v) = b.powi(n) {
                            return self.num(v);
                        }
                    } else if let Some(k) = (e * Number::int(2)).as_integer()
                        && let Some(v) = b.exact_sqrt().and_then(|r| r.powi(k))
                    {
                        // `b^(k/2)` of a perfect square, for every odd `k`: a
                        // power whose inverse is a number would never cancel
                        // against it (common factors of sums recursed forever).
                        return self.num(v);
                    }
                    if !b.is_exact() || !e.is_exact() {
                        let v = b.to_f64().powf(e.to_f64());
                        if v.is_finite()
                            && let Some(n) = Number::float(v)
                        {
                            return self.num(n);
                        }
                    }
                }
                Node::Pow(b2, e2) => {
                    if integer.is_some() && self.as_number(e2).is_none() {
                        // (b^x)^n = b^(x n): `1/m^q` is `m^(-q)`, which cancels
                        // against `m^q` in a product.
                        let ne = self.scale(e, e2);
                        return self.pow(b2, ne);
                    }
                    if let Some(e2n) = self.as_number(e2) {
                        if integer.is_some() {
                            let ne = self.num(e2n * e);
                            return self.pow(b2, ne);
                        }
                        if e2n.as_integer().is_some_and(|k| k % 2 == 0) {
                            // (x^(2k))^e = |x|^(2k e)
                            let ab = self.func(Func::Abs, &[b2]);
                            let ne = self.num(e2n * e);
                            return self.pow(ab, ne);
                        }
                    }
                }
                Node::Prod(c, fs) if integer.is_some() => {
                    let n = integer.unwrap_or(1);
                    let cn = c.powi(n);
                    if let Some(cn) = cn {
                        let mut parts = Vec::with_capacity(fs.len());
                        for f in fs.iter() {
                            parts.push(self.pow(*f, exponent));
                        }
                        return self.product_with(cn, &parts);
                    }
                }
                Node::Func(Func::Abs, args) if integer.is_some_and(|k| k % 2 == 0) => {
                    return self.pow(args[0], exponent);
                }
                Node::Prod(c, fs) => {
                    if let Some(p) = self.pow_even_factors(c, &fs, exponent) {
                        return p;
                    }
                }
                _ => {}
            }
            let base_meta = self.meta(base);
            let order = match integer {
                Some(n) => (i128::from(base_meta.order) * n).clamp(-1000, 1000) as i16,
                // sqrt(q1^2 + q2^2) is as small as q1 (order 1), not O(1):
                // scale the order, rounded toward zero.
                None => (f64::from(base_meta.order) * e.to_f64())
                    .trunc()
                    .clamp(-1000.0, 1000.0) as i16,
            };
            return self.intern(
                Node::Pow(base, exponent),
                Meta {
                    constant: base_meta.constant,
                    order,
                },
            );
        }
        let constant = self.is_constant(base) && self.is_constant(exponent);
        self.intern(Node::Pow(base, exponent), Meta { constant, order: 0 })
    }
}
