//! The `event` item: `event name [unit] "label" { indicator: g, direction:
//! falling, set: { mode: 1 }, reset: { v: -e*v }, stop: true }`. Its block
//! is an option block whose `set` and `reset` take braced `name: value`
//! assignments; every bad entry is reported and skipped.

use proc_macro2::Delimiter;
use syn::Token;
use syn::parse::ParseStream;

use super::ast::{Assignment, Event, EventKey, Opt, OptionKey, Options};
use super::cx::{Cx, PResult, expected, in_group, peek_group, skip_past_comma};
use super::kw;
use super::parse_block::{duplicate, separator, unknown_key};
use super::parse_expr::{expr, label, name, unit};
use crate::diag::Span;

/// What the block of an event holds so far.
#[derive(Default)]
struct Entries {
    options: Vec<Opt<EventKey>>,
    set: Option<(Span, Vec<Assignment>)>,
    reset: Option<(Span, Vec<Assignment>)>,
}

/// `event name [unit] "label" { ... }` (at the keyword).
pub(crate) fn event(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Event> {
    let keyword: kw::event = input.parse()?;
    let name = name(input, cx, "an event name")?;
    let unit = unit(input, cx)?;
    let label = label(input, cx)?;
    if !peek_group(input, Delimiter::Brace) {
        return cx.fail(
            expected(cx, input, &format!("`{{` with the options of event `{}`", name.text)).help(
                "write `event name [unit] { indicator: <expression>, direction: rising, set: { mode: 1 } }`",
            ),
        );
    }
    let (entries, braces) = in_group(input, cx, Delimiter::Brace, |content| {
        let mut entries = Entries::default();
        while !content.is_empty() {
            match entry(content, cx, &mut entries) {
                Ok(last) => {
                    let next_is_entry = content.peek(syn::Ident) && content.peek2(Token![:]);
                    separator(content, cx, last, next_is_entry);
                }
                Err(failed) => {
                    cx.record(failed);
                    skip_past_comma(content);
                }
            }
        }
        Ok(entries)
    })?;
    Ok(Event {
        docs,
        span: cx.span(keyword.span).to(name.span),
        name,
        unit,
        label,
        options: Options {
            entries: entries.options,
            span: cx.span(braces),
        },
        set: entries.set,
        reset: entries.reset,
    })
}

/// One `key: value` of an event's block; returns the span of its value.
fn entry(content: ParseStream, cx: &Cx, entries: &mut Entries) -> PResult<Span> {
    if content.cursor().ident().is_none() {
        return cx.fail(expected(
            cx,
            content,
            "an event option such as `indicator: ...`",
        ));
    }
    let ident: syn::Ident = content.call(syn::ext::IdentExt::parse_any)?;
    let text = ident.to_string();
    let key_span = cx.span(ident.span());
    let key = EventKey::from_str(&text);
    if key.is_none() {
        cx.report(unknown_key::<EventKey>(&text, key_span));
    }
    if !content.peek(Token![:]) || content.peek(Token![::]) {
        return cx.fail(expected(cx, content, &format!("`:` after `{text}`")));
    }
    content.parse::<Token![:]>()?;
    match key {
        Some(key @ (EventKey::Set | EventKey::Reset)) => {
            let (assignments, group) = assignments(content, cx, key)?;
            let slot = match key {
                EventKey::Set => &mut entries.set,
                _ => &mut entries.reset,
            };
            match slot {
                Some((first, _)) => {
                    cx.report(duplicate(key.as_str(), EventKey::WHAT, key_span, *first))
                }
                None => *slot = Some((key_span, assignments)),
            }
            Ok(group)
        }
        _ => {
            let value = expr(content, cx)?;
            if key == Some(EventKey::Indicator) {
                comparison(content, cx)?;
            }
            let last = value.span();
            if let Some(key) = key {
                match entries.options.iter().find(|o| o.key == key) {
                    Some(first) => cx.report(duplicate(
                        key.as_str(),
                        EventKey::WHAT,
                        key_span,
                        first.key_span,
                    )),
                    None => entries.options.push(Opt {
                        key,
                        key_span,
                        value,
                    }),
                }
            }
            Ok(last)
        }
    }
}

/// Refuses a comparison after an indicator's value (`indicator: h < 0`):
/// an indicator is the value whose sign changes, its direction says which
/// way.
fn comparison(content: ParseStream, cx: &Cx) -> PResult<()> {
    if content.peek(Token![<]) || content.peek(Token![>]) || content.peek(Token![==]) {
        return cx.fail(
            expected(cx, content, "`,` or `}` after the indicator").help(
                "an indicator is a value whose sign changes at the event, not a comparison: \
                     for `a < b` write `indicator: a - b, direction: falling` (the event fires \
                     as `a - b` goes below zero)",
            ),
        );
    }
    Ok(())
}

/// `{ name: value, ... }` after `set:` or `reset:`.
fn assignments(content: ParseStream, cx: &Cx, key: EventKey) -> PResult<(Vec<Assignment>, Span)> {
    if !peek_group(content, Delimiter::Brace) {
        let example = match key {
            EventKey::Set => "set: { mode: 1 }",
            _ => "reset: { v: -e*v }",
        };
        return cx.fail(
            expected(
                cx,
                content,
                &format!("`{{` with the assignments of `{}`", key.as_str()),
            )
            .help(format!(
                "write `{example}`: each entry a name and its new value"
            )),
        );
    }
    let (list, group) = in_group(content, cx, Delimiter::Brace, |inner| {
        let mut list = Vec::new();
        while !inner.is_empty() {
            let target = name(inner, cx, "the name of the variable to assign")?;
            if !inner.peek(Token![:]) || inner.peek(Token![::]) {
                let mut d = expected(cx, inner, &format!("`:` after `{}`", target.text));
                if inner.peek(Token![=]) {
                    d = d.help(format!(
                        "assignments are written `{}: <new value>`",
                        target.text
                    ));
                }
                return cx.fail(d);
            }
            inner.parse::<Token![:]>()?;
            let value = expr(inner, cx)?;
            list.push(Assignment { target, value });
            if inner.is_empty() {
                break;
            }
            if !inner.peek(Token![,]) {
                return cx.fail(expected(cx, inner, "`,` or `}`"));
            }
            inner.parse::<Token![,]>()?;
        }
        Ok(list)
    })?;
    Ok((list, cx.span(group)))
}
