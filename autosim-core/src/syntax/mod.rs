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
mod parse_event;
mod parse_expr;
mod parse_items;
mod scene;
mod source;
#[cfg(test)]
mod tests;

use proc_macro2::TokenStream;
use syn::parse::{ParseStream, Parser};

pub use crate::diag::SourceFile;
use crate::diag::{Diagnostic, Diagnostics};
use cx::{Cx, Failed};
pub use scene::{FileArguments, file_arguments};

/// What a parse with recovery read: the model, if a `model` item was
/// found (possibly incomplete where there are errors), and every error.
#[derive(Debug)]
pub struct Parsed {
    /// The model as far as it could be read.
    pub model: Option<ast::Model>,
    /// Every syntax error.
    pub diagnostics: Diagnostics,
}

impl Parsed {
    /// The model, if it parsed without errors.
    pub fn into_result(self) -> Result<ast::Model, Diagnostics> {
        match self.model {
            Some(model) if self.diagnostics.is_empty() => Ok(model),
            _ => Err(self.diagnostics),
        }
    }

    /// The model's name, if the `model` item could be read.
    pub fn name(&self) -> Option<&ast::Name> {
        self.model.as_ref().map(|m| &m.name)
    }
}

/// Parses a model written as Rust tokens (the body of `autosim::model!`).
///
/// Spans in the AST and in the diagnostics are the tokens' own, so
/// [`Diagnostics::to_syn_error`] points the compiler at the user's text.
pub fn parse_tokens(tokens: TokenStream) -> Result<ast::Model, Diagnostics> {
    parse_tokens_recovering(tokens).into_result()
}

/// Like [`parse_tokens`], keeping what could be read despite errors.
pub fn parse_tokens_recovering(tokens: TokenStream) -> Parsed {
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
    parse_source_recovering(file).into_result()
}

/// Like [`parse_source`], keeping what could be read despite errors (for
/// text that does not lex, what the text before the error holds).
pub fn parse_source_recovering(file: &SourceFile) -> Parsed {
    source::parse(file)
}

fn parse_with(cx: Cx, tokens: TokenStream) -> Parsed {
    if let Some(span) = source::too_deep(&tokens) {
        cx.report(Diagnostic::error(
            cx.span(span),
            "delimiters are nested too deeply",
        ));
        return Parsed {
            model: None,
            diagnostics: cx.into_diagnostics(),
        };
    }
    let parsed = (|input: ParseStream| Ok(parse_items::model(input, &cx))).parse2(tokens);
    let model = parsed.unwrap_or_else(|error| {
        cx.record(Failed::Syn(error));
        None
    });
    Parsed {
        model,
        diagnostics: cx.into_diagnostics(),
    }
}
