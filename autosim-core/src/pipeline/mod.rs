//! The whole compiler in one place: text or tokens in, the resolved model,
//! its equations of motion and its scheduled program out.

use crate::diag::{Diagnostic, Diagnostics, SourceFile};
use crate::mech::{Equations, ItemRef};
use crate::model::{FloatType, ResolvedModel, Scene, resolve_scene};
use crate::opt::{Program, build};
use crate::syntax::{self, ast};

mod input;

pub use input::opt_input;

/// A compiled model.
#[derive(Clone, Debug)]
pub struct Compiled {
    /// The resolved model (system, docs, float type).
    pub model: ResolvedModel,
    /// Kane's equations.
    pub equations: Equations,
    /// The scheduled program.
    pub program: Program,
}

/// Resolves, derives and schedules a parsed model.
pub fn compile(model: &ast::Model) -> Result<Compiled, Diagnostics> {
    compile_scene(model, &Scene::default())
}

/// Like [`compile`], with the options of a use site.
pub fn compile_scene(model: &ast::Model, scene: &Scene) -> Result<Compiled, Diagnostics> {
    let mut resolved = resolve_scene(model, scene)?;
    let at = |r: &ResolvedModel, item, message: String, help: Option<&str>| {
        let d = Diagnostic::error(r.spans.item(&r.system, item), message);
        Diagnostics::from(match help {
            Some(h) => d.help(h),
            None => d,
        })
    };
    let equations = match resolved.system.equations() {
        Ok(e) => e,
        Err(e) => return Err(at(&resolved, e.item, e.to_string(), e.error.help())),
    };
    if equations.constraints.is_empty() && equations.prescribed.is_empty() {
        check_mass_matrix(&resolved, &equations)?;
    }
    let program = match build(opt_input(&resolved, &equations)) {
        Ok(p) => p,
        Err(e) => return Err(at(&resolved, e.item(), e.to_string(), e.help())),
    };
    check_literals(&resolved, &program)?;
    Ok(Compiled {
        model: resolved,
        equations,
        program,
    })
}

/// A mass matrix with a zero on its diagonal is singular whatever the
/// state: nothing resists one speed's acceleration. Known at compile time,
/// so reported here (other singularities are reported at run time by the
/// generated solve, naming the speed). Only for trees: with constraints a
/// massless body's speed may be dependent, or inertia may reach it through
/// the constraints.
fn check_mass_matrix(resolved: &ResolvedModel, equations: &Equations) -> Result<(), Diagnostics> {
    let sys = &resolved.system;
    let mut diags = Diagnostics::new();
    for (k, c) in sys.coordinates().iter().enumerate() {
        if !sys.arena.is_zero(equations.mass_matrix[k][k]) {
            continue;
        }
        let body = &sys.body(c.body).name;
        let span = resolved.spans.item(sys, ItemRef::Body(c.body));
        let speed = &sys.arena.symbol(c.u).name;
        diags.push(
            Diagnostic::error(
                span,
                format!(
                    "the mass matrix is singular: nothing resists the acceleration of `{speed}` (a degree of freedom of body `{body}`)"
                ),
            )
            .help(format!(
                "give `{body}` (or a body it carries) mass or inertia that moves with `{speed}`, or lock the coordinate with `lock: [...]`"
            )),
        );
    }
    diags.finish(())
}

/// A constant the equations produced (`1e200 * 1e200` from two terms, or
/// beyond `f32`'s range in an `f32` model) that is not finite in the
/// model's float type. The resolver reports those the model writes; this
/// catches the rest, so no generated literal is ever infinite or NaN.
fn check_literals(resolved: &ResolvedModel, program: &Program) -> Result<(), Diagnostics> {
    let fits = |x: f64| match resolved.float {
        FloatType::F64 => x.is_finite(),
        FloatType::F32 => (x as f32).is_finite(),
    };
    let Some(bad) = program.ir.literals().find(|&x| !fits(x)) else {
        return Ok(());
    };
    let float = match resolved.float {
        FloatType::F64 => "f64",
        FloatType::F32 => "f32",
    };
    Err(Diagnostics::from(
        Diagnostic::error(
            resolved.spans.item(&resolved.system, ItemRef::Model),
            format!("the equations of motion hold a constant, {bad:e}, that is not finite in `{float}`"),
        )
        .help("rescale the model's constants (other units) so their products stay in range, or compute in `f64`"),
    ))
}

/// Compiles a model file's text.
pub fn compile_source(file: &SourceFile) -> Result<Compiled, Diagnostics> {
    compile(&syntax::parse_source(file)?)
}

/// Compiles a model file's text with the options of a use site.
pub fn compile_source_scene(file: &SourceFile, scene: &Scene) -> Result<Compiled, Diagnostics> {
    compile_scene(&syntax::parse_source(file)?, scene)
}

/// Compiles a model written as Rust tokens.
pub fn compile_tokens(tokens: proc_macro2::TokenStream) -> Result<Compiled, Diagnostics> {
    compile(&syntax::parse_tokens(tokens)?)
}
