//! Expression precedence and shapes, printed as S-expressions.

use super::parse_file;
use crate::syntax::ast::{Expr, Item, Member, UnOp};

fn sexpr(expr: &Expr) -> String {
    match expr {
        Expr::Number(n) => n.text.clone(),
        Expr::Name(n) => n.text.clone(),
        Expr::Member {
            base,
            member: Member::Name(n),
            ..
        } => format!("(. {} {})", sexpr(base), n.text),
        Expr::Member {
            base,
            member: Member::Index { index, .. },
            ..
        } => format!("(. {} {index})", sexpr(base)),
        Expr::Call { func, args, .. } => {
            let args: Vec<String> = args.iter().map(sexpr).collect();
            format!("({} {})", func.text, args.join(" ")).replace(" )", ")")
        }
        Expr::Unary {
            op: UnOp::Neg,
            operand,
            ..
        } => format!("(neg {})", sexpr(operand)),
        Expr::Unary {
            op: UnOp::Plus,
            operand,
            ..
        } => format!("(pos {})", sexpr(operand)),
        Expr::Binary { op, lhs, rhs, .. } => {
            format!("({} {} {})", op.as_str(), sexpr(lhs), sexpr(rhs))
        }
        Expr::List { items, .. } => format!(
            "[{}]",
            items.iter().map(sexpr).collect::<Vec<_>>().join(" ")
        ),
        Expr::Paren { inner, .. } => sexpr(inner),
        Expr::Quantity { number, unit, .. } => format!("({} [{}])", number.text, unit.text),
        Expr::As { inner, unit, .. } => format!("(as {} [{}])", sexpr(inner), unit.text),
    }
}

fn check(input: &str, expect: &str) {
    let text = format!("model M;\nlet x = {input};");
    let model = parse_file(&text).unwrap_or_else(|rendered| panic!("{input}: {rendered}"));
    let Some(Item::Let(item)) = model.items.first() else {
        panic!("no let")
    };
    assert_eq!(sexpr(&item.value), expect, "{input}");
    // Display prints back something that parses to the same tree.
    let again =
        parse_file(&format!("model M;\nlet x = {};", item.value)).unwrap_or_else(|r| panic!("{r}"));
    let Some(Item::Let(again)) = again.items.first() else {
        panic!("no let")
    };
    assert_eq!(
        sexpr(&again.value),
        expect,
        "{input} printed as {}",
        item.value
    );
}

#[test]
fn precedence() {
    let cases = [
        ("-x^2", "(neg (^ x 2))"),
        ("a*b^c^d", "(* a (^ b (^ c d)))"),
        ("a-b-c", "(- (- a b) c)"),
        ("a/b/c", "(/ (/ a b) c)"),
        ("a+b*c", "(+ a (* b c))"),
        ("(a+b)*c", "(* (+ a b) c)"),
        ("-a*b", "(* (neg a) b)"),
        ("a*-b", "(* a (neg b))"),
        ("2^-x^2", "(^ 2 (neg (^ x 2)))"),
        ("- -x", "(neg (neg x))"),
        ("k*x as [N]", "(* k (as x [N]))"),
        ("(k*x) as [N m/rad]", "(as (* k x) [N m/rad])"),
        ("-x as [N]", "(neg (as x [N]))"),
        ("x^2 as [N]", "(as (^ x 2) [N])"),
        ("2.5 [mm] + x", "(+ (2.5 [mm]) x)"),
        ("[1 [m], 0, L]", "[(1 [m]) 0 L]"),
        ("+x - 1", "(- (pos x) 1)"),
        ("-a^b*c", "(* (neg (^ a b)) c)"),
        ("a^-1", "(^ a (neg 1))"),
    ];
    for (input, expect) in cases {
        check(input, expect);
    }
}

#[test]
fn shapes() {
    let cases = [
        ("B.cm", "(. B cm)"),
        ("B.1", "(. B 1)"),
        ("q(B.1)", "(q (. B 1))"),
        ("f()", "(f)"),
        ("f(a, b,)", "(f a b)"),
        ("dot(cross(b1, b2), n3)", "(dot (cross b1 b2) n3)"),
        ("[[1, 0], [0, 1]]", "[[1 0] [0 1]]"),
        ("[]", "[]"),
        ("[1.5, 2e3, 0.25]", "[1.5 2e3 0.25]"),
        (
            "LTT1*thrust(t, 1, G*u(B, 4) + q(B, 4))*b1",
            "(* (* LTT1 (thrust t 1 (+ (* G (u B 4)) (q B 4)))) b1)",
        ),
        ("-k*(mag(r) - L0)", "(* (neg k) (- (mag r) L0))"),
    ];
    for (input, expect) in cases {
        check(input, expect);
    }
}
