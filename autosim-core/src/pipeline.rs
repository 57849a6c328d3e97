//! The whole compiler in one place: text or tokens in, the resolved model,
//! its equations of motion and its scheduled program out.

use crate::diag::{Diagnostic, Diagnostics, SourceFile};
use crate::mech::Equations;
use crate::model::{ResolvedModel, Scene, resolve_scene};
use crate::opt::{Program, build};
use crate::syntax::{self, ast};

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
    let equations = resolved
        .system
        .equations()
        .map_err(|e| Diagnostics::from(Diagnostic::error(model.name.span, e.to_string())))?;
    let program = build(&mut resolved, &equations)
        .map_err(|e| Diagnostics::from(Diagnostic::error(model.name.span, e.to_string())))?;
    Ok(Compiled {
        model: resolved,
        equations,
        program,
    })
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
