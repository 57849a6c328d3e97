//! Evaluation of model expressions into values: names, members, operators
//! and the operations of the paper's Tables 6 and 12.

use super::scope::{Lazy, MAX_NESTING, MAX_PENDING, Named, Resolver, describe};
use super::value::{self, Op, Value};
use crate::diag::{Diagnostic, Span};
use crate::expr::{ExprId, Func, Number, SymbolKind};
use crate::mech::{BodyId, PointId, Vector};
use crate::syntax::ast::{self, BinOp, Expr, Member, UnOp};

/// The operations a model can call, with their argument counts (min, max).
pub(crate) const OPERATIONS: &[(&str, usize, usize)] = &[
    ("sqrt", 1, 1),
    ("dot", 2, 2),
    ("cross", 2, 2),
    ("mag", 1, 1),
    ("dir", 1, 1),
    ("angle", 2, 3),
    ("dot_plane", 2, 2),
    ("pos", 1, 2),
    ("vel", 1, 2),
    ("rot", 1, 1),
    ("q", 1, 2),
    ("u", 1, 2),
    ("dxdt", 1, 1),
    ("partial", 2, 2),
    ("nominal", 1, 1),
    ("constant_part", 1, 1),
];

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
            Expr::Name(name) => self.eval_name(name),
            Expr::Paren { inner, .. } => self.eval(inner),
            Expr::Unary { op, operand, span } => {
                let v = self.eval(operand)?;
                match op {
                    UnOp::Plus => Some(v),
                    UnOp::Neg => {
                        let r = value::negate(&mut self.sys, v);
                        self.lift(*span, r)
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
            ..
        } = first
        {
            spine.push((*op, rhs.as_ref(), *op_span));
            first = lhs;
        }
        let mut value = self.eval(first);
        for (op, rhs, op_span) in spine.into_iter().rev() {
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
            value = self.lift(op_span, r);
        }
        value
    }

    fn lift(&mut self, span: Span, r: Result<Value, String>) -> Option<Value> {
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

    /// The value of `let` number `i`, evaluated on first use.
    pub fn let_value(&mut self, i: usize, at: Span) -> Option<Value> {
        match &self.lets[i].1 {
            Lazy::Done(v) => v.clone(),
            Lazy::InProgress => {
                let name = self.lets[i].0.name.text.clone();
                self.push(
                    Diagnostic::error(at, format!("`{name}` is defined in terms of itself"))
                        .help("a `let` cannot refer to itself, directly or through other `let`s"),
                );
                self.lets[i].1 = Lazy::Done(None);
                None
            }
            Lazy::Pending => {
                let item = self.lets[i].0;
                if !self.may_wait(&item.name, at) {
                    self.lets[i].1 = Lazy::Done(None);
                    return None;
                }
                self.lets[i].1 = Lazy::InProgress;
                self.pending += 1;
                let v = self.eval(&item.value);
                self.pending -= 1;
                let v = v.filter(|v| {
                    let depth = value_depth(&self.sys.arena, v);
                    self.shallow_enough(depth, &item.name)
                });
                self.lets[i].1 = Lazy::Done(v.clone());
                v
            }
        }
    }

    /// The point number `i`, created on first use.
    pub fn point_value(&mut self, i: usize, at: Span) -> Option<PointId> {
        match &self.points[i].1 {
            Lazy::Done(p) => *p,
            Lazy::InProgress => {
                let name = self.points[i].0.name.text.clone();
                self.push(
                    Diagnostic::error(
                        at,
                        format!("the coordinates of point `{name}` depend on the point itself"),
                    )
                    .help("a point's coordinates cannot refer to that point"),
                );
                self.points[i].1 = Lazy::Done(None);
                None
            }
            Lazy::Pending => {
                let item = self.points[i].0;
                if !self.may_wait(&item.name, at) {
                    self.points[i].1 = Lazy::Done(None);
                    return None;
                }
                self.points[i].1 = Lazy::InProgress;
                self.pending += 1;
                let p = self.make_point(item);
                self.pending -= 1;
                self.points[i].1 = Lazy::Done(p);
                p
            }
        }
    }

    /// False (reported at `at`, where `name` is used) when too many `let`s
    /// and points already wait on one another.
    fn may_wait(&mut self, name: &ast::Name, at: Span) -> bool {
        if self.pending < MAX_PENDING {
            return true;
        }
        if std::mem::replace(&mut self.too_many_pending, true) {
            return false;
        }
        self.push(
            Diagnostic::error(
                at,
                format!(
                    "`{}` is used through more than {MAX_PENDING} `let`s or points that are defined after their first use",
                    name.text
                ),
            )
            .help("define each `let` and point before the items that use it"),
        );
        false
    }

    /// False (reported at `name`) when the value of `name` nests deeper
    /// than [`MAX_NESTING`].
    fn shallow_enough(&mut self, depth: u32, name: &ast::Name) -> bool {
        if depth <= MAX_NESTING {
            return true;
        }
        self.push(
            Diagnostic::error(
                name.span,
                format!(
                    "`{}` nests operations more than {MAX_NESTING} deep, through the `let`s and points it uses",
                    name.text
                ),
            )
            .help("shorten the chain of `let`s and points that defines it, or compute it in user code (`extern fn`)"),
        );
        false
    }

    fn make_point(&mut self, item: &ast::Point) -> Option<PointId> {
        let body = self.body_by_name(&item.body);
        let coords = self.list3(&item.at, "the coordinates of a point", false);
        let (body, coords) = (body?, coords?);
        let depth = coords.iter().map(|c| self.sys.arena.depth(*c)).max();
        if !self.shallow_enough(depth.unwrap_or(0), &item.name) {
            return None;
        }
        match self.sys.add_point(&item.name.text, body, coords) {
            Ok(p) => {
                if let Some(label) = &item.label {
                    self.sys.describe_point(p, &label.text);
                }
                Some(p)
            }
            Err(e) => {
                self.error(item.name.span, e.to_string());
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
            self.push(
                Diagnostic::error(e.span(), format!("{context} must be constant"))
                    .help("use parameters and numbers only"),
            );
            return None;
        }
        Some(s)
    }

    /// False, with a diagnostic at `span`, when `values` use an
    /// acceleration (`dxdt` of a speed): `what` is needed to compute them.
    pub fn without_acceleration(&mut self, values: &[ExprId], span: Span, what: &str) -> bool {
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
        let (neg, inner) = match e {
            Expr::Unary {
                op: UnOp::Neg,
                operand,
                ..
            } => (true, operand.as_ref()),
            other => (false, other),
        };
        if let Expr::Number(n) = inner {
            if let Ok(v) = n.text.parse::<i64>() {
                return Some(if neg { -v } else { v });
            }
            if n.text.chars().all(|c| c.is_ascii_digit()) {
                self.error(e.span(), format!("`{e}` is too large for {context}"));
                return None;
            }
        }
        self.error(e.span(), format!("{context} must be an integer"));
        None
    }

    fn eval_call(&mut self, func: &ast::Name, args: &[Expr], span: Span) -> Option<Value> {
        let name = func.text.as_str();
        // Built-in scalar functions.
        if let Some(f) = Func::builtin(name) {
            let arity = f.builtin_arity().unwrap_or(1);
            if !self.check_arity(func, args.len(), arity, arity) {
                return None;
            }
            let xs = self.scalars(args, name)?;
            return Some(Value::Scalar(self.sys.arena.func(f, &xs)));
        }
        // User functions.
        if let Some((Named::Function(f), _)) = self.names.get(name).cloned() {
            let arity = self.sys.arena.user_fn(f).arity;
            if !self.check_arity(func, args.len(), arity, arity) {
                return None;
            }
            let xs = self.scalars(args, name)?;
            return Some(Value::Scalar(self.sys.arena.func(Func::User(f), &xs)));
        }
        let Some(&(_, min, max)) = OPERATIONS.iter().find(|(n, _, _)| *n == name) else {
            if let Some((kind, _)) = self.names.get(name).cloned() {
                let help = match kind {
                    Named::Subroutine => {
                        "a subroutine is called once per evaluation, not in expressions: use its outputs by name".to_string()
                    }
                    _ => format!("to multiply, write `{name}*(...)`"),
                };
                self.push(
                    Diagnostic::error(
                        func.span,
                        format!("`{name}` is {}, not a function", describe(&kind)),
                    )
                    .help(help),
                );
                return None;
            }
            let mut candidates: Vec<String> =
                OPERATIONS.iter().map(|(n, _, _)| n.to_string()).collect();
            for f in [
                Func::Sin,
                Func::Cos,
                Func::Tan,
                Func::Asin,
                Func::Acos,
                Func::Atan2,
                Func::Exp,
                Func::Ln,
                Func::Abs,
                Func::Sign,
                Func::Min,
                Func::Max,
            ] {
                candidates.push(f.builtin_name().unwrap_or("").to_string());
            }
            for (n, (k, _)) in &self.names {
                if matches!(k, Named::Function(_)) {
                    candidates.push(n.clone());
                }
            }
            let mut d = Diagnostic::error(func.span, format!("unknown function `{name}`"));
            if let Some(s) = crate::diag::did_you_mean(name, candidates.iter().map(String::as_str))
            {
                d = d.help(format!("did you mean `{s}`?"));
            } else {
                d = d.help(format!("declare user code with `extern fn {name}(...);`"));
            }
            self.push(d);
            return None;
        };
        if !self.check_arity(func, args.len(), min, max) {
            return None;
        }
        self.operation(name, args, span)
    }

    fn check_arity(&mut self, func: &ast::Name, got: usize, min: usize, max: usize) -> bool {
        if got >= min && got <= max {
            return true;
        }
        let expected = if min == max {
            format!("{min} argument{}", if min == 1 { "" } else { "s" })
        } else {
            format!("{min} to {max} arguments")
        };
        self.error(
            func.span,
            format!(
                "`{}` takes {expected}, but {got} {} given",
                func.text,
                if got == 1 { "was" } else { "were" }
            ),
        );
        false
    }

    fn scalars(&mut self, args: &[Expr], name: &str) -> Option<Vec<ExprId>> {
        let mut out = Vec::with_capacity(args.len());
        let mut ok = true;
        for a in args {
            match self.scalar(a, &format!("an argument of `{name}`")) {
                Some(x) => out.push(x),
                None => ok = false,
            }
        }
        ok.then_some(out)
    }

    fn operation(&mut self, name: &str, args: &[Expr], span: Span) -> Option<Value> {
        let ctx = format!("`{name}`");
        match name {
            "sqrt" => {
                let x = self.scalar(&args[0], &ctx)?;
                Some(Value::Scalar(self.sys.arena.sqrt(x)))
            }
            "dot" => {
                let a = self.eval(&args[0]);
                let b = self.eval(&args[1]);
                let r = value::dot(&mut self.sys, a?, b?);
                self.lift(span, r)
            }
            "cross" => {
                let a = self.vector(&args[0], &ctx);
                let b = self.vector(&args[1], &ctx);
                let (a, b) = (a?, b?);
                Some(Value::Vector(self.sys.frames.cross_vec(
                    &mut self.sys.arena,
                    &a,
                    &b,
                )))
            }
            "mag" => {
                let v = self.vector(&args[0], &ctx)?;
                Some(Value::Scalar(self.sys.frames.mag(&mut self.sys.arena, &v)))
            }
            "dir" => {
                let v = self.vector(&args[0], &ctx)?;
                match self.sys.frames.dir(&mut self.sys.arena, &v) {
                    Some(d) => Some(Value::Vector(d)),
                    None => {
                        self.error(args[0].span(), "`dir` of the zero vector is undefined");
                        None
                    }
                }
            }
            "angle" => {
                let a = self.vector(&args[0], &ctx);
                let b = self.vector(&args[1], &ctx);
                let c = match args.get(2) {
                    Some(e) => Some(self.vector(e, &ctx)?),
                    None => None,
                };
                let (a, b) = (a?, b?);
                let angle = self
                    .sys
                    .frames
                    .angle(&mut self.sys.arena, &a, &b, c.as_ref());
                Some(Value::Scalar(angle))
            }
            "dot_plane" => {
                let a = self.vector(&args[0], &ctx);
                let b = self.vector(&args[1], &ctx);
                let (a, b) = (a?, b?);
                Some(Value::Vector(self.sys.frames.dot_plane(
                    &mut self.sys.arena,
                    &a,
                    &b,
                )))
            }
            "pos" | "vel" => {
                let p1 = self.point(&args[0], &ctx);
                let p2 = match args.get(1) {
                    Some(e) => Some(self.point(e, &ctx)?),
                    None => None,
                };
                let p1 = p1?;
                if name == "pos" {
                    Some(Value::Vector(self.sys.pos(p1, p2)))
                } else {
                    match self.sys.vel(p1, p2) {
                        Ok(v) => Some(Value::Vector(v)),
                        Err(e) => {
                            self.error(span, e.to_string());
                            None
                        }
                    }
                }
            }
            "rot" => {
                let b = self.body(&args[0], &ctx)?;
                Some(Value::Vector(self.sys.rot(b)))
            }
            "q" | "u" => self.generalized(name, args),
            "dxdt" => match self.eval(&args[0])? {
                Value::Scalar(s) => match self.sys.arena.dxdt(s) {
                    Ok(d) => Some(Value::Scalar(d)),
                    Err(e) => {
                        self.error(args[0].span(), e.to_string());
                        None
                    }
                },
                Value::Vector(v) => match self.sys.dxdt_vector(&v) {
                    Ok(d) => Some(Value::Vector(d)),
                    Err(e) => {
                        self.error(args[0].span(), e.to_string());
                        None
                    }
                },
                other => {
                    self.error(
                        args[0].span(),
                        format!(
                            "`dxdt` needs a scalar or a vector, but this is a {}",
                            other.kind()
                        ),
                    );
                    None
                }
            },
            "partial" => {
                let y = self.eval(&args[0]);
                let x = self.scalar(&args[1], &ctx);
                let (y, x) = (y?, x?);
                let Some(sym) = self.sys.arena.as_symbol(x) else {
                    self.error(args[1].span(), "`partial` differentiates with respect to a single variable or parameter name");
                    return None;
                };
                let r = match y {
                    Value::Scalar(s) => self
                        .sys
                        .arena
                        .partial(s, sym)
                        .map(Value::Scalar)
                        .map_err(|e| e.to_string()),
                    Value::Vector(v) => self
                        .sys
                        .partial_vector(&v, sym)
                        .map(Value::Vector)
                        .map_err(|e| e.to_string()),
                    other => Err(format!(
                        "`partial` needs a scalar or a vector, but this is a {}",
                        other.kind()
                    )),
                };
                self.lift(args[0].span(), r)
            }
            "nominal" => {
                let x = self.scalar(&args[0], &ctx)?;
                Some(Value::Scalar(self.sys.arena.nominal(x)))
            }
            "constant_part" => {
                let x = self.scalar(&args[0], &ctx)?;
                Some(Value::Scalar(self.sys.arena.constant_part(x)))
            }
            _ => None,
        }
    }

    fn generalized(&mut self, name: &str, args: &[Expr]) -> Option<Value> {
        let b = self.body(&args[0], &format!("`{name}`"))?;
        // Every declared degree of freedom (a locked one is a parameter).
        let coords = self.sys.body(b).dofs.clone();
        let k = match args.get(1) {
            Some(e) => {
                let k = self.integer(e, &format!("the index of `{name}`"))?;
                if k < 1 || k as usize > coords.len() {
                    self.error(
                        e.span(),
                        format!(
                            "body `{}` has {} degree{} of freedom; index {k} is out of range",
                            self.sys.body(b).name,
                            coords.len(),
                            if coords.len() == 1 { "" } else { "s" }
                        ),
                    );
                    return None;
                }
                k as usize - 1
            }
            None if coords.is_empty() => {
                let body = self.sys.body(b).name.clone();
                self.push(
                    Diagnostic::error(
                        args[0].span(),
                        format!("body `{body}` has no degrees of freedom"),
                    )
                    .help(if body == "N" {
                        "`N` is the inertial frame: it does not move".to_string()
                    } else {
                        format!("give `{body}` a `rotate: ...` or `translate: ...` to make it move")
                    }),
                );
                return None;
            }
            None => {
                if coords.len() != 1 {
                    self.push(
                        Diagnostic::error(
                            args[0].span(),
                            format!(
                                "body `{}` has {} degrees of freedom",
                                self.sys.body(b).name,
                                coords.len()
                            ),
                        )
                        .help(format!(
                            "say which one: `{name}({}, k)` with k from 1 to {}",
                            self.sys.body(b).name,
                            coords.len()
                        )),
                    );
                    return None;
                }
                0
            }
        };
        let (q, u) = coords[k];
        Some(Value::Scalar(if name == "q" { q } else { u }))
    }
}

/// The deepest expression in a value (see `Arena::depth`).
fn value_depth(arena: &crate::expr::Arena, v: &Value) -> u32 {
    match v {
        Value::Scalar(s) => arena.depth(*s),
        Value::Vector(v) => v
            .terms()
            .iter()
            .map(|(_, c)| arena.depth(*c))
            .max()
            .unwrap_or(0),
        Value::Dyadic(d) => d
            .terms()
            .iter()
            .map(|(_, c)| arena.depth(*c))
            .max()
            .unwrap_or(0),
        Value::List(items) => items
            .iter()
            .map(|x| value_depth(arena, x))
            .max()
            .unwrap_or(0),
        Value::Point(_) | Value::Body(_) => 0,
    }
}
