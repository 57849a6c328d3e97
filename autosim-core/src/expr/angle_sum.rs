//! Angle sums: `sin a cos b ± cos a sin b → sin(a ± b)` and
//! `cos a cos b ∓ sin a sin b → cos(a ± b)`, with any common factor
//! (`c R sin a cos b + c R cos a sin b → c R sin(a + b)`), in the terms of
//! a sum as the constructor finishes it (`construct.rs`). A planar chain's
//! direction cosines are such sums: the coupler of a four-bar turns by
//! `q1 + q2`. Angles that are both constant (parameters and numbers) are
//! left alone: their sines and cosines cost nothing per call, a new sine
//! of their sum would. The normal form of `trigpoly.rs` expands the sine
//! and cosine of a sum again, so its identities see through the new nodes,
//! and lowering computes `sin(a + b)` as `sin a cos b + cos a sin b` once
//! (`opt/lower/expr.rs`): the terms that shared it shrink, and the program
//! evaluates no sine it did not before.

use super::arena::{Arena, ExprId, Func, Node};
use super::number::Number;

/// Which product of two sines and cosines a term is.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Pair {
    /// `sin a cos b`: with `cos a sin b`, the sine of `a ± b`.
    SinCos,
    /// `cos a cos b`: with `sin a sin b`, the cosine of `a ± b`.
    CosCos,
}

impl Arena {
    /// Finds two terms `c R sin a cos b` and `±c R cos a sin b` (→ `c R
    /// sin(a ± b)`) or `c R cos a cos b` and `∓c R sin a sin b` (→ `c R
    /// cos(a ± b)`) in a list of combined terms, for distinct angles `a`,
    /// `b` not both constant. Rewrites the list (the new term is flattened
    /// into it and `constant`, like terms not yet combined) and returns
    /// `true` if one was found.
    pub(super) fn apply_angle_sum(
        &mut self,
        terms: &mut Vec<(ExprId, Number)>,
        constant: &mut Number,
    ) -> bool {
        for i in 0..terms.len() {
            let (mono, c) = terms[i];
            let factors = self.monomial_factors(mono);
            if factors.len() < 2 {
                continue;
            }
            for k1 in 0..factors.len() {
                for k2 in 0..factors.len() {
                    if k1 == k2 {
                        continue;
                    }
                    let Some(found) = self.angle_pair(&factors, k1, k2) else {
                        continue;
                    };
                    let (pair, a, b) = found;
                    // The partner term: the same rest with the other pair.
                    let (fa, fb) = match pair {
                        Pair::SinCos => (Func::Cos, Func::Sin),
                        Pair::CosCos => (Func::Sin, Func::Sin),
                    };
                    let (Some(pa), Some(pb)) = (
                        self.find(&Node::Func(fa, Box::new([a]))),
                        self.find(&Node::Func(fb, Box::new([b]))),
                    ) else {
                        continue;
                    };
                    let mut partner: Vec<ExprId> = factors
                        .iter()
                        .enumerate()
                        .filter(|(k, _)| *k != k1 && *k != k2)
                        .map(|(_, f)| *f)
                        .collect();
                    let rest = partner.clone();
                    partner.push(pa);
                    partner.push(pb);
                    self.sort_factors(&mut partner);
                    let Some(pm) = self.find_monomial(&partner) else {
                        continue;
                    };
                    let Some(j) = terms
                        .iter()
                        .position(|t| t.0 == pm && (t.1 == c || t.1 == -c))
                    else {
                        continue;
                    };
                    if j == i {
                        continue;
                    }
                    // sin a cos b + cos a sin b = sin(a + b),
                    // cos a cos b - sin a sin b = cos(a + b), and the
                    // differences with the other sign.
                    let same_sign = terms[j].1 == c;
                    let plus = match pair {
                        Pair::SinCos => same_sign,
                        Pair::CosCos => !same_sign,
                    };
                    let angle = if plus { self.add(a, b) } else { self.sub(a, b) };
                    let f = match pair {
                        Pair::SinCos => Func::Sin,
                        Pair::CosCos => Func::Cos,
                    };
                    let t = self.func(f, &[angle]);
                    let mut items = rest;
                    items.push(t);
                    let term = self.product_with(c, &items);
                    let (hi, lo) = (i.max(j), i.min(j));
                    terms.remove(hi);
                    terms.remove(lo);
                    self.collect_term(term, Number::ONE, constant, terms);
                    return true;
                }
            }
        }
        false
    }

    /// `Some((pair, a, b))` if factors `k1` and `k2` are `sin a` and `cos
    /// b` (or `cos a` and `cos b` with `k1 < k2`) of distinct angles that
    /// are not both constant.
    fn angle_pair(
        &self,
        factors: &[ExprId],
        k1: usize,
        k2: usize,
    ) -> Option<(Pair, ExprId, ExprId)> {
        let (f1, a) = self.trig_factor(factors[k1])?;
        let (f2, b) = self.trig_factor(factors[k2])?;
        let pair = match (f1, f2) {
            (Func::Sin, Func::Cos) => Pair::SinCos,
            (Func::Cos, Func::Cos) if k1 < k2 => Pair::CosCos,
            _ => return None,
        };
        if a == b || (self.is_constant(a) && self.is_constant(b)) {
            return None;
        }
        Some((pair, a, b))
    }

    /// `Some((Sin|Cos, x))` if `e` is `sin(x)` or `cos(x)`.
    fn trig_factor(&self, e: ExprId) -> Option<(Func, ExprId)> {
        match self.node(e) {
            Node::Func(f @ (Func::Sin | Func::Cos), args) if args.len() == 1 => Some((*f, args[0])),
            _ => None,
        }
    }
}
