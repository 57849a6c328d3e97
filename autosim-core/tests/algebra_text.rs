//! Property test of the expression algebra's text form: printed
//! expressions read back as the same value, and as the same node where the
//! parser's pairwise `add` allows. The trees and the direct evaluation they
//! are checked against are in `algebra/`.

mod algebra;

use algebra::direct::{close, direct};
use algebra::{build, config, ctx, eval, exponent_of, monomial, tree, value_strategy};
use autosim_core::expr::{Arena, ExprId, Node, Number};
use proptest::prelude::*;

proptest! {
    #![proptest_config(config())]

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

/// Regression (found by `text_round_trip`): `sqrt(x^2*y^2*y^2)` read back as
/// `sqrt(x^2*y^4)`. A product merged its factors by base before taking each
/// power, and `abs(y)^2` (here from `sqrt(y^2)^2`) becomes `y^2`, a power
/// of another base: the product kept `y^2` twice instead of `y^4`. Its
/// square root is `|x| y^2` and reads back as itself.
#[test]
fn sqrt_x2_y2_y2_reads_back_as_sqrt_x2_y4() {
    let mut a = Arena::new();
    let x = a
        .add_symbol("x", autosim_core::expr::SymbolKind::Free)
        .unwrap();
    let y = a
        .add_symbol("y", autosim_core::expr::SymbolKind::Free)
        .unwrap();
    let (x, y) = (a.sym(x), a.sym(y));
    let x2 = a.powi(x, 2);
    let y2 = a.powi(y, 2);
    let abs_y = a.sqrt(y2);
    let built = a.product(&[x2, y2, abs_y, abs_y]);
    let y4 = a.powi(y, 4);
    let direct = a.mul(x2, y4);
    assert_eq!(a.to_text(built), a.to_text(direct));
    assert_eq!(built, direct);
    // The square root of a perfect square takes each even power out:
    // sqrt(x^2*y^4) = |x|*y^2.
    let root = a.sqrt(built);
    let text = a.to_text(root);
    assert_eq!(text, "y^2*abs(x)");
    assert_eq!(a.parse_text(&text), Ok(root));
}
