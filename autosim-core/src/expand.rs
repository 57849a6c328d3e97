//! The `model!` macro's expansion: everything but the `#[proc_macro]`
//! shell in `autosim-macros`. A model inline or in a file (with the scene
//! options of its use) in; the generated module out, or every diagnostic
//! with a placeholder module named from what could be parsed.

use crate::diag::{Diagnostics, SourceFile, Span};
use crate::emit::{EmitOptions, Outline, model_tokens, placeholder};
use crate::model::Scene;
use crate::pipeline::compile_scene;
use crate::syntax::{self, FileArguments, Parsed, file_arguments};
use proc_macro2::TokenStream;
use quote::{quote, quote_spanned};
use std::path::Path;

/// Expands `autosim::model!(input)`; file paths are relative to
/// `crate_root` (the using crate's `CARGO_MANIFEST_DIR`).
pub fn expand_model(input: TokenStream, crate_root: &Path) -> TokenStream {
    match file_arguments(&input) {
        Some(Ok(args)) => {
            let mut mistakes = args.diagnostics.clone();
            match Scene::from_options(&args.options) {
                Ok(scene) if mistakes.is_empty() => expand_file(&args, &scene, crate_root),
                Ok(_) => compile_errors(&mistakes),
                Err(d) => {
                    mistakes.append(d);
                    compile_errors(&mistakes)
                }
            }
        }
        Some(Err(d)) => compile_errors(&d),
        None => {
            let parsed = syntax::parse_tokens_recovering(input);
            let outline = outline(&parsed, &Scene::default());
            match compile(parsed, &Scene::default()) {
                Ok(module) => module,
                Err(d) => {
                    let errors = d.to_syn_error().unwrap_or_else(|| {
                        syn::Error::new(proc_macro2::Span::call_site(), "invalid model")
                    });
                    errors_and_placeholder(errors, outline)
                }
            }
        }
    }
}

/// The errors of the macro's own tokens.
fn compile_errors(d: &Diagnostics) -> TokenStream {
    d.to_syn_error()
        .map(|e| e.to_compile_error())
        .unwrap_or_default()
}

/// The name the generated module and type take, and the user code the
/// model declares, for a placeholder.
fn outline(parsed: &Parsed, scene: &Scene) -> Option<Outline> {
    let name = scene.name.as_ref().or(parsed.name());
    Outline::of(parsed, name.map(|n| n.text.as_str()))
}

/// Every error of a model, the first inside its placeholder module (where
/// it makes the module's items error types: see `emit::placeholder`).
fn errors_and_placeholder(errors: syn::Error, outline: Option<Outline>) -> TokenStream {
    let Some(outline) = outline else {
        return errors.to_compile_error();
    };
    let mut each = errors.into_iter().map(|e| e.to_compile_error());
    let first = each.next().unwrap_or_default();
    let module = placeholder(&outline, first);
    quote!(#module #(#each)*)
}

fn compile(parsed: Parsed, scene: &Scene) -> Result<TokenStream, Diagnostics> {
    let model = parsed.into_result()?;
    let compiled = compile_scene(&model, scene)?;
    Ok(model_tokens(&compiled.program, &EmitOptions::default()))
}

/// A model file: the module (or the errors, each showing `path:line:col`
/// and the excerpt, at the span of the path literal), and an
/// `include_str!` of the file so the crate is rebuilt when it changes.
fn expand_file(args: &FileArguments, scene: &Scene, crate_root: &Path) -> TokenStream {
    let full = crate_root.join(&args.path);
    let span = args.span;
    let file = match SourceFile::read(&full, &args.path, Span::from_token(span)) {
        Ok(f) => f,
        Err(d) => return compile_errors(&d),
    };
    let full_str = full.to_string_lossy().to_string();
    let track = quote_spanned!(span=> const _: &str = include_str!(#full_str););
    let parsed = syntax::parse_source_recovering(&file);
    let outline = outline(&parsed, scene);
    match compile(parsed, scene) {
        Ok(module) => quote!(#module #track),
        Err(d) => {
            let errors = d
                .to_syn_error_in(&file, span)
                .unwrap_or_else(|| syn::Error::new(span, "invalid model"));
            let errors = errors_and_placeholder(errors, outline);
            quote!(#errors #track)
        }
    }
}
