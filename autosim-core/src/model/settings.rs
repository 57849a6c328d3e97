//! The model's `settings` and the scene's options over them: the float
//! type, the small-term threshold, which outputs are generated and whether
//! the linearization is; and the
//! check that every name a scene gives exists in the model.

use super::scope::Resolver;
use super::{FloatType, Formulation, ResolvedModel, Scene};
use crate::diag::{Diagnostic, did_you_mean};
use crate::syntax::ast::{self, Item, SettingKey};

/// Applies the settings, then the scene's overrides; returns the outputs
/// to generate (`None`: all).
pub(super) fn apply_settings(
    r: &mut Resolver<'_>,
    out: &mut ResolvedModel,
    model: &ast::Model,
    scene: &Scene,
) -> Option<Vec<ast::Name>> {
    let mut output_filter: Option<Vec<ast::Name>> = None;
    for item in &model.items {
        let Item::Settings(s) = item else { continue };
        for opt in &s.options.entries {
            match opt.key {
                SettingKey::Threshold => threshold(r, &opt.value),
                SettingKey::Outputs => {
                    let mut names = Vec::new();
                    for it in super::body_options::items(&opt.value) {
                        match it {
                            ast::Expr::Name(n) => names.push(n.clone()),
                            other => r.error(other.span(), "`outputs` takes output names"),
                        }
                    }
                    output_filter = Some(names);
                }
                SettingKey::Linearize => match &opt.value {
                    ast::Expr::Name(n) if n.text == "true" => out.linearize = true,
                    ast::Expr::Name(n) if n.text == "false" => out.linearize = false,
                    other => r.push(
                        Diagnostic::error(other.span(), "`linearize` is `true` or `false`").help(
                            "`linearize: true` generates `linearize`, the model's A, B, C, D",
                        ),
                    ),
                },
                SettingKey::Formulation => {
                    let written = match &opt.value {
                        ast::Expr::Name(n) => n.text.as_str(),
                        _ => "",
                    };
                    match Formulation::named(written) {
                        Some(f) => out.formulation = f,
                        None => r.push(
                            Diagnostic::error(
                                opt.value.span(),
                                "`formulation` is `auto`, `mass_matrix` or `recursive`",
                            )
                            .help(Formulation::help_for(written)),
                        ),
                    }
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
    // The scene overrides the model's settings.
    if let Some(f) = scene.float {
        out.float = f;
    }
    if let Some(k) = scene.threshold {
        r.sys.set_threshold(k);
    }
    if let Some(l) = scene.linearize {
        out.linearize = l;
    }
    if let Some(f) = scene.formulation {
        out.formulation = f;
    }
    scene.outputs.clone().or(output_filter)
}

/// The formulation a setting names.
fn threshold(r: &mut Resolver<'_>, value: &ast::Expr) {
    let Some(k) = r.integer(value, "the threshold") else {
        return;
    };
    match i16::try_from(k)
        .ok()
        .filter(|k| crate::limits::THRESHOLDS.contains(k))
    {
        Some(k) => r.sys.set_threshold(k),
        None => r.error(value.span(), "the threshold must be between 1 and 20"),
    }
}

/// Every `small`/`lock` name of the scene matched a body or coordinate,
/// and every output asked for exists.
pub(super) fn check_scene_names(
    r: &mut Resolver<'_>,
    model: &ast::Model,
    scene: &Scene,
    outputs: Option<&[ast::Name]>,
) {
    for n in scene.small.iter().chain(&scene.lock) {
        if !r.scene_matched.contains(&n.text) {
            let mut d = Diagnostic::error(
                n.span,
                format!(
                    "`{}` is neither a body nor a coordinate of this model",
                    n.text
                ),
            );
            if let Some(s) = did_you_mean(&n.text, r.known_names().iter().map(String::as_str)) {
                d = d.help(format!("did you mean `{s}`?"));
            }
            r.push(d);
        }
    }
    let declared: Vec<&str> = model
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Output(o) => Some(o.name.text.as_str()),
            _ => None,
        })
        .collect();
    for n in outputs.unwrap_or_default() {
        if !declared.contains(&n.text.as_str()) {
            let mut d = Diagnostic::error(
                n.span,
                format!("`{}` is not an output of this model", n.text),
            );
            if let Some(s) = did_you_mean(&n.text, declared.iter().copied()) {
                d = d.help(format!("did you mean `{s}`?"));
            }
            r.push(d);
        }
    }
}
