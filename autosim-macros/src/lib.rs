//! The `model!` procedural macro of autosim: a thin shell around
//! `autosim-core` (tokens or a `.sim` file in, the generated module out,
//! errors with spans).

use autosim_core::diag::{Diagnostics, SourceFile, Span};
use autosim_core::emit::{EmitOptions, model_tokens, snake_case};
use autosim_core::model::{FloatType, Scene};
use autosim_core::pipeline::{compile_source_scene, compile_tokens};
use autosim_core::syntax::ast;
use proc_macro2::{TokenStream, TokenTree};
use quote::{format_ident, quote, quote_spanned};
use std::path::PathBuf;
use syn::parse::Parse;

/// Compiles a model into a Rust module.
///
/// Inline: `autosim::model! { model Pendulum; ... }`. From a file relative to
/// the crate root: `autosim::model!(file = "models/pendulum.sim");` (the crate
/// is rebuilt when the file changes), optionally with scene options that
/// tailor the model to one use: `name = RigidBoom`, `float = f32`,
/// `threshold = 3`, `outputs = [roll, yaw]`, `small = [B, q9]`,
/// `lock = [q9, q10]` (bodies or coordinates). Either way the macro expands to
/// `pub mod <model_name_in_snake_case> { ... }` holding the model type, its
/// `Parameters`, `Inputs` and (if it calls user code) `Externs` trait.
#[proc_macro]
pub fn model(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    expand(input.into()).into()
}

fn expand(input: TokenStream) -> TokenStream {
    match file_argument(&input) {
        Some(Ok((path, span, scene))) => expand_file(&path, span, &scene),
        Some(Err(e)) => e.to_compile_error(),
        None => {
            let name = model_name(&input);
            match compile_tokens(input) {
                Ok(c) => model_tokens(&c.program, &EmitOptions::default()),
                Err(d) => errors(&d, name),
            }
        }
    }
}

/// `file = "path"` and scene options → the path, its span, the scene.
fn file_argument(input: &TokenStream) -> Option<syn::Result<(String, proc_macro2::Span, Scene)>> {
    let tokens: Vec<TokenTree> = input.clone().into_iter().collect();
    match tokens.as_slice() {
        [TokenTree::Ident(i), TokenTree::Punct(p), ..] if i == "file" && p.as_char() == '=' => {
            Some(syn::parse::Parser::parse2(file_args, input.clone()))
        }
        _ => None,
    }
}

fn file_args(input: syn::parse::ParseStream) -> syn::Result<(String, proc_macro2::Span, Scene)> {
    let _: syn::Ident = input.parse()?;
    let _: syn::Token![=] = input.parse()?;
    let lit: syn::LitStr = input.parse().map_err(|e| {
        syn::Error::new(
            e.span(),
            "expected `file = \"path/to/model.sim\"` (a path relative to the crate root)",
        )
    })?;
    let mut scene = Scene::default();
    while !input.is_empty() {
        let _: syn::Token![,] = input.parse()?;
        if input.is_empty() {
            break;
        }
        let key: syn::Ident = input.parse()?;
        let _: syn::Token![=] = input.parse()?;
        let name = |i: &syn::Ident| ast::Name {
            text: i.to_string(),
            span: Span::from_token(i.span()),
        };
        let list = |input: syn::parse::ParseStream| -> syn::Result<Vec<ast::Name>> {
            let content;
            syn::bracketed!(content in input);
            let items = content.parse_terminated(syn::Ident::parse, syn::Token![,])?;
            Ok(items.iter().map(name).collect())
        };
        match key.to_string().as_str() {
            "name" => scene.name = Some(name(&input.parse()?)),
            "float" => {
                let f: syn::Ident = input.parse()?;
                scene.float = Some(match f.to_string().as_str() {
                    "f64" => FloatType::F64,
                    "f32" => FloatType::F32,
                    _ => {
                        return Err(syn::Error::new(
                            f.span(),
                            "the float type is `f64` or `f32`",
                        ));
                    }
                });
            }
            "threshold" => {
                let k: syn::LitInt = input.parse()?;
                let v: i16 = k.base10_parse()?;
                if !(1..=20).contains(&v) {
                    return Err(syn::Error::new(
                        k.span(),
                        "the threshold must be between 1 and 20",
                    ));
                }
                scene.threshold = Some(v);
            }
            "outputs" => scene.outputs = Some(list(input)?),
            "small" => scene.small = list(input)?,
            "lock" => scene.lock = list(input)?,
            other => {
                return Err(syn::Error::new(
                    key.span(),
                    format!(
                        "unknown model option `{other}`: the options are `name`, `float`, `threshold`, `outputs`, `small` and `lock`"
                    ),
                ));
            }
        }
    }
    Ok((lit.value(), lit.span(), scene))
}

fn expand_file(path: &str, span: proc_macro2::Span, scene: &Scene) -> TokenStream {
    let root = std::env::var("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_default();
    let full = root.join(path);
    let file = match SourceFile::read(&full, path, Span::from_token(span)) {
        Ok(f) => f,
        Err(d) => return errors(&d, None),
    };
    let full_str = full.to_string_lossy().to_string();
    let track = quote_spanned!(span=> const _: &str = include_str!(#full_str););
    match compile_source_scene(&file, scene) {
        Ok(c) => {
            let module = model_tokens(&c.program, &EmitOptions::default());
            quote!(#module #track)
        }
        Err(d) => {
            // One error per diagnostic, each showing `path:line:col` and
            // the excerpt, at the span of the path literal.
            let errors = d.to_syn_error_in(&file, span).map(|e| e.to_compile_error());
            let placeholder = placeholder(model_name_in_text(&file.text));
            quote!(#errors #placeholder #track)
        }
    }
}

fn errors(d: &Diagnostics, name: Option<String>) -> TokenStream {
    let mut out = match d.to_syn_error() {
        Some(e) => e.to_compile_error(),
        None => syn::Error::new(proc_macro2::Span::call_site(), "invalid model").to_compile_error(),
    };
    out.extend(placeholder(name));
    out
}

/// A module with the model's type names, so one mistake does not bury the
/// user in follow-on errors about missing items.
fn placeholder(name: Option<String>) -> TokenStream {
    let Some(name) = name else {
        return TokenStream::new();
    };
    // As the generated code names it: a keyword (`model Mod;`) gets a `_`.
    let mut module = snake_case(&name);
    if syn::parse_str::<syn::Ident>(&module).is_err() {
        module.push('_');
    }
    let module = format_ident!("{}", module);
    let ty = format_ident!("{}", name);
    // A model named like one of the other items (an error the resolver
    // reports) must not make them clash.
    let parameters = (name != "Parameters").then(|| {
        quote! {
            /// Placeholder: the model has errors.
            #[derive(Default)]
            pub struct Parameters;
        }
    });
    let inputs = (name != "Inputs").then(|| {
        quote! {
            /// Placeholder: the model has errors.
            #[derive(Default)]
            pub struct Inputs;
        }
    });
    let externs = (name != "Externs").then(|| {
        quote! {
            /// Placeholder: the model has errors.
            pub trait Externs {}
        }
    });
    quote! {
        #[allow(dead_code, non_snake_case)]
        pub mod #module {
            /// Placeholder: the model has errors.
            pub struct #ty<E = ()>(pub E);
            #parameters
            #inputs
            #externs
        }
    }
}

/// The name after `model` in tokens, if it can be found.
fn model_name(input: &TokenStream) -> Option<String> {
    let mut it = input.clone().into_iter();
    while let Some(t) = it.next() {
        if let TokenTree::Ident(i) = &t
            && i == "model"
            && let Some(TokenTree::Ident(n)) = it.next()
        {
            return Some(n.to_string());
        }
    }
    None
}

fn model_name_in_text(text: &str) -> Option<String> {
    let mut words = text.split(|c: char| !(c.is_alphanumeric() || c == '_'));
    while let Some(w) = words.next() {
        if w == "model" {
            let next = words.find(|w| !w.is_empty())?;
            if next.chars().next()?.is_alphabetic() {
                return Some(next.to_string());
            }
            return None;
        }
    }
    None
}
