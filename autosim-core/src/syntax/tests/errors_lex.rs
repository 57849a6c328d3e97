//! Errors in the text itself: characters and delimiters the lexer refuses,
//! bad units and numbers, stray tokens.

use super::errors::check;

#[test]
fn bad_units() {
    // `//` in a unit starts a comment: the `]` is never seen, whether the
    // file ends there or another delimiter closes first.
    let expect = r#"
test.sim:2:22: error: `//` starts a comment, which hides the rest of the line: the `[` before it is never closed
  |
2 | parameters { k = 1 [N//m] }
  |                      ^^
  = help: in a unit, write one `/` before the denominator: `[N/m]`, `[N/(m s)]`, `[m/s^2]`
"#;
    check("model M;\nparameters { k = 1 [N//m] }", expect);
    check(
        "model M;\nparameters { k = 1 [N//m] }\nbody B { translate: 1 }",
        expect,
    );
    check(
        "model M;\nparameters { KB = 2000 [N m/rad, DB = 10 }",
        r#"
test.sim:2:42: error: unexpected closing delimiter `}`
  |
2 | parameters { KB = 2000 [N m/rad, DB = 10 }
  |                                          ^
  = help: close it with `]` first
  = note: the innermost open delimiter is the `[` at 2:24
"#,
    );
    check(
        "model M;\nparameters { L1 = 1.5 (m), L2 = 2 }",
        r#"
test.sim:2:23: error: expected a unit, `,` or the end after the value of `L1`, found `(`
  |
2 | parameters { L1 = 1.5 (m), L2 = 2 }
  |                       ^
  = help: units are written in brackets: `[m]`
"#,
    );
    check(
        "model M;\ninput a [N, m];",
        r#"
test.sim:2:11: error: unexpected `,` in a unit
  |
2 | input a [N, m];
  |           ^
  = help: write units like `[N m/rad]`, `[kg m^2]` or `[m/s^2]`
"#,
    );
    check(
        "model M;\ninput a [];",
        r#"
test.sim:2:9: error: empty unit
  |
2 | input a [];
  |         ^^
  = help: leave out the brackets for a quantity without a unit
"#,
    );
}

#[test]
fn unterminated_and_unbalanced_delimiters() {
    check(
        "model M;\nbody B { parent: N",
        r#"
test.sim:2:8: error: unclosed delimiter `{`
  |
2 | body B { parent: N
  |        ^
  = help: add the matching `}`
"#,
    );
    check(
        "model M;\nlet x = ",
        r#"
test.sim:2:8: error: expected an expression, found end of input
  |
2 | let x =
  |        ^
"#,
    );
    check(
        "model M;\n)",
        r#"
test.sim:2:1: error: unexpected closing delimiter `)`
  |
2 | )
  | ^
  = help: there is no open delimiter for it to close
"#,
    );
    check(
        "model M;\nlet x = [1, 2;",
        r#"
test.sim:2:9: error: unclosed delimiter `[`
  |
2 | let x = [1, 2;
  |         ^
  = help: add the matching `]`
"#,
    );
}

#[test]
fn garbage_tokens() {
    check(
        "model M; @@ $ body B {}",
        r#"
test.sim:1:10: error: expected an item, found `@`
  |
1 | model M; @@ $ body B {}
  |          ^
  = note: items start with one of: model, settings, parameters, parameter, body, point, let, force, moment, gravity, input, extern, state, output, constraint, motion, discrete, event
"#,
    );
}

#[test]
fn weird_characters() {
    check(
        "model M; \u{0}",
        "test.sim:1:10: error: unexpected character `\\0`\n  |\n1 | model M; \u{0}\n  |          ^\n  = help: model files are made of Rust tokens: names, numbers, strings and punctuation\n",
    );
    check(
        "model M; \\",
        r#"
test.sim:1:10: error: unexpected character `\\`
  |
1 | model M; \
  |          ^
  = help: model files are made of Rust tokens: names, numbers, strings and punctuation
"#,
    );
    check(
        "model M; x°",
        r#"
test.sim:1:11: error: unexpected character `°`
  |
1 | model M; x°
  |           ^
  = help: model files are made of Rust tokens: names, numbers, strings and punctuation
"#,
    );
    check(
        "model M; \"abc",
        r#"
test.sim:1:10: error: unterminated or invalid string literal
  |
1 | model M; "abc
  |          ^
"#,
    );
    check(
        "model M; 'a",
        r#"
test.sim:1:10: error: expected an item, found `'`
  |
1 | model M; 'a
  |          ^
  = note: items start with one of: model, settings, parameters, parameter, body, point, let, force, moment, gravity, input, extern, state, output, constraint, motion, discrete, event
"#,
    );
    check(
        "model M; /* abc",
        r#"
test.sim:1:10: error: unterminated block comment
  |
1 | model M; /* abc
  |          ^
"#,
    );
    check(
        "model M; 🚀",
        r#"
test.sim:1:10: error: unexpected character `🚀`
  |
1 | model M; 🚀
  |          ^
  = help: model files are made of Rust tokens: names, numbers, strings and punctuation
"#,
    );
}

#[test]
fn numbers_are_plain_decimals() {
    check(
        "model M;\nparameter a = 2f64;\nparameter b = 0x10;",
        r#"
test.sim:2:15: error: numbers cannot have a type suffix (`f64`)
  |
2 | parameter a = 2f64;
  |               ^^^^
  = help: write `2`; the float type is chosen in `settings`
test.sim:3:15: error: only decimal numbers are allowed
  |
3 | parameter b = 0x10;
  |               ^^^^
  = help: write `16`
"#,
    );
}
