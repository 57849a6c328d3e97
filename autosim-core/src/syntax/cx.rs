//! The parse context: where spans come from (tokens or a file), the
//! diagnostics collected so far, and the helpers every parser shares —
//! describing the next token, parsing inside a group without leaving tokens
//! behind, and skipping ahead after an error.

use std::cell::{Cell, RefCell};

use proc_macro2::{Delimiter, TokenTree};
use syn::buffer::Cursor;
use syn::parse::{ParseBuffer, ParseStream};

use super::kw::ITEM_STARTS;
use crate::diag::{Diagnostic, Diagnostics, LineCol, Span};

pub(crate) use crate::limits::{MAX_DEPTH, MAX_OPERATORS};

/// Why a parser stopped: a syn error not yet recorded, or a diagnostic
/// already pushed into the context.
pub(crate) enum Failed {
    /// An error from syn (expected token, ...), recorded by the caller.
    Syn(syn::Error),
    /// Already reported through [`Cx::report`].
    Reported,
}

impl From<syn::Error> for Failed {
    fn from(error: syn::Error) -> Failed {
        Failed::Syn(error)
    }
}

/// Result of a parser.
pub(crate) type PResult<T> = Result<T, Failed>;

/// Where the tokens come from.
enum Mode {
    /// Rust tokens (macro input): keep the token spans.
    Tokens,
    /// A file lexed by proc-macro2's fallback lexer: keep only line/column.
    File {
        /// Where to report "end of input".
        eof: LineCol,
    },
}

/// The parse context.
pub(crate) struct Cx {
    mode: Mode,
    diags: RefCell<Diagnostics>,
    depth: Cell<usize>,
    /// Binary operators in the current top-level expression.
    operators: Cell<usize>,
}

impl Cx {
    /// A context for Rust tokens.
    pub(crate) fn tokens() -> Cx {
        Cx {
            mode: Mode::Tokens,
            diags: RefCell::default(),
            depth: Cell::new(0),
            operators: Cell::new(0),
        }
    }

    /// A context for a file whose text ends at `eof`.
    pub(crate) fn file(eof: LineCol) -> Cx {
        Cx {
            mode: Mode::File { eof },
            diags: RefCell::default(),
            depth: Cell::new(0),
            operators: Cell::new(0),
        }
    }

    /// Our span for a token span. For a file, the line/column are computed
    /// now (while the fallback source map is valid) and the token span is
    /// dropped; a call-site span (syn's "end of input") becomes the file end.
    pub(crate) fn span(&self, span: proc_macro2::Span) -> Span {
        match self.mode {
            Mode::Tokens => Span::from_token(span),
            Mode::File { eof } => {
                if span.byte_range() == (0..0) {
                    return Span::from_file(eof, eof);
                }
                Span::from_file(line_col(span.start()), line_col(span.end()))
            }
        }
    }

    /// Our span from the start of `first` to the end of `last`.
    pub(crate) fn span_to(&self, first: proc_macro2::Span, last: proc_macro2::Span) -> Span {
        self.span(first).to(self.span(last))
    }

    /// Records a diagnostic.
    pub(crate) fn report(&self, diagnostic: Diagnostic) {
        self.diags.borrow_mut().push(diagnostic);
    }

    /// Records a diagnostic and fails.
    pub(crate) fn fail<T>(&self, diagnostic: Diagnostic) -> PResult<T> {
        self.report(diagnostic);
        Err(Failed::Reported)
    }

    /// Records the error of a failed parser (if it was not recorded yet).
    pub(crate) fn record(&self, failed: Failed) {
        if let Failed::Syn(error) = failed {
            for message in error {
                let span = self.span(message.span());
                self.report(Diagnostic::error(span, message.to_string()));
            }
        }
    }

    /// The diagnostics collected so far.
    pub(crate) fn into_diagnostics(self) -> Diagnostics {
        self.diags.into_inner()
    }

    /// Marks the start of an expression: one that is not nested in another
    /// starts a new count of operators.
    pub(crate) fn begin_expression(&self) {
        if self.depth.get() == 0 {
            self.operators.set(0);
        }
    }

    /// Counts a binary operator of the current expression, failing past
    /// [`MAX_OPERATORS`].
    pub(crate) fn operator(&self, input: ParseStream) -> PResult<()> {
        let count = self.operators.get() + 1;
        self.operators.set(count);
        if count > MAX_OPERATORS {
            return self.fail(
                Diagnostic::error(
                    self.span(input.span()),
                    format!("expression has more than {MAX_OPERATORS} operators"),
                )
                .help("split it into several `let`s"),
            );
        }
        Ok(())
    }

    /// Runs `f` one nesting level deeper, failing at [`MAX_DEPTH`].
    pub(crate) fn nested<T>(
        &self,
        input: ParseStream,
        f: impl FnOnce() -> PResult<T>,
    ) -> PResult<T> {
        let depth = self.depth.get();
        if depth >= MAX_DEPTH {
            return self.fail(Diagnostic::error(
                self.span(input.span()),
                "expression is nested too deeply",
            ));
        }
        self.depth.set(depth + 1);
        let result = f();
        self.depth.set(depth);
        result
    }
}

fn line_col(at: proc_macro2::LineColumn) -> LineCol {
    LineCol {
        line: at.line.max(1),
        col: at.column + 1,
    }
}

/// Describes the next token for "expected X, found Y" messages.
pub(crate) fn found(input: ParseStream) -> String {
    match input.cursor().token_tree() {
        None => "end of input".to_string(),
        Some((TokenTree::Group(group), _)) => match group.delimiter() {
            Delimiter::Parenthesis => "`(`".to_string(),
            Delimiter::Bracket => "`[`".to_string(),
            Delimiter::Brace => "`{`".to_string(),
            Delimiter::None => "an expression".to_string(),
        },
        Some((TokenTree::Literal(literal), _)) => {
            let text = literal.to_string();
            if text.chars().count() > 24 {
                format!("`{}...`", text.chars().take(20).collect::<String>())
            } else {
                format!("`{text}`")
            }
        }
        Some((token, _)) => format!("`{token}`"),
    }
}

/// An error at the next token: "expected {what}, found {next}".
pub(crate) fn expected(cx: &Cx, input: ParseStream, what: &str) -> Diagnostic {
    Diagnostic::error(
        cx.span(input.span()),
        format!("expected {what}, found {}", found(input)),
    )
}

/// Parses the contents of the next group (which the caller has checked is
/// there) with `f`, and makes sure nothing is left inside it: leftover tokens
/// are reported (if `f` succeeded) and skipped, so syn never sees an
/// unconsumed group. Returns the group's span too.
pub(crate) fn in_group<'a, T>(
    input: &ParseBuffer<'a>,
    cx: &Cx,
    delimiter: Delimiter,
    f: impl FnOnce(&ParseBuffer<'a>) -> PResult<T>,
) -> PResult<(T, proc_macro2::Span)> {
    let (content, span) = open(input, delimiter)?;
    let result = f(&content);
    if result.is_ok() && !content.is_empty() {
        let what = match delimiter {
            Delimiter::Parenthesis => "`)`",
            Delimiter::Bracket => "`]`",
            Delimiter::Brace => "`}`",
            Delimiter::None => "the end of the expression",
        };
        cx.report(expected(cx, &content, what));
        skip_all(&content);
        return Err(Failed::Reported);
    }
    skip_all(&content);
    result.map(|value| (value, span))
}

fn open<'a>(
    input: &ParseBuffer<'a>,
    delimiter: Delimiter,
) -> syn::Result<(ParseBuffer<'a>, proc_macro2::Span)> {
    let content;
    let span = match delimiter {
        Delimiter::Brace => syn::braced!(content in input).span.join(),
        Delimiter::Bracket => syn::bracketed!(content in input).span.join(),
        Delimiter::Parenthesis => syn::parenthesized!(content in input).span.join(),
        Delimiter::None => return Err(input.error("expected a delimited group")),
    };
    Ok((content, span))
}

/// True when the next token is a group with `delimiter`.
pub(crate) fn peek_group(input: ParseStream, delimiter: Delimiter) -> bool {
    input.cursor().group(delimiter).is_some()
}

/// Consumes everything left in `input`.
pub(crate) fn skip_all(input: ParseStream) {
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((_, next)) = rest.token_tree() {
            rest = next;
        }
        Ok(((), rest))
    });
}

/// Skips to just after the next `,` (or to the end) of a block's content:
/// recovery from a bad entry.
pub(crate) fn skip_past_comma(input: ParseStream) {
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((token, next)) = rest.token_tree() {
            rest = next;
            if matches!(&token, TokenTree::Punct(p) if p.as_char() == ',') {
                break;
            }
        }
        Ok(((), rest))
    });
}

/// True when `cursor` is at the start of an item (an item keyword, or `#`
/// of a doc comment).
pub(crate) fn at_item_start(cursor: Cursor) -> bool {
    if let Some((ident, _)) = cursor.ident() {
        return ITEM_STARTS.iter().any(|word| ident == word);
    }
    matches!(cursor.punct(), Some((p, _)) if p.as_char() == '#')
}

/// Top-level recovery after an item failed to parse: skips at least one
/// token if the item consumed nothing, then up to and including the next
/// `;` or `{...}` block, or up to the next item keyword.
pub(crate) fn recover(input: ParseStream, item_start: Cursor) {
    let mut must_skip = input.cursor() == item_start;
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((token, next)) = rest.token_tree() {
            if !must_skip && at_item_start(rest) {
                break;
            }
            must_skip = false;
            rest = next;
            match &token {
                TokenTree::Punct(p) if p.as_char() == ';' => break,
                TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => break,
                _ => {}
            }
        }
        Ok(((), rest))
    });
}
