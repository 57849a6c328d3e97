//! The arguments of `autosim::model!(file = "...", key = value, ...)`: the
//! path of a model file and the scene options of this use of it, read as
//! the same option list a `settings` block gives (keys: [`SceneKey`]),
//! every mistake reported at once. The resolver gives them their meaning
//! (`model/settings.rs`).

use super::ast::{Opt, SceneKey};
use super::cx::{Cx, PResult, expected, skip_all};
use super::parse_block::{Assign, entries};
use crate::diag::Diagnostics;
use proc_macro2::{TokenStream, TokenTree};
use syn::Token;
use syn::parse::{ParseStream, Parser};

/// A model file named by a macro, with the options of its use.
#[derive(Clone, Debug)]
pub struct FileArguments {
    /// The path as written (relative to the crate root).
    pub path: String,
    /// The span of the path literal.
    pub span: proc_macro2::Span,
    /// The scene options that could be read, in the order written.
    pub options: Vec<Opt<SceneKey>>,
    /// The mistakes of the option list (each bad entry is skipped).
    pub diagnostics: Diagnostics,
}

/// `Some` if the macro input starts with `file =`: the path and the
/// options with their mistakes, or the mistakes if the path cannot be read.
pub fn file_arguments(input: &TokenStream) -> Option<Result<FileArguments, Diagnostics>> {
    let mut tokens = input.clone().into_iter();
    match (tokens.next(), tokens.next()) {
        (Some(TokenTree::Ident(i)), Some(TokenTree::Punct(p)))
            if i == "file" && p.as_char() == '=' =>
        {
            let cx = Cx::tokens();
            let parsed = (|input: ParseStream| {
                let arguments = arguments(input, &cx);
                skip_all(input);
                Ok(arguments)
            })
            .parse2(input.clone());
            let arguments = match parsed {
                Ok(Ok(arguments)) => Some(arguments),
                Ok(Err(failed)) => {
                    cx.record(failed);
                    None
                }
                Err(error) => {
                    cx.record(error.into());
                    None
                }
            };
            let diagnostics = cx.into_diagnostics();
            Some(match arguments {
                Some(arguments) => Ok(FileArguments {
                    diagnostics,
                    ..arguments
                }),
                None => Err(diagnostics),
            })
        }
        _ => None,
    }
}

fn arguments(input: ParseStream, cx: &Cx) -> PResult<FileArguments> {
    let _: syn::Ident = input.parse()?;
    let _: Token![=] = input.parse()?;
    if !input.peek(syn::LitStr) {
        return cx.fail(expected(
            cx,
            input,
            "`file = \"path/to/model.sim\"` (a path relative to the crate root)",
        ));
    }
    let lit: syn::LitStr = input.parse()?;
    let mut options = Vec::new();
    if !input.is_empty() {
        if !input.peek(Token![,]) {
            return cx.fail(expected(cx, input, "`,` after the path"));
        }
        input.parse::<Token![,]>()?;
        options = entries::<SceneKey>(input, cx, Assign::Equals);
    }
    Ok(FileArguments {
        path: lit.value(),
        span: lit.span(),
        options,
        diagnostics: Diagnostics::new(),
    })
}
