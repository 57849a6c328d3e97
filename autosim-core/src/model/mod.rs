//! The resolver: gives the AST its meaning by building the multibody
//! [`System`] through the `mech` API. Every mistake becomes a diagnostic
//! with the span of the offending text; all are reported together.
//!
//! Names may be used before they are declared: bodies are ordered by parent,
//! and `let`s and points are evaluated on first use.

mod bodies;
mod body_options;
mod constraint_check;
mod constraint_load;
mod declare;
mod events;
mod exprs;
mod finite;
mod items;
mod lazy;
mod loads;
mod operations;
mod quantities;
mod scene;
mod scope;
mod settings;
mod spans;
#[cfg(test)]
mod tests;
mod typed;
pub mod units;
mod value;

pub use scene::Scene;
pub use spans::ItemSpans;
pub use value::Value;

pub use crate::opt::{FloatType, Formulation};

use crate::diag::{Diagnostic, Diagnostics};
use crate::mech::System;
use crate::syntax::ast::{self, Item};
use rustc_hash::FxHashMap;
use scope::Resolver;

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
    /// Doc comments of the items the model declares (parameters, inputs,
    /// outputs, user code), by name; a parameter the compiler declared (a
    /// body's default mass) has none.
    pub item_docs: FxHashMap<String, Vec<String>>,
    /// Formal argument names of user functions and subroutines, by name (a
    /// subroutine argument written as a plain name gives its name, others
    /// are `arg1`, `arg2`, ...).
    pub formal_params: FxHashMap<String, Vec<String>>,
    /// Where each item is declared, for diagnostics of later phases.
    pub spans: ItemSpans,
    /// Generate the linearization (`settings { linearize: true }` or the
    /// scene's `linearize = true`).
    pub linearize: bool,
    /// Generate `derivatives_lanes` (`settings { lanes: true }` or the
    /// scene's `lanes = true`).
    pub lanes: bool,
    /// How the accelerations are solved (`settings { formulation: ... }`
    /// or the scene's `formulation = ...`).
    pub formulation: Formulation,
    /// The unit of each quantity declared without one that the unit check
    /// inferred from its uses, by name (`units::UnitReport::inferred`):
    /// shown in the documentation, not in the generated unit tables.
    pub inferred_units: FxHashMap<String, String>,
    /// The declared units of user code, by name (for the documentation):
    /// of each argument and each result (`""` where none is declared; a
    /// function's one result, a subroutine's outputs).
    pub user_code_units: FxHashMap<String, (Vec<String>, Vec<String>)>,
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
        item_docs: FxHashMap::default(),
        formal_params: FxHashMap::default(),
        spans: ItemSpans::new(model_name.span),
        linearize: false,
        lanes: false,
        formulation: Formulation::Auto,
        inferred_units: FxHashMap::default(),
        user_code_units: FxHashMap::default(),
    };
    check_model_name(&mut r, model_name);
    // Settings first: the threshold affects every expression built later.
    let outputs = settings::apply_settings(&mut r, &mut out, model, scene);
    r.float = out.float;
    declare::declare_values(&mut r, &mut out, model);
    let bodies: Vec<&ast::Body> = model
        .items
        .iter()
        .filter_map(|i| if let Item::Body(b) = i { Some(b) } else { None })
        .collect();
    r.add_bodies(&bodies);
    declare::declare_names(&mut r, &mut out, model);
    items::resolve_items(&mut r, &mut out, model, outputs.as_deref());
    settings::check_scene_names(&mut r, model, scene, outputs.as_deref());
    // One mistake, one message: a unit error at text that already has an
    // error (an acceleration in a load, a constant that is not) is left out.
    let units = units::check(&r, model);
    for d in units.diagnostics {
        if !r.diags.iter().any(|e| overlaps(e.span, d.span)) {
            r.push(d);
        }
    }
    out.inferred_units = units.inferred;
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

/// True when two spans of the model's text share a character (false when
/// either has no position).
fn overlaps(a: crate::diag::Span, b: crate::diag::Span) -> bool {
    match (a.start(), a.end(), b.start(), b.end()) {
        (Some(a0), Some(a1), Some(b0), Some(b1)) => {
            let key = |p: crate::diag::LineCol| (p.line, p.col);
            key(a0) < key(b1) && key(b0) < key(a1)
        }
        _ => false,
    }
}

/// Names the generated module defines beside the model type (see
/// `emit::model`), or uses unqualified.
/// (`Result` and `Option` and their variants: the generated code writes
/// them unqualified, as Rust's prelude names them.)
const TAKEN_TYPE_NAMES: &[&str] = &[
    "Parameters",
    "Inputs",
    "Externs",
    "Constants",
    "Discrete",
    "Default",
    "Result",
    "Option",
    "Some",
    "None",
    "Ok",
    "Err",
];

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
        let why = match TAKEN_TYPE_NAMES.iter().position(|n| *n == text) {
            Some(k) if k >= 6 => "the generated code uses Rust's prelude name unqualified",
            _ => "the generated module has an item of that name",
        };
        r.push(
            Diagnostic::error(
                name.span,
                format!("the model cannot be named `{text}`: {why}"),
            )
            .help(format!("choose another name, such as `{text}Model`")),
        );
    }
}
