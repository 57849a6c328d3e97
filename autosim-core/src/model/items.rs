//! Items that use expressions, resolved in model order once every name is
//! declared: points and `let`s (if nothing used them first), subroutine
//! arguments, added states, gravity, loads and outputs.

use super::ResolvedModel;
use super::loads::{coefficients, force, moment};
use super::scope::{Named, Resolver};
use crate::diag::Diagnostic;
use crate::syntax::ast::{self, Item, StateKey};

/// Resolves every item that uses expressions; `outputs` limits the
/// outputs generated (the others are still checked).
pub(super) fn resolve_items(
    r: &mut Resolver<'_>,
    out: &mut ResolvedModel,
    model: &ast::Model,
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
            _ => {}
        }
    }
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
            if let Some(d) = r.scalar(&opt.value, "the derivative of a state") {
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
        if let Err(e) = r.sys.add_output(&o.name.text, unit, x) {
            r.error(o.name.span, e.to_string());
        }
        if !o.docs.is_empty() {
            r.sys.describe_last_output(&o.docs.join(" "));
        }
    }
    out.item_docs.insert(o.name.text.clone(), o.docs.clone());
}
