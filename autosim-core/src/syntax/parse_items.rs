//! Top-level items, in any order. After an error the parser skips to the
//! next item (past the next `;` or `{...}`, or up to the next item keyword)
//! and goes on, so every syntax error of a model is reported at once.

use proc_macro2::Delimiter;
use syn::Token;
use syn::parse::ParseStream;

use super::ast::{
    Block, Body, Expr, ExternFn, ExternSub, Force, Gravity, Input, Inputs, Item, Let, Model,
    Moment, Name, Output, Parameters, Point, SettingKey, Settings, State, StateKey, SubOutput,
};
use super::cx::{Cx, PResult, at_item_start, expected, in_group, peek_group, recover};
use super::keys::OptionKey;
use super::kw::{self, ITEM_STARTS};
use super::parse_block::{docs, options, parameter, parameter_entries};
use super::parse_expr::{expr, label, name, unit, value};
use crate::diag::{Diagnostic, Span, did_you_mean};

/// What the top level has seen so far.
#[derive(Default)]
struct Top {
    model: Option<(Vec<String>, Name, Span)>,
    inner_docs: Vec<String>,
    items: Vec<Item>,
    settings: Option<Span>,
    gravity: Option<Span>,
}

/// Parses a whole model; `None` (with diagnostics) when there is no `model`
/// item. Never fails: errors go to `cx`.
pub(crate) fn model(input: ParseStream, cx: &Cx) -> Option<Model> {
    let start = cx.span(input.span());
    let mut top = Top::default();
    while !input.is_empty() {
        let item_start = input.cursor();
        if let Err(failed) = item(input, cx, &mut top) {
            cx.record(failed);
            recover(input, item_start);
        }
    }
    let Some((mut docs, name, _)) = top.model else {
        cx.report(
            Diagnostic::error(start.to(start), "missing `model` item")
                .help("name the model first: `model Name;`"),
        );
        return None;
    };
    docs.extend(top.inner_docs);
    Some(Model {
        docs,
        name,
        items: top.items,
    })
}

fn item(input: ParseStream, cx: &Cx, top: &mut Top) -> PResult<()> {
    let docs = docs(input, cx, Some(&mut top.inner_docs))?;
    if input.is_empty() {
        if !docs.is_empty() {
            cx.report(Diagnostic::error(
                cx.span(input.span()),
                "doc comment is not followed by an item",
            ));
        }
        return Ok(());
    }
    if input.peek(Token![;]) {
        input.parse::<Token![;]>()?;
        return Ok(());
    }
    let item = if input.peek(kw::model) {
        return model_item(input, cx, top, docs);
    } else if input.peek(kw::settings) {
        let settings = settings(input, cx, docs)?;
        once(cx, &mut top.settings, settings.span, "settings");
        Item::Settings(settings)
    } else if input.peek(kw::parameters) {
        let keyword: kw::parameters = input.parse()?;
        let (params, _) = parameter_entries(input, cx)?;
        Item::Parameters(Parameters {
            docs,
            span: cx.span(keyword.span),
            params,
        })
    } else if input.peek(kw::parameter) {
        let keyword: kw::parameter = input.parse()?;
        let param = parameter(input, cx, docs)?;
        semi(
            input,
            cx,
            "the parameter",
            param
                .unit
                .as_ref()
                .map_or(param.value.span, |unit| unit.span),
        )?;
        Item::Parameters(Parameters {
            docs: Vec::new(),
            span: cx.span(keyword.span),
            params: vec![param],
        })
    } else if input.peek(kw::body) {
        Item::Body(body(input, cx, docs)?)
    } else if input.peek(kw::point) {
        Item::Point(point(input, cx, docs)?)
    } else if input.peek(Token![let]) {
        Item::Let(let_item(input, cx, docs)?)
    } else if input.peek(kw::force) {
        Item::Force(force(input, cx, docs)?)
    } else if input.peek(kw::moment) {
        Item::Moment(moment(input, cx, docs)?)
    } else if input.peek(kw::gravity) {
        let gravity = gravity(input, cx, docs)?;
        once(cx, &mut top.gravity, gravity.span, "gravity");
        Item::Gravity(gravity)
    } else if input.peek(kw::input) {
        let keyword: kw::input = input.parse()?;
        Item::Inputs(inputs(input, cx, docs, cx.span(keyword.span), "input")?)
    } else if input.peek(Token![extern]) {
        extern_item(input, cx, docs)?
    } else if input.peek(kw::state) {
        Item::State(state(input, cx, docs)?)
    } else if input.peek(kw::output) {
        Item::Output(output(input, cx, docs)?)
    } else if input.peek(kw::constraint) {
        let keyword: kw::constraint = input.parse()?;
        Item::Constraint(block(input, cx, docs, cx.span(keyword.span), "constraint")?)
    } else if input.peek(kw::discrete) {
        let keyword: kw::discrete = input.parse()?;
        Item::Discrete(inputs(
            input,
            cx,
            docs,
            cx.span(keyword.span),
            "discrete variable",
        )?)
    } else if input.peek(kw::event) {
        Item::Event(super::parse_event::event(input, cx, docs)?)
    } else if input.peek(kw::motion) {
        let keyword: kw::motion = input.parse()?;
        Item::Motion(block(input, cx, docs, cx.span(keyword.span), "motion")?)
    } else {
        return cx.fail(not_an_item(input, cx));
    };
    top.items.push(item);
    Ok(())
}

fn not_an_item(input: ParseStream, cx: &Cx) -> Diagnostic {
    let mut diagnostic = expected(cx, input, "an item");
    if let Some((ident, _)) = input.cursor().ident()
        && let Some(suggestion) = did_you_mean(&ident.to_string(), ITEM_STARTS.iter().copied())
    {
        diagnostic = diagnostic.help(format!("did you mean `{suggestion}`?"));
    }
    diagnostic.note(format!(
        "items start with one of: {}",
        ITEM_STARTS.join(", ")
    ))
}

/// Reports a second `settings` or `gravity` item.
fn once(cx: &Cx, seen: &mut Option<Span>, span: Span, what: &str) {
    match seen {
        None => *seen = Some(span),
        Some(first) => {
            let diagnostic = Diagnostic::error(span, format!("duplicate `{what}` item"));
            cx.report(match first.start() {
                Some(at) => diagnostic.note(format!("the first `{what}` item is at {at}")),
                None => diagnostic.note(format!("a model has at most one `{what}` item")),
            });
        }
    }
}

/// `;` ending an item. A missing `;` before the next item or the end is
/// reported and accepted (so the next item still parses); anything else is
/// an error. `last` is the item's last part, where the `;` belongs.
fn semi(input: ParseStream, cx: &Cx, what: &str, last: Span) -> PResult<()> {
    if input.peek(Token![;]) {
        input.parse::<Token![;]>()?;
        return Ok(());
    }
    if input.is_empty() || at_item_start(input.cursor()) {
        cx.report(Diagnostic::error(
            last.after(),
            format!("expected `;` after {what}"),
        ));
        return Ok(());
    }
    cx.fail(expected(cx, input, &format!("`;` after {what}")))
}

fn model_item(input: ParseStream, cx: &Cx, top: &mut Top, docs: Vec<String>) -> PResult<()> {
    let keyword: kw::model = input.parse()?;
    let name = name(input, cx, "the model's name")?;
    let span = cx.span(keyword.span).to(name.span);
    semi(input, cx, "the model's name", name.span)?;
    match &top.model {
        None => top.model = Some((docs, name, span)),
        Some((_, first, _)) => {
            let diagnostic = Diagnostic::error(span, "duplicate `model` item");
            cx.report(match first.span.start() {
                Some(at) => diagnostic.note(format!(
                    "the model was already named `{}` at {at}",
                    first.text
                )),
                None => diagnostic.note(format!("the model was already named `{}`", first.text)),
            });
        }
    }
    Ok(())
}

fn settings(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Settings> {
    let keyword: kw::settings = input.parse()?;
    let options = options::<SettingKey>(input, cx, "`settings`")?;
    Ok(Settings {
        docs,
        span: cx.span(keyword.span),
        options,
    })
}

fn body(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Body> {
    let keyword: kw::body = input.parse()?;
    block(input, cx, docs, cx.span(keyword.span), "body")
}

fn point(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Point> {
    let keyword: kw::point = input.parse()?;
    let name = name(input, cx, "a point name")?;
    let label = label(input, cx)?;
    if !input.peek(Token![in]) {
        return cx.fail(
            expected(cx, input, "`in` and the body the point is fixed in")
                .help(format!("write `point {} in B at [x, y, z];`", name.text)),
        );
    }
    input.parse::<Token![in]>()?;
    let body = self::name(input, cx, "the name of the body the point is fixed in")?;
    if !input.peek(kw::at) {
        return cx.fail(
            expected(cx, input, "`at` and the point's coordinates").help(format!(
                "write `point {} in {} at [x, y, z];`",
                name.text, body.text
            )),
        );
    }
    input.parse::<kw::at>()?;
    let at = expr(input, cx)?;
    semi(input, cx, "the point's coordinates", at.span())?;
    Ok(Point {
        docs,
        span: cx.span(keyword.span).to(name.span),
        name,
        label,
        body,
        at,
    })
}

fn let_item(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Let> {
    let keyword: Token![let] = input.parse()?;
    let name = name(input, cx, "a name to define")?;
    let value = assigned_value(input, cx, &name)?;
    Ok(Let {
        docs,
        span: cx.span(keyword.span).to(name.span),
        name,
        value,
    })
}

fn equals(input: ParseStream, cx: &Cx, after: &str) -> PResult<()> {
    if input.peek(Token![=]) && !input.peek(Token![==]) {
        input.parse::<Token![=]>()?;
        return Ok(());
    }
    cx.fail(expected(cx, input, &format!("`=` after `{after}`")))
}

fn force(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Force> {
    let keyword: kw::force = input.parse()?;
    block(input, cx, docs, cx.span(keyword.span), "force")
}

fn moment(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Moment> {
    let keyword: kw::moment = input.parse()?;
    block(input, cx, docs, cx.span(keyword.span), "moment")
}

fn gravity(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Gravity> {
    let keyword: kw::gravity = input.parse()?;
    equals(input, cx, "gravity")?;
    let value = expr(input, cx)?;
    semi(input, cx, "the gravity vector", value.span())?;
    Ok(Gravity {
        docs,
        span: cx.span(keyword.span),
        value,
    })
}

/// The entries of an `input` (or `discrete`) item after its keyword at
/// `span`: `name [unit] = default, ...;`, `what` naming one in messages.
fn inputs(
    input: ParseStream,
    cx: &Cx,
    docs: Vec<String>,
    span: Span,
    what: &str,
) -> PResult<Inputs> {
    let mut inputs = Vec::new();
    loop {
        let article = if what.starts_with(['a', 'e', 'i', 'o', 'u']) {
            "an"
        } else {
            "a"
        };
        let name = name(input, cx, &format!("{article} {what} name"))?;
        let unit = unit(input, cx)?;
        let default = if input.peek(Token![=]) {
            input.parse::<Token![=]>()?;
            Some(value(
                input,
                cx,
                &format!("the default of `{}`", name.text),
            )?)
        } else {
            None
        };
        let last = default
            .as_ref()
            .map(|v| v.span)
            .or(unit.as_ref().map(|u| u.span))
            .unwrap_or(name.span);
        inputs.push(Input {
            name,
            unit,
            default,
        });
        if input.peek(Token![,]) {
            input.parse::<Token![,]>()?;
            continue;
        }
        semi(input, cx, &format!("the {what}s"), last)?;
        break;
    }
    Ok(Inputs { docs, span, inputs })
}

fn extern_item(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Item> {
    let keyword: Token![extern] = input.parse()?;
    let is_fn = input.peek(Token![fn]);
    if is_fn {
        input.parse::<Token![fn]>()?;
    } else if input.peek(kw::sub) {
        input.parse::<kw::sub>()?;
    } else {
        return cx.fail(
            expected(cx, input, "`fn` or `sub` after `extern`")
                .help("`extern fn f(x, y);` declares a user function, `extern sub s(t) -> (a, b);` a user subroutine"),
        );
    }
    let name = name(
        input,
        cx,
        if is_fn {
            "a function name"
        } else {
            "a subroutine name"
        },
    )?;
    let span = cx.span(keyword.span).to(name.span);
    if !peek_group(input, Delimiter::Parenthesis) {
        return cx.fail(expected(cx, input, "`(` and the arguments"));
    }
    if is_fn {
        let (params, group) = in_group(input, cx, Delimiter::Parenthesis, |content| {
            comma_list(content, cx, |content| {
                let name = self::name(content, cx, "an argument name")?;
                let unit = unit(content, cx)?;
                Ok((name, unit))
            })
        })?;
        let mut end = cx.span(group);
        let mut result_unit = None;
        if input.peek(Token![->]) {
            input.parse::<Token![->]>()?;
            result_unit = unit(input, cx)?;
            match &result_unit {
                Some(u) => end = u.span,
                None => {
                    return cx.fail(
                        expected(cx, input, "the unit of the result in brackets, such as `-> [N]`")
                            .help("a user function returns one number of the model's float type: give its unit, `-> [N]`, or leave out `-> ...` for a dimensionless result")
                            .help("declare a subroutine (`extern sub`) for several results"),
                    );
                }
            }
        }
        semi(input, cx, "the function's arguments", end)?;
        let (params, param_units) = params.into_iter().unzip();
        return Ok(Item::ExternFn(ExternFn {
            docs,
            span,
            name,
            params,
            param_units,
            result_unit,
        }));
    }
    let (args, _) = in_group(input, cx, Delimiter::Parenthesis, |content| {
        comma_list(content, cx, |c| expr(c, cx))
    })?;
    if !input.peek(Token![->]) {
        return cx.fail(
            expected(cx, input, "`->` and the subroutine's outputs").help(format!(
                "write `extern sub {}(...) -> (out1 [unit], out2);`",
                name.text
            )),
        );
    }
    input.parse::<Token![->]>()?;
    if !peek_group(input, Delimiter::Parenthesis) {
        return cx.fail(expected(cx, input, "`(` and the outputs"));
    }
    let (outputs, group) = in_group(input, cx, Delimiter::Parenthesis, |content| {
        comma_list(content, cx, |content| {
            let name = self::name(content, cx, "an output name")?;
            let unit = unit(content, cx)?;
            Ok(SubOutput { name, unit })
        })
    })?;
    semi(input, cx, "the subroutine's outputs", cx.span(group))?;
    Ok(Item::ExternSub(ExternSub {
        docs,
        span,
        name,
        args,
        outputs,
    }))
}

/// `a, b, c` up to the end of a group, trailing comma allowed.
fn comma_list<T>(
    input: ParseStream,
    cx: &Cx,
    mut each: impl FnMut(ParseStream) -> PResult<T>,
) -> PResult<Vec<T>> {
    let mut out = Vec::new();
    while !input.is_empty() {
        out.push(each(input)?);
        if input.is_empty() {
            break;
        }
        if !input.peek(Token![,]) {
            return cx.fail(expected(cx, input, "`,` or `)`"));
        }
        input.parse::<Token![,]>()?;
    }
    Ok(out)
}

fn state(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<State> {
    let keyword: kw::state = input.parse()?;
    let name = name(input, cx, "a state variable name")?;
    let unit = unit(input, cx)?;
    let options = options::<StateKey>(input, cx, &format!("state `{}`", name.text))?;
    Ok(State {
        docs,
        span: cx.span(keyword.span).to(name.span),
        name,
        unit,
        options,
    })
}

fn output(input: ParseStream, cx: &Cx, docs: Vec<String>) -> PResult<Output> {
    let keyword: kw::output = input.parse()?;
    let name = name(input, cx, "an output name")?;
    let unit = unit(input, cx)?;
    let value = assigned_value(input, cx, &name)?;
    Ok(Output {
        docs,
        span: cx.span(keyword.span).to(name.span),
        name,
        unit,
        value,
    })
}

/// The rest of a named block after its keyword (at `keyword`): the name,
/// an optional label and the options, `what` naming the item in messages.
fn block<K: OptionKey>(
    input: ParseStream,
    cx: &Cx,
    docs: Vec<String>,
    keyword: Span,
    what: &str,
) -> PResult<Block<K>> {
    let name = name(input, cx, &format!("a {what} name"))?;
    let unit = match what {
        "constraint" => unit(input, cx)?,
        _ => None,
    };
    let label = label(input, cx)?;
    let options = options::<K>(input, cx, &format!("{what} `{}`", name.text))?;
    Ok(Block {
        docs,
        span: keyword.to(name.span),
        name,
        label,
        unit,
        options,
    })
}

/// `= <expression>;` after `name`.
fn assigned_value(input: ParseStream, cx: &Cx, name: &Name) -> PResult<Expr> {
    equals(input, cx, &name.text)?;
    let value = expr(input, cx)?;
    semi(
        input,
        cx,
        &format!("the value of `{}`", name.text),
        value.span(),
    )?;
    Ok(value)
}
