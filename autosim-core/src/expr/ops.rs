//! Scalar operations of the paper's Table 6 that are not constructors:
//! greatest common factor, constant part, substitution, nominal value.

use super::arena::{Arena, ExprId, Node, SymId, SymbolKind};
use super::number::Number;
use rustc_hash::FxHashMap;

impl Arena {
    /// Factor powers `(base, numeric exponent)` of a non-numeric expression,
    /// and its numeric coefficient.
    fn factor_powers(&self, e: ExprId) -> (Number, Vec<(ExprId, Number)>) {
        let (c, factors) = self.coefficient_and_factors(e);
        let powers = factors
            .into_iter()
            .map(|f| match self.node(f) {
                Node::Pow(b, x) => match self.as_number(*x) {
                    Some(n) => (*b, n),
                    None => (f, Number::ONE),
                },
                _ => (f, Number::ONE),
            })
            .collect();
        (c, powers)
    }

    /// The symbolic greatest common factor of two expressions (no numeric
    /// part), or `None` if they share no factor.
    pub(crate) fn symbolic_gcf(&mut self, a: ExprId, b: ExprId) -> Option<ExprId> {
        if self.as_number(a).is_some() || self.as_number(b).is_some() {
            return None;
        }
        let (_, pa) = self.factor_powers(a);
        let (_, pb) = self.factor_powers(b);
        let mut common: Vec<ExprId> = Vec::new();
        for (base, ea) in &pa {
            if let Some((_, eb)) = pb.iter().find(|(bb, _)| bb == base) {
                let both_pos = !ea.is_negative() && !eb.is_negative();
                let both_neg = ea.is_negative() && eb.is_negative();
                let e = if both_pos {
                    if ea.cmp_value(*eb).is_le() { *ea } else { *eb }
                } else if both_neg {
                    if ea.cmp_value(*eb).is_ge() { *ea } else { *eb }
                } else {
                    continue;
                };
                let ee = self.num(e);
                common.push(self.pow(*base, ee));
            }
        }
        if common.is_empty() {
            return None;
        }
        Some(self.product(&common))
    }

    /// The greatest common factor of two expressions (the paper's `gcf`):
    /// the common symbolic factors times the gcd of the numeric coefficients.
    pub fn gcf(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let (ca, _) = self.coefficient_and_factors(a);
        let (cb, _) = self.coefficient_and_factors(b);
        let g = ca.gcd(cb);
        match self.symbolic_gcf(a, b) {
            Some(s) => self.scale(g, s),
            None => self.num(g),
        }
    }

    /// The paper's `constant-part`: the expression itself if it is
    /// constant, the sum of the constant terms of a sum, otherwise 0.
    pub fn constant_part(&mut self, e: ExprId) -> ExprId {
        if self.is_constant(e) {
            return e;
        }
        match self.node(e).clone() {
            Node::Sum(ts) => {
                let consts: Vec<ExprId> = ts
                    .iter()
                    .copied()
                    .filter(|t| self.is_constant(*t))
                    .collect();
                self.sum(&consts)
            }
            Node::Prod(c, fs) if fs.len() == 1 => {
                let inner = self.constant_part(fs[0]);
                self.scale(c, inner)
            }
            _ => self.zero(),
        }
    }

    /// Rebuilds a node with new children through the simplifying constructors.
    pub(crate) fn rebuild(&mut self, node: &Node, children: &[ExprId]) -> ExprId {
        match node {
            Node::Num(_) | Node::Sym(_) => unreachable_leaf(self, node),
            Node::Sum(_) => self.sum(children),
            Node::Prod(c, _) => self.product_with(*c, children),
            Node::Pow(..) => self.pow(children[0], children[1]),
            Node::Func(f, _) => self.func(*f, children),
        }
    }

    /// Replaces symbols by expressions everywhere in `e`.
    pub fn substitute(&mut self, e: ExprId, map: &FxHashMap<SymId, ExprId>) -> ExprId {
        let mut memo: FxHashMap<ExprId, ExprId> = FxHashMap::default();
        self.substitute_memo(e, map, &mut memo)
    }

    /// Like [`Arena::substitute`], sharing a memo across calls with the same map.
    pub fn substitute_memo(
        &mut self,
        e: ExprId,
        map: &FxHashMap<SymId, ExprId>,
        memo: &mut FxHashMap<ExprId, ExprId>,
    ) -> ExprId {
        if let Some(r) = memo.get(&e) {
            return *r;
        }
        let node = self.node(e).clone();
        let r = match &node {
            Node::Num(_) => e,
            Node::Sym(s) => map.get(s).copied().unwrap_or(e),
            _ => {
                let kids = self.children(e);
                let new: Vec<ExprId> = kids
                    .iter()
                    .map(|k| self.substitute_memo(*k, map, memo))
                    .collect();
                if new == kids {
                    e
                } else {
                    self.rebuild(&node, &new)
                }
            }
        };
        memo.insert(e, r);
        r
    }

    /// The paper's `nominal`: the expression with every generalized
    /// coordinate set to zero.
    pub fn nominal(&mut self, e: ExprId) -> ExprId {
        let zero = self.zero();
        let map: FxHashMap<SymId, ExprId> = self
            .symbols()
            .filter(|(_, s)| matches!(s.kind, SymbolKind::Coordinate { .. }))
            .map(|(id, _)| (id, zero))
            .collect();
        self.substitute(e, &map)
    }

    /// `true` if `e` depends on symbol `s`.
    pub fn depends_on(&self, e: ExprId, s: SymId) -> bool {
        let target = self.sym(s);
        if e == target {
            return true;
        }
        if target > e {
            // Children have smaller ids than parents.
            return false;
        }
        let mut stack = vec![e];
        let mut seen = rustc_hash::FxHashSet::default();
        while let Some(x) = stack.pop() {
            if x == target {
                return true;
            }
            if x < target || !seen.insert(x) {
                continue;
            }
            stack.extend(self.children(x));
        }
        false
    }

    /// The symbols `e` depends on, sorted.
    pub fn free_symbols(&self, e: ExprId) -> Vec<SymId> {
        let mut out = Vec::new();
        let mut stack = vec![e];
        let mut seen = rustc_hash::FxHashSet::default();
        while let Some(x) = stack.pop() {
            if !seen.insert(x) {
                continue;
            }
            match self.node(x) {
                Node::Sym(s) => out.push(*s),
                _ => stack.extend(self.children(x)),
            }
        }
        out.sort();
        out.dedup();
        out
    }
}

fn unreachable_leaf(_arena: &mut Arena, _node: &Node) -> ExprId {
    // Leaves have no children and are never rebuilt; return 0 defensively.
    ExprId(0)
}
