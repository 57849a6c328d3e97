//! Mutations of model texts (tokens and lines deleted, duplicated, swapped;
//! numbers and names changed) and character soups.

use super::Rng;
use super::vocab::ODD_NAMES;

/// Splits text into tokens: identifiers and numbers (with `.`), whitespace
/// runs, and single other characters. Concatenating the pieces gives the text.
pub(crate) fn pieces(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut chars = text.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        let word = |c: char| c.is_alphanumeric() || c == '_' || c == '.';
        let mut end = i + c.len_utf8();
        if word(c) || c.is_whitespace() {
            let same = |d: char| if word(c) { word(d) } else { d.is_whitespace() };
            while let Some(&(j, d)) = chars.peek() {
                if !same(d) {
                    break;
                }
                end = j + d.len_utf8();
                chars.next();
            }
        }
        out.push(&text[start.max(i)..end]);
        start = end;
    }
    out
}

/// Replacements for numbers.
const NUMBER_SWAPS: &[&str] = &[
    "0",
    "-0",
    "0.0",
    "-1",
    "1e38",
    "1e39",
    "1e-38",
    "1e-39",
    "1e308",
    "1e309",
    "1e-320",
    "99999999999999999999999999999999999999999",
    "0.00000000000000000000000000000000000000001",
    "-99999",
    "3",
    "4",
    "-3",
    "1000000",
    "170141183460469231731687303715884105728",
    "1.5",
    "2.",
    "1e",
    "0x10",
    "1u8",
    "1f32",
];

/// One to five random edits of `base`.
pub fn mutate(rng: &mut Rng, base: &str) -> String {
    let mut text = base.to_string();
    for _ in 0..rng.range(1, 5) {
        text = mutate_once(rng, &text);
    }
    text
}

fn mutate_once(rng: &mut Rng, text: &str) -> String {
    let mut toks: Vec<String> = pieces(text).into_iter().map(String::from).collect();
    let significant: Vec<usize> = (0..toks.len())
        .filter(|&i| !toks[i].trim().is_empty())
        .collect();
    if significant.is_empty() {
        return format!("{text}{}", rng.pick(NUMBER_SWAPS));
    }
    let at = *rng.pick(&significant);
    let is_number = |s: &str| s.starts_with(|c: char| c.is_ascii_digit());
    let is_ident = |s: &str| s.starts_with(|c: char| c.is_alphabetic() || c == '_');
    match rng.below(12) {
        0 => toks[at].clear(),
        1 => {
            let t = toks[at].clone();
            toks.insert(at, t);
        }
        2 => {
            let other = *rng.pick(&significant);
            toks.swap(at, other);
        }
        3..=5 => {
            // A number changed (the nearest number after `at`).
            if let Some(i) = (at..toks.len()).chain(0..at).find(|&i| is_number(&toks[i])) {
                toks[i] = rng.pick(NUMBER_SWAPS).to_string();
            }
        }
        6 | 7 => {
            // An identifier renamed: everywhere or once, to another one in the
            // file, a fresh one or an odd one.
            if let Some(i) = (at..toks.len()).chain(0..at).find(|&i| is_ident(&toks[i])) {
                let old = toks[i].clone();
                let idents: Vec<&String> = toks.iter().filter(|t| is_ident(t)).collect();
                let new = match rng.below(3) {
                    0 => (*rng.pick(&idents)).clone(),
                    1 => format!("{old}2"),
                    _ => rng.pick(ODD_NAMES).to_string(),
                };
                if rng.chance(50) {
                    for t in toks.iter_mut().filter(|t| **t == old) {
                        *t = new.clone();
                    }
                } else {
                    toks[i] = new;
                }
            }
        }
        8 => {
            let insert = *rng.pick(&[
                "(", ")", "[", "]", "{", "}", ",", ";", ":", "=", "-", "*", "^", ".", "N", "all",
                "body", "let", "0", "1e39", "dxdt(", "B.cm", "q(B)", "\"", "//", "/*", "///",
            ]);
            toks.insert(at, insert.to_string());
        }
        _ => {
            // Line edits.
            let mut lines: Vec<String> = text.lines().map(String::from).collect();
            let i = rng
                .below(lines.len().max(1))
                .min(lines.len().saturating_sub(1));
            if lines.is_empty() {
                return String::new();
            }
            match rng.below(3) {
                0 => {
                    lines.remove(i);
                }
                1 => {
                    let l = lines[i].clone();
                    lines.insert(i, l);
                }
                _ => {
                    let j = rng.below(lines.len());
                    lines.swap(i, j);
                }
            }
            return lines.join("\n");
        }
    }
    toks.concat()
}

// ---------------------------------------------------------------------------
// Soups.

const SOUP_WORDS: &[&str] = &[
    "model",
    "M",
    ";",
    "body",
    "B",
    "{",
    "}",
    "parent",
    ":",
    "N",
    ",",
    "rotate",
    "translate",
    "1",
    "[",
    "]",
    "mass",
    "inertia",
    "diag",
    "(",
    ")",
    "force",
    "moment",
    "on",
    "vector",
    "n1",
    "let",
    "=",
    "point",
    "in",
    "at",
    "output",
    "state",
    "input",
    "extern",
    "fn",
    "sub",
    "->",
    "gravity",
    "constraint",
    "position",
    "speed",
    "dependent",
    "motion",
    "coordinate",
    "value",
    "-",
    "+",
    "*",
    "/",
    "^",
    "q",
    "u",
    "dot",
    "pos",
    "vel",
    "dxdt",
    "1e39",
    "0",
    "settings",
    "threshold",
    "float",
    "f32",
    "small",
    "all",
    "parameters",
    "parameter",
    "\"x\"",
    "///",
    "\n",
    ".",
    "cm",
    "t",
];

pub(crate) fn soup(rng: &mut Rng) -> String {
    let n = rng.range(0, 120);
    match rng.below(3) {
        0 => {
            let bytes: Vec<u8> = (0..n).map(|_| rng.next_u64() as u8).collect();
            String::from_utf8_lossy(&bytes).into_owned()
        }
        1 => (0..n)
            .map(|_| match rng.below(10) {
                0 => char::from_u32(rng.below(0x11_0000) as u32).unwrap_or('\u{fffd}'),
                1 => *rng.pick(&['\u{0}', '\u{feff}', '\u{202e}', 'é', '°', '🚀', '\r', '\t']),
                _ => (b' ' + rng.below(95) as u8) as char,
            })
            .collect(),
        _ => {
            let mut s = String::from(if rng.chance(70) { "model M; " } else { "" });
            for _ in 0..n {
                s.push_str(rng.pick::<&str>(SOUP_WORDS));
                s.push(' ');
            }
            s
        }
    }
}
