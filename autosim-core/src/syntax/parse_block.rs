//! Doc comments and the braced blocks: `{ key: value, ... }` option blocks
//! (keys checked against an [`OptionKey`] table) and the `parameters { ... }`
//! block. A bad entry is reported and skipped up to the next `,`, so one
//! typo does not hide the rest of the block.

use proc_macro2::Delimiter;
use syn::Token;
use syn::parse::ParseStream;

use super::ast::{Opt, OptionKey, Options, Parameter};
use super::cx::{Cx, PResult, expected, in_group, peek_group, skip_all, skip_past_comma};
use super::parse_expr::{expr, name, unit, value};
use crate::diag::{Diagnostic, Span, did_you_mean};

/// Doc comments (`///` arrives as `#[doc = "..."]`). Inner ones (`//!`) are
/// moved into `inner` when given, and refused otherwise; other attributes
/// are refused.
pub(crate) fn docs(
    input: ParseStream,
    cx: &Cx,
    mut inner: Option<&mut Vec<String>>,
) -> PResult<Vec<String>> {
    let mut docs = Vec::new();
    while input.peek(Token![#]) {
        let pound: Token![#] = input.parse()?;
        let bang = if input.peek(Token![!]) {
            Some(input.parse::<Token![!]>()?)
        } else {
            None
        };
        if !peek_group(input, Delimiter::Bracket) {
            return cx.fail(expected(cx, input, "`[` of an attribute after `#`"));
        }
        let (text, group) = in_group(input, cx, Delimiter::Bracket, |content| {
            if content.peek(syn::Ident) && content.peek2(Token![=]) && content.peek3(syn::LitStr) {
                let ident: syn::Ident = content.parse()?;
                if ident == "doc" {
                    content.parse::<Token![=]>()?;
                    let text: syn::LitStr = content.parse()?;
                    if content.is_empty() {
                        return Ok(Some(text.value()));
                    }
                }
            }
            skip_all(content);
            Ok(None)
        })?;
        let span = cx.span_to(pound.span, group);
        match (text, bang, inner.as_deref_mut()) {
            (None, _, _) => cx.report(
                Diagnostic::error(span, "unsupported attribute")
                    .help("only doc comments (`///`) are allowed here"),
            ),
            (Some(text), None, _) => docs.push(text),
            (Some(text), Some(_), Some(inner)) => inner.push(text),
            (Some(_), Some(_), None) => cx.report(
                Diagnostic::error(
                    span,
                    "inner doc comments (`//!`) are only allowed between items",
                )
                .help("use `///` to document this entry"),
            ),
        }
    }
    Ok(docs)
}

/// A `{ key: value, ... }` block whose keys are `K`s. `owner` names the
/// item for messages (`body `B``).
pub(crate) fn options<K: OptionKey>(
    input: ParseStream,
    cx: &Cx,
    owner: &str,
) -> PResult<Options<K>> {
    if !peek_group(input, Delimiter::Brace) {
        return cx.fail(expected(
            cx,
            input,
            &format!("`{{` with the {}s of {owner}", K::WHAT),
        ));
    }
    let (entries, span) = in_group(input, cx, Delimiter::Brace, |content| {
        Ok(entries::<K>(content, cx, Assign::Colon))
    })?;
    Ok(Options {
        entries,
        span: cx.span(span),
    })
}

/// How an entry gives its key a value: `key: value` in a block, `key =
/// value` among the macro's arguments.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Assign {
    /// `key: value`.
    Colon,
    /// `key = value`.
    Equals,
}

impl Assign {
    fn text(self) -> &'static str {
        match self {
            Assign::Colon => ":",
            Assign::Equals => "=",
        }
    }

    /// Whether the next token is this one (`:` but not `::`).
    fn peek(self, input: ParseStream) -> bool {
        match self {
            Assign::Colon => input.peek(Token![:]) && !input.peek(Token![::]),
            Assign::Equals => input.peek(Token![=]) && !input.peek(Token![==]),
        }
    }
}

/// Entries `key: value` (or `key = value`) separated by commas, up to the
/// end of `content`: every bad entry reported and skipped, a key given
/// twice reported.
pub(crate) fn entries<K: OptionKey>(content: ParseStream, cx: &Cx, assign: Assign) -> Vec<Opt<K>> {
    let mut out: Vec<Opt<K>> = Vec::new();
    while !content.is_empty() {
        let last = match entry::<K>(content, cx, assign) {
            Ok((Some(opt), last)) => {
                match out.iter().find(|seen| seen.key == opt.key) {
                    Some(first) => cx.report(duplicate(
                        opt.key.as_str(),
                        K::WHAT,
                        opt.key_span,
                        first.key_span,
                    )),
                    None => out.push(opt),
                }
                last
            }
            Ok((None, last)) => last,
            Err(failed) => {
                cx.record(failed);
                skip_past_comma(content);
                continue;
            }
        };
        let next_is_entry = content.peek(syn::Ident)
            && match assign {
                Assign::Colon => content.peek2(Token![:]),
                Assign::Equals => content.peek2(Token![=]),
            };
        separator(content, cx, last, next_is_entry);
    }
    out
}

/// After an entry: a `,`, the end, or (reported, then accepted) a missing
/// comma before something that looks like the next entry.
pub(crate) fn separator(content: ParseStream, cx: &Cx, last: Span, next_is_entry: bool) {
    if content.is_empty() {
        return;
    }
    if content.peek(Token![,]) {
        let _ = content.parse::<Token![,]>();
    } else if next_is_entry {
        cx.report(Diagnostic::error(
            last.after(),
            "expected `,` between entries",
        ));
    } else {
        cx.report(expected(cx, content, "`,` or `}`"));
        skip_past_comma(content);
    }
}

/// One `key: value`; `None` for an unknown key (reported). Also returns the
/// span of the value, for a missing-comma message.
fn entry<K: OptionKey>(
    content: ParseStream,
    cx: &Cx,
    assign: Assign,
) -> PResult<(Option<Opt<K>>, Span)> {
    if content.cursor().ident().is_none() {
        let example = K::ALL.first().map_or("key", |(text, _)| text);
        let sep = assign.text();
        return cx.fail(expected(
            cx,
            content,
            &format!("a {} such as `{example}{sep} ...`", K::WHAT),
        ));
    }
    let ident: syn::Ident = content.call(syn::ext::IdentExt::parse_any)?;
    let text = ident.to_string();
    let key_span = cx.span(ident.span());
    let key = K::from_str(&text);
    if key.is_none() {
        cx.report(unknown_key::<K>(&text, key_span));
    }
    if !assign.peek(content) {
        let sep = assign.text();
        let mut diagnostic = expected(cx, content, &format!("`{sep}` after `{text}`"));
        if assign == Assign::Colon && content.peek(Token![=]) {
            diagnostic = diagnostic.help("block entries are written `key: value`");
        }
        if assign == Assign::Equals && content.peek(Token![:]) {
            diagnostic = diagnostic.help("the macro's options are written `key = value`");
        }
        return cx.fail(diagnostic);
    }
    match assign {
        Assign::Colon => drop(content.parse::<Token![:]>()?),
        Assign::Equals => drop(content.parse::<Token![=]>()?),
    }
    let value = expr(content, cx)?;
    let last = value.span();
    Ok((
        key.map(|key| Opt {
            key,
            key_span,
            value,
        }),
        last,
    ))
}

pub(crate) fn unknown_key<K: OptionKey>(text: &str, span: Span) -> Diagnostic {
    let valid: Vec<&str> = K::ALL.iter().map(|(text, _)| *text).collect();
    let mut diagnostic = Diagnostic::error(span, format!("unknown {} `{text}`", K::WHAT));
    if let Some(suggestion) = did_you_mean(text, valid.iter().copied()) {
        diagnostic = diagnostic.help(format!("did you mean `{suggestion}`?"));
    }
    diagnostic.note(format!("the {}s are: {}", K::WHAT, valid.join(", ")))
}

pub(crate) fn duplicate(key: &str, what: &str, span: Span, first: Span) -> Diagnostic {
    let diagnostic = Diagnostic::error(span, format!("duplicate {what} `{key}`"));
    match first.start() {
        Some(at) => diagnostic.note(format!("`{key}` was first given at {at}")),
        None => diagnostic.note(format!("`{key}` was already given earlier in this block")),
    }
}

/// The entries of `parameters { ... }`.
pub(crate) fn parameter_entries(
    input: ParseStream,
    cx: &Cx,
) -> PResult<(Vec<Parameter>, proc_macro2::Span)> {
    if !peek_group(input, Delimiter::Brace) {
        return cx.fail(expected(cx, input, "`{` with the parameters"));
    }
    in_group(input, cx, Delimiter::Brace, |content| {
        let mut params = Vec::new();
        while !content.is_empty() {
            let result = docs(content, cx, None).and_then(|docs| parameter(content, cx, docs));
            let last = match result {
                Ok(param) => {
                    let last = param
                        .unit
                        .as_ref()
                        .map_or(param.value.span, |unit| unit.span);
                    params.push(param);
                    last
                }
                Err(failed) => {
                    cx.record(failed);
                    skip_past_comma(content);
                    continue;
                }
            };
            let next_is_entry =
                content.peek(Token![#]) || (content.peek(syn::Ident) && content.peek2(Token![=]));
            separator(content, cx, last, next_is_entry);
        }
        Ok(params)
    })
}

/// `NAME = value [unit]` (shared by the block and the single form).
pub(crate) fn parameter(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Parameter> {
    let name = name(input, cx, "a parameter name")?;
    if !input.peek(Token![=]) || input.peek(Token![==]) {
        let mut diagnostic = expected(cx, input, &format!("`=` after `{}`", name.text));
        if input.peek(Token![:]) {
            diagnostic = diagnostic.help("parameters are written `NAME = value [unit]`");
        }
        return cx.fail(diagnostic);
    }
    input.parse::<Token![=]>()?;
    let value = value(input, cx, &format!("parameter `{}`", name.text))?;
    let arithmetic = [
        input.peek(Token![+]),
        input.peek(Token![*]),
        input.peek(Token![/]),
        input.peek(Token![^]),
    ]
    .contains(&true)
        || (input.peek(Token![-]) && !input.peek(Token![->]));
    let help = if arithmetic {
        Some("a parameter's value is a single number; define derived quantities with `let`")
    } else if peek_group(input, Delimiter::Parenthesis) {
        Some("units are written in brackets: `[m]`")
    } else {
        None
    };
    if let Some(help) = help {
        let after = format!("a unit, `,` or the end after the value of `{}`", name.text);
        return cx.fail(expected(cx, input, &after).help(help));
    }
    let unit = unit(input, cx)?;
    Ok(Parameter {
        docs,
        name,
        value,
        unit,
    })
}
