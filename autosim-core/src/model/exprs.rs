//! Evaluation of model expressions into values: names, members, operators
//! and the operations of the paper's Tables 6 and 12.

use super::scope::{Named, Resolver, describe};
use super::value::{self, Op, Value};
use crate::diag::{Diagnostic, Span};
use crate::expr::Number;
use crate::syntax::ast::{self, BinOp, Expr, Member, UnOp};

impl Resolver<'_> {
    /// Evaluates an expression; on error reports and returns `None`.
    pub fn eval(&mut self, e: &Expr) -> Option<Value> {
        match e {
            Expr::Number(n) => match Number::parse_decimal(&n.text) {
                Some(x) => Some(Value::Scalar(self.sys.arena.num(x))),
                None => {
                    self.push(
                        Diagnostic::error(
                            n.span,
                            format!("`{}` is not a number this compiler can represent", n.text),
                        )
                        .help("numbers in expressions are exact fractions of at most 38 digits (between 1e-38 and 1e38); declare a parameter for other values"),
                    );
                    None
                }
            },
            Expr::Quantity { number, unit, .. } => {
                let x = self.eval(&Expr::Number(number.clone()))?;
                let factor = super::units::unit_meaning(&unit.text)
                    .map_or(1.0, |u| u.factor)
                    .to_string();
                match Number::parse_decimal(&factor) {
                    Some(f) if factor != "1" => {
                        let f = self.sys.arena.num(f);
                        Some(value::binary(&mut self.sys, Op::Mul, x, Value::Scalar(f)).ok()?)
                    }
                    _ => Some(x),
                }
            }
            Expr::As { inner, .. } => self.eval(inner),
            Expr::Name(name) => self.eval_name(name),
            Expr::Paren { inner, .. } => self.eval(inner),
            Expr::Unary { op, operand, span } => {
                let v = self.eval(operand)?;
                match op {
                    UnOp::Plus => Some(v),
                    UnOp::Neg => {
                        let r = value::negate(&mut self.sys, v);
                        let v = self.lift(*span, r);
                        self.finite(*span, v)
                    }
                }
            }
            Expr::Binary { .. } => self.eval_binary(e),
            Expr::List { items, .. } => {
                let mut out = Vec::with_capacity(items.len());
                let mut ok = true;
                for it in items {
                    match self.eval(it) {
                        Some(v) => out.push(v),
                        None => ok = false,
                    }
                }
                ok.then_some(Value::List(out))
            }
            Expr::Member { base, member, span } => self.eval_member(base, member, *span),
            Expr::Call { func, args, span } => self.eval_call(func, args, *span),
        }
    }

    /// `a + b - c + ...`: a chain is left-deep in the AST, so it is
    /// evaluated from its innermost operator out, in a loop (a sum of
    /// thousands of terms must not recurse once per term).
    fn eval_binary(&mut self, e: &Expr) -> Option<Value> {
        let mut spine = Vec::new();
        let mut first = e;
        while let Expr::Binary {
            op,
            lhs,
            rhs,
            op_span,
            span,
        } = first
        {
            spine.push((*op, rhs.as_ref(), *op_span, *span));
            first = lhs;
        }
        let mut value = self.eval(first);
        for (op, rhs, op_span, span) in spine.into_iter().rev() {
            let b = self.eval(rhs);
            let (Some(a), Some(b)) = (value, b) else {
                value = None;
                continue;
            };
            let op = match op {
                BinOp::Add => Op::Add,
                BinOp::Sub => Op::Sub,
                BinOp::Mul => Op::Mul,
                BinOp::Div => Op::Div,
                BinOp::Pow => Op::Pow,
            };
            let r = value::binary(&mut self.sys, op, a, b);
            let v = self.lift(op_span, r);
            value = self.finite(span, v);
        }
        value
    }

    pub(super) fn lift(&mut self, span: Span, r: Result<Value, String>) -> Option<Value> {
        match r {
            Ok(v) => Some(v),
            Err(msg) => {
                self.error(span, msg);
                None
            }
        }
    }

    fn eval_name(&mut self, name: &ast::Name) -> Option<Value> {
        match self.names.get(&name.text).cloned() {
            Some((Named::Symbol(s), _)) => Some(Value::Scalar(self.sys.arena.sym(s))),
            Some((Named::Constant(e), _)) => Some(Value::Scalar(e)),
            Some((Named::Body(Some(b)), _)) => Some(Value::Body(b)),
            Some((Named::Body(None), _)) => None,
            Some((Named::Point(i), _)) => self.point_value(i, name.span).map(Value::Point),
            Some((Named::Let(i), _)) => self.let_value(i, name.span),
            Some((other, _)) => {
                let what = describe(&other);
                self.push(
                    Diagnostic::error(
                        name.span,
                        format!("`{}` is {what} and cannot be used as a value", name.text),
                    )
                    .help(if matches!(other, Named::Function(_)) {
                        format!("call it: `{}(...)`", name.text)
                    } else {
                        "use a parameter, variable, point, body or `let` name".to_string()
                    }),
                );
                None
            }
            None => {
                if name.text == "pi"
                    && let Some(pi) = crate::expr::Number::float(std::f64::consts::PI)
                {
                    return Some(Value::Scalar(self.sys.arena.num(pi)));
                }
                if let Some(&(b, axis)) = self.uv_short.get(&name.text) {
                    return Some(Value::Vector(self.sys.unit_vector(b, axis)));
                }
                // `n4`: a unit vector of a body that has no axis 4.
                let frame = name.text.trim_end_matches(|c: char| c.is_ascii_digit());
                if frame.len() < name.text.len() && self.uv_short.contains_key(&format!("{frame}1"))
                {
                    self.push(
                        Diagnostic::error(
                            name.span,
                            format!("unknown unit vector `{}`", name.text),
                        )
                        .help(format!(
                            "the axes of a body are 1, 2 and 3: `{frame}1`, `{frame}2`, `{frame}3`"
                        )),
                    );
                    return None;
                }
                self.unknown(name, "name");
                None
            }
        }
    }

    fn eval_member(&mut self, base: &Expr, member: &Member, span: Span) -> Option<Value> {
        let b = match base {
            Expr::Name(n) => self.body_by_name(n)?,
            other => {
                let v = self.eval(other)?;
                self.error(
                    other.span(),
                    format!(
                        "`.` applies to bodies (`B.cm`, `B.origin`, `B.1`), not to a {}",
                        v.kind()
                    ),
                );
                return None;
            }
        };
        match member {
            Member::Index { index, span } => match crate::mech::Axis::number(*index as i64) {
                Some(axis) => Some(Value::Vector(self.sys.unit_vector(b, axis))),
                None => {
                    self.error(
                        *span,
                        format!("unit vector index {index} is out of range: use 1, 2 or 3"),
                    );
                    None
                }
            },
            Member::Name(n) => match n.text.as_str() {
                "cm" => Some(Value::Point(self.sys.body(b).cm_point)),
                "origin" => Some(Value::Point(self.sys.body(b).origin)),
                other => {
                    self.push(
                        Diagnostic::error(n.span, format!("bodies have no member `{other}`"))
                            .help("use `.cm` (mass center), `.origin` (joint point) or `.1`, `.2`, `.3` (unit vectors)"),
                    );
                    let _ = span;
                    None
                }
            },
        }
    }
}
