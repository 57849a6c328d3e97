//! `force` and `moment` items: one path for both. A force acts at points,
//! a moment on bodies; both take a vector (`vector`, or a direction and a
//! `magnitude`), an optional reaction, and cannot use accelerations.

use super::scope::{Named, Resolver};
use crate::diag::{Diagnostic, Span};
use crate::syntax::ast::{self, Expr, ForceKey, MomentKey};

/// A load item as written, whichever kind.
struct LoadItem<'e, T> {
    name: &'e ast::Name,
    /// `force` or `moment`.
    what: &'static str,
    /// `along` or `about`.
    dir_key: &'static str,
    on: Option<&'e Expr>,
    reaction: Option<&'e Expr>,
    vector: Option<&'e Expr>,
    direction: Option<&'e Expr>,
    magnitude: Option<&'e Expr>,
    /// The message and fix when `on` is missing.
    missing_on: (String, &'static str),
    /// What `on` and `reaction` name: a point or a body.
    target: fn(&mut Resolver<'_>, &Expr, &str) -> Option<T>,
}

/// What `on`, `reaction` and the vector resolve to; every option is
/// evaluated even when one fails, so all mistakes of the item are
/// reported together.
fn resolve_load<T>(
    r: &mut Resolver<'_>,
    l: LoadItem<'_, T>,
) -> Option<(T, Option<T>, crate::mech::Vector)> {
    let on = match l.on {
        Some(on) => (l.target)(r, on, "`on`"),
        None => {
            let (message, help) = l.missing_on;
            r.push(Diagnostic::error(l.name.span, message).help(help));
            None
        }
    };
    // `Some(None)`: a reaction was given but failed (reported).
    let reaction = l.reaction.map(|x| (l.target)(r, x, "`reaction`"));
    let vector = load_vector(
        r,
        l.name.span,
        &l.name.text,
        l.what,
        (l.vector, l.direction, l.magnitude),
        l.dir_key,
    );
    Some((on?, reaction.map_or(Some(None), |x| x.map(Some))?, vector?))
}

/// A `force` item.
pub(super) fn force(r: &mut Resolver<'_>, f: &ast::Force) {
    if !r.declare(&f.name, Named::Load) {
        return;
    }
    let o = |k| f.options.get(k).map(|x| &x.value);
    let item = LoadItem {
        name: &f.name,
        what: "force",
        dir_key: "along",
        on: o(ForceKey::On),
        reaction: o(ForceKey::Reaction),
        vector: o(ForceKey::Vector),
        direction: o(ForceKey::Along),
        magnitude: o(ForceKey::Magnitude),
        missing_on: (
            format!("the force `{}` has no point of application", f.name.text),
            "add `on: P` (a point, `B.cm`, or a body for its origin)",
        ),
        target: |r, e, what| r.point(e, what),
    };
    if let Some((p, reaction, v)) = resolve_load(r, item)
        && let Err(e) = r.sys.add_force(&f.name.text, p, reaction, v)
    {
        r.error(f.name.span, e.to_string());
    }
}

/// A `moment` item.
pub(super) fn moment(r: &mut Resolver<'_>, m: &ast::Moment) {
    if !r.declare(&m.name, Named::Load) {
        return;
    }
    let o = |k| m.options.get(k).map(|x| &x.value);
    let item = LoadItem {
        name: &m.name,
        what: "moment",
        dir_key: "about",
        on: o(MomentKey::On),
        reaction: o(MomentKey::Reaction),
        vector: o(MomentKey::Vector),
        direction: o(MomentKey::About),
        magnitude: o(MomentKey::Magnitude),
        missing_on: (
            format!(
                "the moment `{}` does not say which body it acts on",
                m.name.text
            ),
            "add `on: B`",
        ),
        target: |r, e, what| r.body(e, what),
    };
    if let Some((b, reaction, v)) = resolve_load(r, item)
        && let Err(e) = r.sys.add_moment(&m.name.text, b, reaction, v)
    {
        r.error(m.name.span, e.to_string());
    }
}

/// `vector: v` or `along/about: d, magnitude: s`.
fn load_vector(
    r: &mut Resolver<'_>,
    span: Span,
    name: &str,
    what: &str,
    (vector, direction, magnitude): (Option<&Expr>, Option<&Expr>, Option<&Expr>),
    dir_key: &str,
) -> Option<crate::mech::Vector> {
    // A load is needed to compute the accelerations, so it cannot use them.
    let a_load = format!("a {what}");
    match (vector, direction, magnitude) {
        (Some(v), None, None) => {
            let x = r.vector(v, &format!("the {what} vector"))?;
            r.without_acceleration(&coefficients(&x), v.span(), &a_load)
                .then_some(x)
        }
        (None, Some(dir), Some(mag)) => {
            let d = r
                .vector(dir, &format!("`{dir_key}`"))
                .filter(|d| r.without_acceleration(&coefficients(d), dir.span(), &a_load));
            let m = r
                .scalar(mag, "`magnitude`")
                .filter(|&m| r.without_acceleration(&[m], mag.span(), &a_load));
            let (d, m) = (d?, m?);
            Some(d.scale(&mut r.sys.arena, m))
        }
        (Some(v), _, _) => {
            r.push(
                Diagnostic::error(
                    v.span(),
                    format!("the {what} `{name}` has both `vector` and `{dir_key}`/`magnitude`"),
                )
                .help(format!(
                    "give either `vector: ...` or `{dir_key}: ...` with `magnitude: ...`"
                )),
            );
            None
        }
        (None, Some(d), None) => {
            r.push(
                Diagnostic::error(
                    d.span(),
                    format!("the {what} `{name}` has `{dir_key}` but no `magnitude`"),
                )
                .help("add `magnitude: <scalar>`"),
            );
            None
        }
        (None, None, Some(m)) => {
            r.push(
                Diagnostic::error(
                    m.span(),
                    format!("the {what} `{name}` has `magnitude` but no `{dir_key}`"),
                )
                .help(format!("add `{dir_key}: <unit vector>`")),
            );
            None
        }
        (None, None, None) => {
            r.push(
                Diagnostic::error(span, format!("the {what} `{name}` has no value")).help(format!(
                    "add `vector: ...`, or `{dir_key}: ...` with `magnitude: ...`"
                )),
            );
            None
        }
    }
}

/// The scalar coefficients of a vector.
pub(super) fn coefficients(v: &crate::mech::Vector) -> Vec<crate::expr::ExprId> {
    v.terms().iter().map(|&(_, c)| c).collect()
}
