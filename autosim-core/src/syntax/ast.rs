//! The model AST: plain data, a [`Span`] on every name, key and expression.
//!
//! Names are [`Name`]s (a `String` and a [`Span`]), never `syn::Ident`, so
//! tokens lexed from a file never reach generated code. The AST is what the
//! user wrote, in source order; the resolver gives it meaning (which names
//! are bodies, what `small: all` means, which functions exist).

use std::fmt;

use crate::diag::Span;

pub use super::keys::{
    BodyKey, ConstraintKey, EventKey, ForceKey, MomentKey, MotionKey, OptionKey, SceneKey,
    SettingKey, StateKey,
};

/// A whole model: `model Name;` plus its items in source order.
#[derive(Clone, Debug)]
pub struct Model {
    /// Doc comments on the `model` item (and any `//!` inner doc comments).
    pub docs: Vec<String>,
    /// The model's name, from `model Name;`.
    pub name: Name,
    /// Every other item, in source order.
    pub items: Vec<Item>,
}

/// A top-level item other than `model Name;`.
#[derive(Clone, Debug)]
pub enum Item {
    /// `settings { threshold: 2, float: f64 }`
    Settings(Settings),
    /// `parameters { KB = 2000 [N m/rad], ... }` or `parameter g = 9.81 [m/s^2];`
    Parameters(Parameters),
    /// `body B "bus" { parent: N, rotate: [1, 2, 3], ... }`
    Body(Body),
    /// `point P "tip" in F at [0, -L8, 0];`
    Point(Point),
    /// `let r = pos(P, Q);`
    Let(Let),
    /// `force spring "boom spring" { on: P, reaction: Q, along: dir(r), magnitude: ... }`
    Force(Force),
    /// `moment boom1 { on: F, reaction: B, about: e3, magnitude: ... }`
    Moment(Moment),
    /// `gravity = -g*n3;`
    Gravity(Gravity),
    /// `input clkcmd [rad], camcmd [rad] = -0.5;`
    Inputs(Inputs),
    /// `extern fn thrust(t, axis, error);`
    ExternFn(ExternFn),
    /// `extern sub cmd(t) -> (clkcmd2 [rad], camcmd2 [rad]);`
    ExternSub(ExternSub),
    /// `state lag [N] { initial: 0, derivative: (F1 - lag)/tau }`
    State(State),
    /// `output tip_speed [m/s] = mag(vel(P));`
    Output(Output),
    /// `constraint closure { position: dot(pos(E, T), n1), dependent: q3 }`
    Constraint(Constraint),
    /// `motion drive { coordinate: q1, value: omega*t }`
    Motion(Motion),
    /// `discrete mode [1] = 0, toff [s];`
    Discrete(Discretes),
    /// `event bounce [m] { indicator: h, direction: falling, reset: { v: -e*v } }`
    Event(Event),
}

impl Item {
    /// The span of the item's keyword (through its name where there is one).
    pub fn span(&self) -> Span {
        match self {
            Item::Settings(x) => x.span,
            Item::Parameters(x) => x.span,
            Item::Body(x) => x.span,
            Item::Point(x) => x.span,
            Item::Let(x) => x.span,
            Item::Force(x) => x.span,
            Item::Moment(x) => x.span,
            Item::Gravity(x) => x.span,
            Item::Inputs(x) => x.span,
            Item::ExternFn(x) => x.span,
            Item::ExternSub(x) => x.span,
            Item::State(x) => x.span,
            Item::Output(x) => x.span,
            Item::Constraint(x) => x.span,
            Item::Motion(x) => x.span,
            Item::Discrete(x) => x.span,
            Item::Event(x) => x.span,
        }
    }
}

/// An identifier written by the user.
#[derive(Clone, Debug)]
pub struct Name {
    /// The identifier's text (raw identifiers keep their `r#`).
    pub text: String,
    /// Where it was written.
    pub span: Span,
}

/// A numeric literal, kept as written (minus `_` separators) so the core can
/// turn decimals into exact rationals. Integers and decimal floats only:
/// suffixes and `0x`/`0o`/`0b` forms are rejected by the parser.
#[derive(Clone, Debug)]
pub struct Number {
    /// Decimal text, e.g. `2000`, `1.5`, `3.1415926`, `1e-3`.
    pub text: String,
    /// Where it was written.
    pub span: Span,
}

/// A number with an optional minus sign: a parameter value or input default.
#[derive(Clone, Debug)]
pub struct Value {
    /// True when written with a leading `-`.
    pub negative: bool,
    /// The literal after the sign.
    pub number: Number,
    /// Sign and literal.
    pub span: Span,
}

/// A unit in brackets, normalized: tokens joined by single spaces, with no
/// spaces around `*`, `/` and `^` (`N m/rad`, `kg m^2`, `m/s^2`).
#[derive(Clone, Debug)]
pub struct Unit {
    /// The normalized text.
    pub text: String,
    /// The bracketed group.
    pub span: Span,
}

/// A quoted description after a name: `body B "bus"`.
#[derive(Clone, Debug)]
pub struct Label {
    /// The string's value.
    pub text: String,
    /// The string literal.
    pub span: Span,
}

/// `key: value` entries of a braced block, keys unique and checked against `K`.
#[derive(Clone, Debug)]
pub struct Options<K> {
    /// Entries in source order.
    pub entries: Vec<Opt<K>>,
    /// The braces.
    pub span: Span,
}

impl<K: OptionKey> Options<K> {
    /// The entry for `key`, if written.
    pub fn get(&self, key: K) -> Option<&Opt<K>> {
        self.entries.iter().find(|entry| entry.key == key)
    }
}

/// One `key: value` entry.
#[derive(Clone, Debug)]
pub struct Opt<K> {
    /// Which key.
    pub key: K,
    /// Where the key was written.
    pub key_span: Span,
    /// The value (the resolver interprets `[1, 2, 3]`, `diag(...)`, `all`, ...).
    pub value: Expr,
}

/// `settings { ... }`
#[derive(Clone, Debug)]
pub struct Settings {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The `settings` keyword.
    pub span: Span,
    /// The entries.
    pub options: Options<SettingKey>,
}

/// A `parameters { ... }` block, or the single form `parameter x = 1;`
/// (one entry, whose docs are the item's docs).
#[derive(Clone, Debug)]
pub struct Parameters {
    /// Doc comments on the block (empty for the single form).
    pub docs: Vec<String>,
    /// The `parameters`/`parameter` keyword.
    pub span: Span,
    /// The parameters in source order.
    pub params: Vec<Parameter>,
}

impl Parameter {
    /// The value as written (`-0.5`).
    pub fn value_text(&self) -> String {
        let sign = if self.value.negative { "-" } else { "" };
        format!("{sign}{}", self.value.number.text)
    }
}

/// `KB = 2000 [N m/rad]`
#[derive(Clone, Debug)]
pub struct Parameter {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The parameter's name.
    pub name: Name,
    /// Its default value.
    pub value: Value,
    /// Its unit, if given.
    pub unit: Option<Unit>,
}

/// A named block of options: `body B "bus" { ... }`, `force name
/// "label" { on: ..., ... }`, `moment name "label" { on: ..., ... }`.
#[derive(Clone, Debug)]
pub struct Block<K> {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The keyword through the name.
    pub span: Span,
    /// The item's name.
    pub name: Name,
    /// Optional description.
    pub label: Option<Label>,
    /// The unit of the item's value (constraints only: the unit of the
    /// residual), if given.
    pub unit: Option<Unit>,
    /// The options.
    pub options: Options<K>,
}

/// `body B "bus" { ... }`
pub type Body = Block<BodyKey>;

/// `force name "label" { on: ..., ... }`
pub type Force = Block<ForceKey>;

/// `moment name "label" { on: ..., ... }`
pub type Moment = Block<MomentKey>;

/// `constraint name "label" { position: ..., dependent: q }` or
/// `{ speed: ..., dependent: u }`
pub type Constraint = Block<ConstraintKey>;

/// `motion name "label" { coordinate: q, value: ... }`
pub type Motion = Block<MotionKey>;

/// `point P "tip" in F at [0, -L8, 0];`
#[derive(Clone, Debug)]
pub struct Point {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The `point` keyword through the name.
    pub span: Span,
    /// The point's name.
    pub name: Name,
    /// Optional description.
    pub label: Option<Label>,
    /// The body the point is fixed in.
    pub body: Name,
    /// Coordinates in that body (an expression, usually `[x, y, z]`).
    pub at: Expr,
}

/// `let r = pos(P, Q);`
#[derive(Clone, Debug)]
pub struct Let {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The `let` keyword through the name.
    pub span: Span,
    /// The name being defined.
    pub name: Name,
    /// Its value.
    pub value: Expr,
}

/// `gravity = -g*n3;`
#[derive(Clone, Debug)]
pub struct Gravity {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The `gravity` keyword.
    pub span: Span,
    /// The gravity vector.
    pub value: Expr,
}

/// `input clkcmd [rad], camcmd [rad] = -0.5;`
#[derive(Clone, Debug)]
pub struct Inputs {
    /// Doc comments (for all inputs of the item).
    pub docs: Vec<String>,
    /// The `input` keyword.
    pub span: Span,
    /// The inputs in source order.
    pub inputs: Vec<Input>,
}

/// One input variable.
#[derive(Clone, Debug)]
pub struct Input {
    /// Its name.
    pub name: Name,
    /// Its unit, if given.
    pub unit: Option<Unit>,
    /// Its default value, if given.
    pub default: Option<Value>,
}

/// `extern fn thrust(t [s], axis, error [rad]) -> [N];`
#[derive(Clone, Debug)]
pub struct ExternFn {
    /// Doc comments.
    pub docs: Vec<String>,
    /// `extern` through the name.
    pub span: Span,
    /// The function's name.
    pub name: Name,
    /// Formal argument names (they give the arity).
    pub params: Vec<Name>,
    /// The unit of each argument, if given (`speed [m/s]`).
    pub param_units: Vec<Option<Unit>>,
    /// The unit of the result, if given (`-> [N]`; dimensionless without).
    pub result_unit: Option<Unit>,
}

/// `extern sub cmd(t) -> (clkcmd2 [rad], camcmd2 [rad]);`
#[derive(Clone, Debug)]
pub struct ExternSub {
    /// Doc comments.
    pub docs: Vec<String>,
    /// `extern` through the name.
    pub span: Span,
    /// The subroutine's name.
    pub name: Name,
    /// Actual argument expressions.
    pub args: Vec<Expr>,
    /// Named outputs.
    pub outputs: Vec<SubOutput>,
}

/// One output of an `extern sub`.
#[derive(Clone, Debug)]
pub struct SubOutput {
    /// Its name.
    pub name: Name,
    /// Its unit, if given.
    pub unit: Option<Unit>,
}

/// `state lag [N] { initial: 0, derivative: (F1 - lag)/tau }`
#[derive(Clone, Debug)]
pub struct State {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The `state` keyword through the name.
    pub span: Span,
    /// The state variable's name.
    pub name: Name,
    /// Its unit, if given.
    pub unit: Option<Unit>,
    /// The options.
    pub options: Options<StateKey>,
}

/// `discrete mode [1] = 0, toff [s];`: the same shape as an `input`
/// item (a name, a unit, an initial value that defaults to 0).
pub type Discretes = Inputs;

/// `event bounce [m] "impact" { indicator: h, direction: falling,
/// reset: { v: -e*v }, set: { mode: 1 }, stop: false }`
#[derive(Clone, Debug)]
pub struct Event {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The `event` keyword through the name.
    pub span: Span,
    /// The event's name.
    pub name: Name,
    /// The unit of the indicator, if given.
    pub unit: Option<Unit>,
    /// Optional description.
    pub label: Option<Label>,
    /// `indicator`, `direction` and `stop` (the values of `set` and
    /// `reset` are in [`Event::set`] and [`Event::reset`]).
    pub options: Options<EventKey>,
    /// `set: { name: value, ... }`: the key's span and the assignments.
    pub set: Option<(Span, Vec<Assignment>)>,
    /// `reset: { name: value, ... }`: the key's span and the assignments.
    pub reset: Option<(Span, Vec<Assignment>)>,
}

/// `name: value` in an event's `set` or `reset`.
#[derive(Clone, Debug)]
pub struct Assignment {
    /// The variable given a value.
    pub target: Name,
    /// Its new value (an expression of the values before the event).
    pub value: Expr,
}

/// `output clock_angle [rad] = q(C);`
#[derive(Clone, Debug)]
pub struct Output {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The `output` keyword through the name.
    pub span: Span,
    /// The output's name.
    pub name: Name,
    /// Its unit, if given.
    pub unit: Option<Unit>,
    /// Its value.
    pub value: Expr,
}

/// An expression, as written (parentheses kept as [`Expr::Paren`]).
#[derive(Clone, Debug)]
pub enum Expr {
    /// `2000`, `1.5`
    Number(Number),
    /// `KB`, `t`, `all`
    Name(Name),
    /// `B.cm`, `B.origin`, `B.1`
    Member {
        /// The expression before the dot.
        base: Box<Expr>,
        /// The name or index after it.
        member: Member,
        /// Whole node.
        span: Span,
    },
    /// `f(a, b)`: only a plain name can be called.
    Call {
        /// The function's name (not resolved by the parser).
        func: Name,
        /// The arguments.
        args: Vec<Expr>,
        /// Whole node.
        span: Span,
    },
    /// `-x`, `+x`
    Unary {
        /// Which sign.
        op: UnOp,
        /// The operand.
        operand: Box<Expr>,
        /// Whole node.
        span: Span,
    },
    /// `a + b`, `a - b`, `a * b`, `a / b`, `a ^ b`
    Binary {
        /// Which operator.
        op: BinOp,
        /// Left operand.
        lhs: Box<Expr>,
        /// Right operand.
        rhs: Box<Expr>,
        /// The operator token.
        op_span: Span,
        /// Whole node.
        span: Span,
    },
    /// `[a, b, c]`, nested for matrices.
    List {
        /// The elements.
        items: Vec<Expr>,
        /// The brackets.
        span: Span,
    },
    /// `2.5 [mm]`: a number in a unit.
    Quantity {
        /// The number.
        number: Number,
        /// Its unit.
        unit: Unit,
        /// Number and unit.
        span: Span,
    },
    /// `(k*x) as [N]`: the value of `inner`, taken to be in `unit`
    /// without checking (the escape from the unit check).
    As {
        /// The expression.
        inner: Box<Expr>,
        /// The unit it is taken to have.
        unit: Unit,
        /// Expression and unit.
        span: Span,
    },
    /// `(a)`
    Paren {
        /// The expression inside.
        inner: Box<Expr>,
        /// The parentheses.
        span: Span,
    },
}

/// What follows the dot of a member access.
#[derive(Clone, Debug)]
pub enum Member {
    /// `B.cm`
    Name(Name),
    /// `B.1`
    Index {
        /// The index as written.
        index: u32,
        /// Where it was written.
        span: Span,
    },
}

/// A prefix operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnOp {
    /// `-x`
    Neg,
    /// `+x`
    Plus,
}

/// A binary operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^` (power, right-associative, binds tighter than unary minus)
    Pow,
}

impl BinOp {
    /// The operator as written.
    pub fn as_str(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Pow => "^",
        }
    }
}

impl Expr {
    /// The span of the whole expression.
    pub fn span(&self) -> Span {
        match self {
            Expr::Number(number) => number.span,
            Expr::Name(name) => name.span,
            Expr::Member { span, .. }
            | Expr::Call { span, .. }
            | Expr::Unary { span, .. }
            | Expr::Binary { span, .. }
            | Expr::List { span, .. }
            | Expr::Quantity { span, .. }
            | Expr::As { span, .. }
            | Expr::Paren { span, .. } => *span,
        }
    }
}

/// Prints the expression back as model text (parentheses as written,
/// spaces around `+` and `-` only).
impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Expr::Number(number) => f.write_str(&number.text),
            Expr::Name(name) => f.write_str(&name.text),
            Expr::Member {
                base,
                member: Member::Name(name),
                ..
            } => write!(f, "{base}.{}", name.text),
            Expr::Member {
                base,
                member: Member::Index { index, .. },
                ..
            } => write!(f, "{base}.{index}"),
            Expr::Call { func, args, .. } => {
                write!(f, "{}(", func.text)?;
                write_list(f, args)?;
                f.write_str(")")
            }
            Expr::Unary {
                op: UnOp::Neg,
                operand,
                ..
            } => write!(f, "-{operand}"),
            Expr::Unary {
                op: UnOp::Plus,
                operand,
                ..
            } => write!(f, "+{operand}"),
            Expr::Binary {
                op: op @ (BinOp::Add | BinOp::Sub),
                lhs,
                rhs,
                ..
            } => {
                write!(f, "{lhs} {} {rhs}", op.as_str())
            }
            Expr::Binary { op, lhs, rhs, .. } => write!(f, "{lhs}{}{rhs}", op.as_str()),
            Expr::List { items, .. } => {
                f.write_str("[")?;
                write_list(f, items)?;
                f.write_str("]")
            }
            Expr::Paren { inner, .. } => write!(f, "({inner})"),
            Expr::Quantity { number, unit, .. } => write!(f, "{} [{}]", number.text, unit.text),
            Expr::As { inner, unit, .. } => write!(f, "{inner} as [{}]", unit.text),
        }
    }
}

fn write_list(f: &mut fmt::Formatter<'_>, items: &[Expr]) -> fmt::Result {
    for (i, item) in items.iter().enumerate() {
        if i > 0 {
            f.write_str(", ")?;
        }
        write!(f, "{item}")?;
    }
    Ok(())
}
