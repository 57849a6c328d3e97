//! Property tests of the expression algebra's simplification laws (the
//! paper's Tables 5 and 6): the simplifying constructors keep the value of
//! the plain tree, trigonometric identities among other terms, canonical
//! operand order, the greatest common factor, constant parts, and
//! second-order truncation of small variables. The trees and the direct
//! evaluation they are checked against are in `algebra/`.

mod algebra;

use algebra::direct::{close, direct};
use algebra::{
    EPS, K, NAMES, Q, T, X, build, bx, config, ctx, ctx_with, eval, exponent_of, map_children,
    monomial, subst_tree, tree, tree_over, value_strategy,
};
use autosim_core::expr::ExprId;
use proptest::prelude::*;

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
                let ratio = ce.checked_div(cg).unwrap();
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
    match t {
        T::Atan2(a, b) => {
            let a = shift_atan2(a);
            T::Atan2(
                bx(T::Add(bx(T::Int(3)), bx(T::Mul(bx(a.clone()), bx(a))))),
                bx(shift_atan2(b)),
            )
        }
        _ => map_children(t, shift_atan2),
    }
}
