//! The dimension of an expression, read from the model's text (the AST)
//! with the resolver's names: what each name is, the units declared, the
//! joints' coordinates. Mismatches inside the expression (a sum of a mass
//! and a length, the sine of a length) are reported where they are written.

use super::dim::{Dim, Ratio};
use super::infer::{Affine, Mismatch, Shown, Solver, Var};
use super::table::{decimal, parse_unit};
use crate::diag::{Diagnostic, Span};
use crate::expr::{Func, SymId, SymbolKind};
use crate::model::scope::{Lazy, MAX_PENDING, Named, Resolver};
use crate::syntax::ast::{BinOp, Expr, Member, UnOp, Unit};
use rustc_hash::FxHashMap;

/// The dimension of a value.
#[derive(Clone, Debug)]
pub(super) enum Measure {
    /// A scalar, vector or dyadic of this dimension.
    Dim(Affine),
    /// Numbers only (`0.3`, `2*pi`): takes the dimension its place needs.
    Free,
    /// Not a quantity (a point, a body), or not known (a mistake reported
    /// elsewhere, or exponents too large to track): never a mismatch.
    Untracked,
    /// A list `[a, b, c]`.
    List(Vec<Measure>),
}

impl Measure {
    /// A known dimension.
    pub fn known(dim: Dim) -> Measure {
        Measure::Dim(Affine::known(dim))
    }

    fn map(self, f: impl FnOnce(Affine) -> Option<Affine>) -> Measure {
        match self {
            Measure::Dim(a) => f(a).map_or(Measure::Untracked, Measure::Dim),
            other => other,
        }
    }
}

/// The declared units of a user function: its arguments' and its
/// result's (dimensionless when not declared).
pub(super) struct Signature {
    pub args: Vec<Option<Dim>>,
    pub result: Dim,
}

/// The checker's state: the resolver it reads, the unknowns, the `let`s
/// inferred so far, and the mistakes found.
pub(super) struct Checker<'r, 'a> {
    pub r: &'r Resolver<'a>,
    pub solver: Solver,
    pub vars: FxHashMap<SymId, Var>,
    pub lets: Vec<Lazy<Measure>>,
    pub signatures: FxHashMap<String, Signature>,
    pub diags: Vec<Diagnostic>,
    /// How many `let`s are being inferred, one inside another.
    pub pending: usize,
}

/// The unit of one base quantity of mechanics.
pub(super) fn unit_dim(text: &str) -> Dim {
    parse_unit(text).map_or(Dim::ONE, |u| u.dim)
}

impl<'r, 'a> Checker<'r, 'a> {
    /// The dimension of `e`.
    pub fn expr(&mut self, e: &Expr) -> Measure {
        match e {
            Expr::Number(_) => Measure::Free,
            Expr::Quantity { unit, .. } => self.unit(unit, true),
            Expr::As { inner, unit, .. } => {
                self.expr(inner);
                self.unit(unit, false)
            }
            Expr::Name(n) => self.name(&n.text),
            Expr::Paren { inner, .. } => self.expr(inner),
            Expr::Unary { op, operand, .. } => match (op, self.expr(operand)) {
                (UnOp::Neg | UnOp::Plus, Measure::List(_)) => Measure::Untracked,
                (_, q) => q,
            },
            Expr::Binary { .. } => self.binary(e),
            Expr::List { items, .. } => Measure::List(items.iter().map(|i| self.expr(i)).collect()),
            Expr::Member { member, .. } => match member {
                // A unit vector is a pure direction: `9.81*n3` is a number.
                Member::Index { .. } => Measure::Free,
                Member::Name(_) => Measure::Untracked,
            },
            Expr::Call { func, args, span } => self.call(&func.text, args, *span),
        }
    }

    /// The dimension of a unit written in an expression; a unit with a
    /// factor is allowed only after a number (`30 [deg]`).
    fn unit(&mut self, unit: &Unit, factor_allowed: bool) -> Measure {
        match self.meaning(unit, factor_allowed) {
            Some(dim) => Measure::known(dim),
            None => Measure::Untracked,
        }
    }

    /// The dimension of a unit, or a diagnostic; a unit with a factor
    /// (`deg`, `mm`) is reported unless `factor_allowed`, and read as its
    /// coherent unit (the one the error says to declare), so its uses add
    /// no errors of their own.
    pub fn meaning(&mut self, unit: &Unit, factor_allowed: bool) -> Option<Dim> {
        match parse_unit(&unit.text) {
            Ok(u) if u.is_coherent() || factor_allowed => Some(u.dim),
            Ok(u) => {
                self.diags.push(
                    Diagnostic::error(
                        unit.span,
                        format!(
                            "`{}` is not a coherent SI unit (1 {} = {} {}): this value is computed in, or passed as, {}",
                            unit.text, unit.text, u.factor, u.dim, u.dim
                        ),
                    )
                    .help(format!("declare it in `[{}]`; a unit with a factor is converted only where a number is written: a parameter's value (`a = 30 [{}]`) or a number in an expression (`2 [{}]`)", u.dim, unit.text, unit.text)),
                );
                Some(u.dim)
            }
            Err(err) => {
                self.diags
                    .push(Diagnostic::error(unit.span, err.message).help(err.help));
                None
            }
        }
    }

    fn name(&mut self, name: &str) -> Measure {
        match self.r.names.get(name) {
            Some((Named::Symbol(s), _)) => self.symbol(*s),
            Some((Named::Let(i), _)) => self.let_quantity(*i),
            // The speed of a locked degree of freedom (zero): which speed
            // is not recorded, so its unit is not known here.
            Some((Named::Constant(_), _)) => Measure::Untracked,
            Some(_) => Measure::Untracked,
            None if self.r.uv_short.contains_key(name) => Measure::Free,
            None if name == "pi" => Measure::Free,
            None => Measure::Untracked,
        }
    }

    /// The dimension of a symbol: its unit, time's second, or an unknown
    /// for a quantity declared without a unit.
    pub fn symbol(&mut self, s: SymId) -> Measure {
        let sym = self.r.sys.arena.symbol(s);
        if matches!(sym.kind, SymbolKind::Time) {
            return Measure::known(unit_dim("s"));
        }
        match &sym.unit {
            Some(text) => match parse_unit(text) {
                Ok(u) => Measure::known(u.dim),
                Err(_) => Measure::Untracked, // reported at the declaration
            },
            None => {
                let name = sym.name.clone();
                let solver = &mut self.solver;
                let v = *self.vars.entry(s).or_insert_with(|| solver.fresh(&name));
                Measure::Dim(Affine::var(v))
            }
        }
    }

    /// The dimension of `let` number `i`, inferred on first use.
    ///
    /// A `let` the resolver could not evaluate (a cycle, a chain of `let`s
    /// waiting on one another past [`MAX_PENDING`]: both reported) is not
    /// tracked, so the check recurses no deeper than the resolver.
    pub fn let_quantity(&mut self, i: usize) -> Measure {
        match &self.lets[i] {
            Lazy::Done(q) => return q.clone().unwrap_or(Measure::Untracked),
            Lazy::InProgress => return Measure::Untracked,
            Lazy::Pending => {}
        }
        let (item, resolved) = &self.r.lets[i];
        if !matches!(resolved, Lazy::Done(Some(_))) || self.pending >= MAX_PENDING {
            return Measure::Untracked;
        }
        self.lets[i] = Lazy::InProgress;
        self.pending += 1;
        let q = self.expr(&item.value);
        self.pending -= 1;
        self.lets[i] = Lazy::Done(Some(q.clone()));
        q
    }

    /// A chain `a + b - c * d ...`, evaluated from its innermost operator
    /// out in a loop (as the resolver does: thousands of terms must not
    /// recurse once per term).
    fn binary(&mut self, e: &Expr) -> Measure {
        let mut spine = Vec::new();
        let mut first = e;
        while let Expr::Binary {
            op, lhs, rhs, span, ..
        } = first
        {
            spine.push((*op, rhs.as_ref(), *span, first));
            first = lhs;
        }
        let mut value = self.expr(first);
        for (op, rhs, span, whole) in spine.into_iter().rev() {
            value = match op {
                BinOp::Add | BinOp::Sub => {
                    let b = self.expr(rhs);
                    self.sum(op, (value, b), (whole, rhs), span)
                }
                BinOp::Mul => {
                    let b = self.expr(rhs);
                    product(value, b, Affine::times)
                }
                BinOp::Div => {
                    let b = self.expr(rhs);
                    product(value, b, Affine::over)
                }
                BinOp::Pow => self.power(value, rhs, whole),
            };
        }
        value
    }

    /// `a + b` or `a - b` (`whole`, its last term `term`): both sides the
    /// same dimension.
    fn sum(
        &mut self,
        op: BinOp,
        (a, b): (Measure, Measure),
        (whole, term): (&Expr, &Expr),
        span: Span,
    ) -> Measure {
        self.one_unit(a, b, |l, r| {
            let verb = match op {
                BinOp::Add => format!("adds {l} to {r}"),
                _ => format!("subtracts {r} from {l}"),
            };
            let mut d = Diagnostic::error(span, format!("`{}` {verb}", short(whole)))
                .help("the terms of a sum must have one unit: check the formula, and the units declared for the names it uses");
            if let Expr::Binary { lhs, .. } = whole
                && matches!(lhs.as_ref(), Expr::Binary { op: BinOp::Add | BinOp::Sub, .. })
            {
                d = d.help(format!(
                    "the term `{}` is in {r}, the terms before it in {l}",
                    short(term)
                ));
            }
            d
        })
    }

    /// `a` and `b` in one dimension (a number takes the other's); when
    /// they differ, `report` makes the diagnostic from the two units.
    fn one_unit(
        &mut self,
        a: Measure,
        b: Measure,
        report: impl FnOnce(String, String) -> Diagnostic,
    ) -> Measure {
        match (a, b) {
            (Measure::Free, q) | (q, Measure::Free) => q,
            (Measure::Dim(x), Measure::Dim(y)) => match self.solver.unify(&x, &y) {
                Ok(()) => Measure::Dim(x),
                Err(m) => {
                    let l = quantity(&self.show(&m.left));
                    let r = quantity(&self.show(&m.right));
                    self.diags.push(report(l, r));
                    Measure::Untracked
                }
            },
            _ => Measure::Untracked,
        }
    }

    /// `a^b`: a constant rational power of a quantity, or any power of a
    /// dimensionless number.
    fn power(&mut self, base: Measure, exponent: &Expr, whole: &Expr) -> Measure {
        let e = self.expr(exponent);
        if !self.require(e, Dim::ONE, exponent, "an exponent") {
            return Measure::Untracked;
        }
        match (base, constant_ratio(exponent)) {
            (Measure::Free, _) => match constant_ratio(exponent) {
                Some(_) => Measure::Free,
                None => Measure::known(Dim::ONE),
            },
            (Measure::Dim(a), Some(p)) => Measure::Dim(a).map(|a| a.pow(p)),
            (Measure::Dim(a), None) => {
                if let Err(m) = self.solver.unify(&a, &Affine::known(Dim::ONE)) {
                    let found = quantity(&self.show(&m.left));
                    self.diags.push(
                        Diagnostic::error(
                            whole.span(),
                            format!("`{}` raises {found} to a power that is not a constant number", short(whole)),
                        )
                        .help("a quantity with a unit takes only a fixed power such as `^2`, `^-1` or `^(1/2)`; write the power as a number"),
                    );
                }
                Measure::known(Dim::ONE)
            }
            _ => Measure::Untracked,
        }
    }

    /// Reports unless `q` is of dimension `dim` (or free, or untracked);
    /// `what` says what the expression is, e.g. "a force's magnitude".
    pub fn require(&mut self, q: Measure, dim: Dim, e: &Expr, what: &str) -> bool {
        self.require_affine(q, &Affine::known(dim), e, what)
    }

    /// As [`Checker::require`], for a dimension with unknowns; false when
    /// a mismatch was reported.
    pub fn require_affine(&mut self, q: Measure, need: &Affine, e: &Expr, what: &str) -> bool {
        match q {
            Measure::Dim(a) => match self.solver.unify(&a, need) {
                Ok(()) => true,
                Err(m) => {
                    self.mismatch(m, e, what);
                    false
                }
            },
            Measure::List(items) => match e {
                Expr::List { items: exprs, .. } => {
                    let mut ok = true;
                    for (q, e) in items.into_iter().zip(exprs) {
                        ok &= self.require_affine(q, need, e, what);
                    }
                    ok
                }
                _ => true,
            },
            Measure::Free | Measure::Untracked => true,
        }
    }

    /// "{what} must be in {need}, but `e` is in {found}".
    fn mismatch(&mut self, m: Box<Mismatch>, e: &Expr, what: &str) {
        let (found, need) = (self.show(&m.left), self.show(&m.right));
        let unit = self
            .solver
            .known(&m.right)
            .map_or(need.clone(), |d| d.to_string());
        self.diags.push(
            Diagnostic::error(
                e.span(),
                format!("{what} must be {}, but `{}` is {}", in_unit(&need), short(e), in_unit(&found)),
            )
            .help(format!("check the formula and the units declared for the names it uses; if it is right, say so with `({}) as [{unit}]`", short(e))),
        );
    }

    /// A dimension with unknowns, as said in messages (`1` when
    /// dimensionless).
    pub fn show(&self, a: &Affine) -> String {
        let a = self.solver.resolve(a).unwrap_or_else(|| a.clone());
        Shown(&a, &self.solver).to_string()
    }

    /// Arguments that must be dimensionless (or angles), for `name`.
    fn dimensionless_args(&mut self, args: &[Expr], name: &str) -> bool {
        let mut free = true;
        for a in args {
            let q = self.expr(a);
            free &= matches!(q, Measure::Free);
            self.require(q, Dim::ONE, a, &format!("the argument of `{name}`"));
        }
        free
    }

    fn call(&mut self, name: &str, args: &[Expr], span: Span) -> Measure {
        if let Some(f) = Func::builtin(name) {
            return self.builtin(f, name, args, span);
        }
        if let Some(sig) = self.signatures.get(name) {
            let (units, result) = (sig.args.clone(), sig.result);
            // A call with the wrong number of arguments is reported as
            // such: its arguments match no declared position.
            let counted = units.len() == args.len();
            for (k, a) in args.iter().enumerate() {
                let q = self.expr(a);
                if let (true, Some(Some(dim))) = (counted, units.get(k)) {
                    self.require(q, *dim, a, &format!("argument {} of `{name}`", k + 1));
                }
            }
            return Measure::known(result);
        }
        super::operations::operation(self, name, args)
    }

    fn builtin(&mut self, f: Func, name: &str, args: &[Expr], span: Span) -> Measure {
        let free_or = |free: bool, d: Dim| {
            if free {
                Measure::Free
            } else {
                Measure::known(d)
            }
        };
        match f {
            Func::Sin | Func::Cos | Func::Tan | Func::Exp | Func::Ln => {
                free_or(self.dimensionless_args(args, name), Dim::ONE)
            }
            Func::Asin | Func::Acos => {
                free_or(self.dimensionless_args(args, name), unit_dim("rad"))
            }
            Func::Sign => {
                let q = args.first().map(|a| self.expr(a));
                free_or(matches!(q, Some(Measure::Free)), Dim::ONE)
            }
            Func::Abs => args.first().map_or(Measure::Untracked, |a| self.expr(a)),
            Func::Atan2 | Func::Min | Func::Max => {
                let (Some(a), Some(b)) = (args.first(), args.get(1)) else {
                    return Measure::Untracked;
                };
                let (qa, qb) = (self.expr(a), self.expr(b));
                let whole = Expr::Call {
                    func: crate::syntax::ast::Name {
                        text: name.to_string(),
                        span,
                    },
                    args: args.to_vec(),
                    span,
                };
                let q = self.same(qa, qb, &whole, name);
                match (f, q) {
                    (Func::Atan2, Measure::Free) => Measure::Free,
                    (Func::Atan2, _) => Measure::known(unit_dim("rad")),
                    (_, q) => q,
                }
            }
            Func::User(_) => Measure::Untracked,
        }
    }

    /// The two arguments of `min`, `max`, `atan2`: one dimension.
    fn same(&mut self, a: Measure, b: Measure, whole: &Expr, name: &str) -> Measure {
        self.one_unit(a, b, |l, r| {
            Diagnostic::error(
                whole.span(),
                format!("`{}` compares {l} with {r}", short(whole)),
            )
            .help(format!("the two arguments of `{name}` must have one unit"))
        })
    }
}

/// "N m", or "a dimensionless number" for `1`.
pub(super) fn quantity(shown: &str) -> String {
    match shown {
        "1" => "a dimensionless number".to_string(),
        unit => unit.to_string(),
    }
}

/// "in N m", or "dimensionless" for `1`.
pub(super) fn in_unit(shown: &str) -> String {
    match shown {
        "1" => "dimensionless".to_string(),
        unit => format!("in {unit}"),
    }
}

/// `a * b` or `a / b`: numbers are plain factors.
fn product(a: Measure, b: Measure, op: fn(&Affine, &Affine) -> Option<Affine>) -> Measure {
    let one = || Affine::known(Dim::ONE);
    match (a, b) {
        (Measure::Free, Measure::Free) => Measure::Free,
        (Measure::Free, Measure::Dim(y)) => op(&one(), &y).map_or(Measure::Untracked, Measure::Dim),
        (Measure::Dim(x), Measure::Free) => Measure::Dim(x),
        (Measure::Dim(x), Measure::Dim(y)) => op(&x, &y).map_or(Measure::Untracked, Measure::Dim),
        _ => Measure::Untracked,
    }
}

/// The value of an exponent made of numbers only (`2`, `-1`, `1/2`,
/// `(1/3)`), as an exact ratio.
pub(super) fn constant_ratio(e: &Expr) -> Option<Ratio> {
    match e {
        Expr::Number(n) => decimal(&n.text),
        Expr::Paren { inner, .. } => constant_ratio(inner),
        Expr::Unary {
            op: UnOp::Neg,
            operand,
            ..
        } => constant_ratio(operand).map(Ratio::negated),
        Expr::Unary {
            op: UnOp::Plus,
            operand,
            ..
        } => constant_ratio(operand),
        Expr::Binary { op, lhs, rhs, .. } => {
            let (a, b) = (constant_ratio(lhs)?, constant_ratio(rhs)?);
            match op {
                BinOp::Add => a.plus(b),
                BinOp::Sub => a.plus(b.negated()),
                BinOp::Mul => a.times(b),
                BinOp::Div => a.times(b.recip()?),
                BinOp::Pow => None,
            }
        }
        _ => None,
    }
}

/// An expression as written, shortened for a message (a long chain
/// `a + b + ...` is printed in a loop and cut after about 60 characters).
pub(super) fn short(e: &Expr) -> String {
    let mut out = String::new();
    write_short(e, &mut out);
    match out.char_indices().nth(60) {
        Some((k, _)) => format!("{}...", &out[..k]),
        None => out,
    }
}

fn write_short(e: &Expr, out: &mut String) {
    if out.len() > 64 {
        return;
    }
    let mut spine = Vec::new();
    let mut first = e;
    while let Expr::Binary { op, lhs, rhs, .. } = first {
        spine.push((*op, rhs.as_ref()));
        first = lhs;
    }
    if spine.is_empty() {
        let list = |items: &[Expr], out: &mut String| {
            for (k, item) in items.iter().enumerate() {
                if k > 0 {
                    out.push_str(", ");
                }
                write_short(item, out);
            }
        };
        match e {
            Expr::Call { func, args, .. } => {
                out.push_str(&format!("{}(", func.text));
                list(args, out);
                out.push(')');
            }
            Expr::List { items, .. } => {
                out.push('[');
                list(items, out);
                out.push(']');
            }
            Expr::Paren { inner, .. } => {
                out.push('(');
                write_short(inner, out);
                out.push(')');
            }
            Expr::Unary { op, operand, .. } => {
                out.push(if *op == UnOp::Neg { '-' } else { '+' });
                write_short(operand, out);
            }
            Expr::As { inner, unit, .. } => {
                write_short(inner, out);
                out.push_str(&format!(" as [{}]", unit.text));
            }
            other => out.push_str(&other.to_string()),
        }
        return;
    }
    write_short(first, out);
    for (op, rhs) in spine.into_iter().rev() {
        if out.len() > 64 {
            return;
        }
        match op {
            BinOp::Add | BinOp::Sub => out.push_str(&format!(" {} ", op.as_str())),
            _ => out.push_str(op.as_str()),
        }
        write_short(rhs, out);
    }
}
