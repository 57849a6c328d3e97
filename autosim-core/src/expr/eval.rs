//! Numeric evaluation of expressions: the oracle every optimization and every
//! generated program is checked against.

use super::Number;
use super::arena::{Arena, ExprId, Func, Node, SymId, UserFnId};
use rustc_hash::FxHashSet;

/// Values of user functions during evaluation.
pub trait UserFunctions {
    /// Calls user function `f` (named `name`) with `args`.
    fn call(&mut self, f: UserFnId, name: &str, args: &[f64]) -> f64;
}

/// User functions that are not available: every call gives NaN.
pub struct NoUserFunctions;

impl UserFunctions for NoUserFunctions {
    fn call(&mut self, _f: UserFnId, _name: &str, _args: &[f64]) -> f64 {
        f64::NAN
    }
}

impl<F: FnMut(UserFnId, &str, &[f64]) -> f64> UserFunctions for F {
    fn call(&mut self, f: UserFnId, name: &str, args: &[f64]) -> f64 {
        self(f, name, args)
    }
}

/// Values of symbols for evaluation; unset symbols evaluate to NaN.
#[derive(Clone, Debug, Default)]
pub struct Bindings {
    values: Vec<f64>,
}

impl Bindings {
    /// All symbols of `arena` unset, parameters and inputs at their defaults.
    pub fn with_defaults(arena: &Arena) -> Bindings {
        use super::arena::SymbolKind;
        let values = arena
            .symbols()
            .map(|(_, s)| match s.kind {
                SymbolKind::Parameter { default }
                | SymbolKind::Input { default }
                | SymbolKind::Discrete { default } => default,
                _ => f64::NAN,
            })
            .collect();
        Bindings { values }
    }

    /// Sets a symbol's value.
    pub fn set(&mut self, s: SymId, value: f64) {
        if self.values.len() <= s.index() {
            self.values.resize(s.index() + 1, f64::NAN);
        }
        self.values[s.index()] = value;
    }

    /// A symbol's value (NaN if unset).
    pub fn get(&self, s: SymId) -> f64 {
        self.values.get(s.index()).copied().unwrap_or(f64::NAN)
    }
}

impl Arena {
    /// Evaluates one expression.
    pub fn eval(&self, e: ExprId, bindings: &Bindings, user: &mut dyn UserFunctions) -> f64 {
        self.eval_many(&[e], bindings, user)[0]
    }

    /// Evaluates several expressions, sharing common subexpressions.
    pub fn eval_many(
        &self,
        roots: &[ExprId],
        bindings: &Bindings,
        user: &mut dyn UserFunctions,
    ) -> Vec<f64> {
        // Collect the reachable nodes; children have smaller ids, so
        // ascending order evaluates every node after its children.
        let mut seen: FxHashSet<ExprId> = FxHashSet::default();
        let mut stack: Vec<ExprId> = roots.to_vec();
        let mut order: Vec<ExprId> = Vec::new();
        while let Some(x) = stack.pop() {
            if seen.insert(x) {
                order.push(x);
                stack.extend(self.children(x));
            }
        }
        order.sort_unstable();
        let mut values: rustc_hash::FxHashMap<ExprId, f64> = rustc_hash::FxHashMap::default();
        values.reserve(order.len());
        let mut args: Vec<f64> = Vec::new();
        for &x in &order {
            let v = match self.node(x) {
                Node::Num(n) => n.to_f64(),
                Node::Sym(s) => bindings.get(*s),
                Node::Sum(ts) => ts.iter().map(|t| values[t]).sum(),
                Node::Prod(c, fs) => fs.iter().fold(c.to_f64(), |acc, f| acc * values[f]),
                Node::Pow(b, e) => {
                    let (bv, ev) = (values[b], values[e]);
                    match self.as_number(*e).and_then(|n| n.as_integer()) {
                        Some(k) if (-64..=64).contains(&k) => bv.powi(k as i32),
                        _ => bv.powf(ev),
                    }
                }
                Node::Func(f, a) => {
                    args.clear();
                    args.extend(a.iter().map(|k| values[k]));
                    apply(self, *f, &args, user)
                }
            };
            values.insert(x, v);
        }
        roots.iter().map(|r| values[r]).collect()
    }
}

impl Arena {
    /// The value of a number, or of a function or power of numbers (what
    /// constant folding leaves unevaluated when its value is not finite:
    /// `sqrt(-1)`, `ln(0)`); `None` for anything that involves a symbol or
    /// a user function. The resolver checks each value it builds with it,
    /// so a non-finite constant is reported where it is written.
    pub fn numeric_value(&self, e: ExprId) -> Option<f64> {
        match self.node(e) {
            Node::Num(n) => Some(n.to_f64()),
            Node::Pow(b, x) => {
                self.as_number(*b)?;
                self.as_number(*x)?;
                Some(self.eval(e, &Bindings::default(), &mut NoUserFunctions))
            }
            Node::Func(f, args) if !matches!(f, Func::User(_)) => {
                let values: Option<Vec<f64>> = args
                    .iter()
                    .map(|a| self.as_number(*a).map(Number::to_f64))
                    .collect();
                f.eval_builtin(&values?)
            }
            _ => None,
        }
    }
}

fn apply(arena: &Arena, f: Func, a: &[f64], user: &mut dyn UserFunctions) -> f64 {
    match f {
        Func::User(u) => user.call(u, &arena.user_fn(u).name, a),
        builtin => builtin.eval_builtin(a).unwrap_or(f64::NAN),
    }
}
