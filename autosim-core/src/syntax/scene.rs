//! The arguments of `autosim::model!(file = "...", ...)`: the path of a
//! model file and the scene options of this use of it (see
//! [`Scene`](crate::model::Scene)).

use crate::diag::Span;
use crate::model::{FloatType, Formulation, Scene};
use crate::syntax::ast;
use proc_macro2::{TokenStream, TokenTree};
use syn::parse::{Parse, ParseStream, Parser};

/// A model file named by a macro, with the options of its use.
#[derive(Clone, Debug)]
pub struct FileArguments {
    /// The path as written (relative to the crate root).
    pub path: String,
    /// The span of the path literal.
    pub span: proc_macro2::Span,
    /// The scene options.
    pub scene: Scene,
}

/// The options a use site may set, in the order the docs list them.
pub const SCENE_OPTIONS: &[&str] = &[
    "name",
    "float",
    "threshold",
    "outputs",
    "small",
    "lock",
    "linearize",
    "formulation",
];

/// `Some` if the macro input starts with `file =`: the path and options,
/// or the error of a malformed argument list.
pub fn file_arguments(input: &TokenStream) -> Option<syn::Result<FileArguments>> {
    let mut tokens = input.clone().into_iter();
    match (tokens.next(), tokens.next()) {
        (Some(TokenTree::Ident(i)), Some(TokenTree::Punct(p)))
            if i == "file" && p.as_char() == '=' =>
        {
            Some(Parser::parse2(arguments, input.clone()))
        }
        _ => None,
    }
}

fn arguments(input: ParseStream) -> syn::Result<FileArguments> {
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
        option(input, &key, &mut scene)?;
    }
    Ok(FileArguments {
        path: lit.value(),
        span: lit.span(),
        scene,
    })
}

fn name(i: &syn::Ident) -> ast::Name {
    ast::Name {
        text: i.to_string(),
        span: Span::from_token(i.span()),
    }
}

fn names(input: ParseStream) -> syn::Result<Vec<ast::Name>> {
    let content;
    syn::bracketed!(content in input);
    let items = content.parse_terminated(syn::Ident::parse, syn::Token![,])?;
    Ok(items.iter().map(name).collect())
}

/// One `key = value` option.
fn option(input: ParseStream, key: &syn::Ident, scene: &mut Scene) -> syn::Result<()> {
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
            if !crate::limits::THRESHOLDS.contains(&v) {
                return Err(syn::Error::new(
                    k.span(),
                    "the threshold must be between 1 and 20",
                ));
            }
            scene.threshold = Some(v);
        }
        "outputs" => scene.outputs = Some(names(input)?),
        "linearize" => {
            let b: syn::LitBool = input.parse()?;
            scene.linearize = Some(b.value);
        }
        "formulation" => {
            let f: syn::Ident = input.parse()?;
            let name = f.to_string();
            scene.formulation = Some(Formulation::named(&name).ok_or_else(|| {
                syn::Error::new(
                    f.span(),
                    format!(
                        "the formulation is `auto`, `mass_matrix` or `recursive`: {}",
                        Formulation::help_for(&name)
                    ),
                )
            })?);
        }
        "small" => scene.small = names(input)?,
        "lock" => scene.lock = names(input)?,
        other => {
            return Err(syn::Error::new(
                key.span(),
                format!(
                    "unknown model option `{other}`: the options are `name`, `float`, `threshold`, `outputs`, `small`, `lock`, `linearize` and `formulation`"
                ),
            ));
        }
    }
    Ok(())
}
