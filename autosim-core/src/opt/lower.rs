//! Lowering canonical expressions to the program IR: products are split into
//! a constant factor (hoisted, computed once per parameter set) and variable
//! factors multiplied pairwise (the paper's Eqs. 15-16), reciprocal powers
//! become divisions, and the constant terms of a sum are grouped into one
//! constant.

use super::ir::{Ir, Nid, Op};
use crate::expr::{Arena, ExprId, Node, Number, SymId};
use indexmap::IndexMap;
use rustc_hash::FxHashMap;

/// Lowers expressions of one arena into an IR, memoized per expression.
pub struct Lowering<'a> {
    arena: &'a mut Arena,
    ir: &'a mut Ir,
    leaves: &'a FxHashMap<SymId, Nid>,
    memo: FxHashMap<ExprId, Nid>,
}

/// A symbol with no value in the program (e.g. a free symbol).
#[derive(Clone, Debug, PartialEq)]
pub struct UnboundSymbol(pub String);

impl<'a> Lowering<'a> {
    /// A lowering where symbols take the IR values in `leaves`.
    pub fn new(arena: &'a mut Arena, ir: &'a mut Ir, leaves: &'a FxHashMap<SymId, Nid>) -> Self {
        Lowering {
            arena,
            ir,
            leaves,
            memo: FxHashMap::default(),
        }
    }

    /// The IR being built (for operations beside lowering).
    pub fn ir(&mut self) -> &mut Ir {
        self.ir
    }

    /// `true` if `e` is exactly zero.
    pub fn is_zero(&self, e: ExprId) -> bool {
        self.arena.is_zero(e)
    }

    /// The user-function calls lowered so far: (expression, IR node).
    pub fn user_calls(&self) -> Vec<(ExprId, Nid)> {
        self.memo
            .iter()
            .filter(|(e, _)| {
                matches!(
                    self.arena.node(**e),
                    Node::Func(crate::expr::Func::User(_), _)
                )
            })
            .map(|(e, n)| (*e, *n))
            .collect()
    }

    /// The IR node computing `e`.
    pub fn lower(&mut self, e: ExprId) -> Result<Nid, UnboundSymbol> {
        if let Some(n) = self.memo.get(&e) {
            return Ok(*n);
        }
        let node = self.arena.node(e).clone();
        let r = match node {
            Node::Num(n) => self.ir.num(n.to_f64()),
            Node::Sym(s) => match self.leaves.get(&s) {
                Some(n) => *n,
                None => return Err(UnboundSymbol(self.arena.symbol(s).name.clone())),
            },
            Node::Sum(terms) => self.lower_sum(&terms)?,
            Node::Prod(c, fs) => self.lower_prod(c, &fs)?,
            Node::Pow(b, x) => self.lower_pow(b, x)?,
            Node::Func(f, args) => {
                let mut xs = Vec::with_capacity(args.len());
                for a in args.iter() {
                    xs.push(self.lower(*a)?);
                }
                self.ir.call(f, xs)
            }
        };
        self.memo.insert(e, r);
        Ok(r)
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
        let (vpos, vneg) = self.common_constant_factors(vpos, vneg);
        Ok(self.ir.sum(vpos, vneg))
    }

    /// Terms `k·a ± k·b ± …` with one constant factor `k` become
    /// `k·(a ± b ± …)`: one multiplication instead of one per term.
    fn common_constant_factors(&mut self, pos: Vec<Nid>, neg: Vec<Nid>) -> (Vec<Nid>, Vec<Nid>) {
        let split = |ir: &Ir, n: Nid| match *ir.op(n) {
            Op::Mul(a, b) if ir.is_constant(a) && !ir.is_constant(b) => Some((a, b)),
            Op::Mul(a, b) if ir.is_constant(b) && !ir.is_constant(a) => Some((b, a)),
            _ => None,
        };
        // Factor → (added, subtracted) cofactors, in order of appearance.
        let mut groups: IndexMap<Nid, (Vec<Nid>, Vec<Nid>)> = IndexMap::new();
        for (negative, n) in pos
            .iter()
            .map(|n| (false, *n))
            .chain(neg.iter().map(|n| (true, *n)))
        {
            if let Some((k, v)) = split(self.ir, n) {
                let g = groups.entry(k).or_default();
                if negative { g.1.push(v) } else { g.0.push(v) }
            }
        }
        groups.retain(|_, (p, m)| p.len() + m.len() >= 2);
        if groups.is_empty() {
            return (pos, neg);
        }
        let grouped =
            |ir: &Ir, n: &Nid| split(ir, *n).is_some_and(|(k, _)| groups.contains_key(&k));
        let mut out_pos: Vec<Nid> = pos
            .iter()
            .copied()
            .filter(|n| !grouped(self.ir, n))
            .collect();
        let out_neg: Vec<Nid> = neg
            .iter()
            .copied()
            .filter(|n| !grouped(self.ir, n))
            .collect();
        for (k, (p, m)) in groups {
            let inner = self.ir.sum(p, m);
            out_pos.push(self.ir.mul(k, inner));
        }
        (out_pos, out_neg)
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
            let pos = self.arena.num(n.neg());
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
