//! Data-driven tests of the simplifying constructors and the text form.

use super::*;

fn check(input: &str, expect: &str) {
    let mut a = Arena::new();
    let e = a
        .parse_text(input)
        .unwrap_or_else(|err| panic!("{input}: {err}"));
    assert_eq!(a.to_text(e), expect, "input: {input}");
}

#[test]
fn canonical_forms() {
    check("a + b - a", "b");
    check("2*a + 3*a", "5*a");
    check("a*b*a", "a^2*b");
    check("x^2*x^-2", "1");
    check("(a*b)^2", "a^2*b^2");
    check("(x^2)^3", "x^6");
    check("sqrt(x^2)", "abs(x)");
    check("0*a + 1", "1");
    check("-a - b", "-a - b");
    check("(a + b) - (a + b)", "0");
    check("2*(a + b) - 2*a", "2*b");
    check("sin(-x)", "-sin(x)");
    check("cos(-x)", "cos(x)");
    check("sin(asin(x))", "x");
    check("sin(x)^2 + cos(x)^2", "1");
    check("3*y*sin(x)^2 + 3*y*cos(x)^2", "3*y");
    check("1 - sin(x)^2", "cos(x)^2");
    check("a*b + a*c", "a*(b + c)");
    check("a*b + a*c - a*b", "a*c");
    check("atan2(2*y, 4*x)", "atan2(y, 2*x)");
    check("0.25*x", "x/4");
    check("1/2 + 1/3", "5/6");
    check("2^-1", "1/2");
    check("4^(1/2)", "2");
}

#[test]
fn commutative_operands_are_one_node() {
    let mut a = Arena::new();
    let s = a.parse_text("a + b").unwrap();
    let n = a.parse_text("-a - b").unwrap();
    assert_eq!(a.neg(s), n, "a sum and its negation share the sum node");
    assert_eq!(a.node(n), &Node::Prod(Number::MINUS_ONE, Box::new([s])));
    let x = a.parse_text("x + sin(y)").unwrap();
    let y = a.parse_text("sin(y) + x").unwrap();
    assert_eq!(x, y);
    let p = a.parse_text("x*cos(y)*z").unwrap();
    let q = a.parse_text("z*x*cos(y)").unwrap();
    assert_eq!(p, q);
}

#[test]
fn small_terms_are_dropped_relative_to_the_lowest_order() {
    let mut a = Arena::new();
    let x = a.add_symbol("x", SymbolKind::Free).unwrap();
    let y = a.add_symbol("y", SymbolKind::Free).unwrap();
    a.set_small(x, true);
    a.set_small(y, true);
    check_in(&mut a, "1 - x^2", "1");
    check_in(&mut a, "1 + x", "1 + x");
    check_in(&mut a, "x + x*y", "x*(1 + y)");
    check_in(&mut a, "x + x*y^2", "x");
    check_in(&mut a, "sin(x)", "x");
    check_in(&mut a, "cos(x)", "1");
    check_in(&mut a, "cos(x + 1)", "cos(1 + x)");
    a.set_threshold(3);
    check_in(&mut a, "cos(y)", "1 - y^2/2");
    check_in(&mut a, "sin(y)", "y*(1 - y^2/6)");
}

fn check_in(a: &mut Arena, input: &str, expect: &str) {
    let e = a.parse_text(input).unwrap();
    assert_eq!(a.to_text(e), expect, "input: {input}");
}

#[test]
fn text_round_trip() {
    let mut a = Arena::new();
    for s in [
        "a + b*c",
        "-(a + b)*c",
        "sin(x)^2*y/z",
        "atan2(y, x) - 3/4*sqrt(a + b)",
        "a/(b + c)^2",
        "x^(1/3)",
        "2.5f*x",
        "-x/2",
        "(a - b)^-2",
    ] {
        let e = a.parse_text(s).unwrap();
        let t = a.to_text(e);
        let e2 = a.parse_text(&t).unwrap_or_else(|err| panic!("{t}: {err}"));
        assert_eq!(e, e2, "{s} printed as {t}");
    }
}

#[test]
fn derivatives() {
    let mut a = Arena::new();
    let e = a.parse_text("x^3 + sin(x)*y").unwrap();
    let x = a.symbol_named("x").unwrap();
    let d = a.partial(e, x).unwrap();
    assert_eq!(a.to_text(d), "3*x^2 + y*cos(x)");
}

#[test]
fn half_integer_power_of_a_perfect_square_is_a_number() {
    check("65536^(-1/2)", "1/256");
    check("4^(3/2)", "8");
    check("(9/4)^(-3/2)", "8/27");
    check("2^(-1/2)*2^(1/2)", "1");
    // A sum whose terms share such a factor used to overflow the stack.
    let mut a = Arena::new();
    let e = a.parse_text("65536^(-1/2)*x + 65536^(-1/2)*y").unwrap();
    assert_eq!(a.to_text(e), "x/256 + y/256");
}

#[test]
fn depth_is_one_more_than_the_deepest_child() {
    let mut a = Arena::new();
    let x = a.parse_text("x").unwrap();
    assert_eq!(a.depth(x), 1);
    let e = a.parse_text("sin(x) + 2*y").unwrap();
    assert_eq!(a.depth(e), 3);
    let e = a.parse_text("sin(sin(sin(x)))").unwrap();
    assert_eq!(a.depth(e), 4);
}

#[test]
fn common_factor_with_a_symbolic_exponent_does_not_recurse_forever() {
    // `1/m^q` stayed a power of `m^q`, which never cancelled against the
    // `m^q` of each term: pulling it out of the sum recursed until the stack
    // overflowed.
    check("(m^q)^-1", "m^(-q)");
    check("m^q*x + m^q*y", "m^q*(x + y)");
    check("(m^q)^2/m^q", "m^q");
}

#[test]
fn repeated_partials_stop_at_a_size_limit_instead_of_filling_the_memory() {
    // Each derivative of a derivative of a deep composition multiplies its
    // size: a chain of `let`s alternating `partial` with other functions
    // took seconds and gigabytes, and one link more ran out of memory.
    let mut a = Arena::new();
    a.derivative_limit = 20_000; // 500 000 in a model: seconds in a debug build
    let x = a.add_symbol("x", SymbolKind::Free).unwrap();
    let xs = a.sym(x);
    let mut e = a.parse_text("sqrt(x^2 + 1)").unwrap();
    for _ in 0..8 {
        let t = a.func(Func::Atan2, &[e, xs]);
        let one = a.one();
        let d = a.add(one, e);
        e = a.div(t, d);
    }
    let mut refused = None;
    for k in 0..30 {
        match a.partial(e, x) {
            Ok(d) => e = a.add(d, e),
            Err(err) => {
                refused = Some((k, err));
                break;
            }
        }
    }
    let (k, err) = refused.expect("the derivatives grow past the limit");
    assert_eq!(err, ExprError::TooLarge(20_000), "after {k} derivatives");
    assert!(a.len() < 80_000, "{} nodes", a.len());
}

/// `input` and `expect` parsed into one arena are one node (hash-consing:
/// the same canonical expression, whatever order the terms print in).
fn same_node(a: &mut Arena, input: &str, expect: &str) {
    let e = a.parse_text(input).unwrap();
    let x = a.parse_text(expect).unwrap();
    assert_eq!(e, x, "{input} gave {}, not {expect}", a.to_text(e));
}

#[test]
fn sines_and_cosines_of_two_angles_become_the_sine_or_cosine_of_their_sum() {
    let mut a = Arena::new();
    same_node(&mut a, "sin(a)*cos(b) + cos(a)*sin(b)", "sin(a + b)");
    same_node(&mut a, "sin(a)*cos(b) - cos(a)*sin(b)", "sin(a - b)");
    same_node(&mut a, "cos(a)*sin(b) - sin(a)*cos(b)", "-sin(a - b)");
    same_node(&mut a, "cos(a)*cos(b) - sin(a)*sin(b)", "cos(a + b)");
    same_node(&mut a, "cos(a)*cos(b) + sin(a)*sin(b)", "cos(a - b)");
    same_node(&mut a, "sin(a)*sin(b) - cos(a)*cos(b)", "-cos(a + b)");
    // A common factor and coefficient, and other terms beside the pair.
    same_node(
        &mut a,
        "3*x*y*sin(a)*cos(b) + 3*x*y*cos(a)*sin(b)",
        "3*x*y*sin(a + b)",
    );
    same_node(
        &mut a,
        "z - 2*x*cos(a)*cos(b) + 2*x*sin(a)*sin(b) + w",
        "z + w - 2*x*cos(a + b)",
    );
    // Angles that are sums themselves: a chain's absolute angles.
    same_node(
        &mut a,
        "sin(a + b)*cos(c) + cos(a + b)*sin(c)",
        "sin(a + b + c)",
    );
    same_node(
        &mut a,
        "cos(a)*cos(b)*cos(c) - sin(a)*sin(b)*cos(c) - sin(a)*cos(b)*sin(c) - cos(a)*sin(b)*sin(c)",
        "cos(a + b + c)",
    );
    // One angle a parameter, the other not.
    a.add_symbol("p", SymbolKind::Parameter { default: 0.5 })
        .unwrap();
    same_node(&mut a, "sin(p)*cos(q) + cos(p)*sin(q)", "sin(p + q)");
}

#[test]
fn angle_sums_are_not_made_where_the_terms_do_not_match() {
    let mut a = Arena::new();
    let kept = |a: &mut Arena, s: &str| {
        let e = a.parse_text(s).unwrap();
        let text = a.to_text(e);
        assert!(
            !text.contains("sin(a + b)") && !text.contains("cos(a + b)"),
            "{s}: {text}"
        );
        assert!(
            !text.contains("- b)") && !text.contains("- a)"),
            "{s}: {text}"
        );
        assert!(
            matches!(a.node(e), Node::Sum(_) | Node::Prod(..)),
            "{s}: {text}"
        );
    };
    // Different coefficients, different common factors, a missing partner.
    kept(&mut a, "2*sin(a)*cos(b) + cos(a)*sin(b)");
    kept(&mut a, "x*sin(a)*cos(b) + y*cos(a)*sin(b)");
    kept(&mut a, "sin(a)*cos(b) + sin(a)*sin(b)");
    kept(&mut a, "cos(a)*cos(b) + sin(a)*cos(b)");
    // Powers are not the factor the identity needs.
    kept(&mut a, "sin(a)^2*cos(b) + cos(a)^2*sin(b)");
    // One angle: sin(2a) and cos(2a) would be new functions to compute.
    same_node(&mut a, "sin(a)*cos(a) + cos(a)*sin(a)", "2*sin(a)*cos(a)");
    let e = a.parse_text("cos(a)^2 - sin(a)^2").unwrap();
    assert!(!a.to_text(e).contains("2*a"), "{}", a.to_text(e));
    // Constant angles (parameters and numbers) are left alone: their sines
    // cost nothing per call, the sine of their sum would.
    a.add_symbol("p", SymbolKind::Parameter { default: 0.5 })
        .unwrap();
    a.add_symbol("r", SymbolKind::Parameter { default: 0.25 })
        .unwrap();
    for s in [
        "sin(p)*cos(r) + cos(p)*sin(r)",
        "cos(p)*cos(r) - sin(p)*sin(r)",
        "sin(1)*cos(2) + cos(1)*sin(2)",
        "x*sin(p)*cos(1) + x*cos(p)*sin(1)",
    ] {
        let e = a.parse_text(s).unwrap();
        let text = a.to_text(e);
        assert!(
            !text.contains("p + ") && !text.contains("+ p"),
            "{s}: {text}"
        );
        assert!(
            !text.contains("1 + ") && !text.contains("+ 1"),
            "{s}: {text}"
        );
    }
}

#[test]
fn the_trigonometric_normal_form_sees_through_sines_of_sums() {
    // sin(a + b)^2 + cos(a + b)^2 with the cosine written out: 1 only if
    // sin(a + b) is expanded into sines and cosines of a and b.
    check(
        "sin(a + b)^2 + cos(a)^2*cos(b)^2 - 2*cos(a)*cos(b)*sin(a)*sin(b) + sin(a)^2*sin(b)^2",
        "1",
    );
    check(
        "sin(a - b)^2 + cos(a)^2*cos(b)^2 + 2*cos(a)*cos(b)*sin(a)*sin(b) + sin(a)^2*sin(b)^2",
        "1",
    );
    // ... and a sum that is not a number is kept.
    let mut a = Arena::new();
    let e = a
        .parse_text("sin(a + b)^2 + cos(a)^2*cos(b)^2 + sin(a)^2*sin(b)^2")
        .unwrap();
    assert!(a.as_number(e).is_none(), "{}", a.to_text(e));
}

#[test]
fn angle_sums_keep_the_value() {
    use crate::expr::{Bindings, NoUserFunctions};
    let mut a = Arena::new();
    type Value = fn(f64, f64, f64, f64) -> f64;
    let cases: [(&str, Value); 2] = [
        (
            "3*x*sin(a)*cos(b) - 3*x*cos(a)*sin(b) + y",
            |x: f64, y: f64, a: f64, b: f64| {
                3.0 * x * a.sin() * b.cos() - 3.0 * x * a.cos() * b.sin() + y
            },
        ),
        (
            "x*cos(a)*cos(b) + x*sin(a)*sin(b) - y*cos(a)",
            |x: f64, y: f64, a: f64, b: f64| {
                x * a.cos() * b.cos() + x * a.sin() * b.sin() - y * a.cos()
            },
        ),
    ];
    for (s, f) in cases {
        let e = a.parse_text(s).unwrap();
        let mut bind = Bindings::with_defaults(&a);
        let vals = [("x", 1.3), ("y", -0.4), ("a", 0.7), ("b", -2.1)];
        for (name, v) in vals {
            bind.set(a.symbol_named(name).unwrap(), v);
        }
        let got = a.eval(e, &bind, &mut NoUserFunctions);
        let want = f(1.3, -0.4, 0.7, -2.1);
        assert!((got - want).abs() < 1e-14, "{s}: {got} vs {want}");
        assert!(a.to_text(e).contains(" b)"), "{s}: {}", a.to_text(e));
    }
}
