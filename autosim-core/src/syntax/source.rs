//! Model files: text to tokens with proc-macro2's fallback lexer, so spans
//! carry line and column, and readable messages for text that does not
//! even lex (unclosed delimiters, stray characters, unterminated strings).
//!
//! Inside a proc macro, `proc_macro2::fallback::force()` is global: every
//! token made while it is on is a fallback token, and mixing one into
//! compiler tokens panics. So [`parse`] keeps it on only for the lex and the
//! parse, turns every span into line/column before it ends, and returns
//! nothing that holds a fallback span.

use std::str::FromStr;

use proc_macro2::{TokenStream, TokenTree};

use super::Parsed;
use super::ast::Model;
use super::cx::{Cx, MAX_DEPTH};
use crate::diag::{Diagnostic, LineCol, SourceFile, Span};

/// Turns the fallback lexer on for its lifetime (off again on drop, even on
/// an early return).
struct Fallback;

impl Fallback {
    fn on() -> Fallback {
        proc_macro2::fallback::force();
        Fallback
    }
}

impl Drop for Fallback {
    fn drop(&mut self) {
        proc_macro2::fallback::unforce();
    }
}

/// Parses a model file (see [`super::parse_source_recovering`]).
pub(crate) fn parse(file: &SourceFile) -> Parsed {
    let text = file.text.strip_prefix('\u{feff}').unwrap_or(&file.text);
    let fallback = Fallback::on();
    let parsed = match TokenStream::from_str(text) {
        Ok(tokens) => super::parse_with(Cx::file(end_of(text)), tokens),
        Err(error) => Parsed {
            model: readable_prefix(&error, text),
            diagnostics: lex_error(&error, text).into(),
        },
    };
    drop(fallback);
    parsed
}

/// What the text before a lexing error holds (its `model` item names the
/// placeholder a macro emits on error), read without reporting.
fn readable_prefix(error: &proc_macro2::LexError, text: &str) -> Option<Model> {
    let offset = byte_offset(text, start_of(error.span()))?;
    let prefix = text.get(..offset)?;
    let tokens = TokenStream::from_str(prefix).ok()?;
    super::parse_with(Cx::file(end_of(prefix)), tokens).model
}

/// The position just after the last non-blank character.
fn end_of(text: &str) -> LineCol {
    let trimmed = text.trim_end();
    let line = 1 + trimmed.matches('\n').count();
    let last_line = trimmed.rsplit('\n').next().unwrap_or("");
    LineCol {
        line,
        col: last_line.chars().count() + 1,
    }
}

/// The byte offset of a (1-based) line and column.
fn byte_offset(text: &str, at: LineCol) -> Option<usize> {
    let mut offset = 0;
    for (index, line) in text.split('\n').enumerate() {
        if index + 1 == at.line {
            let within = line
                .char_indices()
                .nth(at.col - 1)
                .map_or(line.len(), |(i, _)| i);
            return Some(offset + within);
        }
        offset += line.len() + 1;
    }
    None
}

fn start_of(span: proc_macro2::Span) -> LineCol {
    let start = span.start();
    LineCol {
        line: start.line.max(1),
        col: start.column + 1,
    }
}

/// A diagnostic for text the lexer refused, from the character it stopped at.
fn lex_error(error: &proc_macro2::LexError, text: &str) -> Diagnostic {
    let at = start_of(error.span());
    let offset = byte_offset(text, at).unwrap_or(text.len());
    let rest = text.get(offset..).unwrap_or("");
    let width = rest.chars().next().map_or(0, |_| 1);
    let span = Span::from_file(
        at,
        LineCol {
            line: at.line,
            col: at.col + width,
        },
    );
    if let Some(d) = comment_in_unit(text, offset) {
        return d;
    }
    match rest.chars().next() {
        None => Diagnostic::error(span, "unexpected end of file"),
        Some(open @ ('(' | '[' | '{')) => {
            Diagnostic::error(span, format!("unclosed delimiter `{open}`"))
                .help(format!("add the matching `{}`", closing(open)))
        }
        Some(close @ (')' | ']' | '}')) => {
            let diagnostic =
                Diagnostic::error(span, format!("unexpected closing delimiter `{close}`"));
            match unclosed_before(text, offset) {
                Some((open, at)) => diagnostic
                    .note(format!(
                        "the innermost open delimiter is the `{open}` at {at}"
                    ))
                    .help(format!("close it with `{}` first", closing(open))),
                None => diagnostic.help("there is no open delimiter for it to close"),
            }
        }
        Some('"') => Diagnostic::error(span, "unterminated or invalid string literal"),
        Some('/') if rest.starts_with("/*") => {
            Diagnostic::error(span, "unterminated block comment")
        }
        Some('\'') => {
            Diagnostic::error(span, "unexpected `'`").help("strings are written in double quotes")
        }
        Some(c) if c.is_ascii_digit() => Diagnostic::error(span, "invalid number"),
        Some(c) => Diagnostic::error(span, format!("unexpected character `{}`", c.escape_debug()))
            .help("model files are made of Rust tokens: names, numbers, strings and punctuation"),
    }
}

/// `[N//m]`: `//` starts a comment, which hides the `]` of the unit. When
/// the delimiter left open where the lexer stopped (at `offset`) is a `[`
/// with `//` after it on its line, says so at the `//`.
fn comment_in_unit(text: &str, offset: usize) -> Option<Diagnostic> {
    let open_at = match text.get(offset..)?.chars().next() {
        Some('[') => offset,
        _ => {
            let (open, at) = unclosed_before(text, offset)?;
            if open != '[' {
                return None;
            }
            byte_offset(text, at)?
        }
    };
    let line = text.get(open_at..)?.lines().next()?;
    let slashes = open_at + line.find("//")?;
    let start = line_col(text, slashes);
    let end = LineCol {
        line: start.line,
        col: start.col + 2,
    };
    Some(
        Diagnostic::error(
            Span::from_file(start, end),
            "`//` starts a comment, which hides the rest of the line: the `[` before it is never closed",
        )
        .help("in a unit, write one `/` before the denominator: `[N/m]`, `[N/(m s)]`, `[m/s^2]`"),
    )
}

/// The line and column (1-based) of byte `offset` of `text`.
fn line_col(text: &str, offset: usize) -> LineCol {
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    LineCol { line, col }
}

fn closing(open: char) -> char {
    match open {
        '(' => ')',
        '[' => ']',
        _ => '}',
    }
}

/// The innermost delimiter still open at `offset`: lexing the text before
/// it fails at that delimiter.
fn unclosed_before(text: &str, offset: usize) -> Option<(char, LineCol)> {
    let prefix = text.get(..offset)?;
    let error = TokenStream::from_str(prefix).err()?;
    let at = start_of(error.span());
    let open = prefix.get(byte_offset(prefix, at)?..)?.chars().next()?;
    matches!(open, '(' | '[' | '{').then_some((open, at))
}

/// The opening span of the first group nested deeper than [`MAX_DEPTH`]
/// (syn's token buffer and our parser recurse on nesting).
pub(crate) fn too_deep(tokens: &TokenStream) -> Option<proc_macro2::Span> {
    let mut stack = vec![tokens.clone().into_iter()];
    while let Some(top) = stack.last_mut() {
        match top.next() {
            Some(TokenTree::Group(group)) => {
                if stack.len() >= MAX_DEPTH {
                    return Some(group.span_open());
                }
                stack.push(group.stream().into_iter());
            }
            Some(_) => {}
            None => {
                stack.pop();
            }
        }
    }
    None
}
