//! Items that use expressions, resolved in model order once every name is
//! declared: points and `let`s (if nothing used them first), subroutine
//! arguments, added states, gravity, loads, outputs, constraints,
//! motions and events.

use super::ResolvedModel;
use super::loads::{coefficients, force, moment};
use super::scope::{Named, Resolver};
use crate::diag::Diagnostic;
use crate::syntax::ast::{self, Item, StateKey};

/// Resolves every item that uses expressions; `outputs` limits the
/// outputs generated (the others are still checked).
pub(super) fn resolve_items<'a>(
    r: &mut Resolver<'a>,
    out: &mut ResolvedModel,
    model: &'a ast::Model,
    outputs: Option<&[ast::Name]>,
) {
    let mut gravity_seen = false;
    for item in &model.items {
        match item {
            Item::Point(p) => {
                if let Some((Named::Point(i), _)) = r.names.get(&p.name.text).cloned() {
                    r.point_value(i, p.name.span);
                }
            }
            Item::Let(l) => {
                if let Some((Named::Let(i), _)) = r.names.get(&l.name.text).cloned() {
                    r.let_value(i, l.name.span);
                }
            }
            Item::ExternSub(sub) => subroutine_arguments(r, sub),
            Item::State(s) => state(r, s),
            Item::Gravity(g) => {
                if gravity_seen {
                    r.error(g.span, "gravity is set twice");
                }
                gravity_seen = true;
                if let Some(v) = r.vector(&g.value, "gravity")
                    && r.without_acceleration(&coefficients(&v), g.value.span(), "gravity")
                {
                    r.sys.set_gravity(v);
                }
            }
            Item::Force(f) => force(r, f),
            Item::Moment(m) => moment(r, m),
            Item::Output(o) => output(r, out, o, outputs),
            Item::Constraint(c) => constraint(r, out, c),
            Item::Motion(m) => motion(r, out, m),
            Item::Event(e) => super::events::event(r, out, e),
            _ => {}
        }
    }
    super::quantities::finish(r);
}

fn subroutine_arguments(r: &mut Resolver<'_>, sub: &ast::ExternSub) {
    let Some(index) = r
        .sys
        .subroutines()
        .iter()
        .position(|s| s.name == sub.name.text)
    else {
        return; // not declared: already reported
    };
    let mut args = Vec::new();
    let mut ok = true;
    for a in &sub.args {
        match r.scalar(a, "an argument of a subroutine") {
            Some(x) if r.subroutine_argument(x, index, &sub.name.text, a.span()) => args.push(x),
            _ => ok = false,
        }
    }
    if ok {
        let _ = r.sys.set_subroutine_args(index, args);
    }
}

fn state(r: &mut Resolver<'_>, s: &ast::State) {
    let Some((Named::Symbol(sym), _)) = r.names.get(&s.name.text).cloned() else {
        return;
    };
    if let Some(opt) = s.options.get(StateKey::Initial)
        && let Some(x) = r.constant(&opt.value, "the initial value of a state")
    {
        let _ = r.sys.set_state_initial(sym, x);
    }
    match s.options.get(StateKey::Derivative) {
        Some(opt) => {
            if let Some(d) = r.scalar(&opt.value, "the derivative of a state")
                && r.without_deferred(&[d], opt.value.span(), "the derivative of a state")
            {
                let _ = r.sys.set_state_derivative(sym, d);
            }
        }
        None => r.push(
            Diagnostic::error(
                s.name.span,
                format!("the state `{}` has no derivative", s.name.text),
            )
            .help("add `derivative: <expression>` to its block"),
        ),
    }
}

fn output(
    r: &mut Resolver<'_>,
    out: &mut ResolvedModel,
    o: &ast::Output,
    outputs: Option<&[ast::Name]>,
) {
    if !r.declare(&o.name, Named::Output) {
        return;
    }
    // Outputs the scene did not ask for are not generated (their
    // expressions are still checked).
    let wanted = outputs.is_none_or(|names| names.iter().any(|n| n.text == o.name.text));
    let value = r.scalar(&o.value, "an output");
    if !wanted {
        return;
    }
    if let Some(x) = value {
        let unit = o.unit.as_ref().map(|u| u.text.as_str());
        let x = in_declared_unit(r, x, unit);
        if let Err(e) = r.sys.add_output(&o.name.text, unit, x) {
            r.error(o.name.span, e.to_string());
        }
        if !o.docs.is_empty() {
            r.sys.describe_last_output(&o.docs.join(" "));
        }
    }
    out.item_docs.insert(o.name.text.clone(), o.docs.clone());
}

/// An output's value `x` (computed in coherent SI units) in its declared
/// unit: divided by the unit's factor (`[deg]`: times 180/π).
fn in_declared_unit(
    r: &mut Resolver<'_>,
    x: crate::expr::ExprId,
    unit: Option<&str>,
) -> crate::expr::ExprId {
    let factor = unit
        .and_then(super::units::unit_meaning)
        .map_or(1.0, |u| u.factor);
    match crate::expr::Number::parse_decimal(&(1.0 / factor).to_string()) {
        Some(f) if factor != 1.0 => {
            let f = r.sys.arena.num(f);
            r.sys.arena.mul(x, f)
        }
        _ => x,
    }
}

/// Where a mistake in option `key` of an item is written (its value), or
/// the item's name.
fn option_span<K: crate::syntax::ast::OptionKey>(
    item: &crate::syntax::ast::Block<K>,
    key: &str,
) -> crate::diag::Span {
    item.options
        .entries
        .iter()
        .find(|e| e.key.as_str() == key)
        .map_or(item.name.span, |e| e.value.span())
}

/// Reports an error of `mech` about an item at the option it names.
fn report<K: crate::syntax::ast::OptionKey>(
    r: &mut Resolver<'_>,
    item: &crate::syntax::ast::Block<K>,
    e: crate::mech::ModelError,
) {
    let span = match &e {
        crate::mech::ModelError::Option { key, .. } => option_span(item, key),
        _ => item.name.span,
    };
    let d = Diagnostic::error(span, e.to_string());
    r.push(match e.help() {
        Some(h) => d.help(h),
        None => d,
    });
}

/// The symbol a plain name stands for, or a diagnostic.
fn symbol_named(r: &mut Resolver<'_>, e: &ast::Expr, what: &str) -> Option<crate::expr::SymId> {
    match e {
        ast::Expr::Name(n) => match r.names.get(&n.text).cloned() {
            Some((Named::Symbol(s), _)) => Some(s),
            Some(_) => {
                r.error(n.span, format!("`{}` is not a {what}", n.text));
                None
            }
            None => {
                r.unknown(n, what);
                None
            }
        },
        other => {
            r.error(other.span(), format!("give the {what} by its name"));
            None
        }
    }
}

fn constraint<'a>(r: &mut Resolver<'a>, out: &mut ResolvedModel, c: &'a ast::Constraint) {
    use crate::mech::ConstraintKind;
    use crate::syntax::ast::ConstraintKey;
    if !r.declare(&c.name, Named::Load) {
        return;
    }
    let (kind, value) = match (
        c.options.get(ConstraintKey::Position),
        c.options.get(ConstraintKey::Speed),
    ) {
        (Some(p), None) => (ConstraintKind::Position, &p.value),
        (None, Some(s)) => (ConstraintKind::Speed, &s.value),
        (Some(p), Some(_)) => {
            r.push(
                Diagnostic::error(
                    p.key_span,
                    format!(
                        "the constraint `{}` has both `position` and `speed`",
                        c.name.text
                    ),
                )
                .help("a constraint is on positions or on speeds: split it into two constraints"),
            );
            return;
        }
        (None, None) => {
            r.push(
                Diagnostic::error(c.name.span, format!("the constraint `{}` has no expression", c.name.text))
                    .help("add `position: <expression>` (a configuration that must hold) or `speed: <expression>` (linear in the speeds)"),
            );
            return;
        }
    };
    let value_ast = value;
    let what = match kind {
        ConstraintKind::Position => "a position constraint",
        ConstraintKind::Speed => "a speed constraint",
    };
    let value = r
        .scalar(value, what)
        .filter(|&x| r.without_deferred(&[x], value.span(), what));
    let dependent = match c.options.get(ConstraintKey::Dependent) {
        Some(d) => symbol_named(r, &d.value, "coordinate or speed").map(Some),
        None => Some(None),
    };
    let (Some(value), Some(dependent)) = (value, dependent) else {
        return;
    };
    let constraint = crate::mech::Constraint {
        name: c.name.text.clone(),
        kind,
        value,
        dependent,
        unit: c.unit.as_ref().map(|u| u.text.clone()),
    };
    match r.sys.add_constraint(constraint) {
        Ok(()) => r.constraint_exprs.push(value_ast),
        Err(e) => report(r, c, e),
    }
    out.item_docs.insert(c.name.text.clone(), c.docs.clone());
}

fn motion(r: &mut Resolver<'_>, out: &mut ResolvedModel, m: &ast::Motion) {
    use crate::syntax::ast::MotionKey;
    if !r.declare(&m.name, Named::Load) {
        return;
    }
    let missing = |r: &mut Resolver<'_>, key: &str| {
        r.push(
            Diagnostic::error(
                m.name.span,
                format!("the motion `{}` has no `{key}`", m.name.text),
            )
            .help("write `motion name { coordinate: q, value: <function of t> }`"),
        );
    };
    let coordinate = match m.options.get(MotionKey::Coordinate) {
        Some(o) => symbol_named(r, &o.value, "coordinate"),
        None => {
            missing(r, "coordinate");
            None
        }
    };
    let value = match m.options.get(MotionKey::Value) {
        Some(o) => r
            .scalar(&o.value, "a motion")
            .filter(|&x| r.without_deferred(&[x], o.value.span(), "a motion")),
        None => {
            missing(r, "value");
            None
        }
    };
    let (Some(q), Some(value)) = (coordinate, value) else {
        return;
    };
    if let Err(e) = r.sys.add_motion(&m.name.text, q, value) {
        report(r, m, e);
    }
    out.item_docs.insert(m.name.text.clone(), m.docs.clone());
}
