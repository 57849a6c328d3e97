//! Symbolic differentiation: partial derivatives and time derivatives.

use super::arena::{Arena, ExprError, ExprId, Func, Node, SymId};
use super::number::Number;
use rustc_hash::FxHashMap;

impl Arena {
    /// The partial derivative `∂e/∂x` (the paper's `partial`).
    pub fn partial(&mut self, e: ExprId, x: SymId) -> Result<ExprId, ExprError> {
        let mut memo = FxHashMap::default();
        self.partial_memo(e, x, &mut memo)
    }

    /// Like [`Arena::partial`], sharing a memo across calls for the same `x`.
    pub fn partial_memo(
        &mut self,
        e: ExprId,
        x: SymId,
        memo: &mut FxHashMap<ExprId, ExprId>,
    ) -> Result<ExprId, ExprError> {
        let target = self.sym(x);
        let skip_constants = !self.symbol(x).is_constant();
        self.differentiate(
            e,
            memo,
            &mut |arena, s| {
                Ok(if arena.sym(s) == target {
                    arena.one()
                } else {
                    arena.zero()
                })
            },
            Some(target),
            skip_constants,
            self.len() + self.derivative_limit,
        )
    }

    /// The time derivative `de/dt` (the paper's `dxdt`), using each
    /// symbol's declared derivative.
    pub fn dxdt(&mut self, e: ExprId) -> Result<ExprId, ExprError> {
        let mut memo = FxHashMap::default();
        self.dxdt_memo(e, &mut memo)
    }

    /// Like [`Arena::dxdt`], sharing a memo across calls.
    pub fn dxdt_memo(
        &mut self,
        e: ExprId,
        memo: &mut FxHashMap<ExprId, ExprId>,
    ) -> Result<ExprId, ExprError> {
        self.differentiate(
            e,
            memo,
            &mut |arena, s| {
                arena
                    .dxdt_of_symbol(s)
                    .ok_or_else(|| ExprError::NoDerivative(arena.symbol(s).name.clone()))
            },
            None,
            true,
            self.len() + self.derivative_limit,
        )
    }

    /// Derivative by the chain rule; `leaf` gives the derivative of each
    /// symbol. With `only`, subtrees with ids below that symbol's node (which
    /// cannot contain it) are skipped. Fails once the arena has `limit` nodes.
    fn differentiate(
        &mut self,
        e: ExprId,
        memo: &mut FxHashMap<ExprId, ExprId>,
        leaf: &mut dyn FnMut(&mut Arena, SymId) -> Result<ExprId, ExprError>,
        only: Option<ExprId>,
        skip_constants: bool,
        limit: usize,
    ) -> Result<ExprId, ExprError> {
        if let Some(t) = only
            && e < t
        {
            return Ok(self.zero());
        }
        if skip_constants && self.is_constant(e) {
            return Ok(self.zero());
        }
        if let Some(r) = memo.get(&e) {
            return Ok(*r);
        }
        if self.len() >= limit {
            return Err(ExprError::TooLarge(self.derivative_limit));
        }
        let node = self.node(e).clone();
        let r = match node {
            Node::Num(_) => self.zero(),
            Node::Sym(s) => leaf(self, s)?,
            Node::Sum(ts) => {
                let mut parts = Vec::with_capacity(ts.len());
                for t in ts.iter() {
                    parts.push(self.differentiate(*t, memo, leaf, only, skip_constants, limit)?);
                }
                self.sum(&parts)
            }
            Node::Prod(c, fs) => {
                let mut parts = Vec::with_capacity(fs.len());
                for i in 0..fs.len() {
                    let d = self.differentiate(fs[i], memo, leaf, only, skip_constants, limit)?;
                    if self.is_zero(d) {
                        continue;
                    }
                    let mut factors: Vec<ExprId> = Vec::with_capacity(fs.len());
                    factors.extend(
                        fs.iter()
                            .enumerate()
                            .filter(|(j, _)| *j != i)
                            .map(|(_, f)| *f),
                    );
                    factors.push(d);
                    parts.push(self.product_with(c, &factors));
                }
                self.sum(&parts)
            }
            Node::Pow(b, x) => {
                let db = self.differentiate(b, memo, leaf, only, skip_constants, limit)?;
                if let Some(n) = self.as_number(x) {
                    // n b^(n-1) db
                    let nm1 = self.num(n - Number::ONE);
                    let p = self.pow(b, nm1);
                    let t = self.mul(p, db);
                    self.scale(n, t)
                } else {
                    // b^x (dx ln b + x db / b)
                    let dx = self.differentiate(x, memo, leaf, only, skip_constants, limit)?;
                    let lnb = self.func(Func::Ln, &[b]);
                    let t1 = self.mul(dx, lnb);
                    let t2 = self.product(&[x, db]);
                    let t2 = self.div(t2, b);
                    let s = self.sum(&[t1, t2]);
                    self.mul(e, s)
                }
            }
            Node::Func(f, args) => {
                let mut dargs = Vec::with_capacity(args.len());
                for a in args.iter() {
                    dargs.push(self.differentiate(*a, memo, leaf, only, skip_constants, limit)?);
                }
                if dargs.iter().all(|d| self.is_zero(*d)) {
                    self.zero()
                } else {
                    self.func_derivative(f, &args, &dargs)?
                }
            }
        };
        memo.insert(e, r);
        Ok(r)
    }

    fn func_derivative(
        &mut self,
        f: Func,
        args: &[ExprId],
        dargs: &[ExprId],
    ) -> Result<ExprId, ExprError> {
        let a = args[0];
        let da = dargs[0];
        Ok(match f {
            Func::Sin => {
                let c = self.cos(a);
                self.mul(c, da)
            }
            Func::Cos => {
                let s = self.sin(a);
                let t = self.mul(s, da);
                self.neg(t)
            }
            Func::Tan => {
                // (1 + tan²) da
                let t = self.func(Func::Tan, &[a]);
                let t2 = self.powi(t, 2);
                let one = self.one();
                let s = self.sum(&[one, t2]);
                self.mul(s, da)
            }
            Func::Asin | Func::Acos => {
                let a2 = self.powi(a, 2);
                let one = self.one();
                let na2 = self.neg(a2);
                let s = self.sum(&[one, na2]);
                let r = self.sqrt(s);
                let q = self.div(da, r);
                if f == Func::Acos { self.neg(q) } else { q }
            }
            Func::Atan2 => {
                // (x dy - y dx) / (x² + y²)
                let (y, x) = (args[0], args[1]);
                let (dy, dx) = (dargs[0], dargs[1]);
                let t1 = self.mul(x, dy);
                let t2 = self.mul(y, dx);
                let num = self.sub(t1, t2);
                let x2 = self.powi(x, 2);
                let y2 = self.powi(y, 2);
                let den = self.sum(&[x2, y2]);
                self.div(num, den)
            }
            Func::Exp => {
                let e = self.func(Func::Exp, &[a]);
                self.mul(e, da)
            }
            Func::Ln => self.div(da, a),
            Func::Abs => {
                let s = self.func(Func::Sign, &[a]);
                self.mul(s, da)
            }
            Func::Sign => self.zero(),
            Func::Min | Func::Max => {
                return Err(ExprError::NotDifferentiable(self.func_name(f).to_string()));
            }
            Func::User(u) => {
                return Err(ExprError::NotDifferentiable(self.user_fn(u).name.clone()));
            }
        })
    }
}
