//! The text form of expressions: a printer and a parser, for tests, debugging
//! and documentation.
//!
//! Syntax: numbers (`3`, `1/2` as a quotient, floats as `2.5f`), names,
//! `+ - * / ^`, parentheses and calls `f(a, b)`. `x^(1/2)` prints as
//! `sqrt(x)`. Decimal numbers without the `f` suffix parse exactly
//! (`0.25` is the rational 1/4).

use super::arena::{Arena, ExprId, Func, Node, SymbolKind};
use super::number::Number;
use std::fmt::Write;

/// Binding strength of the printed form of a node (the symbolic text form
/// and the generated Rust share it).
#[derive(Clone, Copy, PartialEq, PartialOrd)]
pub(crate) enum Prec {
    Sum = 1,
    Prod = 2,
    Unary = 3,
    Pow = 4,
    Atom = 5,
}

impl Arena {
    /// The text form of an expression (a tree: shared subexpressions are
    /// repeated, so use it on small expressions).
    pub fn to_text(&self, e: ExprId) -> String {
        let mut s = String::new();
        self.write_expr(&mut s, e, Prec::Sum);
        s
    }

    fn prec_of(&self, e: ExprId) -> Prec {
        match self.node(e) {
            Node::Num(Number::Rational { num, den }) => {
                if *num < 0 {
                    Prec::Unary
                } else if *den != 1 {
                    Prec::Prod
                } else {
                    Prec::Atom
                }
            }
            Node::Num(n) => {
                if n.is_negative() {
                    Prec::Unary
                } else {
                    Prec::Atom
                }
            }
            Node::Sym(_) | Node::Func(..) => Prec::Atom,
            Node::Sum(_) => Prec::Sum,
            Node::Prod(c, fs)
                if *c == Number::MINUS_ONE
                    && fs.len() == 1
                    && matches!(self.node(fs[0]), Node::Sum(_)) =>
            {
                Prec::Sum
            }
            Node::Prod(c, _) => {
                if c.is_negative() {
                    Prec::Unary
                } else {
                    Prec::Prod
                }
            }
            Node::Pow(_, x) => match self.as_number(*x) {
                Some(n) if n == Number::rational(1, 2).unwrap_or(Number::ZERO) => Prec::Atom,
                Some(n) if n.is_negative() => Prec::Prod,
                _ => Prec::Pow,
            },
        }
    }

    fn write_expr(&self, out: &mut String, e: ExprId, min: Prec) {
        let p = self.prec_of(e);
        let paren = p < min;
        if paren {
            out.push('(');
        }
        self.write_node(out, e);
        if paren {
            out.push(')');
        }
    }

    fn write_number(out: &mut String, n: Number) {
        match n {
            Number::Float(bits) => {
                let x = f64::from_bits(bits);
                let _ = write!(out, "{x:?}f");
            }
            other => {
                let _ = write!(out, "{other}");
            }
        }
    }

    fn write_node(&self, out: &mut String, e: ExprId) {
        match self.node(e) {
            Node::Num(n) => Self::write_number(out, *n),
            Node::Sym(s) => out.push_str(&self.symbol(*s).name),
            Node::Sum(ts) => self.write_sum(out, ts, false),
            Node::Prod(c, fs)
                if *c == Number::MINUS_ONE
                    && fs.len() == 1
                    && matches!(self.node(fs[0]), Node::Sum(_)) =>
            {
                if let Node::Sum(ts) = self.node(fs[0]) {
                    self.write_sum(out, ts, true);
                }
            }
            Node::Prod(c, fs) => {
                // A negative product with a sum factor reads better with
                // the sum negated: `y*(1 - y^2/6)`, not `-y*(y^2/6 - 1)`.
                let sum_at = fs
                    .iter()
                    .position(|f| matches!(self.node(*f), Node::Sum(_)));
                match sum_at {
                    Some(k) if c.is_negative() => {
                        let mut t = String::new();
                        self.write_prod_parts(&mut t, c.abs(), &[]);
                        let rest: Vec<ExprId> = fs
                            .iter()
                            .enumerate()
                            .filter(|(i, _)| *i != k)
                            .map(|(_, f)| *f)
                            .collect();
                        let first = t == "1";
                        if !first {
                            out.push_str(&t);
                        }
                        if !self.write_factors(out, first, &rest) {
                            out.push('*');
                        }
                        out.push('(');
                        if let Node::Sum(ts) = self.node(fs[k]) {
                            self.write_sum(out, ts, true);
                        }
                        out.push(')');
                    }
                    _ => {
                        if c.is_negative() {
                            out.push('-');
                        }
                        self.write_prod_parts(out, c.abs(), fs);
                    }
                }
            }
            Node::Pow(b, x) => match self.as_number(*x) {
                Some(n) if n.is_negative() => {
                    out.push_str("1/");
                    self.write_divisor(out, *b, -n);
                }
                Some(n) => self.write_pow(out, *b, n),
                None => {
                    self.write_expr(out, *b, Prec::Atom);
                    out.push('^');
                    self.write_expr(out, *x, Prec::Atom);
                }
            },
            Node::Func(f, args) => {
                out.push_str(self.func_name(*f));
                out.push('(');
                for (i, a) in args.iter().enumerate() {
                    if i > 0 {
                        out.push_str(", ");
                    }
                    self.write_expr(out, *a, Prec::Sum);
                }
                out.push(')');
            }
        }
    }

    fn write_pow(&self, out: &mut String, b: ExprId, n: Number) {
        if Some(n) == Number::rational(1, 2) {
            out.push_str("sqrt(");
            self.write_expr(out, b, Prec::Sum);
            out.push(')');
            return;
        }
        self.write_expr(out, b, Prec::Atom);
        out.push('^');
        match n {
            Number::Rational { num, den: 1 } if num >= 0 => {
                let _ = write!(out, "{num}");
            }
            other => {
                out.push('(');
                Self::write_number(out, other);
                out.push(')');
            }
        }
    }

    /// Prints a sum (negated if `flip`), positive terms first.
    fn write_sum(&self, out: &mut String, terms: &[ExprId], flip: bool) {
        let mut signed: Vec<(bool, ExprId)> = terms
            .iter()
            .map(|t| (self.split_sign_ref(*t).0 != flip, *t))
            .collect();
        signed.sort_by_key(|(neg, _)| *neg);
        for (i, (neg, t)) in signed.iter().enumerate() {
            if i == 0 {
                if *neg {
                    out.push('-');
                }
            } else if *neg {
                out.push_str(" - ");
            } else {
                out.push_str(" + ");
            }
            match self.node(*t) {
                Node::Num(n) => Self::write_number(out, n.abs()),
                Node::Prod(c, fs) => self.write_prod_parts(out, c.abs(), fs),
                _ => self.write_expr(out, *t, Prec::Prod),
            }
        }
    }

    fn write_prod_parts(&self, out: &mut String, c: Number, fs: &[ExprId]) {
        // Same as the Prod arm of write_node for a positive coefficient.
        let (num, den): (Vec<ExprId>, Vec<ExprId>) = fs.iter().partition(|f| {
            !matches!(self.node(**f), Node::Pow(_, x) if self.as_number(*x).is_some_and(|n| n.is_negative()))
        });
        let (cn, cd) = match c {
            Number::Rational { num: a, den: b } => (a, b),
            _ => (0, 1),
        };
        let mut first = true;
        if let Number::Float(_) = c {
            // A float 1 before divisors only (`1.0f/x`) must still print.
            if !c.is_one() || num.is_empty() {
                Self::write_number(out, c);
                first = false;
            }
        } else if cn != 1 || num.is_empty() {
            let _ = write!(out, "{cn}");
            first = false;
        }
        self.write_factors(out, first, &num);
        if cd != 1 {
            let _ = write!(out, "/{cd}");
        }
        for f in &den {
            out.push('/');
            if let Node::Pow(b, x) = self.node(*f) {
                let n = -self.as_number(*x).unwrap_or(Number::MINUS_ONE);
                self.write_divisor(out, *b, n);
            }
        }
    }

    /// Writes the divisor `b^n` after a `/`: `b`, or `(b^n)`.
    fn write_divisor(&self, out: &mut String, b: ExprId, n: Number) {
        if n.is_one() {
            self.write_expr(out, b, Prec::Atom);
        } else {
            out.push('(');
            self.write_pow(out, b, n);
            out.push(')');
        }
    }

    /// Writes `factors` joined by `*` (preceded by one unless `first`:
    /// nothing written yet); whether nothing has been written still.
    fn write_factors(&self, out: &mut String, mut first: bool, factors: &[ExprId]) -> bool {
        for f in factors {
            if !first {
                out.push('*');
            }
            self.write_expr(out, *f, Prec::Pow);
            first = false;
        }
        first
    }

    fn split_sign_ref(&self, e: ExprId) -> (bool, ExprId) {
        match self.node(e) {
            Node::Num(n) if n.is_negative() => (true, e),
            Node::Prod(c, _) if c.is_negative() => (true, e),
            _ => (false, e),
        }
    }

    /// Parses the text form. Unknown names become free symbols; calls must
    /// name a built-in function, `sqrt`, or a declared user function.
    pub fn parse_text(&mut self, text: &str) -> Result<ExprId, String> {
        let tokens = tokenize(text)?;
        let mut p = Parser {
            tokens,
            pos: 0,
            arena: self,
        };
        let e = p.expr()?;
        if p.pos != p.tokens.len() {
            return Err(format!("unexpected `{}`", p.tokens[p.pos].text()));
        }
        Ok(e)
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Num(Number),
    Name(String),
    Op(char),
}

impl Tok {
    fn text(&self) -> String {
        match self {
            Tok::Num(n) => n.to_string(),
            Tok::Name(s) => s.clone(),
            Tok::Op(c) => c.to_string(),
        }
    }
}

fn tokenize(text: &str) -> Result<Vec<Tok>, String> {
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    let mut out = Vec::new();
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let start = i;
            while i < chars.len()
                && (chars[i].is_ascii_digit()
                    || chars[i] == '.'
                    || ((chars[i] == 'e' || chars[i] == 'E')
                        && i + 1 < chars.len()
                        && (chars[i + 1].is_ascii_digit() || chars[i + 1] == '-')))
            {
                if (chars[i] == 'e' || chars[i] == 'E') && chars[i + 1] == '-' {
                    i += 1;
                }
                i += 1;
            }
            let s: String = chars[start..i].iter().collect();
            if i < chars.len() && chars[i] == 'f' {
                i += 1;
                let v: f64 = s.parse().map_err(|_| format!("bad number `{s}`"))?;
                out.push(Tok::Num(Number::float(v).ok_or("NaN")?));
            } else {
                out.push(Tok::Num(
                    Number::parse_decimal(&s).ok_or_else(|| format!("bad number `{s}`"))?,
                ));
            }
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push(Tok::Name(chars[start..i].iter().collect()));
        } else if "+-*/^(),".contains(c) {
            out.push(Tok::Op(c));
            i += 1;
        } else {
            return Err(format!("unexpected character `{c}`"));
        }
    }
    Ok(out)
}

struct Parser<'a> {
    tokens: Vec<Tok>,
    pos: usize,
    arena: &'a mut Arena,
}

/// A binary operation of the arena, joining two operands.
type Join = fn(&mut Arena, ExprId, ExprId) -> ExprId;

impl Parser<'_> {
    fn peek_op(&self, c: char) -> bool {
        self.tokens.get(self.pos) == Some(&Tok::Op(c))
    }

    fn expect(&mut self, c: char) -> Result<(), String> {
        if self.peek_op(c) {
            self.pos += 1;
            Ok(())
        } else {
            Err(format!("expected `{c}`"))
        }
    }

    fn expr(&mut self) -> Result<ExprId, String> {
        self.left_assoc(Self::term, [('+', Arena::add), ('-', Arena::sub)])
    }

    fn term(&mut self) -> Result<ExprId, String> {
        self.left_assoc(Self::unary, [('*', Arena::mul), ('/', Arena::div)])
    }

    /// Operands read by `operand`, joined left to right by either of two
    /// operators of one precedence level.
    fn left_assoc(
        &mut self,
        operand: fn(&mut Self) -> Result<ExprId, String>,
        operators: [(char, Join); 2],
    ) -> Result<ExprId, String> {
        let mut acc = operand(self)?;
        while let Some(&(_, join)) = operators.iter().find(|(op, _)| self.peek_op(*op)) {
            self.pos += 1;
            let rhs = operand(self)?;
            acc = join(self.arena, acc, rhs);
        }
        Ok(acc)
    }

    fn unary(&mut self) -> Result<ExprId, String> {
        if self.peek_op('-') {
            self.pos += 1;
            let e = self.unary()?;
            return Ok(self.arena.neg(e));
        }
        if self.peek_op('+') {
            self.pos += 1;
            return self.unary();
        }
        self.power()
    }

    fn power(&mut self) -> Result<ExprId, String> {
        let base = self.atom()?;
        if self.peek_op('^') {
            self.pos += 1;
            let e = self.unary()?;
            return Ok(self.arena.pow(base, e));
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<ExprId, String> {
        let tok = self
            .tokens
            .get(self.pos)
            .cloned()
            .ok_or_else(|| "unexpected end of expression".to_string())?;
        self.pos += 1;
        match tok {
            Tok::Num(n) => Ok(self.arena.num(n)),
            Tok::Op('(') => {
                let e = self.expr()?;
                self.expect(')')?;
                Ok(e)
            }
            Tok::Name(name) => {
                if self.peek_op('(') {
                    self.pos += 1;
                    let mut args = Vec::new();
                    if !self.peek_op(')') {
                        loop {
                            args.push(self.expr()?);
                            if self.peek_op(',') {
                                self.pos += 1;
                            } else {
                                break;
                            }
                        }
                    }
                    self.expect(')')?;
                    if name == "sqrt" && args.len() == 1 {
                        return Ok(self.arena.sqrt(args[0]));
                    }
                    let f = Func::builtin(&name)
                        .or_else(|| self.arena.user_fn_named(&name).map(Func::User))
                        .ok_or_else(|| format!("unknown function `{name}`"))?;
                    return Ok(self.arena.func(f, &args));
                }
                let s = match self.arena.symbol_named(&name) {
                    Some(s) => s,
                    None => self
                        .arena
                        .add_symbol(&name, SymbolKind::Free)
                        .map_err(|e| e.to_string())?,
                };
                Ok(self.arena.sym(s))
            }
            Tok::Op(c) => Err(format!("unexpected `{c}`")),
        }
    }
}
