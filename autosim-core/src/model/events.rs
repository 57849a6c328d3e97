//! `event` items: the indicator, its direction, the actions (discrete
//! variables set, states reset, the run stopped), each mistake a
//! diagnostic at the text that makes it. Indicators and new values may
//! call `extern fn` user functions; they may not read an `extern sub`'s
//! outputs.

use super::ResolvedModel;
use super::scope::{Named, Resolver};
use crate::diag::{Diagnostic, Span, did_you_mean};
use crate::expr::{ExprId, SymId, SymbolKind};
use crate::mech::{Event, EventDirection};
use crate::syntax::ast::{self, EventKey};

/// Resolves an `event` item and adds it to the system.
pub(super) fn event(r: &mut Resolver<'_>, out: &mut ResolvedModel, e: &ast::Event) {
    if !r.declare(&e.name, Named::Load) {
        return;
    }
    let indicator = match e.options.get(EventKey::Indicator) {
        Some(o) => value(r, &o.value, "an event indicator"),
        None => {
            r.push(
                Diagnostic::error(e.name.span, format!("the event `{}` has no indicator", e.name.text))
                    .help("add `indicator: <expression>`: the event happens where it changes sign (e.g. `indicator: h` for a height reaching zero)"),
            );
            None
        }
    };
    let direction = direction(r, e);
    let stop = stop(r, e);
    let sets = assignments(r, e.set.as_ref(), Target::Discrete);
    let resets = assignments(r, e.reset.as_ref(), Target::State);
    let (Some(indicator), Some(direction), Some(stop), Some(sets), Some(resets)) =
        (indicator, direction, stop, sets, resets)
    else {
        return;
    };
    let added = r.sys.add_event(Event {
        name: e.name.text.clone(),
        indicator,
        direction,
        sets,
        resets,
        stop,
        unit: e.unit.as_ref().map(|u| u.text.clone()),
    });
    if let Err(err) = added {
        r.error(e.name.span, err.to_string());
    }
    out.item_docs.insert(e.name.text.clone(), e.docs.clone());
}

/// A scalar of the state an event reads: no acceleration, no quantity
/// only outputs may read, no output of a user subroutine (user functions
/// are called where the event computes it).
fn value(r: &mut Resolver<'_>, e: &ast::Expr, what: &str) -> Option<ExprId> {
    let x = r.scalar(e, what)?;
    if !r.without_acceleration(&[x], e.span(), what) {
        return None;
    }
    let arena = &r.sys.arena;
    let sub = arena
        .free_symbols(x)
        .into_iter()
        .find(|&s| matches!(arena.symbol(s).kind, SymbolKind::ExternOutput { .. }));
    match sub {
        None => Some(x),
        Some(s) => {
            let name = arena.symbol(s).name.clone();
            r.push(
                Diagnostic::error(e.span(), format!("{what} cannot use the subroutine output `{name}`"))
                    .note("an `extern sub` is called by `derivatives` and `outputs` only; events call user code through `extern fn` functions")
                    .help("declare the computation as an `extern fn` of the values it needs and call it here, or keep the decision in a discrete variable that an event sets"),
            );
            None
        }
    }
}

/// `direction: rising | falling | either` (default `either`).
fn direction(r: &mut Resolver<'_>, e: &ast::Event) -> Option<EventDirection> {
    let Some(o) = e.options.get(EventKey::Direction) else {
        return Some(EventDirection::Either);
    };
    let found = match &o.value {
        ast::Expr::Name(n) => EventDirection::named(&n.text),
        _ => None,
    };
    if found.is_none() {
        let text = o.value.to_string();
        let mut d = Diagnostic::error(o.value.span(), format!("`{text}` is not an event direction"))
            .note("`rising`: the indicator goes from negative to positive; `falling`: from positive to negative; `either`: both");
        d = match did_you_mean(&text, EventDirection::NAMES) {
            Some(s) => d.help(format!("did you mean `{s}`?")),
            None => d.help("write `direction: rising`, `falling` or `either`"),
        };
        r.push(d);
    }
    found
}

/// `stop: true | false` (default `false`).
fn stop(r: &mut Resolver<'_>, e: &ast::Event) -> Option<bool> {
    let Some(o) = e.options.get(EventKey::Stop) else {
        return Some(false);
    };
    match &o.value {
        ast::Expr::Name(n) if n.text == "true" => Some(true),
        ast::Expr::Name(n) if n.text == "false" => Some(false),
        other => {
            r.push(
                Diagnostic::error(other.span(), format!("`{other}` is not `true` or `false`"))
                    .help("write `stop: true` to end the run at the event"),
            );
            None
        }
    }
}

/// What an action assigns.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Target {
    /// `set`: discrete variables.
    Discrete,
    /// `reset`: coordinates, speeds, added states.
    State,
}

/// The assignments of `set` or `reset`, each target checked, none twice.
fn assignments(
    r: &mut Resolver<'_>,
    list: Option<&(Span, Vec<ast::Assignment>)>,
    target: Target,
) -> Option<Vec<(SymId, ExprId)>> {
    let Some((_, list)) = list else {
        return Some(Vec::new());
    };
    let mut out: Vec<(SymId, ExprId)> = Vec::new();
    let mut ok = true;
    for (k, a) in list.iter().enumerate() {
        if let Some(first) = list[..k].iter().find(|b| b.target.text == a.target.text) {
            let mut d = Diagnostic::error(a.target.span, format!("`{}` is assigned twice by this event", a.target.text))
                .help("assign each variable once: the values are computed from those before the event, all at once");
            if let Some(line) = first.target.span.line() {
                d = d.note(format!("first assigned at line {line}"));
            }
            r.push(d);
            ok = false;
            continue;
        }
        let s = assigned(r, &a.target, target);
        let what = match target {
            Target::Discrete => "the new value of a discrete variable",
            Target::State => "the new value of a state",
        };
        let v = value(r, &a.value, what);
        match (s, v) {
            (Some(s), Some(v)) => out.push((s, v)),
            _ => ok = false,
        }
    }
    ok.then_some(out)
}

/// The symbol `name` names, if `set` (discrete) or `reset` (state) may
/// assign it; a diagnostic saying where it belongs otherwise.
fn assigned(r: &mut Resolver<'_>, name: &ast::Name, target: Target) -> Option<SymId> {
    let Some((named, _)) = r.names.get(&name.text).cloned() else {
        if r.declared_by_failed_body(&name.text) {
            // That body's error says what is wrong.
            return None;
        }
        let (what, help) = match target {
            Target::Discrete => (
                "discrete variable",
                format!(
                    "declare it: `discrete {} [unit] = <initial value>;`",
                    name.text
                ),
            ),
            Target::State => (
                "state",
                "`reset` gives new values to coordinates, speeds and added states".to_string(),
            ),
        };
        let known = r.known_names();
        let mut d = Diagnostic::error(name.span, format!("unknown {what} `{}`", name.text));
        d = match did_you_mean(&name.text, known.iter().map(String::as_str)) {
            Some(s) => d.help(format!("did you mean `{s}`?")),
            None => d.help(help),
        };
        r.push(d);
        return None;
    };
    let kind = match named {
        Named::Symbol(s) => Some((s, r.sys.arena.symbol(s).kind.clone())),
        _ => None,
    };
    let is_state = |k: &SymbolKind| {
        matches!(
            k,
            SymbolKind::Coordinate { .. } | SymbolKind::Speed { .. } | SymbolKind::State { .. }
        )
    };
    match (target, kind) {
        (Target::Discrete, Some((s, SymbolKind::Discrete { .. }))) => Some(s),
        (Target::State, Some((s, k))) if is_state(&k) => Some(s),
        (Target::Discrete, Some((_, k))) if is_state(&k) => {
            r.push(
                Diagnostic::error(
                    name.span,
                    format!("`{}` is a state, not a discrete variable", name.text),
                )
                .help(format!(
                    "give a state a new value under `reset`: `reset: {{ {}: ... }}`",
                    name.text
                )),
            );
            None
        }
        (Target::State, Some((_, SymbolKind::Discrete { .. }))) => {
            r.push(
                Diagnostic::error(
                    name.span,
                    format!("`{}` is a discrete variable, not a state", name.text),
                )
                .help(format!(
                    "give a discrete variable a new value under `set`: `set: {{ {}: ... }}`",
                    name.text
                )),
            );
            None
        }
        _ => {
            let (what, help) = match target {
                Target::Discrete => (
                    "a discrete variable",
                    format!(
                        "declare it with `discrete {} [unit] = <initial value>;` to change it in events",
                        name.text
                    ),
                ),
                Target::State => (
                    "a state",
                    "`reset` gives new values to coordinates, speeds and added states".to_string(),
                ),
            };
            r.push(
                Diagnostic::error(name.span, format!("`{}` is not {what}", name.text))
                    .note("parameters and inputs are set from outside the model, `let`s and outputs are computed")
                    .help(help),
            );
            None
        }
    }
}
