//! What the property tests of the expression algebra share (the paper's
//! Tables 5 and 6; `algebra_simplify.rs`, `algebra_calculus.rs` and
//! `algebra_text.rs` include it as `mod algebra;`).
//!
//! Random expression trees are built twice: through the arena's simplifying
//! constructors ([`build`]), and as a plain tree evaluated directly in f64
//! with no simplification at all ([`direct::direct`]). The direct evaluation
//! is the independent truth; it also carries a first-order error bound (a
//! running error analysis) so that ill-conditioned points get a fair
//! tolerance instead of being skipped.

// Each test file uses a part of it.
#![allow(dead_code)]

use autosim_core::expr::{
    Arena, Bindings, ExprId, NoUserFunctions, Node, Number, SymId, SymbolKind,
};
use proptest::prelude::*;
use rustc_hash::FxHashMap;

pub mod direct;

pub const EPS: f64 = f64::EPSILON;

/// Symbols of the trees: x, y (free), q (a coordinate), p (free, positive),
/// k (a parameter, positive).
pub const NAMES: [&str; 5] = ["x", "y", "q", "p", "k"];
pub const X: usize = 0;
pub const Q: usize = 2;
pub const P: usize = 3;
pub const K: usize = 4;

#[derive(Clone, Debug)]
pub enum T {
    Sym(usize),
    Int(i64),
    Rat(i64, i64),
    Flt(f64),
    Add(Box<T>, Box<T>),
    Sub(Box<T>, Box<T>),
    Mul(Box<T>, Box<T>),
    Div(Box<T>, Box<T>),
    Neg(Box<T>),
    PowI(Box<T>, i64),
    Sin(Box<T>),
    Cos(Box<T>),
    Exp(Box<T>),
    Atan2(Box<T>, Box<T>),
    /// Only ever of a non-negative argument.
    Sqrt(Box<T>),
}

pub fn bx(t: T) -> Box<T> {
    Box::new(t)
}

pub fn leaf(nsyms: usize) -> impl Strategy<Value = T> {
    prop_oneof![
        5 => (0..nsyms).prop_map(T::Sym),
        1 => (-3i64..=3).prop_map(T::Int),
        1 => ((-3i64..=3), (1i64..=4)).prop_map(|(n, d)| T::Rat(n, d)),
        1 => prop::sample::select(vec![0.5, 1.5, -0.25, 2.75]).prop_map(T::Flt),
    ]
}

pub fn tree_over(nsyms: usize, depth: u32) -> impl Strategy<Value = T> {
    leaf(nsyms).prop_recursive(depth, 32, 2, |inner| {
        prop_oneof![
            3 => (inner.clone(), inner.clone()).prop_map(|(a, b)| T::Add(bx(a), bx(b))),
            2 => (inner.clone(), inner.clone()).prop_map(|(a, b)| T::Sub(bx(a), bx(b))),
            3 => (inner.clone(), inner.clone()).prop_map(|(a, b)| T::Mul(bx(a), bx(b))),
            1 => (inner.clone(), inner.clone()).prop_map(|(a, b)| T::Div(bx(a), bx(b))),
            1 => inner.clone().prop_map(|a| T::Neg(bx(a))),
            1 => (inner.clone(), prop::sample::select(vec![-2i64, -1, 2, 3]))
                .prop_map(|(a, n)| T::PowI(bx(a), n)),
            1 => inner.clone().prop_map(|a| T::Sin(bx(a))),
            1 => inner.clone().prop_map(|a| T::PowI(bx(T::Sin(bx(a))), 2)),
            1 => inner.clone().prop_map(|a| T::PowI(bx(T::Cos(bx(a))), 2)),
            1 => inner.clone().prop_map(|a| T::Cos(bx(a))),
            1 => inner.clone().prop_map(|a| T::Exp(bx(a))),
            1 => (inner.clone(), inner.clone()).prop_map(|(a, b)| T::Atan2(bx(a), bx(b))),
            1 => (inner.clone(), 0u8..4).prop_map(|(a, kind)| T::Sqrt(bx(positive(a, kind)))),
        ]
    })
}

pub fn tree() -> impl Strategy<Value = T> {
    tree_over(NAMES.len(), 4)
}

/// A non-negative expression made from `a`.
pub fn positive(a: T, kind: u8) -> T {
    match kind {
        0 => T::Add(bx(T::Mul(bx(a.clone()), bx(a))), bx(T::Rat(1, 2))),
        1 => T::Exp(bx(a)),
        2 => T::Mul(bx(a.clone()), bx(a)),
        _ => T::Mul(
            bx(T::Sym(P)),
            bx(T::Add(bx(T::Mul(bx(a.clone()), bx(a))), bx(T::Int(1)))),
        ),
    }
}

/// `t` with each child replaced by `f(child)` (leaves as they are).
pub fn map_children(t: &T, mut f: impl FnMut(&T) -> T) -> T {
    let mut s = |a: &T| bx(f(a));
    match t {
        T::Sym(_) | T::Int(_) | T::Rat(..) | T::Flt(_) => t.clone(),
        T::Add(a, b) => T::Add(s(a), s(b)),
        T::Sub(a, b) => T::Sub(s(a), s(b)),
        T::Mul(a, b) => T::Mul(s(a), s(b)),
        T::Div(a, b) => T::Div(s(a), s(b)),
        T::Neg(a) => T::Neg(s(a)),
        T::PowI(a, n) => T::PowI(s(a), *n),
        T::Sin(a) => T::Sin(s(a)),
        T::Cos(a) => T::Cos(s(a)),
        T::Exp(a) => T::Exp(s(a)),
        T::Atan2(a, b) => T::Atan2(s(a), s(b)),
        T::Sqrt(a) => T::Sqrt(s(a)),
    }
}

/// Replaces symbols by trees.
pub fn subst_tree(t: &T, map: &FxHashMap<usize, T>) -> T {
    match t {
        T::Sym(i) => map.get(i).cloned().unwrap_or(T::Sym(*i)),
        _ => map_children(t, |a| subst_tree(a, map)),
    }
}

// ----- building through the constructors -----

pub struct Ctx {
    pub arena: Arena,
    pub syms: Vec<SymId>,
}

pub fn ctx_with(small: &[usize]) -> Ctx {
    let mut arena = Arena::new();
    let mut syms = Vec::new();
    for (i, n) in NAMES.iter().enumerate() {
        let kind = match i {
            Q => SymbolKind::Coordinate { index: 0 },
            K => SymbolKind::Parameter { default: 1.0 },
            _ => SymbolKind::Free,
        };
        let s = arena.add_symbol(n, kind).unwrap();
        if small.contains(&i) {
            arena.set_small(s, true);
        }
        syms.push(s);
    }
    Ctx { arena, syms }
}

pub fn ctx() -> Ctx {
    ctx_with(&[])
}

pub fn build(c: &mut Ctx, t: &T) -> ExprId {
    use autosim_core::expr::Func;
    match t {
        T::Sym(i) => c.arena.sym(c.syms[*i]),
        T::Int(n) => c.arena.int(*n),
        T::Rat(n, d) => c.arena.rational(*n, *d),
        T::Flt(v) => c.arena.num(Number::float(*v).unwrap()),
        T::Add(a, b) => build_binary(c, a, b, Arena::add),
        T::Sub(a, b) => build_binary(c, a, b, Arena::sub),
        T::Mul(a, b) => build_binary(c, a, b, Arena::mul),
        T::Div(a, b) => build_binary(c, a, b, Arena::div),
        T::Neg(a) => build_unary(c, a, Arena::neg),
        T::PowI(a, n) => {
            let a = build(c, a);
            c.arena.powi(a, *n)
        }
        T::Sin(a) => build_unary(c, a, Arena::sin),
        T::Cos(a) => build_unary(c, a, Arena::cos),
        T::Exp(a) => build_unary(c, a, |arena, a| arena.func(Func::Exp, &[a])),
        T::Atan2(a, b) => build_binary(c, a, b, |arena, a, b| arena.func(Func::Atan2, &[a, b])),
        T::Sqrt(a) => build_unary(c, a, Arena::sqrt),
    }
}

/// `op` of the built operand.
fn build_unary(c: &mut Ctx, a: &T, op: fn(&mut Arena, ExprId) -> ExprId) -> ExprId {
    let a = build(c, a);
    op(&mut c.arena, a)
}

/// `op` of the built operands, built left first.
fn build_binary(c: &mut Ctx, a: &T, b: &T, op: fn(&mut Arena, ExprId, ExprId) -> ExprId) -> ExprId {
    let (a, b) = (build(c, a), build(c, b));
    op(&mut c.arena, a, b)
}

pub fn eval(c: &Ctx, e: ExprId, vals: &[f64]) -> f64 {
    let mut b = Bindings::with_defaults(&c.arena);
    for (i, v) in vals.iter().enumerate() {
        b.set(c.syms[i], *v);
    }
    c.arena.eval(e, &b, &mut NoUserFunctions)
}

pub fn value_strategy() -> impl Strategy<Value = [f64; 5]> {
    (
        -2.0..2.0f64,
        -2.0..2.0f64,
        -2.0..2.0f64,
        0.2..2.0f64,
        0.2..2.0f64,
    )
        .prop_map(|(x, y, q, p, k)| [x, y, q, p, k])
}

pub fn config() -> ProptestConfig {
    ProptestConfig {
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(256),
        ..ProptestConfig::default()
    }
}

// ----- factor structure, for gcf -----

/// (coefficient, [(base, numeric exponent)]) of an expression, by the
/// definition of a monomial: a product's factors, a power's base.
pub fn monomial(a: &Arena, e: ExprId) -> (Number, Vec<(ExprId, Number)>) {
    let (c, fs) = match a.node(e) {
        Node::Num(n) => (*n, vec![]),
        Node::Prod(c, fs) => (*c, fs.to_vec()),
        _ => (Number::ONE, vec![e]),
    };
    let powers = fs
        .into_iter()
        .map(|f| match a.node(f) {
            Node::Pow(b, x) => match a.as_number(*x) {
                Some(n) => (*b, n),
                None => (f, Number::ONE),
            },
            _ => (f, Number::ONE),
        })
        .collect();
    (c, powers)
}

pub fn exponent_of(m: &[(ExprId, Number)], base: ExprId) -> Number {
    m.iter()
        .find(|(b, _)| *b == base)
        .map(|(_, n)| *n)
        .unwrap_or(Number::ZERO)
}
