//! The model language's front end: Rust tokens in, [`ast::Model`] out.
//!
//! The same parser reads a model written inline (`autosim::model! { ... }`,
//! through [`parse_tokens`]) and a `.sim` file (through [`parse_source`]).
//! It knows the grammar only: which names are bodies and which functions
//! exist is decided later, by the resolver. Every syntax error is reported
//! (the parser recovers at the next entry of a block or the next item), each
//! with a span and, where there is one, the fix.
//!
//! ```text
//! /// The paper's spacecraft.
//! model Satellite;
//! parameters { KB = 2000 [N m/rad], L1 = 1.5 [m] }
//! body B "bus" { translate: [1, 2, 3], rotate: [1, 2, 3], small: all }
//! body F "boom" { parent: B, joint: [0, -L1, 0], rotate: 1 }
//! moment boom { on: F, reaction: B, about: f1, magnitude: -KB*q(F) }
//! output boom_angle [rad] = q(F);
//! ```

pub mod ast;
mod cx;
mod keys;
mod kw;
mod parse_block;
mod parse_expr;
mod parse_items;
mod source;
#[cfg(test)]
mod tests;

use proc_macro2::TokenStream;
use syn::parse::{ParseStream, Parser};

pub use crate::diag::SourceFile;
use crate::diag::{Diagnostic, Diagnostics};
use cx::{Cx, Failed};

/// Parses a model written as Rust tokens (the body of `autosim::model!`).
///
/// Spans in the AST and in the diagnostics are the tokens' own, so
/// [`Diagnostics::to_syn_error`] points the compiler at the user's text.
pub fn parse_tokens(tokens: TokenStream) -> Result<ast::Model, Diagnostics> {
    parse_with(Cx::tokens(), tokens)
}

/// Parses a model file.
///
/// Spans in the AST and in the diagnostics carry line and column in
/// `file` ([`Diagnostics::render`] prints them as `path:line:col`) and no
/// token span: used in generated code they become `Span::call_site()`.
/// Safe to call inside a proc macro: the fallback lexer is switched on only
/// for the duration of the call.
pub fn parse_source(file: &SourceFile) -> Result<ast::Model, Diagnostics> {
    source::parse(file)
}

fn parse_with(cx: Cx, tokens: TokenStream) -> Result<ast::Model, Diagnostics> {
    if let Some(span) = source::too_deep(&tokens) {
        cx.report(Diagnostic::error(
            cx.span(span),
            "delimiters are nested too deeply",
        ));
        return Err(cx.into_diagnostics());
    }
    let parsed = (|input: ParseStream| Ok(parse_items::model(input, &cx))).parse2(tokens);
    let model = parsed.unwrap_or_else(|error| {
        cx.record(Failed::Syn(error));
        None
    });
    let diagnostics = cx.into_diagnostics();
    match model {
        Some(model) if diagnostics.is_empty() => Ok(model),
        _ => Err(diagnostics),
    }
}
