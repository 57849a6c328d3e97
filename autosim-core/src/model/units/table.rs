//! The units a model may write, and how unit text (`N m/rad`, `kg m^2`,
//! `km/h`) reads: a [`UnitMeaning`] is a dimension and the factor that
//! turns a number in that unit into the coherent SI unit (the unit the
//! generated code computes in): 1 for `N`, π/180 for `deg`, 1e-3 for `mm`.

use super::dim::{Dim, Ratio};
use std::f64::consts::PI;

/// What a unit means: its dimension and its factor to the coherent SI
/// unit of that dimension.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitMeaning {
    /// The dimension.
    pub dim: Dim,
    /// The value of one of this unit in the coherent SI unit (`deg`:
    /// π/180; `N`: 1).
    pub factor: f64,
}

impl UnitMeaning {
    /// True when the unit is coherent: a number in it is the number in
    /// SI units (no factor).
    pub fn is_coherent(&self) -> bool {
        self.factor == 1.0
    }
}

/// One named unit: its symbol, exponents over kg, m, s, A, K, mol, cd,
/// rad, its factor, whether SI prefixes apply, and what it is.
pub struct NamedUnit {
    /// The symbol written in brackets.
    pub symbol: &'static str,
    /// Exponents over [`super::dim::BASES`].
    pub exponents: [i64; 8],
    /// The value of one of it in coherent SI units.
    pub factor: f64,
    /// Whether `k`, `m`, ... may precede it.
    pub prefixable: bool,
    /// Its name, for the documentation.
    pub name: &'static str,
}

const fn unit(
    symbol: &'static str,
    exponents: [i64; 8],
    factor: f64,
    prefixable: bool,
    name: &'static str,
) -> NamedUnit {
    NamedUnit {
        symbol,
        exponents,
        factor,
        prefixable,
        name,
    }
}

/// Every unit a model may write (docs/language.md prints this table).
pub const UNITS: &[NamedUnit] = &[
    unit("kg", [1, 0, 0, 0, 0, 0, 0, 0], 1.0, false, "kilogram"),
    unit("g", [1, 0, 0, 0, 0, 0, 0, 0], 1e-3, true, "gram"),
    unit("m", [0, 1, 0, 0, 0, 0, 0, 0], 1.0, true, "metre"),
    unit("s", [0, 0, 1, 0, 0, 0, 0, 0], 1.0, true, "second"),
    unit("A", [0, 0, 0, 1, 0, 0, 0, 0], 1.0, true, "ampere"),
    unit("K", [0, 0, 0, 0, 1, 0, 0, 0], 1.0, true, "kelvin"),
    unit("mol", [0, 0, 0, 0, 0, 1, 0, 0], 1.0, true, "mole"),
    unit("cd", [0, 0, 0, 0, 0, 0, 1, 0], 1.0, true, "candela"),
    unit("rad", [0, 0, 0, 0, 0, 0, 0, 1], 1.0, true, "radian"),
    unit(
        "deg",
        [0, 0, 0, 0, 0, 0, 0, 1],
        PI / 180.0,
        false,
        "degree (π/180 rad)",
    ),
    unit(
        "rev",
        [0, 0, 0, 0, 0, 0, 0, 1],
        2.0 * PI,
        false,
        "revolution (2π rad)",
    ),
    unit(
        "rpm",
        [0, 0, -1, 0, 0, 0, 0, 1],
        PI / 30.0,
        false,
        "revolution per minute (π/30 rad/s)",
    ),
    unit(
        "N",
        [1, 1, -2, 0, 0, 0, 0, 0],
        1.0,
        true,
        "newton (kg m/s^2)",
    ),
    unit("J", [1, 2, -2, 0, 0, 0, 0, 0], 1.0, true, "joule (N m)"),
    unit("W", [1, 2, -3, 0, 0, 0, 0, 0], 1.0, true, "watt (J/s)"),
    unit(
        "Pa",
        [1, -1, -2, 0, 0, 0, 0, 0],
        1.0,
        true,
        "pascal (N/m^2)",
    ),
    unit("Hz", [0, 0, -1, 0, 0, 0, 0, 0], 1.0, true, "hertz (1/s)"),
    unit("C", [0, 0, 1, 1, 0, 0, 0, 0], 1.0, true, "coulomb (A s)"),
    unit("V", [1, 2, -3, -1, 0, 0, 0, 0], 1.0, true, "volt (W/A)"),
    unit("Ohm", [1, 2, -3, -2, 0, 0, 0, 0], 1.0, true, "ohm (V/A)"),
    unit(
        "L",
        [0, 3, 0, 0, 0, 0, 0, 0],
        1e-3,
        true,
        "litre (10^-3 m^3)",
    ),
    unit(
        "min",
        [0, 0, 1, 0, 0, 0, 0, 0],
        60.0,
        false,
        "minute (60 s)",
    ),
    unit(
        "h",
        [0, 0, 1, 0, 0, 0, 0, 0],
        3600.0,
        false,
        "hour (3600 s)",
    ),
    unit(
        "bar",
        [1, -1, -2, 0, 0, 0, 0, 0],
        1e5,
        false,
        "bar (10^5 Pa)",
    ),
    unit(
        "%",
        [0, 0, 0, 0, 0, 0, 0, 0],
        0.01,
        false,
        "per cent (0.01)",
    ),
];

/// The SI prefixes a prefixable unit may take: symbol and factor.
pub const PREFIXES: &[(&str, f64)] = &[
    ("G", 1e9),
    ("M", 1e6),
    ("k", 1e3),
    ("c", 1e-2),
    ("m", 1e-3),
    ("u", 1e-6),
    ("µ", 1e-6),
    ("n", 1e-9),
];

/// The meaning of one unit symbol, with or without a prefix (`mm`, `kN`).
pub fn lookup(symbol: &str) -> Option<UnitMeaning> {
    let meaning = |u: &NamedUnit, factor: f64| UnitMeaning {
        dim: Dim::of(u.exponents),
        factor: u.factor * factor,
    };
    if let Some(u) = UNITS.iter().find(|u| u.symbol == symbol) {
        return Some(meaning(u, 1.0));
    }
    PREFIXES.iter().find_map(|(prefix, factor)| {
        let rest = symbol.strip_prefix(prefix)?;
        let u = UNITS.iter().find(|u| u.symbol == rest && u.prefixable)?;
        Some(meaning(u, *factor))
    })
}

/// A mistake in unit text: what is wrong, and how to write it.
#[derive(Clone, Debug, PartialEq)]
pub struct UnitError {
    /// What is wrong.
    pub message: String,
    /// The fix.
    pub help: String,
}

impl UnitError {
    fn new(message: impl Into<String>, help: impl Into<String>) -> UnitError {
        UnitError {
            message: message.into(),
            help: help.into(),
        }
    }
}

const FORM: &str = "write units as products of symbols with powers, one `/` before the denominator: `[N m/rad]`, `[kg m^2]`, `[m/s^2]`, `[J/(kg K)]`";

/// Reads unit text as written in brackets (normalized by the parser:
/// `N m/rad`, `kg m^2`, `m/s^2`, `1/s`, `J/(kg K)`, `m^-1`, `m^(1/2)`).
pub fn parse_unit(text: &str) -> Result<UnitMeaning, UnitError> {
    let tokens = tokenize(text)?;
    let mut p = Parser { tokens, at: 0 };
    let u = p.quotient()?;
    match p.peek() {
        None => Ok(u),
        Some(Tok::Slash) => Err(UnitError::new(
            format!("`{text}` has more than one `/`"),
            "write the whole denominator after one `/`: `[m/s^2]`, `[J/(kg K)]`",
        )),
        Some(t) => Err(UnitError::new(
            format!("unexpected `{}` in the unit `{text}`", t.text()),
            FORM,
        )),
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Word(String),
    Number(String),
    Star,
    Slash,
    Caret,
    Minus,
    Open,
    Close,
}

impl Tok {
    fn text(&self) -> String {
        match self {
            Tok::Word(w) | Tok::Number(w) => w.clone(),
            Tok::Star => "*".into(),
            Tok::Slash => "/".into(),
            Tok::Caret => "^".into(),
            Tok::Minus => "-".into(),
            Tok::Open => "(".into(),
            Tok::Close => ")".into(),
        }
    }
}

fn tokenize(text: &str) -> Result<Vec<Tok>, UnitError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut k = 0;
    while k < chars.len() {
        let c = chars[k];
        let start = k;
        k += 1;
        let tok = match c {
            ' ' => continue,
            '*' | '.' if !chars.get(k).is_some_and(char::is_ascii_digit) => Tok::Star,
            '/' => Tok::Slash,
            '^' => Tok::Caret,
            '-' => Tok::Minus,
            '(' => Tok::Open,
            ')' => Tok::Close,
            c if c.is_ascii_digit() || c == '.' => {
                while k < chars.len() && (chars[k].is_ascii_digit() || chars[k] == '.') {
                    k += 1;
                }
                Tok::Number(chars[start..k].iter().collect())
            }
            c if c.is_alphabetic() || c == '%' || c == '_' => {
                while k < chars.len() && (chars[k].is_alphanumeric() || chars[k] == '_') {
                    k += 1;
                }
                Tok::Word(chars[start..k].iter().collect())
            }
            other => {
                return Err(UnitError::new(
                    format!("unexpected `{other}` in the unit `{text}`"),
                    FORM,
                ));
            }
        };
        out.push(tok);
    }
    Ok(out)
}

struct Parser {
    tokens: Vec<Tok>,
    at: usize,
}

impl Parser {
    fn peek(&self) -> Option<&Tok> {
        self.tokens.get(self.at)
    }

    fn next(&mut self) -> Option<Tok> {
        let t = self.tokens.get(self.at).cloned();
        self.at += 1;
        t
    }

    /// `product ('/' product)?`
    fn quotient(&mut self) -> Result<UnitMeaning, UnitError> {
        let up = self.product()?;
        if self.peek() != Some(&Tok::Slash) {
            return Ok(up);
        }
        self.at += 1;
        let down = self.product()?;
        let dim = up.dim.over(down.dim).ok_or_else(too_large)?;
        Ok(UnitMeaning {
            dim,
            factor: up.factor / down.factor,
        })
    }

    /// Factors side by side or joined by `*`.
    fn product(&mut self) -> Result<UnitMeaning, UnitError> {
        let mut u = self.factor()?;
        loop {
            match self.peek() {
                Some(Tok::Star) => self.at += 1,
                Some(Tok::Word(_) | Tok::Number(_) | Tok::Open) => {}
                _ => return Ok(u),
            }
            let v = self.factor()?;
            u = UnitMeaning {
                dim: u.dim.times(v.dim).ok_or_else(too_large)?,
                factor: u.factor * v.factor,
            };
        }
    }

    /// `atom ('^' exponent)?`
    fn factor(&mut self) -> Result<UnitMeaning, UnitError> {
        let u = self.atom()?;
        if self.peek() != Some(&Tok::Caret) {
            return Ok(u);
        }
        self.at += 1;
        let p = self.exponent()?;
        Ok(UnitMeaning {
            dim: u.dim.pow(p).ok_or_else(too_large)?,
            factor: u.factor.powf(p.num() as f64 / p.den() as f64),
        })
    }

    fn atom(&mut self) -> Result<UnitMeaning, UnitError> {
        match self.next() {
            Some(Tok::Word(w)) => lookup(&w).ok_or_else(|| unknown_unit(&w)),
            Some(Tok::Number(n)) if n == "1" => Ok(UnitMeaning {
                dim: Dim::ONE,
                factor: 1.0,
            }),
            Some(Tok::Open) => {
                let u = self.quotient()?;
                match self.next() {
                    Some(Tok::Close) => Ok(u),
                    _ => Err(UnitError::new("unclosed `(` in a unit", FORM)),
                }
            }
            Some(t) => Err(UnitError::new(
                format!("unexpected `{}` in a unit", t.text()),
                FORM,
            )),
            None => Err(UnitError::new("a unit ends where a symbol is needed", FORM)),
        }
    }

    /// `n`, `-n`, `(n/m)`, `(-n/m)`, or a decimal `0.5`.
    fn exponent(&mut self) -> Result<Ratio, UnitError> {
        let bad = || {
            UnitError::new(
                "a unit's power must be a number such as `2`, `-1` or `(1/2)`",
                FORM,
            )
        };
        match self.next() {
            Some(Tok::Minus) => Ok(self.exponent()?.negated()),
            Some(Tok::Number(n)) => decimal(&n).ok_or_else(bad),
            Some(Tok::Open) => {
                let sign = if self.peek() == Some(&Tok::Minus) {
                    self.at += 1;
                    -1
                } else {
                    1
                };
                let (
                    Some(Tok::Number(a)),
                    Some(Tok::Slash),
                    Some(Tok::Number(b)),
                    Some(Tok::Close),
                ) = (self.next(), self.next(), self.next(), self.next())
                else {
                    return Err(bad());
                };
                let (a, b) = (decimal(&a).ok_or_else(bad)?, decimal(&b).ok_or_else(bad)?);
                let q = a.times(b.recip().ok_or_else(bad)?).ok_or_else(bad)?;
                Ok(if sign < 0 { q.negated() } else { q })
            }
            _ => Err(bad()),
        }
    }
}

/// A decimal `2`, `0.5` as an exact ratio.
pub fn decimal(text: &str) -> Option<Ratio> {
    let (whole, frac) = text.split_once('.').unwrap_or((text, ""));
    if frac.len() > 9 || whole.len() > 9 || (whole.is_empty() && frac.is_empty()) {
        return None;
    }
    let digits = format!("{whole}{frac}");
    Ratio::new(digits.parse().ok()?, 10i64.pow(frac.len() as u32))
}

fn too_large() -> UnitError {
    UnitError::new("the powers in this unit are too large", FORM)
}

fn unknown_unit(word: &str) -> UnitError {
    let known: Vec<&str> = UNITS.iter().map(|u| u.symbol).collect();
    let help = match crate::diag::did_you_mean(word, known.iter().copied()) {
        Some(s) => {
            format!("did you mean `{s}`? The units are listed in docs/language.md, \"Units\"")
        }
        None => format!(
            "the units are {} with the prefixes G, M, k, c, m, u (µ), n (docs/language.md, \"Units\")",
            known.join(", ")
        ),
    };
    UnitError::new(format!("unknown unit `{word}`"), help)
}
