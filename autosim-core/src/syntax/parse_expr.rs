//! Expressions (a precedence-climbing parser), and the small leaves every
//! item uses: names, numbers, signed values, units and labels.
//!
//! Precedence, loosest first: `+ -` (left), `* /` (left), prefix `- +`,
//! `^` (right; `-x^2` is `-(x^2)`), then `.member` and calls.

use proc_macro2::{Delimiter, TokenStream, TokenTree};
use syn::parse::ParseStream;
use syn::{Lit, Token};

use super::ast::{BinOp, Expr, Label, Member, Name, Number, UnOp, Unit, Value};
use super::cx::{Cx, PResult, expected, in_group, peek_group};
use crate::diag::{Diagnostic, Span};

/// Binding power of a prefix sign's operand: tighter than `*`, looser than `^`.
const PREFIX_BP: u8 = 5;

/// Parses one expression.
pub(crate) fn expr(input: ParseStream, cx: &Cx) -> PResult<Expr> {
    cx.begin_expression();
    expr_bp(input, cx, 0)
}

fn peek_binop(input: ParseStream) -> Option<(BinOp, u8, u8)> {
    if input.peek(Token![+]) {
        Some((BinOp::Add, 1, 2))
    } else if input.peek(Token![-]) && !input.peek(Token![->]) {
        Some((BinOp::Sub, 1, 2))
    } else if input.peek(Token![*]) {
        Some((BinOp::Mul, 3, 4))
    } else if input.peek(Token![/]) {
        Some((BinOp::Div, 3, 4))
    } else if input.peek(Token![^]) {
        Some((BinOp::Pow, 7, 6))
    } else {
        None
    }
}

/// Binding power of `as [unit]`: as a prefix sign (tighter than `*`,
/// looser than `^`), so `k*x as [N]` is `k*(x as [N])`, as in Rust.
const AS_BP: u8 = 5;

fn expr_bp(input: ParseStream, cx: &Cx, min_bp: u8) -> PResult<Expr> {
    cx.nested(input, || {
        let mut lhs = prefix(input, cx)?;
        loop {
            if input.peek(Token![as]) && AS_BP >= min_bp {
                lhs = as_unit(input, cx, lhs)?;
                continue;
            }
            let Some((op, left_bp, right_bp)) = peek_binop(input) else {
                break;
            };
            if left_bp < min_bp {
                break;
            }
            cx.operator(input)?;
            let op_span = cx.span(input.span());
            match op {
                BinOp::Add => _ = input.parse::<Token![+]>()?,
                BinOp::Sub => _ = input.parse::<Token![-]>()?,
                BinOp::Mul => _ = input.parse::<Token![*]>()?,
                BinOp::Div => _ = input.parse::<Token![/]>()?,
                BinOp::Pow => _ = input.parse::<Token![^]>()?,
            }
            let rhs = expr_bp(input, cx, right_bp)?;
            let span = lhs.span().to(rhs.span());
            lhs = Expr::Binary {
                op,
                lhs: Box::new(lhs),
                rhs: Box::new(rhs),
                op_span,
                span,
            };
        }
        Ok(lhs)
    })
}

/// `expr as [unit]`, after `expr`.
fn as_unit(input: ParseStream, cx: &Cx, inner: Expr) -> PResult<Expr> {
    let keyword: Token![as] = input.parse()?;
    let Some(unit) = unit(input, cx)? else {
        return cx.fail(
            expected(cx, input, "a unit in brackets after `as`")
                .help("`(expression) as [N m]` takes the expression to be in N m, unchecked"),
        );
    };
    let _ = keyword;
    let span = inner.span().to(unit.span);
    Ok(Expr::As {
        inner: Box::new(inner),
        unit,
        span,
    })
}

fn prefix(input: ParseStream, cx: &Cx) -> PResult<Expr> {
    let op = if input.peek(Token![-]) {
        UnOp::Neg
    } else if input.peek(Token![+]) {
        UnOp::Plus
    } else {
        return postfix(input, cx);
    };
    let op_span = cx.span(input.span());
    match op {
        UnOp::Neg => _ = input.parse::<Token![-]>()?,
        UnOp::Plus => _ = input.parse::<Token![+]>()?,
    }
    let operand = expr_bp(input, cx, PREFIX_BP)?;
    let span = op_span.to(operand.span());
    Ok(Expr::Unary {
        op,
        operand: Box::new(operand),
        span,
    })
}

fn postfix(input: ParseStream, cx: &Cx) -> PResult<Expr> {
    let mut base = primary(input, cx)?;
    loop {
        if input.peek(Token![.]) && !input.peek(Token![..]) {
            input.parse::<Token![.]>()?;
            let member = member(input, cx)?;
            let end = match &member {
                Member::Name(name) => name.span,
                Member::Index { span, .. } => *span,
            };
            let span = base.span().to(end);
            base = Expr::Member {
                base: Box::new(base),
                member,
                span,
            };
        } else if peek_group(input, Delimiter::Parenthesis) {
            return cx.fail(
                Diagnostic::error(
                    cx.span(input.span()),
                    format!("`{base}` cannot be called: only a name can be called"),
                )
                .help("write `*` to multiply"),
            );
        } else {
            return Ok(base);
        }
    }
}

fn member(input: ParseStream, cx: &Cx) -> PResult<Member> {
    if input.cursor().ident().is_some() {
        let ident: syn::Ident = input.call(syn::ext::IdentExt::parse_any)?;
        return Ok(Member::Name(Name {
            text: ident.to_string(),
            span: cx.span(ident.span()),
        }));
    }
    if input.peek(syn::LitInt) {
        let lit: syn::LitInt = input.parse()?;
        let span = cx.span(lit.span());
        if lit.suffix().is_empty()
            && let Ok(index) = lit.base10_digits().parse::<u32>()
        {
            return Ok(Member::Index { index, span });
        }
        return cx.fail(Diagnostic::error(
            span,
            format!("`{lit}` is not a valid member index"),
        ));
    }
    cx.fail(expected(
        cx,
        input,
        "a name or an index after `.` (such as `B.cm` or `B.1`)",
    ))
}

fn primary(input: ParseStream, cx: &Cx) -> PResult<Expr> {
    if input.peek(syn::Ident) {
        let func = name(input, cx, "a name")?;
        if !peek_group(input, Delimiter::Parenthesis) {
            return Ok(Expr::Name(func));
        }
        let group = group_span(input, cx, Delimiter::Parenthesis);
        let (args, _) = in_group(input, cx, Delimiter::Parenthesis, |content| {
            list(content, cx, "`)`")
        })?;
        let span = func.span.to(group);
        return Ok(Expr::Call { func, args, span });
    }
    if input.peek(syn::LitInt) || input.peek(syn::LitFloat) {
        let number = number(input, cx)?;
        return Ok(match unit(input, cx)? {
            Some(unit) => Expr::Quantity {
                span: number.span.to(unit.span),
                number,
                unit,
            },
            None => Expr::Number(number),
        });
    }
    // `true` and `false` (settings) read as names; elsewhere they are
    // unknown names.
    if input.peek(syn::LitBool) {
        let b: syn::LitBool = input.parse()?;
        return Ok(Expr::Name(Name {
            text: b.value.to_string(),
            span: cx.span(b.span),
        }));
    }
    if peek_group(input, Delimiter::Bracket) {
        let span = group_span(input, cx, Delimiter::Bracket);
        let (items, _) = in_group(input, cx, Delimiter::Bracket, |content| {
            list(content, cx, "`]`")
        })?;
        return Ok(Expr::List { items, span });
    }
    if peek_group(input, Delimiter::Parenthesis) {
        let span = group_span(input, cx, Delimiter::Parenthesis);
        let (inner, _) = in_group(input, cx, Delimiter::Parenthesis, |content| {
            let inner = expr(content, cx)?;
            if content.peek(Token![,]) {
                return cx.fail(
                    Diagnostic::error(cx.span(content.span()), "expected `)`, found `,`")
                        .help("vectors are written in brackets: `[x, y, z]`"),
                );
            }
            Ok(inner)
        })?;
        return Ok(Expr::Paren {
            inner: Box::new(inner),
            span,
        });
    }
    let mut diagnostic = expected(cx, input, "an expression");
    if let Some((ident, _)) = input.cursor().ident() {
        diagnostic = diagnostic.help(format!(
            "`{ident}` is a Rust keyword and cannot be used as a name"
        ));
    } else if input.peek(Token![*]) {
        diagnostic = diagnostic.help("powers are written `x^2`");
    }
    cx.fail(diagnostic)
}

/// The span of the group that comes next, from its opening to its closing
/// delimiter (so [`Span::after`](crate::diag::Span::after) of an expression
/// that ends with a group is its closing delimiter, where a missing `;`
/// belongs, not the whole group).
fn group_span(input: ParseStream, cx: &Cx, delimiter: Delimiter) -> Span {
    match input.cursor().group(delimiter) {
        Some((_, delims, _)) => cx.span(delims.open()).to(cx.span(delims.close())),
        None => cx.span(input.span()),
    }
}

/// Comma-separated expressions up to the end of `input` (a trailing comma
/// is allowed); `close` names the closing delimiter for messages.
fn list(input: ParseStream, cx: &Cx, close: &str) -> PResult<Vec<Expr>> {
    let mut items = Vec::new();
    while !input.is_empty() {
        items.push(expr(input, cx)?);
        if input.is_empty() {
            break;
        }
        if !input.peek(Token![,]) {
            return cx.fail(expected(cx, input, &format!("`,` or {close}")));
        }
        input.parse::<Token![,]>()?;
    }
    Ok(items)
}

/// A name (an identifier that is not a Rust keyword).
pub(crate) fn name(input: ParseStream, cx: &Cx, what: &str) -> PResult<Name> {
    if input.peek(syn::Ident) {
        let ident: syn::Ident = input.parse()?;
        return Ok(Name {
            text: ident.to_string(),
            span: cx.span(ident.span()),
        });
    }
    let mut diagnostic = expected(cx, input, what);
    if let Some((ident, _)) = input.cursor().ident()
        && ident != "_"
    {
        diagnostic = diagnostic.help(format!("`{ident}` is a Rust keyword; choose another name"));
    }
    cx.fail(diagnostic)
}

/// A numeric literal: decimal integer or float, no suffix.
pub(crate) fn number(input: ParseStream, cx: &Cx) -> PResult<Number> {
    let lit: Lit = input.parse()?;
    let span = cx.span(lit.span());
    let (repr, suffix, digits) = match &lit {
        Lit::Int(int) => (
            int.to_string(),
            int.suffix().to_string(),
            int.base10_digits().to_string(),
        ),
        Lit::Float(float) => (
            float.to_string(),
            float.suffix().to_string(),
            float.base10_digits().to_string(),
        ),
        _ => return cx.fail(Diagnostic::error(span, "expected a number")),
    };
    if !suffix.is_empty() {
        return cx.fail(
            Diagnostic::error(
                span,
                format!("numbers cannot have a type suffix (`{suffix}`)"),
            )
            .help(format!(
                "write `{digits}`; the float type is chosen in `settings`"
            )),
        );
    }
    let lower = repr.to_ascii_lowercase();
    if ["0x", "0o", "0b"]
        .iter()
        .any(|prefix| lower.starts_with(prefix))
    {
        return cx.fail(
            Diagnostic::error(span, "only decimal numbers are allowed")
                .help(format!("write `{digits}`")),
        );
    }
    Ok(Number { text: digits, span })
}

/// A number with an optional `-`: a parameter value or input default.
pub(crate) fn value(input: ParseStream, cx: &Cx, what: &str) -> PResult<Value> {
    let minus = if input.peek(Token![-]) {
        Some(input.parse::<Token![-]>()?)
    } else {
        None
    };
    if !(input.peek(syn::LitInt) || input.peek(syn::LitFloat)) {
        return cx.fail(expected(cx, input, &format!("a number for {what}")).help(
            "values are numbers such as `1.5` or `-2`; define derived quantities with `let`",
        ));
    }
    let number = number(input, cx)?;
    let span = match minus {
        Some(minus) => cx.span(minus.span).to(number.span),
        None => number.span,
    };
    Ok(Value {
        negative: minus.is_some(),
        number,
        span,
    })
}

/// An optional `"label"` after a name.
pub(crate) fn label(input: ParseStream, cx: &Cx) -> PResult<Option<Label>> {
    if !input.peek(syn::LitStr) {
        return Ok(None);
    }
    let lit: syn::LitStr = input.parse()?;
    Ok(Some(Label {
        text: lit.value(),
        span: cx.span(lit.span()),
    }))
}

/// An optional unit in brackets, normalized (`[N m / rad]` → `N m/rad`).
pub(crate) fn unit(input: ParseStream, cx: &Cx) -> PResult<Option<Unit>> {
    if !peek_group(input, Delimiter::Bracket) {
        return Ok(None);
    }
    let group = input.step(|cursor| match cursor.token_tree() {
        Some((TokenTree::Group(group), rest)) if group.delimiter() == Delimiter::Bracket => {
            Ok((group, rest))
        }
        _ => Err(cursor.error("expected a unit in brackets")),
    })?;
    let span = cx.span(group.span());
    let text = unit_text(group.stream(), cx)?;
    if text.is_empty() {
        return cx.fail(
            Diagnostic::error(span, "empty unit")
                .help("leave out the brackets for a quantity without a unit"),
        );
    }
    Ok(Some(Unit { text, span }))
}

fn unit_text(tokens: TokenStream, cx: &Cx) -> PResult<String> {
    let mut text = String::new();
    let mut prev_tight = true;
    for token in tokens {
        let (piece, tight) = match &token {
            TokenTree::Ident(ident) => (ident.to_string(), false),
            TokenTree::Literal(literal) => {
                let piece = literal.to_string();
                if !piece.chars().all(|c| c.is_ascii_digit() || c == '.') {
                    return cx.fail(bad_unit_token(cx, &token));
                }
                (piece, false)
            }
            TokenTree::Punct(punct) if matches!(punct.as_char(), '*' | '/' | '^' | '-' | '.') => {
                (punct.as_char().to_string(), true)
            }
            TokenTree::Punct(punct) if punct.as_char() == '%' => ("%".to_string(), false),
            TokenTree::Group(group) if group.delimiter() == Delimiter::Parenthesis => {
                (format!("({})", unit_text(group.stream(), cx)?), false)
            }
            _ => return cx.fail(bad_unit_token(cx, &token)),
        };
        if !text.is_empty() && !prev_tight && !tight {
            text.push(' ');
        }
        text.push_str(&piece);
        prev_tight = tight;
    }
    Ok(text)
}

fn bad_unit_token(cx: &Cx, token: &TokenTree) -> Diagnostic {
    let shown = match token {
        TokenTree::Group(group) => match group.delimiter() {
            Delimiter::Bracket => "[".to_string(),
            Delimiter::Brace => "{".to_string(),
            _ => "(".to_string(),
        },
        other => other.to_string(),
    };
    Diagnostic::error(
        cx.span(token.span()),
        format!("unexpected `{shown}` in a unit"),
    )
    .help("write units like `[N m/rad]`, `[kg m^2]` or `[m/s^2]`")
}
