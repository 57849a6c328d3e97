//! Values of the kind an item needs: a scalar, a constant, a vector, a
//! point, a body, three coordinates, an integer; each reporting, with the
//! span, when the expression is of another kind.

use super::scope::{Named, Resolver};
use super::value::Value;
use crate::diag::{Diagnostic, Span};
use crate::expr::{ExprId, SymbolKind};
use crate::mech::{BodyId, PointId, Vector};
use crate::syntax::ast::{Expr, UnOp};

impl Resolver<'_> {
    /// A scalar, or a diagnostic saying what was needed.
    pub fn scalar(&mut self, e: &Expr, context: &str) -> Option<ExprId> {
        match self.eval(e)? {
            Value::Scalar(s) => Some(s),
            other => {
                let hint = match &other {
                    Value::Vector(_) => {
                        "; take a component with `dot(v, b1)` or the length with `mag(v)`"
                    }
                    Value::List(_) => "; write a single expression",
                    Value::Point(_) => "; use `pos(P)` for its position",
                    _ => "",
                };
                self.error(
                    e.span(),
                    format!(
                        "{context} needs a scalar, but this is a {}{hint}",
                        other.kind()
                    ),
                );
                None
            }
        }
    }

    /// A scalar that depends only on parameters and numbers.
    pub fn constant(&mut self, e: &Expr, context: &str) -> Option<ExprId> {
        let s = self.scalar(e, context)?;
        if !self.sys.arena.is_constant(s) {
            let culprit = self.varying_symbol(s);
            self.push(
                Diagnostic::error(e.span(), format!("{context} must be constant{culprit}"))
                    .help("use parameters and numbers only"),
            );
            return None;
        }
        Some(s)
    }

    /// `, but `name` is …` for the first symbol of `e` that is not a
    /// parameter (empty when only a user function call varies).
    fn varying_symbol(&self, e: ExprId) -> String {
        let arena = &self.sys.arena;
        let found = arena.free_symbols(e).into_iter().find_map(|s| {
            let symbol = arena.symbol(s);
            let kind = match symbol.kind {
                SymbolKind::Parameter { .. } => return None,
                SymbolKind::Coordinate { .. } => "a coordinate",
                SymbolKind::Speed { .. } => "a speed",
                SymbolKind::SpeedRate { .. } => "an acceleration",
                SymbolKind::State { .. } => "a state",
                SymbolKind::Input { .. } => "an input",
                SymbolKind::Discrete { .. } => "a discrete variable",
                SymbolKind::ExternOutput { .. } => "an output of a user subroutine",
                SymbolKind::Time => "the time",
                SymbolKind::Free => "a variable",
            };
            Some(format!(", but `{}` is {kind}", symbol.name))
        });
        found.unwrap_or_else(|| ", but it calls user code".into())
    }

    /// False, with a diagnostic at `span`, when `values` use an
    /// acceleration (`dxdt` of a speed): `what` is needed to compute them.
    pub fn without_acceleration(&mut self, values: &[ExprId], span: Span, what: &str) -> bool {
        if !self.without_deferred(values, span, what) {
            return false;
        }
        let arena = &self.sys.arena;
        let found = values
            .iter()
            .flat_map(|&e| arena.free_symbols(e))
            .find(|&s| matches!(arena.symbol(s).kind, SymbolKind::SpeedRate { .. }));
        let Some(s) = found else {
            return true;
        };
        let name = arena.symbol(s).name.clone();
        self.push(
            Diagnostic::error(
                span,
                format!("{what} cannot use an acceleration (`{name}`, the `dxdt` of a speed)"),
            )
            .help("accelerations are solved from the forces and moments; use them only in outputs and state derivatives"),
        );
        false
    }

    /// False, with a diagnostic at `span`, when `x`, an argument of
    /// subroutine number `sub` (`name`), cannot be computed before the call:
    /// subroutines are called in declaration order, before the equations.
    pub fn subroutine_argument(&mut self, x: ExprId, sub: usize, name: &str, span: Span) -> bool {
        let what = format!("an argument of subroutine `{name}`");
        if !self.without_acceleration(&[x], span, &what) {
            return false;
        }
        let arena = &self.sys.arena;
        let later = arena
            .free_symbols(x)
            .into_iter()
            .find_map(|s| match arena.symbol(s).kind {
                SymbolKind::ExternOutput { sub: other, .. } if other >= sub => Some((s, other)),
                _ => None,
            });
        let Some((s, other)) = later else {
            return true;
        };
        let output = arena.symbol(s).name.clone();
        let message = if other == sub {
            format!("subroutine `{name}` cannot take its own output `{output}` as an argument")
        } else {
            format!(
                "{what} uses `{output}`, an output of subroutine `{}` declared after it",
                self.sys.subroutines()[other].name
            )
        };
        self.push(Diagnostic::error(span, message).help(
            "subroutines are called in the order they are declared: an argument may only use the outputs of subroutines declared before",
        ));
        false
    }

    /// A vector, or a diagnostic.
    pub fn vector(&mut self, e: &Expr, context: &str) -> Option<Vector> {
        match self.eval(e)? {
            Value::Vector(v) => Some(v),
            Value::Scalar(s) if self.sys.arena.is_zero(s) => Some(Vector::zero()),
            other => {
                let hint = match (&other, e) {
                    // `about: 3`: an axis number where its unit vector belongs.
                    (Value::Scalar(_), Expr::Number(n))
                        if matches!(n.text.as_str(), "1" | "2" | "3") =>
                    {
                        format!(
                            "; an axis is a unit vector: write `n{k}` for axis {k} of N, or `b{k}` for axis {k} of a body `B`",
                            k = n.text
                        )
                    }
                    (Value::Scalar(_), Expr::Name(n)) if self.shadowed_axis(&n.text).is_some() => {
                        let (body, axis) = self.shadowed_axis(&n.text).unwrap_or_default();
                        format!(
                            "; `{}` names a scalar declared in the model, which hides the unit vector of the same spelling: write `{body}.{axis}` for axis {axis} of body `{body}`",
                            n.text
                        )
                    }
                    (Value::Scalar(_), _) if context == "gravity" => {
                        "; multiply it by a unit vector, e.g. `-g*n3` (g downwards along N's third axis)".to_string()
                    }
                    (Value::Scalar(_), _) => {
                        "; multiply it by a unit vector, e.g. `F*b1`".to_string()
                    }
                    (Value::List(_), _) => {
                        "; a list `[x, y, z]` has no axes: write `x*b1 + y*b2 + z*b3`".to_string()
                    }
                    (Value::Point(_), _) => "; use `pos(P)` for its position".to_string(),
                    _ => String::new(),
                };
                self.error(
                    e.span(),
                    format!(
                        "{context} needs a vector, but this is a {}{hint}",
                        other.kind()
                    ),
                );
                None
            }
        }
    }

    /// The body and axis a name like `c2` would be the unit vector of,
    /// when a declared name hides that shorthand.
    fn shadowed_axis(&self, name: &str) -> Option<(String, u8)> {
        let digit = name.chars().last()?.to_digit(10)?;
        if !(1..=3).contains(&digit) || self.uv_short.contains_key(name) {
            return None;
        }
        let stem = &name[..name.len() - 1];
        self.sys
            .bodies()
            .iter()
            .find(|b| b.name.to_lowercase() == stem)
            .map(|b| (b.name.clone(), digit as u8))
    }

    /// A point (a body stands for its origin).
    pub fn point(&mut self, e: &Expr, context: &str) -> Option<PointId> {
        if let Expr::Name(n) = e
            && self.is_undeclared(n)
        {
            self.unknown_of_kind(
                n,
                "point",
                |k| matches!(k, Named::Point(_) | Named::Body(_)),
                format!(
                    "declare it with `point {} in B at [x, y, z];`, or use `B.cm` or a body (its origin)",
                    n.text
                ),
            );
            return None;
        }
        match self.eval(e)? {
            Value::Point(p) => Some(p),
            Value::Body(b) => Some(self.sys.body(b).origin),
            other => {
                self.error(
                    e.span(),
                    format!(
                        "{context} needs a point (or a body for its origin), but this is a {}",
                        other.kind()
                    ),
                );
                None
            }
        }
    }

    /// A body.
    pub fn body(&mut self, e: &Expr, context: &str) -> Option<BodyId> {
        if let Expr::Name(n) = e
            && self.is_undeclared(n)
        {
            return self.body_by_name(n);
        }
        match self.eval(e)? {
            Value::Body(b) => Some(b),
            other => {
                self.error(
                    e.span(),
                    format!("{context} needs a body, but this is a {}", other.kind()),
                );
                None
            }
        }
    }

    /// `[x, y, z]` of scalars (constant if `constant`).
    pub fn list3(&mut self, e: &Expr, context: &str, constant: bool) -> Option<[ExprId; 3]> {
        let Expr::List { items, span } = e else {
            self.push(Diagnostic::error(
                e.span(),
                format!("{context} must be a list `[x, y, z]`"),
            ));
            return None;
        };
        if items.len() != 3 {
            self.error(
                *span,
                format!("{context} must have 3 entries, not {}", items.len()),
            );
            return None;
        }
        let mut out = [self.sys.arena.zero(); 3];
        let mut ok = true;
        for (k, it) in items.iter().enumerate() {
            let v = if constant {
                self.constant(it, context)
            } else {
                self.scalar(it, context)
            };
            match v {
                Some(x) => out[k] = x,
                None => ok = false,
            }
        }
        ok.then_some(out)
    }

    /// An integer literal (possibly negative).
    pub fn integer(&mut self, e: &Expr, context: &str) -> Option<i64> {
        match integer_literal(e) {
            Some(Ok(v)) => return Some(v),
            Some(Err(())) => self.error(e.span(), format!("`{e}` is too large for {context}")),
            None => self.error(e.span(), format!("{context} must be an integer")),
        }
        None
    }
}

/// The value of an integer literal (possibly negative): `None` if `e` is
/// none, `Err` if it does not fit an `i64`.
pub(super) fn integer_literal(e: &Expr) -> Option<Result<i64, ()>> {
    let (neg, inner) = match e {
        Expr::Unary {
            op: UnOp::Neg,
            operand,
            ..
        } => (true, operand.as_ref()),
        other => (false, other),
    };
    let Expr::Number(n) = inner else { return None };
    match n.text.parse::<i64>() {
        Ok(v) => Some(Ok(if neg { -v } else { v })),
        Err(_) if n.text.chars().all(|c| c.is_ascii_digit()) => Some(Err(())),
        Err(_) => None,
    }
}
