//! The model's `settings` and the scene's options over them, both read by
//! one set of checks (one wording for each mistake): the float type, the
//! small-term threshold, which outputs are generated, whether the
//! linearization is and how the accelerations are solved; the scene's own
//! name, `small` and `lock`; and the check that every name a scene gives
//! exists in the model.

use super::scope::Resolver;
use super::{FloatType, Formulation, ResolvedModel, Scene};
use crate::diag::{Diagnostic, Diagnostics, Span, did_you_mean};
use crate::syntax::ast::{self, Expr, Item, Opt, SceneKey, SettingKey};

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
            let value = &opt.value;
            let applied = match opt.key {
                SettingKey::Threshold => threshold(value).map(|k| r.sys.set_threshold(k)),
                SettingKey::Outputs => outputs(value).map(|n| output_filter = Some(n)),
                SettingKey::Linearize => linearize(value).map(|l| out.linearize = l),
                SettingKey::Lanes => lanes(value).map(|l| out.lanes = l),
                SettingKey::Formulation => formulation(value).map(|f| out.formulation = f),
                SettingKey::Float => float_type(value).map(|f| out.float = f),
            };
            if let Err(d) = applied {
                r.push(*d);
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
    if let Some(l) = scene.lanes {
        out.lanes = l;
    }
    if let Some(f) = scene.formulation {
        out.formulation = f;
    }
    scene.outputs.clone().or(output_filter)
}

impl Scene {
    /// The scene the macro's options give (`autosim::model!(file = "...",
    /// key = value, ...)`), checked as the model's `settings` are: every
    /// mistake at once.
    pub fn from_options(options: &[Opt<SceneKey>]) -> Result<Scene, Diagnostics> {
        let mut scene = Scene::default();
        let mut diagnostics = Diagnostics::new();
        for opt in options {
            let value = &opt.value;
            let applied = match opt.key {
                SceneKey::Name => name(value).map(|n| scene.name = Some(n)),
                SceneKey::Float => float_type(value).map(|f| scene.float = Some(f)),
                SceneKey::Threshold => threshold(value).map(|k| scene.threshold = Some(k)),
                SceneKey::Outputs => outputs(value).map(|n| scene.outputs = Some(n)),
                SceneKey::Small => body_names(value, "small").map(|n| scene.small = n),
                SceneKey::Lock => body_names(value, "lock").map(|n| scene.lock = n),
                SceneKey::Linearize => linearize(value).map(|l| scene.linearize = Some(l)),
                SceneKey::Lanes => lanes(value).map(|l| scene.lanes = Some(l)),
                SceneKey::Formulation => formulation(value).map(|f| scene.formulation = Some(f)),
            };
            if let Err(d) = applied {
                diagnostics.push(*d);
            }
        }
        diagnostics.finish(scene)
    }
}

/// The value of an option, or the one diagnostic of its mistake.
type Checked<T> = Result<T, Box<Diagnostic>>;

/// The diagnostic of a mistaken value.
fn mistake(span: Span, message: impl Into<String>) -> Box<Diagnostic> {
    Box::new(Diagnostic::error(span, message))
}

/// `float`: `f64` or `f32`.
fn float_type(value: &Expr) -> Checked<FloatType> {
    match value {
        Expr::Name(n) if n.text == "f64" => Ok(FloatType::F64),
        Expr::Name(n) if n.text == "f32" => Ok(FloatType::F32),
        other => Err(mistake(other.span(), "the float type is `f64` or `f32`")),
    }
}

/// `threshold`: an integer from 1 to 20.
fn threshold(value: &Expr) -> Checked<i16> {
    super::typed::integer_literal(value)
        .and_then(Result::ok)
        .and_then(|k| i16::try_from(k).ok())
        .filter(|k| crate::limits::THRESHOLDS.contains(k))
        .ok_or_else(|| mistake(value.span(), "the threshold is an integer from 1 to 20"))
}

/// `linearize`: `true` or `false`.
fn linearize(value: &Expr) -> Checked<bool> {
    boolean(
        value,
        "linearize",
        "`true` also generates `linearize`, the model's A, B, C, D",
    )
}

/// `lanes`: `true` or `false`.
fn lanes(value: &Expr) -> Checked<bool> {
    boolean(
        value,
        "lanes",
        "`true` also generates `derivatives_lanes`, the derivatives at several states per call",
    )
}

/// The option `key`: `true` or `false` (`help` says what `true` does).
fn boolean(value: &Expr, key: &str, help: &str) -> Checked<bool> {
    match value {
        Expr::Name(n) if n.text == "true" => Ok(true),
        Expr::Name(n) if n.text == "false" => Ok(false),
        other => Err(Box::new(
            Diagnostic::error(other.span(), format!("`{key}` is `true` or `false`"))
                .help(help.to_string()),
        )),
    }
}

/// `formulation`: `auto`, `mass_matrix` or `recursive`.
fn formulation(value: &Expr) -> Checked<Formulation> {
    let written = match value {
        Expr::Name(n) => n.text.as_str(),
        _ => "",
    };
    Formulation::named(written).ok_or_else(|| {
        Box::new(
            Diagnostic::error(
                value.span(),
                "`formulation` is `auto`, `mass_matrix` or `recursive`",
            )
            .help(Formulation::help_for(written)),
        )
    })
}

/// `name`: the model's new name.
fn name(value: &Expr) -> Checked<ast::Name> {
    match value {
        Expr::Name(n) => Ok(n.clone()),
        other => Err(mistake(
            other.span(),
            "`name` is the model's new name, such as `RigidBoom`",
        )),
    }
}

/// `outputs`: output names.
fn outputs(value: &Expr) -> Checked<Vec<ast::Name>> {
    names(value).map_err(|span| mistake(span, "`outputs` takes output names"))
}

/// `small` or `lock` (named `key`): names of bodies or coordinates.
fn body_names(value: &Expr, key: &str) -> Checked<Vec<ast::Name>> {
    names(value).map_err(|span| {
        mistake(
            span,
            format!("`{key}` takes names of bodies or coordinates"),
        )
    })
}

/// The names of a list (or one name); the span of the first item that is
/// no name.
fn names(value: &Expr) -> Result<Vec<ast::Name>, Span> {
    super::body_options::items(value)
        .into_iter()
        .map(|item| match item {
            Expr::Name(n) => Ok(n.clone()),
            other => Err(other.span()),
        })
        .collect()
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
