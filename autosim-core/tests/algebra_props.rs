//! Property tests of the expression algebra (the paper's Tables 5 and 6).
//!
//! Random expression trees are built twice: through the arena's simplifying
//! constructors, and as a plain tree evaluated directly in f64 with no
//! simplification at all. The direct evaluation is the independent truth;
//! it also carries a first-order error bound (a running error analysis) so
//! that ill-conditioned points get a fair tolerance instead of being
//! skipped.

use autosim_core::expr::{
    Arena, Bindings, ExprId, NoUserFunctions, Node, Number, SymId, SymbolKind,
};
use proptest::prelude::*;
use rustc_hash::FxHashMap;

const EPS: f64 = f64::EPSILON;

/// Symbols of the trees: x, y (free), q (a coordinate), p (free, positive),
/// k (a parameter, positive).
const NAMES: [&str; 5] = ["x", "y", "q", "p", "k"];
const X: usize = 0;
const Q: usize = 2;
const P: usize = 3;
const K: usize = 4;

#[derive(Clone, Debug)]
enum T {
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

fn bx(t: T) -> Box<T> {
    Box::new(t)
}

fn leaf(nsyms: usize) -> impl Strategy<Value = T> {
    prop_oneof![
        5 => (0..nsyms).prop_map(T::Sym),
        1 => (-3i64..=3).prop_map(T::Int),
        1 => ((-3i64..=3), (1i64..=4)).prop_map(|(n, d)| T::Rat(n, d)),
        1 => prop::sample::select(vec![0.5, 1.5, -0.25, 2.75]).prop_map(T::Flt),
    ]
}

fn tree_over(nsyms: usize, depth: u32) -> impl Strategy<Value = T> {
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

fn tree() -> impl Strategy<Value = T> {
    tree_over(NAMES.len(), 4)
}

/// A non-negative expression made from `a`.
fn positive(a: T, kind: u8) -> T {
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

/// Replaces symbols by trees.
fn subst_tree(t: &T, map: &FxHashMap<usize, T>) -> T {
    let s = |a: &T| bx(subst_tree(a, map));
    match t {
        T::Sym(i) => map.get(i).cloned().unwrap_or(T::Sym(*i)),
        T::Int(_) | T::Rat(..) | T::Flt(_) => t.clone(),
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

// ----- building through the constructors -----

struct Ctx {
    arena: Arena,
    syms: Vec<SymId>,
}

fn ctx_with(small: &[usize]) -> Ctx {
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

fn ctx() -> Ctx {
    ctx_with(&[])
}

fn build(c: &mut Ctx, t: &T) -> ExprId {
    match t {
        T::Sym(i) => c.arena.sym(c.syms[*i]),
        T::Int(n) => c.arena.int(*n),
        T::Rat(n, d) => c.arena.rational(*n, *d),
        T::Flt(v) => c.arena.num(Number::float(*v).unwrap()),
        T::Add(a, b) => {
            let (a, b) = (build(c, a), build(c, b));
            c.arena.add(a, b)
        }
        T::Sub(a, b) => {
            let (a, b) = (build(c, a), build(c, b));
            c.arena.sub(a, b)
        }
        T::Mul(a, b) => {
            let (a, b) = (build(c, a), build(c, b));
            c.arena.mul(a, b)
        }
        T::Div(a, b) => {
            let (a, b) = (build(c, a), build(c, b));
            c.arena.div(a, b)
        }
        T::Neg(a) => {
            let a = build(c, a);
            c.arena.neg(a)
        }
        T::PowI(a, n) => {
            let a = build(c, a);
            c.arena.powi(a, *n)
        }
        T::Sin(a) => {
            let a = build(c, a);
            c.arena.sin(a)
        }
        T::Cos(a) => {
            let a = build(c, a);
            c.arena.cos(a)
        }
        T::Exp(a) => {
            let a = build(c, a);
            c.arena.func(autosim_core::expr::Func::Exp, &[a])
        }
        T::Atan2(a, b) => {
            let (a, b) = (build(c, a), build(c, b));
            c.arena.func(autosim_core::expr::Func::Atan2, &[a, b])
        }
        T::Sqrt(a) => {
            let a = build(c, a);
            c.arena.sqrt(a)
        }
    }
}

fn eval(c: &Ctx, e: ExprId, vals: &[f64]) -> f64 {
    let mut b = Bindings::with_defaults(&c.arena);
    for (i, v) in vals.iter().enumerate() {
        b.set(c.syms[i], *v);
    }
    c.arena.eval(e, &b, &mut NoUserFunctions)
}

// ----- direct evaluation with a running error bound -----

/// Value `v`; magnitude bound `s` (the tree evaluated with absolute values,
/// ordinary symbols at least 1 in magnitude); first-order error bound `e`:
/// the output's change when every intermediate result is perturbed by a
/// relative amount of its magnitude bound (a sum by the sum of its terms'
/// magnitudes), in units of that relative amount.
#[derive(Clone, Copy, Debug)]
struct V {
    v: f64,
    s: f64,
    e: f64,
}

fn direct(t: &T, vals: &[f64], small: &[usize]) -> V {
    let d = |a: &T| direct(a, vals, small);
    match t {
        T::Sym(i) => {
            let v = vals[*i];
            let s = if small.contains(i) {
                v.abs()
            } else {
                v.abs().max(1.0)
            };
            V { v, s, e: 0.0 }
        }
        T::Int(n) => num(*n as f64),
        T::Rat(n, dd) => num(*n as f64 / *dd as f64),
        T::Flt(v) => num(*v),
        T::Add(a, b) | T::Sub(a, b) => {
            let (a, b) = (d(a), d(b));
            let v = if matches!(t, T::Add(..)) {
                a.v + b.v
            } else {
                a.v - b.v
            };
            let s = a.s + b.s;
            V {
                v,
                s,
                e: a.e + b.e + s,
            }
        }
        T::Mul(a, b) => {
            let (a, b) = (d(a), d(b));
            let s = a.s * b.s;
            V {
                v: a.v * b.v,
                s,
                e: b.v.abs() * a.e + a.v.abs() * b.e + s,
            }
        }
        T::Div(a, b) => {
            let (a, b) = (d(a), d(b));
            let s = a.s / b.v.abs();
            V {
                v: a.v / b.v,
                s,
                e: a.e / b.v.abs() + a.v.abs() * b.e / (b.v * b.v) + s,
            }
        }
        T::Neg(a) => {
            let a = d(a);
            V { v: -a.v, ..a }
        }
        T::PowI(a, n) => {
            let a = d(a);
            let v = a.v.powi(*n as i32);
            let s = if *n > 0 { a.s.powi(*n as i32) } else { v.abs() };
            let dv = (*n as f64).abs() * a.v.abs().powi(*n as i32 - 1);
            V {
                v,
                s,
                e: dv * a.e + s,
            }
        }
        T::Sin(a) => {
            let a = d(a);
            let v = a.v.sin();
            V {
                v,
                s: v.abs().max(a.s.min(1.0)),
                e: a.v.cos().abs() * a.e + a.s + v.abs(),
            }
        }
        T::Cos(a) => {
            let a = d(a);
            let v = a.v.cos();
            V {
                v,
                s: 1.0,
                e: a.v.sin().abs() * a.e + 1.0 + a.s,
            }
        }
        T::Exp(a) => {
            let a = d(a);
            let v = a.v.exp();
            V {
                v,
                s: v,
                e: v * a.e + v * (1.0 + a.s),
            }
        }
        T::Atan2(y, x) => {
            let (y, x) = (d(y), d(x));
            // On the branch cut (y = 0 within rounding, x < 0) the value
            // is ±π depending on the sign of a zero: no reference value.
            let on_cut = x.v < 0.0 && y.v.abs() <= 64.0 * EPS * y.e;
            let v = if on_cut { f64::NAN } else { y.v.atan2(x.v) };
            let r2 = x.v * x.v + y.v * y.v;
            V {
                v,
                s: v.abs(),
                e: (x.v.abs() * y.e + y.v.abs() * x.e) / r2 + v.abs(),
            }
        }
        T::Sqrt(a) => {
            let a = d(a);
            let v = a.v.sqrt();
            V {
                v,
                s: a.s.sqrt(),
                e: a.e / (2.0 * v) + v,
            }
        }
    }
}

fn num(v: f64) -> V {
    V {
        v,
        s: v.abs(),
        e: 0.0,
    }
}

fn value_strategy() -> impl Strategy<Value = [f64; 5]> {
    (
        -2.0..2.0f64,
        -2.0..2.0f64,
        -2.0..2.0f64,
        0.2..2.0f64,
        0.2..2.0f64,
    )
        .prop_map(|(x, y, q, p, k)| [x, y, q, p, k])
}

/// Asserts `got` matches the direct evaluation `want` to relative 1e-9 plus
/// the rounding allowance; skips non-finite reference values.
fn close(got: f64, want: V) -> Result<(), TestCaseError> {
    if !want.v.is_finite() || !want.e.is_finite() {
        return Ok(());
    }
    let tol = 1e-9 * want.v.abs() + 64.0 * EPS * want.e;
    prop_assert!(
        (got - want.v).abs() <= tol,
        "constructed {got} vs direct {} (tolerance {tol:e})",
        want.v
    );
    Ok(())
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(256),
        ..ProptestConfig::default()
    }
}

// ----- numeric derivatives of the direct tree -----

/// Central differences along `dir` with one Richardson step; `None` where
/// two step sizes disagree (a kink, a branch cut, or ill-conditioning).
fn directional_derivative(t: &T, vals: &[f64], dir: &[f64]) -> Option<(f64, f64)> {
    let f = |h: f64| {
        let moved: Vec<f64> = vals.iter().zip(dir).map(|(v, d)| v + h * d).collect();
        direct(t, &moved, &[])
    };
    let scale_x = vals
        .iter()
        .zip(dir)
        .filter(|(_, d)| **d != 0.0)
        .fold(1.0f64, |a, (v, _)| a.max(v.abs()));
    let h = 1e-4 * scale_x;
    let c = |h: f64| (f(h).v - f(-h).v) / (2.0 * h);
    let (d1, d2) = (c(h), c(h / 2.0));
    let r = (4.0 * d2 - d1) / 3.0;
    let f0 = f(0.0);
    if !r.is_finite() || !f0.e.is_finite() {
        return None;
    }
    // The steps must stay well inside the region where f is smooth: near a
    // pole or a kink f changes by a large fraction of itself across them.
    let spread = [h, -h, h / 2.0, -h / 2.0]
        .iter()
        .map(|s| (f(*s).v - f0.v).abs())
        .fold(
            0.0f64,
            |a, x| if x.is_nan() { f64::INFINITY } else { a.max(x) },
        );
    if spread > 0.01 * f0.v.abs().max(1.0) {
        return None;
    }
    let scale = r.abs().max(1.0);
    let noise = 1e3 * EPS * f0.e / h;
    if (d1 - d2).abs() > 1e-3 * scale + noise {
        return None;
    }
    Some((r, 1e-6 * scale + noise))
}

// ----- factor structure, for gcf -----

/// (coefficient, [(base, numeric exponent)]) of an expression, by the
/// definition of a monomial: a product's factors, a power's base.
fn monomial(a: &Arena, e: ExprId) -> (Number, Vec<(ExprId, Number)>) {
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

/// `true` if two non-numeric terms have a factor base with exponents of
/// the same sign (what `add` would factor out).
fn shares_factor(a: &Arena, x: ExprId, y: ExprId) -> bool {
    if a.as_number(x).is_some() || a.as_number(y).is_some() {
        return false;
    }
    let (_, mx) = monomial(a, x);
    let (_, my) = monomial(a, y);
    mx.iter().any(|(b, n)| {
        let m = exponent_of(&my, *b);
        !m.is_zero() && m.is_negative() == n.is_negative()
    })
}

fn exponent_of(m: &[(ExprId, Number)], base: ExprId) -> Number {
    m.iter()
        .find(|(b, _)| *b == base)
        .map(|(_, n)| *n)
        .unwrap_or(Number::ZERO)
}

proptest! {
    #![proptest_config(config())]

    /// Constructors simplify without changing the value.
    #[test]
    fn constructors_preserve_value(t in tree(), points in prop::collection::vec(value_strategy(), 4)) {
        let mut c = ctx();
        let e = build(&mut c, &t);
        for vals in &points {
            close(eval(&c, e, vals), direct(&t, vals, &[]))?;
        }
    }

    /// Sums built to trigger the identities sin² + cos² = 1 and
    /// 1 - sin² = cos² (with common factors, numeric multiples, in any
    /// order, among other terms) keep their value.
    #[test]
    fn trig_identities_preserve_value(
        parts in prop::collection::vec((0u8..5, -3i64..=3, 0usize..2), 1..7),
        m in tree_over(NAMES.len(), 2),
        args in (tree_over(NAMES.len(), 2), tree_over(NAMES.len(), 2)),
        vals in value_strategy(),
    ) {
        let mut c = ctx();
        let me = build(&mut c, &m);
        let arg_trees = [args.0, args.1];
        let arg_ids = [build(&mut c, &arg_trees[0]), build(&mut c, &arg_trees[1])];
        let mut terms = Vec::new();
        let mut want_terms = Vec::new();
        for (kind, k, which) in &parts {
            let a = arg_ids[*which];
            let at = arg_trees[*which].clone();
            let (e, t) = match kind {
                0 => { let s = c.arena.sin(a); (c.arena.powi(s, 2), T::PowI(bx(T::Sin(bx(at))), 2)) }
                1 => { let s = c.arena.cos(a); (c.arena.powi(s, 2), T::PowI(bx(T::Cos(bx(at))), 2)) }
                2 => (c.arena.one(), T::Int(1)),
                3 => { let s = c.arena.sin(a); (s, T::Sin(bx(at))) }
                _ => (c.arena.int(-1), T::Int(-1)),
            };
            let kk = c.arena.int(*k);
            terms.push(c.arena.product(&[kk, me, e]));
            want_terms.push(T::Mul(bx(T::Mul(bx(T::Int(*k)), bx(m.clone()))), bx(t)));
        }
        let s = c.arena.sum(&terms);
        let mut pairwise = terms[0];
        for t in &terms[1..] {
            pairwise = c.arena.add(pairwise, *t);
        }
        let want_tree = want_terms.into_iter().reduce(|a, b| T::Add(bx(a), bx(b))).unwrap();
        let want = direct(&want_tree, &vals, &[]);
        close(eval(&c, s, &vals), want)?;
        close(eval(&c, pairwise, &vals), want)?;
    }

    /// Sums and products are canonical: operand order does not matter.
    #[test]
    fn commutative_operands_give_one_node(a in tree(), b in tree()) {
        let mut c = ctx();
        let (ea, eb) = (build(&mut c, &a), build(&mut c, &b));
        let ab = c.arena.add(ea, eb);
        let ba = c.arena.add(eb, ea);
        prop_assert_eq!(ab, ba, "{} + {}", c.arena.to_text(ea), c.arena.to_text(eb));
        let ab = c.arena.mul(ea, eb);
        let ba = c.arena.mul(eb, ea);
        prop_assert_eq!(ab, ba, "{} * {}", c.arena.to_text(ea), c.arena.to_text(eb));
        let s1 = c.arena.sum(&[ea, eb]);
        let s2 = c.arena.sum(&[eb, ea]);
        prop_assert_eq!(s1, s2);
        let p1 = c.arena.product(&[ea, eb]);
        let p2 = c.arena.product(&[eb, ea]);
        prop_assert_eq!(p1, p2);
    }

    /// gcf(x, y) divides both: as monomials (every factor of the gcf occurs
    /// in x at least as often, the coefficient ratio is an integer), and
    /// numerically gcf * (x/gcf) = x with x/gcf finite.
    #[test]
    fn gcf_divides_both(a in tree(), b in tree(), vals in value_strategy()) {
        let mut c = ctx();
        let (ea, eb) = (build(&mut c, &a), build(&mut c, &b));
        let g = c.arena.gcf(ea, eb);
        let (cg, mg) = monomial(&c.arena, g);
        let exact = monomial(&c.arena, ea).0.is_exact() && monomial(&c.arena, eb).0.is_exact();
        for (e, t) in [(ea, &a), (eb, &b)] {
            let (ce, me) = monomial(&c.arena, e);
            for (base, n) in &mg {
                let have = exponent_of(&me, *base);
                let ok = if n.is_negative() {
                    have.cmp_value(*n).is_le()
                } else {
                    have.cmp_value(*n).is_ge()
                };
                prop_assert!(ok, "gcf {} has {}^{n} but {} has exponent {have}",
                    c.arena.to_text(g), c.arena.to_text(*base), c.arena.to_text(e));
            }
            if exact && !ce.is_zero() {
                let ratio = ce.div(cg).unwrap();
                prop_assert!(ratio.as_integer().is_some(), "coefficient {ce} / {cg}");
            }
            let q = c.arena.div(e, g);
            let want = direct(t, &vals, &[]);
            let (gv, qv) = (eval(&c, g, &vals), eval(&c, q, &vals));
            if want.v.is_finite() && want.v != 0.0 && gv.is_finite() && gv != 0.0 {
                prop_assert!(qv.is_finite(), "{} / {} is not finite", c.arena.to_text(e), c.arena.to_text(g));
                close(gv * qv, want)?;
            }
        }
    }

    /// gcf of monomials over distinct atoms: the common powers (smaller
    /// positive, or larger negative, exponent; none for mixed signs) times
    /// the gcd of the integer coefficients.
    #[test]
    fn gcf_of_monomials(
        ex in prop::collection::vec((-3i64..=3, -3i64..=3), 5),
        ca in 1i64..=12, cb in 1i64..=12, sa in any::<bool>(), sb in any::<bool>(),
        vals in value_strategy(),
    ) {
        let mut c = ctx();
        let atoms = ["x", "sin(y)", "1 + q", "exp(x + y)", "p"];
        let atom_ids: Vec<ExprId> = atoms.iter().map(|s| c.arena.parse_text(s).unwrap()).collect();
        let atom_vals: Vec<f64> = atom_ids.iter().map(|e| eval(&c, *e, &vals)).collect();
        let mut fa = vec![c.arena.int(if sa { -ca } else { ca })];
        let mut fb = vec![c.arena.int(if sb { -cb } else { cb })];
        let mut want = gcd(ca, cb) as f64;
        for (i, (na, nb)) in ex.iter().enumerate() {
            fa.push(c.arena.powi(atom_ids[i], *na));
            fb.push(c.arena.powi(atom_ids[i], *nb));
            let common = if *na > 0 && *nb > 0 {
                (*na).min(*nb)
            } else if *na < 0 && *nb < 0 {
                (*na).max(*nb)
            } else {
                0
            };
            want *= atom_vals[i].powi(common as i32);
        }
        let ea = c.arena.product(&fa);
        let eb = c.arena.product(&fb);
        let g = c.arena.gcf(ea, eb);
        let got = eval(&c, g, &vals);
        prop_assert!((got - want).abs() <= 1e-12 * want.abs(),
            "gcf({}, {}) = {} = {got}, want {want}",
            c.arena.to_text(ea), c.arena.to_text(eb), c.arena.to_text(g));
    }

    /// constant_part of (constant + variable part) is the constant part,
    /// also when the sum is negated.
    #[test]
    fn constant_part_of_sums(kt in tree_over(NAMES.len(), 3), vt in tree_over(2, 3), vals in value_strategy()) {
        // Constant trees use only k (a parameter) and numbers; variable
        // parts are q * (tree over x, y), so they share no factor with the
        // constant part and have no constant term.
        let only_k = |t: &T| subst_tree(t, &(0..NAMES.len()).filter(|i| *i != K).map(|i| (i, T::Sym(K))).collect());
        let kt = only_k(&kt);
        let mut c = ctx();
        let ke = build(&mut c, &kt);
        prop_assert!(c.arena.is_constant(ke));
        let ve0 = build(&mut c, &vt);
        let q = c.arena.sym(c.syms[Q]);
        let ve = c.arena.mul(q, ve0);
        // When the two parts share a factor (the variable tree can cancel to
        // a constant), `add` factors it out and the sum is a product, whose
        // constant part is 0 by definition: not this property.
        let g = c.arena.gcf(ke, ve);
        if c.arena.as_number(g).is_none() {
            return Ok(());
        }
        let s = c.arena.add(ke, ve);
        let cp = c.arena.constant_part(s);
        let want = direct(&kt, &vals, &[]);
        close(eval(&c, cp, &vals), want)?;
        let ns = c.arena.neg(s);
        let ncp = c.arena.constant_part(ns);
        close(-eval(&c, ncp, &vals), want)?;
        // A variable product has no constant part.
        let z = c.arena.constant_part(ve);
        prop_assert!(c.arena.is_zero(z) || c.arena.is_zero(ve0));
    }

    /// nominal sets the coordinates to zero.
    #[test]
    fn nominal_is_value_at_zero_coordinates(t in tree(), vals in value_strategy()) {
        let mut c = ctx();
        let e = build(&mut c, &t);
        let n = c.arena.nominal(e);
        prop_assert!(!c.arena.depends_on(n, c.syms[Q]));
        let mut at_zero = vals;
        at_zero[Q] = 0.0;
        close(eval(&c, n, &vals), direct(&t, &at_zero, &[]))?;
    }

    /// Substitution gives the value of the tree with the trees substituted.
    #[test]
    fn substitute_preserves_value(t in tree(), sx in tree(), sq in tree(), vals in value_strategy()) {
        let mut c = ctx();
        let e = build(&mut c, &t);
        let (ex, eq) = (build(&mut c, &sx), build(&mut c, &sq));
        let mut map = FxHashMap::default();
        map.insert(c.syms[X], ex);
        map.insert(c.syms[Q], eq);
        let r = c.arena.substitute(e, &map);
        let mut tmap = FxHashMap::default();
        tmap.insert(X, sx);
        tmap.insert(Q, sq);
        let composite = subst_tree(&t, &tmap);
        close(eval(&c, r, &vals), direct(&composite, &vals, &[]))?;
    }

    /// partial agrees with central differences, for every symbol.
    #[test]
    fn partial_matches_finite_differences(t in tree(), vals in value_strategy()) {
        let mut c = ctx();
        let e = build(&mut c, &t);
        for i in 0..NAMES.len() {
            let d = c.arena.partial(e, c.syms[i]).unwrap();
            let mut dir = [0.0; 5];
            dir[i] = 1.0;
            if let Some((want, tol)) = directional_derivative(&t, &vals, &dir) {
                let got = eval(&c, d, &vals);
                prop_assert!((got - want).abs() <= tol,
                    "d/d{} of {}: {} = {got}, differences {want}", NAMES[i],
                    c.arena.to_text(e), c.arena.to_text(d));
            }
        }
    }

    /// dxdt is the chain rule: sum of partials times the declared rates.
    #[test]
    fn dxdt_matches_chain_rule(t in tree(), vals in value_strategy(), rates in value_strategy()) {
        let mut c = ctx();
        let mut rate_syms = Vec::new();
        for (i, n) in NAMES.iter().enumerate().take(K) {
            let r = c.arena.add_symbol(&format!("{n}_rate"), SymbolKind::Free).unwrap();
            let re = c.arena.sym(r);
            c.arena.set_dxdt(c.syms[i], re);
            rate_syms.push(r);
        }
        let e = build(&mut c, &t);
        let d = c.arena.dxdt(e).unwrap();
        // k is a parameter: its rate is zero.
        let mut dir = rates;
        dir[K] = 0.0;
        if let Some((want, tol)) = directional_derivative(&t, &vals, &dir) {
            let mut b = Bindings::with_defaults(&c.arena);
            for (s, v) in c.syms.iter().zip(vals) {
                b.set(*s, v);
            }
            for (i, r) in rate_syms.iter().enumerate() {
                b.set(*r, rates[i]);
            }
            let got = c.arena.eval(d, &b, &mut NoUserFunctions);
            prop_assert!((got - want).abs() <= tol,
                "dxdt of {}: {} = {got}, chain rule {want}", c.arena.to_text(e), c.arena.to_text(d));
        }
    }

    /// The text form reads back as the same value always, and as the same
    /// node unless a printed sum has two terms with a common factor.
    ///
    /// Known limitation (not fixed, reported): the parser reads `a + b + c`
    /// as `(a + b) + c` through `add`, which factors out a common factor of
    /// each pair (the paper's `add`), so the canonical sum `p + x*p - x`
    /// (built as `x*p + (p - x)`) reads back as `p*(1 + x) - x`.
    #[test]
    fn text_round_trip(t in tree(), points in prop::collection::vec(value_strategy(), 2)) {
        let mut c = ctx();
        let e = build(&mut c, &t);
        // 0^-n (a division by zero) prints as 1/(0^n), which reads back as
        // 1/0: a degenerate expression with no value, left out.
        let nodes = reachable(&c.arena, e);
        let divides_by_zero = nodes.iter().any(|i| {
            matches!(c.arena.node(*i), Node::Pow(b, x)
                if c.arena.as_number(*b).is_some_and(|n| n.is_zero())
                    && c.arena.as_number(*x).is_some_and(|n| n.is_negative()))
        });
        if divides_by_zero {
            return Ok(());
        }
        let text = c.arena.to_text(e);
        let back = c.arena.parse_text(&text);
        prop_assert!(back.is_ok(), "{text}: {:?}", back);
        let back = back.unwrap();
        for vals in &points {
            let want = direct(&t, vals, &[]);
            close(eval(&c, back, vals), want)?;
        }
        let pairwise_factor = nodes.iter().any(|i| match c.arena.node(*i) {
            Node::Sum(ts) => ts.iter().enumerate().any(|(j, a)| {
                ts[j + 1..].iter().any(|b| shares_factor(&c.arena, *a, *b))
            }),
            _ => false,
        });
        // A float coefficient -1.0 (from user floats such as -0.25f - 3/4)
        // is kept as a float while +1.0 is dropped like an exact 1, so
        // `x - 1.0f/x` reads back with an exact -1: same value, other node.
        let float_unit = nodes.iter().any(|i| matches!(c.arena.node(*i),
            Node::Prod(Number::Float(b), _) if f64::from_bits(*b).abs() == 1.0));
        if !pairwise_factor && !float_unit {
            prop_assert_eq!(back, e, "{} read back as {}", text, c.arena.to_text(back));
        }
    }

    /// With x and q small (order 1), the truncated expression agrees with
    /// the unsimplified tree to second order: evaluated at x, q = ±σ ε, the
    /// error relative to the magnitudes involved (the running error bound)
    /// falls like ε² (threshold 2: every dropped term is two orders below
    /// the leading term of its sum, every Taylor remainder two orders below
    /// its leading term). The check is on the rate, from ε = 1e-6 to 1e-7
    /// (a factor 100 expected, at least 30 demanded; a wrongly dropped term
    /// one order down would give 10), because the constant depends on the
    /// ordinary values (a small x over an ordinary y near 0 is not small).
    #[test]
    fn small_variable_truncation_is_second_order(
        t in tree(),
        vals in value_strategy(),
        sx in 0.5..2.0f64, sq in 0.5..2.0f64, nx in any::<bool>(), nq in any::<bool>(),
    ) {
        let small = [X, Q];
        let t = shift_atan2(&t);
        let mut c = ctx_with(&small);
        let e = build(&mut c, &t);
        let rel = |eps: f64| -> Option<(f64, f64, f64)> {
            let mut v = vals;
            v[X] = if nx { -sx } else { sx } * eps;
            v[Q] = if nq { -sq } else { sq } * eps;
            let want = direct(&t, &v, &small);
            let got = eval(&c, e, &v);
            if !want.v.is_finite() || !want.e.is_finite() || !got.is_finite() {
                return None;
            }
            let diff = (got - want.v).abs();
            Some((if diff == 0.0 { 0.0 } else { diff / want.e }, got, want.v))
        };
        if let (Some((r1, g1, w1)), Some((r2, g2, w2))) = (rel(1e-6), rel(1e-7)) {
            prop_assert!(r1 <= 1e-3 && r2 <= r1 / 30.0 + 1e3 * EPS,
                "{}: relative errors {r1:e} at 1e-6 ({g1} vs {w1}), {r2:e} at 1e-7 ({g2} vs {w2})",
                c.arena.to_text(e));
        }
    }
}

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 { a.abs() } else { gcd(b, a % b) }
}

/// The truncation test above is not vacuous: dropping happens, and a term
/// only one order down is kept.
#[test]
fn small_terms_really_are_dropped() {
    let mut c = ctx_with(&[X]);
    let one = c.arena.parse_text("1 + x^2").unwrap();
    assert_eq!(c.arena.to_text(one), "1");
    let kept = c.arena.parse_text("y + x").unwrap();
    assert_eq!(c.arena.to_text(kept), "x + y");
    let cosx = c.arena.parse_text("cos(x)").unwrap();
    assert_eq!(c.arena.to_text(cosx), "1");
    let sinx = c.arena.parse_text("sin(x)*y").unwrap();
    assert_eq!(c.arena.to_text(sinx), "x*y");
}

/// Replaces every `atan2(a, b)` by `atan2(3 + a^2, b)`. atan2 has no small
/// order (atan2(ε, x) is O(ε) for x > 0 but ±π for x < 0), so the arena
/// gives it order 0; a small first argument would make it an O(ε) term
/// that claims to be O(1), and terms two orders below the claim but only
/// one below its value would be dropped. Known limitation, kept out of the
/// truncation property.
fn shift_atan2(t: &T) -> T {
    let s = |a: &T| bx(shift_atan2(a));
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
        T::Atan2(a, b) => {
            let a = shift_atan2(a);
            T::Atan2(
                bx(T::Add(bx(T::Int(3)), bx(T::Mul(bx(a.clone()), bx(a))))),
                s(b),
            )
        }
        T::Sqrt(a) => T::Sqrt(s(a)),
    }
}

/// Every node reachable from `e`.
fn reachable(a: &Arena, e: ExprId) -> Vec<ExprId> {
    let mut seen = std::collections::BTreeSet::new();
    let mut stack = vec![e];
    while let Some(x) = stack.pop() {
        if seen.insert(x) {
            stack.extend(a.children(x));
        }
    }
    seen.into_iter().collect()
}
