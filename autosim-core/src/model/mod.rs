//! The resolver: gives the AST its meaning by building the multibody
//! [`System`] through the `mech` API. Every mistake becomes a diagnostic
//! with the span of the offending text; all are reported together.
//!
//! Names may be used before they are declared: bodies are ordered by parent,
//! and `let`s and points are evaluated on first use.

mod bodies;
mod body_options;
mod exprs;
mod scene;
mod scope;
mod spans;
#[cfg(test)]
mod tests;
mod value;

pub use scene::Scene;
pub use spans::ItemSpans;
pub use value::Value;

use crate::diag::{Diagnostic, Diagnostics};
use crate::expr::Number;
use crate::mech::System;
use crate::syntax::ast::{self, ForceKey, Item, MomentKey, SettingKey, StateKey};
use scope::{Lazy, Named, Resolver};

/// The float type generated code computes in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FloatType {
    /// `f64` (default).
    #[default]
    F64,
    /// `f32`.
    F32,
}

/// Documentation of one declared item, for generated docs.
#[derive(Clone, Debug, Default)]
pub struct ItemDoc {
    /// The name.
    pub name: String,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Unit, if any.
    pub unit: Option<String>,
}

/// A user function (`extern fn`).
#[derive(Clone, Debug)]
pub struct ExternFnInfo {
    /// Name.
    pub name: String,
    /// Formal argument names.
    pub params: Vec<String>,
    /// Doc comments.
    pub docs: Vec<String>,
}

/// The resolved model: the system plus what code generation and
/// documentation need to know about the source.
#[derive(Clone, Debug)]
pub struct ResolvedModel {
    /// The multibody system.
    pub system: System,
    /// Float type of generated code.
    pub float: FloatType,
    /// Doc comments of the model.
    pub docs: Vec<String>,
    /// Parameters as declared (docs and units).
    pub parameter_docs: Vec<ItemDoc>,
    /// Inputs as declared.
    pub input_docs: Vec<ItemDoc>,
    /// Outputs as declared.
    pub output_docs: Vec<ItemDoc>,
    /// User functions.
    pub extern_fns: Vec<ExternFnInfo>,
    /// Doc comments of user subroutines, in declaration order.
    pub subroutine_docs: Vec<Vec<String>>,
    /// Parameter names of user subroutines (an argument written as a plain
    /// name gives its name, others are `arg1`, `arg2`, ...).
    pub subroutine_params: Vec<Vec<String>>,
    /// Where each item is declared, for diagnostics of later phases.
    pub spans: ItemSpans,
}

/// Resolves a parsed model.
pub fn resolve(model: &ast::Model) -> Result<ResolvedModel, Diagnostics> {
    resolve_scene(model, &Scene::default())
}

/// Resolves a parsed model with the options of a scene.
pub fn resolve_scene(model: &ast::Model, scene: &Scene) -> Result<ResolvedModel, Diagnostics> {
    let model_name = scene.name.as_ref().unwrap_or(&model.name);
    let mut r = Resolver::new(&model_name.text);
    r.scene = scene.clone();
    let mut out = ResolvedModel {
        system: System::default(),
        float: FloatType::F64,
        docs: model.docs.clone(),
        parameter_docs: Vec::new(),
        input_docs: Vec::new(),
        output_docs: Vec::new(),
        extern_fns: Vec::new(),
        subroutine_docs: Vec::new(),
        subroutine_params: Vec::new(),
        spans: ItemSpans::new(model_name.span),
    };

    // Only these outputs are generated, if the settings say so.
    let mut output_filter: Option<Vec<ast::Name>> = None;
    check_model_name(&mut r, model_name);

    // Settings first: the threshold affects every expression built later.
    for item in &model.items {
        if let Item::Settings(s) = item {
            for opt in &s.options.entries {
                match opt.key {
                    SettingKey::Threshold => {
                        if let Some(k) = r.integer(&opt.value, "the threshold") {
                            match i16::try_from(k)
                                .ok()
                                .filter(|k| crate::limits::THRESHOLDS.contains(k))
                            {
                                Some(k) => r.sys.set_threshold(k),
                                None => r.error(
                                    opt.value.span(),
                                    "the threshold must be between 1 and 20",
                                ),
                            }
                        }
                    }
                    SettingKey::Outputs => {
                        let items: Vec<&ast::Expr> = match &opt.value {
                            ast::Expr::List { items, .. } => items.iter().collect(),
                            other => vec![other],
                        };
                        let mut names = Vec::new();
                        for it in items {
                            match it {
                                ast::Expr::Name(n) => names.push(n.clone()),
                                other => r.error(other.span(), "`outputs` takes output names"),
                            }
                        }
                        output_filter = Some(names);
                    }
                    SettingKey::Float => match &opt.value {
                        ast::Expr::Name(n) if n.text == "f64" => out.float = FloatType::F64,
                        ast::Expr::Name(n) if n.text == "f32" => out.float = FloatType::F32,
                        other => r.push(Diagnostic::error(
                            other.span(),
                            "the float type must be `f64` or `f32`",
                        )),
                    },
                }
            }
        }
    }

    // The scene overrides the model's settings.
    if let Some(f) = scene.float {
        out.float = f;
    }
    if let Some(k) = scene.threshold {
        r.sys.set_threshold(k);
    }
    if let Some(names) = &scene.outputs {
        output_filter = Some(names.clone());
    }

    // Declarations that do not depend on bodies.
    for item in &model.items {
        match item {
            Item::Parameters(ps) => {
                for p in &ps.params {
                    let value = finite_value(&mut r, &p.value);
                    if !r.declare(&p.name, Named::Load) {
                        continue;
                    }
                    let unit = p.unit.as_ref().map(|u| u.text.as_str());
                    match r.sys.add_parameter(&p.name.text, value, unit) {
                        Ok(s) => {
                            r.names
                                .insert(p.name.text.clone(), (Named::Symbol(s), p.name.span));
                        }
                        Err(e) => r.error(p.name.span, e.to_string()),
                    }
                    let docs = if p.docs.is_empty() {
                        ps.docs.clone()
                    } else {
                        p.docs.clone()
                    };
                    out.parameter_docs.push(ItemDoc {
                        name: p.name.text.clone(),
                        docs,
                        unit: p.unit.as_ref().map(|u| u.text.clone()),
                    });
                }
            }
            Item::Inputs(is) => {
                for i in &is.inputs {
                    if !r.declare(&i.name, Named::Load) {
                        continue;
                    }
                    let default = i.default.as_ref().map_or(0.0, |v| finite_value(&mut r, v));
                    let unit = i.unit.as_ref().map(|u| u.text.as_str());
                    match r.sys.add_input(&i.name.text, default, unit) {
                        Ok(s) => {
                            r.names
                                .insert(i.name.text.clone(), (Named::Symbol(s), i.name.span));
                        }
                        Err(e) => r.error(i.name.span, e.to_string()),
                    }
                    out.input_docs.push(ItemDoc {
                        name: i.name.text.clone(),
                        docs: is.docs.clone(),
                        unit: i.unit.as_ref().map(|u| u.text.clone()),
                    });
                }
            }
            Item::ExternFn(f) => {
                if crate::expr::Func::builtin(&f.name.text).is_some()
                    || exprs::OPERATIONS.iter().any(|(n, _, _)| *n == f.name.text)
                {
                    r.push(
                        Diagnostic::error(
                            f.name.span,
                            format!("`{}` is a built-in function", f.name.text),
                        )
                        .help("give the user function another name"),
                    );
                    continue;
                }
                if !r.declare(&f.name, Named::Load) {
                    continue;
                }
                match r.sys.add_user_function(&f.name.text, f.params.len()) {
                    Ok(id) => {
                        r.names
                            .insert(f.name.text.clone(), (Named::Function(id), f.name.span));
                    }
                    Err(e) => r.error(f.name.span, e.to_string()),
                }
                out.extern_fns.push(ExternFnInfo {
                    name: f.name.text.clone(),
                    params: f.params.iter().map(|p| p.text.clone()).collect(),
                    docs: f.docs.clone(),
                });
            }
            _ => {}
        }
    }

    // Bodies, parents first.
    let bodies: Vec<&ast::Body> = model
        .items
        .iter()
        .filter_map(|i| if let Item::Body(b) = i { Some(b) } else { None })
        .collect();
    r.add_bodies(&bodies);

    // Names whose values are computed on demand, and state and subroutine
    // symbols (so any expression may use them).
    for item in &model.items {
        match item {
            Item::Let(l) => {
                let idx = r.lets.len();
                if r.declare(&l.name, Named::Let(idx)) {
                    r.lets.push((l, Lazy::Pending));
                }
            }
            Item::Point(p) => {
                let idx = r.points.len();
                if r.declare(&p.name, Named::Point(idx)) {
                    r.points.push((p, Lazy::Pending));
                }
            }
            Item::State(s) => {
                if !r.declare(&s.name, Named::Load) {
                    continue;
                }
                let zero = r.sys.arena.zero();
                let unit = s.unit.as_ref().map(|u| u.text.as_str());
                match r.sys.add_state(&s.name.text, unit, zero) {
                    Ok(sym) => {
                        r.names
                            .insert(s.name.text.clone(), (Named::Symbol(sym), s.name.span));
                    }
                    Err(e) => r.error(s.name.span, e.to_string()),
                }
            }
            Item::ExternSub(sub) => {
                let mut ok = r.declare(&sub.name, Named::Subroutine);
                for o in &sub.outputs {
                    ok &= r.declare(&o.name, Named::Load);
                }
                if !ok {
                    continue;
                }
                let outs: Vec<(&str, Option<&str>)> = sub
                    .outputs
                    .iter()
                    .map(|o| {
                        (
                            o.name.text.as_str(),
                            o.unit.as_ref().map(|u| u.text.as_str()),
                        )
                    })
                    .collect();
                match r.sys.add_subroutine(&sub.name.text, Vec::new(), &outs) {
                    Ok(syms) => {
                        for (o, s) in sub.outputs.iter().zip(syms) {
                            r.names
                                .insert(o.name.text.clone(), (Named::Symbol(s), o.name.span));
                        }
                    }
                    Err(e) => r.error(sub.name.span, e.to_string()),
                }
                out.subroutine_docs.push(sub.docs.clone());
                out.subroutine_params.push(
                    sub.args
                        .iter()
                        .enumerate()
                        .map(|(k, a)| match a {
                            ast::Expr::Name(n) => n.text.clone(),
                            _ => format!("arg{}", k + 1),
                        })
                        .collect(),
                );
            }
            _ => {}
        }
    }

    // Everything that uses expressions.
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
            Item::ExternSub(sub) => {
                let Some(index) = r
                    .sys
                    .subroutines()
                    .iter()
                    .position(|s| s.name == sub.name.text)
                else {
                    continue; // not declared: already reported
                };
                let mut args = Vec::new();
                let mut ok = true;
                for a in &sub.args {
                    match r.scalar(a, "an argument of a subroutine") {
                        Some(x) if r.subroutine_argument(x, index, &sub.name.text, a.span()) => {
                            args.push(x)
                        }
                        _ => ok = false,
                    }
                }
                if ok {
                    let _ = r.sys.set_subroutine_args(index, args);
                }
            }
            Item::State(s) => {
                let Some((Named::Symbol(sym), _)) = r.names.get(&s.name.text).cloned() else {
                    continue;
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
            Item::Force(f) => force(&mut r, f),
            Item::Moment(m) => moment(&mut r, m),
            Item::Output(o) => {
                if !r.declare(&o.name, Named::Output) {
                    continue;
                }
                // Outputs the scene did not ask for are not generated (their
                // expressions are still checked).
                let wanted = output_filter
                    .as_ref()
                    .is_none_or(|names| names.iter().any(|n| n.text == o.name.text));
                let value = r.scalar(&o.value, "an output");
                if !wanted {
                    continue;
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
                out.output_docs.push(ItemDoc {
                    name: o.name.text.clone(),
                    docs: o.docs.clone(),
                    unit: o.unit.as_ref().map(|u| u.text.clone()),
                });
            }
            _ => {}
        }
    }

    // Scene `small`/`lock` names must each match a body or coordinate.
    for n in scene.small.iter().chain(&scene.lock) {
        if !r.scene_matched.contains(&n.text) {
            let mut d = Diagnostic::error(
                n.span,
                format!(
                    "`{}` is neither a body nor a coordinate of this model",
                    n.text
                ),
            );
            if let Some(s) =
                crate::diag::did_you_mean(&n.text, r.known_names().iter().map(String::as_str))
            {
                d = d.help(format!("did you mean `{s}`?"));
            }
            r.push(d);
        }
    }
    if let Some(names) = &output_filter {
        for n in names {
            let declared = model
                .items
                .iter()
                .any(|i| matches!(i, Item::Output(o) if o.name.text == n.text));
            if !declared {
                let outputs: Vec<&str> = model
                    .items
                    .iter()
                    .filter_map(|i| {
                        if let Item::Output(o) = i {
                            Some(o.name.text.as_str())
                        } else {
                            None
                        }
                    })
                    .collect();
                let mut d = Diagnostic::error(
                    n.span,
                    format!("`{}` is not an output of this model", n.text),
                );
                if let Some(s) = crate::diag::did_you_mean(&n.text, outputs.iter().copied()) {
                    d = d.help(format!("did you mean `{s}`?"));
                }
                r.push(d);
            }
        }
    }
    if !r.diags.is_empty() {
        return Err(r.diags);
    }
    for (name, (_, span)) in &r.names {
        out.spans.insert(name, *span);
    }
    for (name, span) in &r.implicit_parameters {
        out.spans.insert(name, *span);
    }
    out.system = r.sys;
    Ok(out)
}

/// Names the generated module defines beside the model type (see
/// `emit::model`), or uses unqualified.
const TAKEN_TYPE_NAMES: &[&str] = &["Parameters", "Inputs", "Externs", "Constants", "Default"];

/// The model's name becomes a Rust type: `UpperCamelCase`, and not the name
/// of another item of the generated module.
fn check_model_name(r: &mut Resolver<'_>, name: &ast::Name) {
    let text = name.text.strip_prefix("r#").unwrap_or(&name.text);
    if !text.starts_with(char::is_uppercase) || text.contains('_') {
        let camel: String = text
            .split('_')
            .filter(|part| !part.is_empty())
            .map(|part| {
                let mut chars = part.chars();
                chars.next().map_or(String::new(), |first| {
                    first
                        .to_uppercase()
                        .chain(chars.map(|c| c.to_ascii_lowercase()))
                        .collect()
                })
            })
            .collect();
        let d = Diagnostic::error(
            name.span,
            format!("the model's name `{}` is not in UpperCamelCase", name.text),
        )
        .note("it names the generated Rust type (and, in snake case, its module)");
        r.push(match camel.starts_with(char::is_uppercase) {
            true => d.help(format!("write `model {camel};`")),
            false => d.help("start it with an upper-case letter"),
        });
    } else if TAKEN_TYPE_NAMES.contains(&text) {
        r.push(
            Diagnostic::error(
                name.span,
                format!("the model cannot be named `{text}`: the generated module has an item of that name"),
            )
            .help(format!("choose another name, such as `{text}Model`")),
        );
    }
}

/// The value of a parameter or input default, reported when it does not
/// fit a float (`1e999` would become infinity in generated code).
fn finite_value(r: &mut Resolver<'_>, v: &ast::Value) -> f64 {
    let x = value_f64(v);
    if !x.is_finite() {
        r.push(
            Diagnostic::error(
                v.span,
                format!(
                    "`{}` is too large for a floating-point number",
                    v.number.text
                ),
            )
            .help("values must be finite: at most about 1.8e308"),
        );
    }
    x
}

fn value_f64(v: &ast::Value) -> f64 {
    // Rust's parser rounds correctly (once), so `0.018562500000000003`
    // is the same double as in any other program.
    let x = v
        .number
        .text
        .parse::<f64>()
        .ok()
        .or_else(|| Number::parse_decimal(&v.number.text).map(|n| n.to_f64()))
        .unwrap_or(0.0);
    if v.negative { -x } else { x }
}

fn force(r: &mut Resolver<'_>, f: &ast::Force) {
    if !r.declare(&f.name, Named::Load) {
        return;
    }
    // Every option is evaluated even when one fails, so all mistakes of
    // the item are reported together.
    let o = &f.options;
    let point = match o.get(ForceKey::On) {
        Some(on) => r.point(&on.value, "`on`"),
        None => {
            r.push(
                Diagnostic::error(
                    f.name.span,
                    format!("the force `{}` has no point of application", f.name.text),
                )
                .help("add `on: P` (a point, `B.cm`, or a body for its origin)"),
            );
            None
        }
    };
    // `Some(None)`: a reaction was given but failed (reported).
    let reaction = o
        .get(ForceKey::Reaction)
        .map(|x| r.point(&x.value, "`reaction`"));
    let vector = load_vector(
        r,
        f.name.span,
        &f.name.text,
        "force",
        o.get(ForceKey::Vector).map(|x| &x.value),
        o.get(ForceKey::Along).map(|x| &x.value),
        o.get(ForceKey::Magnitude).map(|x| &x.value),
        "along",
    );
    if let (Some(p), Some(v), Some(reaction)) =
        (point, vector, reaction.map_or(Some(None), |x| x.map(Some)))
        && let Err(e) = r.sys.add_force(&f.name.text, p, reaction, v)
    {
        r.error(f.name.span, e.to_string());
    }
}

fn moment(r: &mut Resolver<'_>, m: &ast::Moment) {
    if !r.declare(&m.name, Named::Load) {
        return;
    }
    // As for forces: every option is evaluated even when one fails.
    let o = &m.options;
    let body = match o.get(MomentKey::On) {
        Some(on) => r.body(&on.value, "`on`"),
        None => {
            r.push(
                Diagnostic::error(
                    m.name.span,
                    format!(
                        "the moment `{}` does not say which body it acts on",
                        m.name.text
                    ),
                )
                .help("add `on: B`"),
            );
            None
        }
    };
    // `Some(None)`: a reaction was given but failed (reported).
    let reaction = o
        .get(MomentKey::Reaction)
        .map(|x| r.body(&x.value, "`reaction`"));
    let vector = load_vector(
        r,
        m.name.span,
        &m.name.text,
        "moment",
        o.get(MomentKey::Vector).map(|x| &x.value),
        o.get(MomentKey::About).map(|x| &x.value),
        o.get(MomentKey::Magnitude).map(|x| &x.value),
        "about",
    );
    if let (Some(b), Some(v), Some(reaction)) =
        (body, vector, reaction.map_or(Some(None), |x| x.map(Some)))
        && let Err(e) = r.sys.add_moment(&m.name.text, b, reaction, v)
    {
        r.error(m.name.span, e.to_string());
    }
}

/// `vector: v` or `along/about: d, magnitude: s`.
#[allow(clippy::too_many_arguments)]
fn load_vector(
    r: &mut Resolver<'_>,
    span: crate::diag::Span,
    name: &str,
    what: &str,
    vector: Option<&ast::Expr>,
    direction: Option<&ast::Expr>,
    magnitude: Option<&ast::Expr>,
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
fn coefficients(v: &crate::mech::Vector) -> Vec<crate::expr::ExprId> {
    v.terms().iter().map(|&(_, c)| c).collect()
}
