//! The built-ins that read a quantity of the whole model: joint reactions
//! (`reaction_force`, `reaction_moment`), energies (`kinetic_energy`,
//! `potential_energy`), momenta (`momentum`, `angular_momentum`), the
//! power of a load (`power`) and the load a constraint carries
//! (`constraint_force`, its multiplier: the constrained lowering gives it
//! its value, from the accelerations).
//!
//! Those that depend on items resolved in model order (the loads and
//! gravity) cannot be computed where they are written: they stand as
//! placeholder symbols (`Deferred`) until every item is resolved, when
//! [`finish`] puts their values into the outputs. Only outputs (and the
//! `let`s they use) may read them; any other use is reported.

use super::scope::{Named, Resolver};
use super::value::Value;
use crate::diag::{Diagnostic, Span};
use crate::expr::{ExprId, SymId, SymbolKind};
use crate::mech::{Axis, BodyId, ConstraintLoad, PointId, Vector};
use crate::syntax::ast::Expr;
use rustc_hash::FxHashMap;

/// A value known once every item is resolved.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Quantity {
    /// `reaction_force(B)`.
    ReactionForce(BodyId),
    /// `reaction_moment(B[, P])`.
    ReactionMoment(BodyId, Option<PointId>),
    /// `potential_energy(...)` of these bodies.
    Potential(Vec<BodyId>),
    /// `power(load)`.
    Power(String),
    /// `constraint_force(constraint)`.
    ConstraintForce(String),
}

/// A placeholder: the quantity, its symbols (one for a scalar, three for a
/// vector's components in `frame_of`'s axes) and where it was first
/// written.
#[derive(Clone, Debug)]
pub(crate) struct Deferred {
    quantity: Quantity,
    symbols: Vec<SymId>,
    frame_of: BodyId,
    span: Span,
}

/// `reaction_force(B)`.
pub(super) fn reaction_force(
    r: &mut Resolver<'_>,
    args: &[Expr],
    span: Span,
    ctx: &str,
) -> Option<Value> {
    let b = jointed_body(r, &args[0], ctx)?;
    Some(r.deferred(Quantity::ReactionForce(b), b, span))
}

/// `reaction_moment(B)`, `reaction_moment(B, P)`.
pub(super) fn reaction_moment(
    r: &mut Resolver<'_>,
    args: &[Expr],
    span: Span,
    ctx: &str,
) -> Option<Value> {
    let b = jointed_body(r, &args[0], ctx);
    let p = match args.get(1) {
        Some(e) => Some(r.point(e, ctx)?),
        None => None,
    };
    let b = b?;
    Some(r.deferred(Quantity::ReactionMoment(b, p), b, span))
}

/// `kinetic_energy(...)`.
pub(super) fn kinetic_energy(
    r: &mut Resolver<'_>,
    args: &[Expr],
    _: Span,
    ctx: &str,
) -> Option<Value> {
    let bodies = moving_bodies(r, args, ctx)?;
    Some(Value::Scalar(r.sys.kinetic_energy_of(&bodies)))
}

/// `potential_energy(...)`.
pub(super) fn potential_energy(
    r: &mut Resolver<'_>,
    args: &[Expr],
    span: Span,
    ctx: &str,
) -> Option<Value> {
    let bodies = moving_bodies(r, args, ctx)?;
    Some(r.deferred(Quantity::Potential(bodies), BodyId::N, span))
}

/// `momentum(...)`.
pub(super) fn momentum(r: &mut Resolver<'_>, args: &[Expr], _: Span, ctx: &str) -> Option<Value> {
    let bodies = moving_bodies(r, args, ctx)?;
    Some(Value::Vector(r.sys.momentum(&bodies)))
}

/// `angular_momentum(P, ...)`.
pub(super) fn angular_momentum(
    r: &mut Resolver<'_>,
    args: &[Expr],
    _: Span,
    ctx: &str,
) -> Option<Value> {
    let p = r.point(&args[0], ctx);
    let bodies = moving_bodies(r, &args[1..], ctx)?;
    Some(Value::Vector(r.sys.angular_momentum(p?, &bodies)))
}

/// `power(load)`.
pub(super) fn power(r: &mut Resolver<'_>, args: &[Expr], span: Span, _: &str) -> Option<Value> {
    let Expr::Name(n) = &args[0] else {
        r.push(
            Diagnostic::error(args[0].span(), "`power` takes the name of a force or moment")
                .help("write `power(spring)` with a `force spring { ... }` or `moment spring { ... }` of the model"),
        );
        return None;
    };
    match r.names.get(&n.text).cloned() {
        Some((Named::Load, _)) => {
            Some(r.deferred(Quantity::Power(n.text.clone()), BodyId::N, span))
        }
        Some((other, _)) => {
            r.push(
                Diagnostic::error(
                    n.span,
                    format!(
                        "`power` needs a force or moment, but `{}` is {}",
                        n.text,
                        super::scope::describe(&other)
                    ),
                )
                .help("name a `force` or `moment` of the model"),
            );
            None
        }
        None => {
            r.unknown_of_kind(
                n,
                "force or moment",
                |k| matches!(k, Named::Load),
                format!(
                    "declare it with `force {} {{ ... }}` or `moment {} {{ ... }}`",
                    n.text, n.text
                ),
            );
            None
        }
    }
}

/// `constraint_force(constraint)`.
pub(super) fn constraint_force(
    r: &mut Resolver<'_>,
    args: &[Expr],
    span: Span,
    _: &str,
) -> Option<Value> {
    let Expr::Name(n) = &args[0] else {
        r.push(
            Diagnostic::error(
                args[0].span(),
                "`constraint_force` takes the name of a constraint",
            )
            .help("write `constraint_force(loop)` with a `constraint loop { ... }` of the model"),
        );
        return None;
    };
    match r.names.get(&n.text).cloned() {
        // Constraints, motions, forces and moments share a namespace: which
        // one it is is known once every item is resolved (`finish`).
        Some((Named::Load, _)) => {
            Some(r.deferred(Quantity::ConstraintForce(n.text.clone()), BodyId::N, span))
        }
        Some((other, _)) => {
            r.push(
                Diagnostic::error(
                    n.span,
                    format!(
                        "`constraint_force` needs a constraint, but `{}` is {}",
                        n.text,
                        super::scope::describe(&other)
                    ),
                )
                .help("name a `constraint` of the model"),
            );
            None
        }
        None => {
            r.unknown_of_kind(
                n,
                "constraint",
                |k| matches!(k, Named::Load),
                format!("declare it with `constraint {} {{ ... }}`", n.text),
            );
            None
        }
    }
}

/// A body with a joint (not N).
fn jointed_body(r: &mut Resolver<'_>, e: &Expr, ctx: &str) -> Option<BodyId> {
    let b = r.body(e, ctx)?;
    if b == BodyId::N {
        r.push(
            Diagnostic::error(
                e.span(),
                format!("{ctx} needs a body with a joint, but `N` is the inertial frame"),
            )
            .help("name the body whose joint to its parent carries the load"),
        );
        return None;
    }
    Some(b)
}

/// The bodies named (every body but N when none is).
fn moving_bodies(r: &mut Resolver<'_>, args: &[Expr], ctx: &str) -> Option<Vec<BodyId>> {
    if args.is_empty() {
        return Some(r.sys.moving_bodies());
    }
    let mut out = Vec::with_capacity(args.len());
    let mut ok = true;
    for a in args {
        match jointed_body(r, a, ctx) {
            Some(b) if !out.contains(&b) => out.push(b),
            Some(_) => {
                r.error(a.span(), format!("{ctx} names this body twice"));
                ok = false;
            }
            None => ok = false,
        }
    }
    ok.then_some(out)
}

impl Resolver<'_> {
    /// The placeholder of `q` (made on first use): a scalar, or a vector
    /// with components in `frame_of`'s axes.
    fn deferred(&mut self, q: Quantity, frame_of: BodyId, span: Span) -> Value {
        let vector = !matches!(
            q,
            Quantity::Potential(_) | Quantity::Power(_) | Quantity::ConstraintForce(_)
        );
        let symbols = match self.deferred.iter().find(|d| d.quantity == q) {
            Some(d) => d.symbols.clone(),
            None => {
                let k = self.deferred.len();
                let count = if vector { 3 } else { 1 };
                let mut symbols = Vec::with_capacity(count);
                for i in 0..count {
                    // Names no model can write (they never reach generated
                    // code): `dxdt` of one is reported under this name.
                    let name = format!("{} #{k}.{i}", describe_quantity(&q, &self.sys));
                    match self.sys.arena.add_symbol(&name, SymbolKind::Free) {
                        Ok(s) => symbols.push(s),
                        Err(_) => return Value::Scalar(self.sys.arena.zero()),
                    }
                }
                self.deferred.push(Deferred {
                    quantity: q,
                    symbols: symbols.clone(),
                    frame_of,
                    span,
                });
                symbols
            }
        };
        if !vector {
            return Value::Scalar(self.sys.arena.sym(symbols[0]));
        }
        let mut v = Vector::zero();
        for (i, axis) in Axis::ALL.into_iter().enumerate() {
            let u = self.sys.unit_vector(frame_of, axis);
            let c = self.sys.arena.sym(symbols[i]);
            let t = u.scale(&mut self.sys.arena, c);
            v = v.add(&mut self.sys.arena, &t);
        }
        Value::Vector(v)
    }

    /// The name of the quantity a placeholder in `values` stands for, if
    /// any.
    pub(super) fn deferred_in(&self, values: &[ExprId]) -> Option<String> {
        if self.deferred.is_empty() {
            return None;
        }
        let arena = &self.sys.arena;
        let found = values
            .iter()
            .flat_map(|&e| arena.free_symbols(e))
            .find(|s| self.deferred.iter().any(|d| d.symbols.contains(s)))?;
        let d = self.deferred.iter().find(|d| d.symbols.contains(&found))?;
        Some(describe_quantity(&d.quantity, &self.sys))
    }

    /// False, with a diagnostic at `span`, when `values` read a quantity
    /// only outputs may read: `what` is needed to compute it.
    pub(super) fn without_deferred(&mut self, values: &[ExprId], span: Span, what: &str) -> bool {
        let Some(name) = self.deferred_in(values) else {
            return true;
        };
        self.push(
            Diagnostic::error(span, format!("{what} cannot use `{name}`"))
                .help("reactions, potential energy, power and constraint forces are computed from the model's loads and accelerations: use them only in outputs (and the `let`s outputs use)"),
        );
        false
    }
}

/// `reaction_force(B)`, ... as written (for messages).
fn describe_quantity(q: &Quantity, sys: &crate::mech::System) -> String {
    let bodies = |bs: &[BodyId]| {
        bs.iter()
            .map(|b| sys.body(*b).name.clone())
            .collect::<Vec<_>>()
            .join(", ")
    };
    match q {
        Quantity::ReactionForce(b) => format!("reaction_force({})", sys.body(*b).name),
        Quantity::ReactionMoment(b, None) => format!("reaction_moment({})", sys.body(*b).name),
        Quantity::ReactionMoment(b, Some(_)) => {
            format!("reaction_moment({}, ...)", sys.body(*b).name)
        }
        Quantity::Potential(bs) if bs.len() + 1 == sys.bodies().len() => {
            "potential_energy()".to_string()
        }
        Quantity::Potential(bs) => format!("potential_energy({})", bodies(bs)),
        Quantity::Power(name) => format!("power({name})"),
        Quantity::ConstraintForce(name) => format!("constraint_force({name})"),
    }
}

/// Once every item is resolved: the values of the placeholders, put into
/// the outputs. Joint reactions of a model with constraints are errors: a
/// constraint does not say where its load acts.
pub(super) fn finish(r: &mut Resolver<'_>) {
    if r.deferred.is_empty() {
        return;
    }
    let outputs: Vec<ExprId> = r.sys.outputs().iter().map(|o| o.expr).collect();
    let used: Vec<Deferred> = r
        .deferred
        .clone()
        .into_iter()
        .filter(|d| {
            outputs.iter().any(|&e| {
                d.symbols
                    .iter()
                    .any(|s| r.sys.arena.free_symbols(e).contains(s))
            })
        })
        .collect();
    let is_reaction = |d: &&Deferred| {
        matches!(
            d.quantity,
            Quantity::ReactionForce(_) | Quantity::ReactionMoment(..)
        )
    };
    let reactions_needed = used.iter().any(|d| is_reaction(&d));
    let reactions = match reactions_needed {
        false => None,
        true => match constraint_loads(r) {
            Ok(extra) => Some(r.sys.joint_reactions_with(&extra)),
            Err(unknown) => {
                let says = match unknown.contains(',') {
                    false => format!("the constraint {unknown} does not say where its load acts"),
                    true => format!("the constraints {unknown} do not say where their loads act"),
                };
                for d in used.iter().filter(is_reaction) {
                    let what = describe_quantity(&d.quantity, &r.sys);
                    r.push(
                        Diagnostic::error(d.span, format!("`{what}` cannot be computed: {says}"))
                            .note("a joint's reaction includes the loads the constraints carry; a constraint written through the velocities of the points and bodies its load acts on (`dot(vel(P), d)`, `dot(vel(P, Q), d)`, `dot(rot(B), e)`, sums of them, through `let`s and `cross`; a position constraint the same with `pos`) is held by the force `λ d` at `P` (`−λ d` at `Q`) and the moment `λ e` on `B`, when that load does exactly what the constraint does (checked); this one is not written so, or its load does not match it")
                            .help("write the constraint through the point where its load acts, e.g. a wheel's contact `dot(vel(W) + cross(rot(W), contact), n1)`, a loop closed at a pin `dot(pos(E, T), n2)`, a ground contact `dot(pos(C), n3)` with `C` the contact point (a `point` of the wheel at `contact`); or ask for reactions in a model without such constraints (motions are fine)"),
                    );
                }
                return;
            }
        },
    };
    let mut map: FxHashMap<SymId, ExprId> = FxHashMap::default();
    for d in &used {
        let value = match &d.quantity {
            Quantity::ReactionForce(b) => Ok(Value::Vector(
                reactions
                    .as_ref()
                    .map(|x| x[b.index()].force.clone())
                    .unwrap_or_else(Vector::zero),
            )),
            Quantity::ReactionMoment(b, p) => {
                let Some(x) = reactions.as_ref().map(|x| x[b.index()].clone()) else {
                    continue;
                };
                Ok(Value::Vector(moment_about(r, *b, *p, x)))
            }
            Quantity::Potential(bs) => Ok(Value::Scalar(r.sys.gravitational_energy(bs))),
            // The name was resolved to a constraint, a force or a moment;
            // absent from the system, that item failed and its own error
            // is reported (a second one here would name the wrong kind).
            Quantity::ConstraintForce(name) => {
                match r.sys.constraints.iter().position(|c| &c.name == name) {
                    Some(k) => r.sys.constraint_forces.push((k, d.symbols[0])),
                    None if r.diags.is_empty() => r.error(
                        d.span,
                        format!("`constraint_force` needs a constraint, but `{name}` is a force, moment or motion"),
                    ),
                    None => {}
                }
                continue;
            }
            Quantity::Power(name) => match r.sys.power_of(name) {
                Some(Ok(p)) => Ok(Value::Scalar(p)),
                Some(Err(e)) => Err(e.to_string()),
                None if r.diags.is_empty() => Err(format!(
                    "`power` needs a force or moment, but `{name}` is a constraint or motion"
                )),
                None => continue,
            },
        };
        match value {
            Ok(Value::Scalar(x)) => {
                map.insert(d.symbols[0], x);
            }
            Ok(Value::Vector(v)) => {
                let frame = r.sys.body(d.frame_of).frame;
                let c = r.sys.frames.express_in(&mut r.sys.arena, &v, frame);
                for (s, x) in d.symbols.iter().zip(c) {
                    map.insert(*s, x);
                }
            }
            Ok(_) => {}
            Err(message) => r.error(d.span, message),
        }
    }
    r.sys.substitute_in_outputs(&map);
}

/// The loads every constraint carries (each read from its expression and
/// checked, [`super::constraint_load`], times a symbol for its multiplier
/// that the constrained lowering gives its value), or the names of the
/// constraints whose load is not known.
fn constraint_loads(r: &mut Resolver<'_>) -> Result<ConstraintLoad, String> {
    let mut all = ConstraintLoad::default();
    let mut unknown = Vec::new();
    let exprs = r.constraint_exprs.clone();
    for (k, c) in r.sys.constraints.clone().into_iter().enumerate() {
        let load = exprs
            .get(k)
            .and_then(|g| super::constraint_load::read(r, g, c.kind))
            .filter(|load| super::constraint_check::holds(r, &c, load));
        let name = format!("constraint_force({}) #r{k}", c.name);
        let (Some(load), Ok(s)) = (load, r.sys.arena.add_symbol(&name, SymbolKind::Free)) else {
            unknown.push(format!("`{}`", c.name));
            continue;
        };
        r.sys.constraint_forces.push((k, s));
        let lambda = r.sys.arena.sym(s);
        for (p, f) in load.forces {
            all.forces.push((p, f.scale(&mut r.sys.arena, lambda)));
        }
        for (b, m) in load.moments {
            all.moments.push((b, m.scale(&mut r.sys.arena, lambda)));
        }
    }
    match unknown.is_empty() {
        true => Ok(all),
        false => Err(unknown.join(", ")),
    }
}

/// The reaction moment of `b`'s joint about point `p` (its origin when
/// `None`): `M_O + r_PO × F`.
fn moment_about(
    r: &mut Resolver<'_>,
    b: BodyId,
    p: Option<PointId>,
    x: crate::mech::JointReaction,
) -> Vector {
    let Some(p) = p else {
        return x.moment;
    };
    let origin = r.sys.body(b).origin;
    let arm = r.sys.pos(origin, Some(p));
    let t = r.sys.frames.cross_vec(&mut r.sys.arena, &arm, &x.force);
    x.moment.add(&mut r.sys.arena, &t)
}
