//! Calls in model expressions: built-in functions, user functions, and the
//! operations of the paper's Tables 6 and 12, each a row of
//! [`OPERATIONS`] with its argument counts and its handler.

use super::quantities;
use super::scope::{Named, Resolver, describe};
use super::value::{self, Value};
use crate::diag::{Diagnostic, Span, did_you_mean};
use crate::expr::{ExprId, Func};
use crate::mech::{System, Vector};
use crate::syntax::ast::{self, Expr};

/// An operation's handler: the resolver, the arguments (their count
/// checked), the call's span, and `` `name` `` for messages.
type Handler = fn(&mut Resolver<'_>, &[Expr], Span, &str) -> Option<Value>;

/// The operations a model can call: name, argument counts (min, max), and
/// what they do.
pub(crate) const OPERATIONS: &[(&str, usize, usize, Handler)] = &[
    ("sqrt", 1, 1, sqrt),
    ("dot", 2, 2, dot),
    ("cross", 2, 2, cross),
    ("mag", 1, 1, mag),
    ("dir", 1, 1, dir),
    ("angle", 2, 3, angle),
    ("dot_plane", 2, 2, dot_plane),
    ("pos", 1, 2, pos),
    ("vel", 1, 2, vel),
    ("rot", 1, 1, rot),
    ("q", 1, 2, |r, args, _, _| r.generalized("q", args)),
    ("u", 1, 2, |r, args, _, _| r.generalized("u", args)),
    ("dxdt", 1, 1, dxdt),
    ("partial", 2, 2, partial),
    ("nominal", 1, 1, nominal),
    ("constant_part", 1, 1, constant_part),
    ("reaction_force", 1, 1, quantities::reaction_force),
    ("reaction_moment", 1, 2, quantities::reaction_moment),
    ("kinetic_energy", 0, usize::MAX, quantities::kinetic_energy),
    (
        "potential_energy",
        0,
        usize::MAX,
        quantities::potential_energy,
    ),
    ("momentum", 0, usize::MAX, quantities::momentum),
    (
        "angular_momentum",
        1,
        usize::MAX,
        quantities::angular_momentum,
    ),
    ("power", 1, 1, quantities::power),
    ("constraint_force", 1, 1, quantities::constraint_force),
];

/// The names of the built-in functions.
const BUILTINS: [Func; 12] = [
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
];

/// Whether `name` is a built-in function or an operation (so a bare
/// `vel` is a call with its arguments left out).
pub(crate) fn is_function(name: &str) -> bool {
    Func::builtin(name).is_some() || OPERATIONS.iter().any(|(n, ..)| *n == name)
}

impl Resolver<'_> {
    /// The value of a call `func(args)`.
    pub(super) fn eval_call(
        &mut self,
        func: &ast::Name,
        args: &[Expr],
        span: Span,
    ) -> Option<Value> {
        let name = func.text.as_str();
        // Built-in scalar functions.
        if let Some(f) = Func::builtin(name) {
            let arity = f.builtin_arity().unwrap_or(1);
            if !self.check_arity(func, args.len(), arity, arity) {
                return None;
            }
            let xs = self.scalars(args, name)?;
            let v = Some(Value::Scalar(self.sys.arena.func(f, &xs)));
            return self.finite(span, v);
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
        let Some(&(_, min, max, handler)) = OPERATIONS.iter().find(|(n, ..)| *n == name) else {
            self.not_a_function(func);
            return None;
        };
        if !self.check_arity(func, args.len(), min, max) {
            return None;
        }
        let v = handler(self, args, span, &format!("`{name}`"));
        self.finite(span, v)
    }

    /// Reports a call of something that is not a function.
    fn not_a_function(&mut self, func: &ast::Name) {
        let name = func.text.as_str();
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
            return;
        }
        let mut candidates: Vec<String> = OPERATIONS.iter().map(|(n, ..)| n.to_string()).collect();
        candidates.extend(
            BUILTINS
                .iter()
                .filter_map(|f| f.builtin_name())
                .map(String::from),
        );
        for (n, (k, _)) in &self.names {
            if matches!(k, Named::Function(_)) {
                candidates.push(n.clone());
            }
        }
        let d = Diagnostic::error(func.span, format!("unknown function `{name}`"));
        let d = match did_you_mean(name, candidates.iter().map(String::as_str)) {
            Some(s) => d.help(format!("did you mean `{s}`?")),
            None => d.help(format!("declare user code with `extern fn {name}(...);`")),
        };
        self.push(d);
    }

    fn check_arity(&mut self, func: &ast::Name, got: usize, min: usize, max: usize) -> bool {
        if got >= min && got <= max {
            return true;
        }
        let expected = if max == usize::MAX {
            format!("at least {min} argument{}", if min == 1 { "" } else { "s" })
        } else if min == max {
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

    /// Two vector arguments, both evaluated (every mistake reported).
    fn two_vectors(
        &mut self,
        args: &[Expr],
        ctx: &str,
    ) -> Option<(crate::mech::Vector, crate::mech::Vector)> {
        let a = self.vector(&args[0], ctx);
        let b = self.vector(&args[1], ctx);
        Some((a?, b?))
    }

    /// `q(B)`, `q(B, k)`, `u(B)`, `u(B, k)`.
    fn generalized(&mut self, name: &str, args: &[Expr]) -> Option<Value> {
        let b = self.body(&args[0], &format!("`{name}`"))?;
        // Every declared degree of freedom (a locked one is a parameter).
        let coords = self.sys.body(b).dofs.clone();
        let body = self.sys.body(b).name.clone();
        let n = coords.len();
        let k = match args.get(1) {
            Some(e) => {
                let k = self.integer(e, &format!("the index of `{name}`"))?;
                if k < 1 || k as usize > n {
                    self.error(
                        e.span(),
                        format!(
                            "body `{body}` has {n} degree{} of freedom; index {k} is out of range",
                            if n == 1 { "" } else { "s" }
                        ),
                    );
                    return None;
                }
                k as usize - 1
            }
            None if n == 1 => 0,
            None => {
                let d = match n {
                    0 => Diagnostic::error(
                        args[0].span(),
                        format!("body `{body}` has no degrees of freedom"),
                    )
                    .help(if body == "N" {
                        "`N` is the inertial frame: it does not move".to_string()
                    } else {
                        format!("give `{body}` a `rotate: ...` or `translate: ...` to make it move")
                    }),
                    _ => Diagnostic::error(
                        args[0].span(),
                        format!("body `{body}` has {n} degrees of freedom"),
                    )
                    .help(format!(
                        "say which one: `{name}({body}, k)` with k from 1 to {n}"
                    )),
                };
                self.push(d);
                return None;
            }
        };
        let (q, u) = coords[k];
        Some(Value::Scalar(if name == "q" { q } else { u }))
    }
}

fn sqrt(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let x = r.scalar(&args[0], ctx)?;
    Some(Value::Scalar(r.sys.arena.sqrt(x)))
}

fn dot(r: &mut Resolver<'_>, args: &[Expr], span: Span, _: &str) -> Option<Value> {
    let a = r.eval(&args[0]);
    let b = r.eval(&args[1]);
    let v = value::dot(&mut r.sys, a?, b?);
    r.lift(span, v)
}

fn cross(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let (a, b) = r.two_vectors(args, ctx)?;
    let v = r.sys.frames.cross_vec(&mut r.sys.arena, &a, &b);
    Some(Value::Vector(v))
}

fn mag(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let v = r.vector(&args[0], ctx)?;
    Some(Value::Scalar(r.sys.frames.mag(&mut r.sys.arena, &v)))
}

fn dir(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let v = r.vector(&args[0], ctx)?;
    match r.sys.frames.dir(&mut r.sys.arena, &v) {
        Some(d) => Some(Value::Vector(d)),
        None => {
            r.error(args[0].span(), "`dir` of the zero vector is undefined");
            None
        }
    }
}

fn angle(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let a = r.vector(&args[0], ctx);
    let b = r.vector(&args[1], ctx);
    let c = match args.get(2) {
        Some(e) => Some(r.vector(e, ctx)?),
        None => None,
    };
    let (a, b) = (a?, b?);
    let angle = r.sys.frames.angle(&mut r.sys.arena, &a, &b, c.as_ref());
    Some(Value::Scalar(angle))
}

fn dot_plane(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let (a, b) = r.two_vectors(args, ctx)?;
    let v = r.sys.frames.dot_plane(&mut r.sys.arena, &a, &b);
    Some(Value::Vector(v))
}

/// The points of `pos` and `vel`: one, or two (from the second).
fn points(
    r: &mut Resolver<'_>,
    args: &[Expr],
    ctx: &str,
) -> Option<(crate::mech::PointId, Option<crate::mech::PointId>)> {
    let p1 = r.point(&args[0], ctx);
    let p2 = match args.get(1) {
        Some(e) => Some(r.point(e, ctx)?),
        None => None,
    };
    Some((p1?, p2))
}

fn pos(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let (p1, p2) = points(r, args, ctx)?;
    Some(Value::Vector(r.sys.pos(p1, p2)))
}

fn vel(r: &mut Resolver<'_>, args: &[Expr], span: Span, ctx: &str) -> Option<Value> {
    let (p1, p2) = points(r, args, ctx)?;
    let v = r
        .sys
        .vel(p1, p2)
        .map(Value::Vector)
        .map_err(|e| e.to_string());
    r.lift(span, v)
}

fn rot(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let b = r.body(&args[0], ctx)?;
    Some(Value::Vector(r.sys.rot(b)))
}

fn dxdt(r: &mut Resolver<'_>, args: &[Expr], _: Span, _: &str) -> Option<Value> {
    let y = r.eval(&args[0])?;
    if !computed_later(r, &y, "dxdt", &args[0]) {
        return None;
    }
    let d = derivative(
        r,
        y,
        "dxdt",
        |sys, s| sys.arena.dxdt(s).map_err(|e| e.to_string()),
        |sys, v| sys.dxdt_vector(v).map_err(|e| e.to_string()),
    );
    r.lift(args[0].span(), d)
}

fn partial(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let y = r.eval(&args[0]);
    let x = r.scalar(&args[1], ctx);
    let (y, x) = (y?, x?);
    if !computed_later(r, &y, "partial", &args[0]) {
        return None;
    }
    let Some(sym) = r.sys.arena.as_symbol(x) else {
        r.error(
            args[1].span(),
            "`partial` differentiates with respect to a single variable or parameter name",
        );
        return None;
    };
    let d = derivative(
        r,
        y,
        "partial",
        |sys, s| sys.arena.partial(s, sym).map_err(|e| e.to_string()),
        |sys, v| sys.partial_vector(v, sym).map_err(|e| e.to_string()),
    );
    r.lift(args[0].span(), d)
}

/// False, with a diagnostic at `e`, when `y` reads a quantity the model
/// computes after its equations (reactions, potential energy, power,
/// constraint forces): it stands for a value, not an expression, and
/// its derivative `name` would be taken as zero.
fn computed_later(r: &mut Resolver<'_>, y: &Value, name: &str, e: &Expr) -> bool {
    let values = match y {
        Value::Scalar(s) => vec![*s],
        Value::Vector(v) => super::loads::coefficients(v),
        _ => return true,
    };
    let Some(quantity) = r.deferred_in(&values) else {
        return true;
    };
    r.push(
        Diagnostic::error(e.span(), format!("`{name}` cannot differentiate `{quantity}`"))
            .help("reactions, potential energy, power and constraint forces are values the model computes, not expressions: differentiate the expression itself (for a potential energy, its formula, e.g. `m*g*dot(pos(B), n3)`)"),
    );
    false
}

/// The derivative `name` of a scalar or of a vector (the other kinds of
/// value are a mistake).
fn derivative(
    r: &mut Resolver<'_>,
    y: Value,
    name: &str,
    scalar: impl FnOnce(&mut System, ExprId) -> Result<ExprId, String>,
    vector: impl FnOnce(&mut System, &Vector) -> Result<Vector, String>,
) -> Result<Value, String> {
    match y {
        Value::Scalar(s) => scalar(&mut r.sys, s).map(Value::Scalar),
        Value::Vector(v) => vector(&mut r.sys, &v).map(Value::Vector),
        other => Err(format!(
            "`{name}` needs a scalar or a vector, but this is a {}",
            other.kind()
        )),
    }
}

fn nominal(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let x = r.scalar(&args[0], ctx)?;
    Some(Value::Scalar(r.sys.arena.nominal(x)))
}

fn constant_part(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let x = r.scalar(&args[0], ctx)?;
    Some(Value::Scalar(r.sys.arena.constant_part(x)))
}
