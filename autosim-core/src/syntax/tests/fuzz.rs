//! No input makes the parser panic: random token soups, random mutations of
//! the satellite model, and pathological nesting.

use proptest::prelude::*;

use super::satellite::SATELLITE;
use crate::diag::SourceFile;
use crate::syntax::kw::ITEM_STARTS;
use crate::syntax::{parse_source, parse_tokens};

/// Words the soups are made of, besides the item keywords.
const VOCAB: &[&str] = &[
    "fn",
    "sub",
    "state",
    "output",
    "in",
    "at",
    "B",
    "N",
    "x",
    "q",
    "u",
    "all",
    "type",
    "self",
    "_",
    "r#x",
    "0",
    "1",
    "2.5",
    "1e-3",
    "0x1F",
    "7u8",
    "1.",
    "\"bus\"",
    "b\"x\"",
    "'a'",
    "'a",
    ";",
    ",",
    ":",
    "::",
    "=",
    "==",
    "+",
    "-",
    "*",
    "/",
    "^",
    "**",
    ".",
    "..",
    "->",
    "#",
    "!",
    "@",
    "$",
    "?",
    "&",
    "|",
    "<",
    ">",
    "%",
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    "/// doc",
    "//! inner",
    "/* c */",
    "\n",
    "\t",
    "°",
    "\\",
    "\u{0}",
    "\u{feff}",
    "🚀",
    "\"",
    "/*",
    "[N m/rad]",
    "[m/s^2]",
    "{ parent: B, rotate: 3 }",
    "diag(1, 2, 3)",
    "#[doc = \"x\"]",
    "#[derive(Debug)]",
];

/// The item keywords and [`VOCAB`].
fn vocab() -> Vec<&'static str> {
    ITEM_STARTS.iter().chain(VOCAB).copied().collect()
}

/// Parses as a file and (if it lexes) as tokens; renders any diagnostics.
fn parse_everything(text: &str) {
    let file = SourceFile::new("fuzz.sim", text);
    if let Err(diags) = parse_source(&file) {
        assert!(!diags.is_empty());
        let _ = diags.render(&file);
        let _ = diags.to_syn_error();
    }
    if let Ok(tokens) = text.parse::<proc_macro2::TokenStream>() {
        let _ = parse_tokens(tokens).map_err(|diags| diags.to_syn_error());
    }
}

fn floor_char_boundary(text: &str, at: usize) -> usize {
    let mut at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn token_soup_never_panics(words in prop::collection::vec(0..vocab().len(), 0..80)) {
        let vocab = vocab();
        let text: Vec<&str> = words.iter().map(|&i| vocab[i]).collect();
        parse_everything(&text.join(" "));
        parse_everything(&text.concat());
    }

    #[test]
    fn mutated_satellite_never_panics(
        edits in prop::collection::vec((0..SATELLITE.len(), 0usize..40, 0..vocab().len(), 0u8..3), 1..6)
    ) {
        let mut text = SATELLITE.to_string();
        for (at, len, word, kind) in edits {
            let start = floor_char_boundary(&text, at);
            let end = floor_char_boundary(&text, start + len);
            match kind {
                0 => text.replace_range(start..end, ""),
                1 => text.insert_str(start, vocab()[word]),
                _ => text.replace_range(start..end, vocab()[word]),
            }
        }
        parse_everything(&text);
    }
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    let deep = |open: &str, close: &str, n: usize| {
        format!("model M; let x = {}1{};", open.repeat(n), close.repeat(n))
    };
    for text in [
        deep("(", ")", 5000),
        deep("[", "]", 5000),
        deep("f(", ")", 5000),
        format!("model M; let x = {}1;", "-".repeat(5000)),
        format!("model M; let x = 1{};", "^1".repeat(5000)),
        format!("model M; let x = 1{};", "+1".repeat(5000)),
        format!("model M; {}", "{".repeat(5000)),
    ] {
        parse_everything(&text);
    }
    // Moderate nesting is fine.
    let ok = format!("model M; let x = {}1{};", "(".repeat(30), ")".repeat(30));
    assert!(parse_source(&SourceFile::new("m.sim", ok)).is_ok());
}
