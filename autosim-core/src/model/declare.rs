//! Declarations: the names that exist before any expression is evaluated
//! (parameters, inputs, discrete variables, user functions; then, after the bodies, `let`s and
//! points to evaluate on first use, added states and the outputs of user
//! subroutines), so any expression may use any of them.

use super::ResolvedModel;
use super::scope::{Lazy, Named, Resolver};
use crate::diag::Diagnostic;
use crate::expr::{Number, SymId};
use crate::mech::{ModelError, System};
use crate::syntax::ast::{self, Item};

/// Declares the parameters, inputs and user functions.
pub(super) fn declare_values(r: &mut Resolver<'_>, out: &mut ResolvedModel, model: &ast::Model) {
    for item in &model.items {
        match item {
            Item::Parameters(ps) => parameters(r, out, ps),
            Item::Inputs(is) => inputs(r, out, is),
            Item::Discrete(ds) => discrete(r, out, ds),
            Item::ExternFn(f) => extern_fn(r, out, f),
            _ => {}
        }
    }
}

/// Declares `let`s and points (evaluated on first use), added states and
/// subroutine outputs.
pub(super) fn declare_names<'a>(
    r: &mut Resolver<'a>,
    out: &mut ResolvedModel,
    model: &'a ast::Model,
) {
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
            Item::State(s) => state(r, s),
            Item::ExternSub(sub) => subroutine(r, out, sub),
            _ => {}
        }
    }
}

fn parameters(r: &mut Resolver<'_>, out: &mut ResolvedModel, ps: &ast::Parameters) {
    for p in &ps.params {
        let value = finite_value(r, &p.value);
        if !r.declare(&p.name, Named::Load) {
            continue;
        }
        let (value, unit, converted) = coherent_value(p, value);
        let added = r.sys.add_parameter(&p.name.text, value, unit.as_deref());
        bind_symbol(r, &p.name, added);
        let mut docs = if p.docs.is_empty() {
            ps.docs.clone()
        } else {
            p.docs.clone()
        };
        docs.extend(converted);
        out.item_docs.insert(p.name.text.clone(), docs);
    }
}

/// A parameter's value and unit in coherent SI units, the units generated
/// code computes in: `a = 30 [deg]` is 0.5235987755982988 rad, and its
/// documentation says what was written.
fn coherent_value(p: &ast::Parameter, value: f64) -> (f64, Option<String>, Option<String>) {
    let Some(unit) = &p.unit else {
        return (value, None, None);
    };
    match super::units::unit_meaning(&unit.text) {
        Some(u) if !u.is_coherent() => {
            let si = u.dim.to_string();
            let note = format!(
                "Written `{} [{}]`: {} {si} in the generated code.",
                p.value_text(),
                unit.text,
                value * u.factor
            );
            (value * u.factor, Some(si), Some(note))
        }
        _ => (value, Some(unit.text.clone()), None),
    }
}

fn inputs(r: &mut Resolver<'_>, out: &mut ResolvedModel, is: &ast::Inputs) {
    run_time_values(r, out, is, System::add_input);
}

/// `discrete mode [1] = 0, ...;`: symbols like inputs, set only by events.
fn discrete(r: &mut Resolver<'_>, out: &mut ResolvedModel, ds: &ast::Discretes) {
    run_time_values(r, out, ds, System::add_discrete);
}

/// The entries of an `input` or `discrete` item, each declared by `add`
/// with its value (0 when none is written) and unit.
fn run_time_values(
    r: &mut Resolver<'_>,
    out: &mut ResolvedModel,
    is: &ast::Inputs,
    add: fn(&mut System, &str, f64, Option<&str>) -> Result<SymId, ModelError>,
) {
    for i in &is.inputs {
        if !r.declare(&i.name, Named::Load) {
            continue;
        }
        let value = i.default.as_ref().map_or(0.0, |v| finite_value(r, v));
        let unit = i.unit.as_ref().map(|u| u.text.as_str());
        let added = add(&mut r.sys, &i.name.text, value, unit);
        bind_symbol(r, &i.name, added);
        out.item_docs.insert(i.name.text.clone(), is.docs.clone());
    }
}

fn extern_fn(r: &mut Resolver<'_>, out: &mut ResolvedModel, f: &ast::ExternFn) {
    if crate::expr::Func::builtin(&f.name.text).is_some()
        || super::operations::OPERATIONS
            .iter()
            .any(|(n, ..)| *n == f.name.text)
    {
        r.push(
            Diagnostic::error(
                f.name.span,
                format!("`{}` is a built-in function", f.name.text),
            )
            .help("give the user function another name"),
        );
        return;
    }
    if !r.declare(&f.name, Named::Load) {
        return;
    }
    match r.sys.add_user_function(&f.name.text, f.params.len()) {
        Ok(id) => {
            r.names
                .insert(f.name.text.clone(), (Named::Function(id), f.name.span));
        }
        Err(e) => r.error(f.name.span, e.to_string()),
    }
    out.item_docs.insert(f.name.text.clone(), f.docs.clone());
    let params = f.params.iter().map(|p| p.text.clone()).collect();
    out.formal_params.insert(f.name.text.clone(), params);
    let text = |u: &Option<ast::Unit>| u.as_ref().map(|u| u.text.clone()).unwrap_or_default();
    let args = f.param_units.iter().map(text).collect();
    out.user_code_units
        .insert(f.name.text.clone(), (args, vec![text(&f.result_unit)]));
}

fn state(r: &mut Resolver<'_>, s: &ast::State) {
    if !r.declare(&s.name, Named::Load) {
        return;
    }
    let zero = r.sys.arena.zero();
    let unit = s.unit.as_ref().map(|u| u.text.as_str());
    let added = r.sys.add_state(&s.name.text, unit, zero);
    bind_symbol(r, &s.name, added);
}

/// `name` names the symbol the system just added, or the error is
/// reported at it.
fn bind_symbol(r: &mut Resolver<'_>, name: &ast::Name, added: Result<SymId, ModelError>) {
    match added {
        Ok(s) => {
            r.names
                .insert(name.text.clone(), (Named::Symbol(s), name.span));
        }
        Err(e) => r.error(name.span, e.to_string()),
    }
}

fn subroutine(r: &mut Resolver<'_>, out: &mut ResolvedModel, sub: &ast::ExternSub) {
    let mut ok = r.declare(&sub.name, Named::Subroutine);
    for o in &sub.outputs {
        ok &= r.declare(&o.name, Named::Load);
    }
    if !ok {
        return;
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
    out.item_docs
        .insert(sub.name.text.clone(), sub.docs.clone());
    let params = sub
        .args
        .iter()
        .enumerate()
        .map(|(k, a)| match a {
            ast::Expr::Name(n) => n.text.clone(),
            _ => format!("arg{}", k + 1),
        })
        .collect();
    out.formal_params.insert(sub.name.text.clone(), params);
    let results = sub
        .outputs
        .iter()
        .map(|o| o.unit.as_ref().map(|u| u.text.clone()).unwrap_or_default())
        .collect();
    out.user_code_units
        .insert(sub.name.text.clone(), (Vec::new(), results));
}

/// The value of a parameter or input default, reported when it does not
/// fit the model's float (`1e999` would become infinity in generated code,
/// and `1e300` in an `f32` model).
pub(super) fn finite_value(r: &mut Resolver<'_>, v: &ast::Value) -> f64 {
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
    } else if r.float == super::FloatType::F32 && (x as f32).is_infinite() {
        r.push(
            Diagnostic::error(
                v.span,
                format!(
                    "`{}` is too large for `f32` (at most about 3.4e38)",
                    v.number.text
                ),
            )
            .note("the model computes in `f32` (`float: f32`), where it would be infinite")
            .help("rescale the quantity (other units), or compute in `f64`"),
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
