//! Lowering canonical expressions to the program IR: products are split into
//! a constant factor (hoisted, computed once per parameter set) and variable
//! factors multiplied pairwise (the paper's Eqs. 15-16), reciprocal powers
//! become divisions, the constant terms of a sum are grouped into one
//! constant, and terms of a sum sharing a factor multiply it once
//! (`k·a + k·b` as `k·(a + b)`; constant factors first, which may add a
//! sum to the constants block to save a product in every call); the sine
//! and cosine of an angle sum are computed from its terms' sines and
//! cosines (`sin(a + b) = sin a cos b + cos a sin b`), not called.

use super::context::{Lowering, UnboundSymbol};
use crate::expr::{ExprId, Func, Node, Number};
use crate::opt::ir::{Nid, Op};
use indexmap::IndexMap;

impl Lowering<'_> {
    /// The IR node computing `e`.
    pub(super) fn lower(&mut self, e: ExprId) -> Result<Nid, UnboundSymbol> {
        if let Some(n) = self.memo.get(&e) {
            return Ok(*n);
        }
        let node = self.arena.node(e).clone();
        let r = match node {
            Node::Num(n) => self.ir.num(n.to_f64()),
            Node::Sym(s) => match self.env.get(&s) {
                Some(n) => *n,
                None => return Err(UnboundSymbol(self.arena.symbol(s).name.clone())),
            },
            Node::Sum(terms) => self.lower_sum(&terms)?,
            Node::Prod(c, fs) => self.lower_prod(c, &fs)?,
            Node::Pow(b, x) => self.lower_pow(b, x)?,
            Node::Func(f, args) => match self.lower_angle_sum(f, &args)? {
                Some(n) => n,
                None => {
                    let mut xs = Vec::with_capacity(args.len());
                    for a in args.iter() {
                        xs.push(self.lower(*a)?);
                    }
                    self.ir.call(f, xs)
                }
            },
        };
        self.memo.insert(e, r);
        Ok(r)
    }

    /// `sin(x)` or `cos(x)` of a sum `x = r + t` (`t` its last term) as
    /// `sin r cos t + cos r sin t` or `cos r cos t - sin r sin t`, when the
    /// sine and cosine of every term of `x` are expressions of the model
    /// (the constructor made `sin(x)` of their products, `angle_sum.rs`):
    /// three operations from sines the program takes anyway (two at a
    /// time, `emit/sines.rs`), where a call would be a new sine of an angle
    /// the program computes, one call each. `None` for any other function
    /// or argument, and for a constant `x` (computed once per parameter
    /// set).
    fn lower_angle_sum(&mut self, f: Func, args: &[ExprId]) -> Result<Option<Nid>, UnboundSymbol> {
        if !matches!(f, Func::Sin | Func::Cos) || args.len() != 1 {
            return Ok(None);
        }
        let x = args[0];
        let Node::Sum(items) = self.arena.node(x).clone() else {
            return Ok(None);
        };
        if self.arena.is_constant(x) {
            return Ok(None);
        }
        for &t in items.iter() {
            let (_, abs) = self.arena.split_sign(t);
            for g in [Func::Sin, Func::Cos] {
                if self.arena.find(&Node::Func(g, Box::new([abs]))).is_none() {
                    return Ok(None);
                }
            }
        }
        let (t, r) = self.angle_split(&items);
        let (sr, cr) = (self.arena.sin(r), self.arena.cos(r));
        let (st, ct) = (self.arena.sin(t), self.arena.cos(t));
        let [sr, cr, st, ct] = [sr, cr, st, ct].map(|e| self.lower(e));
        let (sr, cr, st, ct) = (sr?, cr?, st?, ct?);
        Ok(Some(match f {
            Func::Sin => {
                let (a, b) = (self.ir.mul(sr, ct), self.ir.mul(cr, st));
                self.ir.sum(vec![a, b], Vec::new())
            }
            _ => {
                let (a, b) = (self.ir.mul(cr, ct), self.ir.mul(sr, st));
                self.ir.sum(vec![a], vec![b])
            }
        }))
    }

    /// A term `t` of the angle sum `items` and the sum `r` of the others,
    /// `x = r + t`: the first split whose rest's sine and cosine are
    /// already lowered, else are expressions, else the first term (a
    /// chain's relative angles `q3 + (q4 + q5)` share `q4 + q5`).
    fn angle_split(&mut self, items: &[ExprId]) -> (ExprId, ExprId) {
        let n = items.len();
        let order = std::iter::once(0).chain((1..n).rev());
        let mut best: Option<(u8, usize, ExprId)> = None;
        for k in order {
            let rest: Vec<ExprId> = (0..n).filter(|&i| i != k).map(|i| items[i]).collect();
            let r = match rest.as_slice() {
                [one] => Some(*one),
                _ => self.arena.find(&Node::Sum(rest.into())),
            };
            let Some(r) = r else { continue };
            let trig =
                [Func::Sin, Func::Cos].map(|g| self.arena.find(&Node::Func(g, Box::new([r]))));
            let score = if trig
                .iter()
                .all(|f| f.is_some_and(|f| self.memo.contains_key(&f)))
            {
                3
            } else if trig.iter().all(Option::is_some) {
                2
            } else if trig.iter().any(Option::is_some) {
                1
            } else {
                0
            };
            if best.is_none_or(|b| score > b.0) {
                best = Some((score, k, r));
            }
        }
        match best {
            Some((_, k, r)) => (items[k], r),
            None => {
                let r = self.arena.sum(&items[1..]);
                (items[0], r)
            }
        }
    }

    fn lower_sum(&mut self, terms: &[ExprId]) -> Result<Nid, UnboundSymbol> {
        let (mut cpos, mut cneg, mut vpos, mut vneg) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for &t in terms {
            let (negative, abs) = self.arena.split_sign(t);
            let n = self.lower(abs)?;
            let constant = self.arena.is_constant(t);
            match (constant, negative) {
                (true, false) => cpos.push(n),
                (true, true) => cneg.push(n),
                (false, false) => vpos.push(n),
                (false, true) => vneg.push(n),
            }
        }
        if !cpos.is_empty() || !cneg.is_empty() {
            // All constant terms become one (hoistable) constant.
            let c = self.ir.sum(cpos, cneg);
            vpos.push(c);
        }
        let (vpos, vneg) = self.common_factors(vpos, vneg);
        Ok(self.ir.sum(vpos, vneg))
    }

    /// Terms `k·a ± k·b ± …` sharing a factor `k` become `k·(a ± b ± …)`:
    /// one multiplication instead of one per term. Constant factors first,
    /// then the factor shared by the most terms, until none is shared.
    fn common_factors(&mut self, pos: Vec<Nid>, neg: Vec<Nid>) -> (Vec<Nid>, Vec<Nid>) {
        let mut terms: Vec<(bool, Nid)> = pos
            .iter()
            .map(|n| (false, *n))
            .chain(neg.iter().map(|n| (true, *n)))
            .collect();
        loop {
            // How many product terms each operand appears in.
            let mut count: IndexMap<Nid, usize> = IndexMap::new();
            for (_, n) in &terms {
                if self.ir.is_constant(*n) {
                    continue;
                }
                if let Op::Mul(a, b) = *self.ir.op(*n) {
                    *count.entry(a).or_default() += 1;
                    *count.entry(b).or_default() += 1;
                }
            }
            let best = count
                .iter()
                .filter(|(_, c)| **c >= 2)
                .max_by_key(|(k, c)| (self.ir.is_constant(**k), **c, std::cmp::Reverse(**k)))
                .map(|(k, _)| *k);
            let Some(k) = best else { break };
            let (mut p, mut m, mut rest) = (Vec::new(), Vec::new(), Vec::new());
            for (negative, n) in terms {
                let other = match *self.ir.op(n) {
                    _ if self.ir.is_constant(n) => None,
                    Op::Mul(a, b) if a == k => Some(b),
                    Op::Mul(a, b) if b == k => Some(a),
                    _ => None,
                };
                match (other, negative) {
                    (Some(v), false) => p.push(v),
                    (Some(v), true) => m.push(v),
                    (None, _) => rest.push((negative, n)),
                }
            }
            let inner = self.ir.sum(p, m);
            rest.push((false, self.ir.mul(k, inner)));
            terms = rest;
        }
        let pos = terms.iter().filter(|t| !t.0).map(|t| t.1).collect();
        let neg = terms.iter().filter(|t| t.0).map(|t| t.1).collect();
        (pos, neg)
    }

    fn lower_prod(&mut self, c: Number, fs: &[ExprId]) -> Result<Nid, UnboundSymbol> {
        let (constant, variable): (Vec<ExprId>, Vec<ExprId>) =
            fs.iter().partition(|f| self.arena.is_constant(**f));
        let sign_negative = c.is_negative();
        let abs_c = c.abs();
        let r = if !constant.is_empty() && !variable.is_empty() {
            // Pull the constant part out: K * V, K computed once.
            let k = self.arena.product_with(abs_c, &constant);
            let v = self.arena.product(&variable);
            let kn = self.lower(k)?;
            let vn = self.lower(v)?;
            self.ir.mul(kn, vn)
        } else {
            // Numerator factors pairwise, then the denominator, then the
            // numeric coefficient.
            let mut num: Vec<Nid> = Vec::new();
            let mut den: Vec<Nid> = Vec::new();
            for &f in fs {
                match self.reciprocal_base(f) {
                    Some(b) => den.push(self.lower(b)?),
                    None => num.push(self.lower(f)?),
                }
            }
            let n = self.pairwise(&num);
            let d = self.pairwise(&den);
            let lit = abs_c.to_f64();
            let q = match (n, d) {
                (Some(n), Some(d)) => self.ir.div(n, d),
                (Some(n), None) => n,
                (None, Some(d)) => {
                    let l = self.ir.num(lit);
                    let q = self.ir.div(l, d);
                    return Ok(self.signed(q, sign_negative));
                }
                (None, None) => self.ir.num(1.0),
            };
            let l = self.ir.num(lit);
            self.ir.mul(l, q)
        };
        Ok(self.signed(r, sign_negative))
    }

    fn signed(&mut self, n: Nid, negative: bool) -> Nid {
        if negative { self.ir.neg(n) } else { n }
    }

    /// For `b^-k` (k a positive number), the expression `b^k`.
    fn reciprocal_base(&mut self, f: ExprId) -> Option<ExprId> {
        if let Node::Pow(b, x) = self.arena.node(f).clone()
            && let Some(n) = self.arena.as_number(x)
            && n.is_negative()
        {
            let pos = self.arena.num(-n);
            return Some(self.arena.pow(b, pos));
        }
        None
    }

    fn pairwise(&mut self, xs: &[Nid]) -> Option<Nid> {
        let mut it = xs.iter();
        let mut acc = *it.next()?;
        for &x in it {
            acc = self.ir.mul(acc, x);
        }
        Some(acc)
    }

    fn lower_pow(&mut self, b: ExprId, x: ExprId) -> Result<Nid, UnboundSymbol> {
        let base = self.lower(b)?;
        Ok(match self.arena.as_number(x) {
            Some(n) => {
                if let Some(k) = n.as_integer().and_then(|k| i32::try_from(k).ok()) {
                    self.ir.powi(base, k)
                } else if Some(n) == Number::rational(1, 2) {
                    self.ir.sqrt(base)
                } else if Some(n) == Number::rational(-1, 2) {
                    let one = self.ir.num(1.0);
                    let s = self.ir.sqrt(base);
                    self.ir.div(one, s)
                } else {
                    let e = self.ir.num(n.to_f64());
                    self.ir.powf(base, e)
                }
            }
            None => {
                let e = self.lower(x)?;
                self.ir.powf(base, e)
            }
        })
    }
}
