//! The `model!` procedural macro of autosim: a thin shell around
//! `autosim-core` (tokens or a `.sim` file in, the generated module out,
//! errors with spans).

use autosim_core::diag::{Diagnostics, SourceFile, Span};
use autosim_core::emit::{EmitOptions, model_tokens, snake_case};
use autosim_core::pipeline::{compile_source, compile_tokens};
use proc_macro2::{TokenStream, TokenTree};
use quote::{format_ident, quote, quote_spanned};
use std::path::PathBuf;

/// Compiles a model into a Rust module.
///
/// Inline: `autosim::model! { model Pendulum; ... }`. From a file relative to
/// the crate root: `autosim::model!(file = "models/pendulum.sim");` (the crate
/// is rebuilt when the file changes). Either way the macro expands to
/// `pub mod <model_name_in_snake_case> { ... }` holding the model type, its
/// `Parameters`, `Inputs` and (if it calls user code) `Externs` trait.
#[proc_macro]
pub fn model(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    expand(input.into()).into()
}

fn expand(input: TokenStream) -> TokenStream {
    match file_argument(&input) {
        Some(Ok((path, span))) => expand_file(&path, span),
        Some(Err(e)) => e.to_compile_error(),
        None => {
            let name = model_name(&input);
            match compile_tokens(input) {
                Ok(c) => model_tokens(&c, &EmitOptions::default()),
                Err(d) => errors(&d, name),
            }
        }
    }
}

/// `file = "path"` → the path literal and its span.
fn file_argument(input: &TokenStream) -> Option<syn::Result<(String, proc_macro2::Span)>> {
    let tokens: Vec<TokenTree> = input.clone().into_iter().collect();
    match tokens.as_slice() {
        [TokenTree::Ident(i), TokenTree::Punct(p), rest @ ..]
            if i == "file" && p.as_char() == '=' =>
        {
            let lit: syn::Result<syn::LitStr> = syn::parse2(rest.iter().cloned().collect());
            Some(lit.map(|l| (l.value(), l.span())).map_err(|e| {
                syn::Error::new(
                    e.span(),
                    "expected `file = \"path/to/model.sim\"` (a path relative to the crate root)",
                )
            }))
        }
        _ => None,
    }
}

fn expand_file(path: &str, span: proc_macro2::Span) -> TokenStream {
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
    match compile_source(&file) {
        Ok(c) => {
            let module = model_tokens(&c, &EmitOptions::default());
            quote!(#module #track)
        }
        Err(d) => {
            let text = d.render(&file);
            let name = model_name_in_text(&file.text);
            let placeholder = placeholder(name);
            quote_spanned!(span=> ::core::compile_error!(#text);)
                .into_iter()
                .chain(placeholder)
                .chain(track)
                .collect()
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
    let module = format_ident!("{}", snake_case(&name));
    let ty = format_ident!("{}", name);
    quote! {
        #[allow(dead_code, non_snake_case)]
        pub mod #module {
            /// Placeholder: the model has errors.
            pub struct #ty<E = ()>(pub E);
            /// Placeholder: the model has errors.
            #[derive(Default)]
            pub struct Parameters;
            /// Placeholder: the model has errors.
            #[derive(Default)]
            pub struct Inputs;
            /// Placeholder: the model has errors.
            pub trait Externs {}
        }
    }
}

/// The name after `model` in tokens, if it can be found.
fn model_name(input: &TokenStream) -> Option<String> {
    let mut it = input.clone().into_iter();
    while let Some(t) = it.next() {
        if let TokenTree::Ident(i) = &t
            && i == "model"
                && let Some(TokenTree::Ident(n)) = it.next() {
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
