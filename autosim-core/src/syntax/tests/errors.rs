//! Every syntax error: message, help and `line:col`, as a user sees them
//! (the file is `test.sim`; the expected text is the rendered diagnostics).

use super::parse_file;

/// Parses `input` as a file and compares the rendered diagnostics
/// (a leading newline in `expect` is ignored).
pub(super) fn check(input: &str, expect: &str) {
    let rendered = match parse_file(input) {
        Ok(_) => "OK\n".to_string(),
        Err(rendered) => rendered,
    };
    let expect = expect.strip_prefix('\n').unwrap_or(expect);
    assert_eq!(rendered, expect, "\ninput: {input:?}\n--- got:\n{rendered}");
}

#[test]
fn missing_semicolon_is_reported_after_the_item() {
    check(
        "model M\nbody B { }",
        r#"
test.sim:1:8: error: expected `;` after the model's name
  |
1 | model M
  |        ^
"#,
    );
    check(
        "model M;\nlet x = a b;\nlet y = 1;",
        r#"
test.sim:2:11: error: expected `;` after the value of `x`, found `b`
  |
2 | let x = a b;
  |           ^
"#,
    );
}

#[test]
fn unknown_keys_list_the_valid_ones_and_suggest() {
    check(
        "model M;\nbody C \"clock\" { parent: B, rotat: 3 }",
        r#"
test.sim:2:29: error: unknown body option `rotat`
  |
2 | body C "clock" { parent: B, rotat: 3 }
  |                             ^^^^^
  = help: did you mean `rotate`?
  = note: the body options are: parent, joint, translate, rotate, reference, small, lock, mass, inertia, cm, q, u, initial, initial_speeds
"#,
    );
    check(
        "model M;\nforce f { on: P, along: 1, magnitde: 2 }",
        r#"
test.sim:2:28: error: unknown force option `magnitde`
  |
2 | force f { on: P, along: 1, magnitde: 2 }
  |                            ^^^^^^^^
  = help: did you mean `magnitude`?
  = note: the force options are: on, reaction, vector, along, magnitude
"#,
    );
    check(
        "model M;\nstate s [N] { initial: 0, derivativ: 1 }\nsettings { treshold: 2 }\nmoment m { on: B, abut: e3 }",
        r#"
test.sim:2:27: error: unknown state option `derivativ`
  |
2 | state s [N] { initial: 0, derivativ: 1 }
  |                           ^^^^^^^^^
  = help: did you mean `derivative`?
  = note: the state options are: initial, derivative
test.sim:3:12: error: unknown setting `treshold`
  |
3 | settings { treshold: 2 }
  |            ^^^^^^^^
  = help: did you mean `threshold`?
  = note: the settings are: threshold, float, outputs, linearize, formulation, lanes
test.sim:4:19: error: unknown moment option `abut`
  |
4 | moment m { on: B, abut: e3 }
  |                   ^^^^
  = help: did you mean `about`?
  = note: the moment options are: on, reaction, vector, about, magnitude
"#,
    );
}

#[test]
fn duplicate_keys() {
    check(
        "model M;\nbody C { rotate: 1, rotate: 2 }",
        r#"
test.sim:2:21: error: duplicate body option `rotate`
  |
2 | body C { rotate: 1, rotate: 2 }
  |                     ^^^^^^
  = note: `rotate` was first given at 2:10
"#,
    );
}

#[test]
fn model_item_is_required() {
    check(
        "body B { }",
        r#"
test.sim:1:1: error: missing `model` item
  |
1 | body B { }
  | ^^^^
  = help: name the model first: `model Name;`
"#,
    );
    check(
        "",
        r#"
test.sim:1:1: error: missing `model` item
  |
1 | 
  | ^
  = help: name the model first: `model Name;`
"#,
    );
}

#[test]
fn misspelled_item_keyword() {
    check(
        "model M;\nbdy B {}",
        r#"
test.sim:2:1: error: expected an item, found `bdy`
  |
2 | bdy B {}
  | ^^^
  = help: did you mean `body`?
  = note: items start with one of: model, settings, parameters, parameter, body, point, let, force, moment, gravity, input, extern, state, output, constraint, motion, discrete, event
"#,
    );
}

#[test]
fn parameter_and_input_values_are_numbers() {
    check(
        "model M;\nparameters { a = 2*b }",
        r#"
test.sim:2:19: error: expected a unit, `,` or the end after the value of `a`, found `*`
  |
2 | parameters { a = 2*b }
  |                   ^
  = help: a parameter's value is a single number; define derived quantities with `let`
"#,
    );
    check(
        "model M;\ninput a = x;",
        r#"
test.sim:2:11: error: expected a number for the default of `a`, found `x`
  |
2 | input a = x;
  |           ^
  = help: values are numbers such as `1.5` or `-2`; define derived quantities with `let`
"#,
    );
}

#[test]
fn externs() {
    check(
        "model M;\nextern fn f(x) -> f64;",
        r#"
test.sim:2:19: error: expected the unit of the result in brackets, such as `-> [N]`, found `f64`
  |
2 | extern fn f(x) -> f64;
  |                   ^^^
  = help: a user function returns one number of the model's float type: give its unit, `-> [N]`, or leave out `-> ...` for a dimensionless result
  = help: declare a subroutine (`extern sub`) for several results
"#,
    );
    check(
        "model M;\nextern sub s(t);",
        r#"
test.sim:2:16: error: expected `->` and the subroutine's outputs, found `;`
  |
2 | extern sub s(t);
  |                ^
  = help: write `extern sub s(...) -> (out1 [unit], out2);`
"#,
    );
    check(
        "model M;\nextern x;",
        r#"
test.sim:2:8: error: expected `fn` or `sub` after `extern`, found `x`
  |
2 | extern x;
  |        ^
  = help: `extern fn f(x, y);` declares a user function, `extern sub s(t) -> (a, b);` a user subroutine
"#,
    );
}

#[test]
fn duplicate_items() {
    check(
        "model M;\nmodel N;",
        r#"
test.sim:2:1: error: duplicate `model` item
  |
2 | model N;
  | ^^^^^^^
  = note: the model was already named `M` at 1:7
"#,
    );
    check(
        "model M;\nsettings {}\nsettings {}",
        r#"
test.sim:3:1: error: duplicate `settings` item
  |
3 | settings {}
  | ^^^^^^^^
  = note: the first `settings` item is at 2:1
"#,
    );
    check(
        "model M;\ngravity = -g*n3;\ngravity = n1;",
        r#"
test.sim:3:1: error: duplicate `gravity` item
  |
3 | gravity = n1;
  | ^^^^^^^
  = note: the first `gravity` item is at 2:1
"#,
    );
}

#[test]
fn rust_keywords_are_not_names() {
    check(
        "model M;\nbody type {}",
        r#"
test.sim:2:6: error: expected a body name, found `type`
  |
2 | body type {}
  |      ^^^^
  = help: `type` is a Rust keyword; choose another name
"#,
    );
}

#[test]
fn missing_commas_are_reported_and_accepted() {
    check(
        "model M;\nbody B { parent: B rotate: 3 }",
        r#"
test.sim:2:19: error: expected `,` between entries
  |
2 | body B { parent: B rotate: 3 }
  |                   ^
"#,
    );
    check(
        "model M;\nparameters { /// doc\n a = 1 b = 2 }",
        r#"
test.sim:3:7: error: expected `,` between entries
  |
3 |  a = 1 b = 2 }
  |       ^
"#,
    );
}

#[test]
fn expressions() {
    check(
        "model M;\nlet x = a**2;",
        r#"
test.sim:2:11: error: expected an expression, found `*`
  |
2 | let x = a**2;
  |           ^
  = help: powers are written `x^2`
"#,
    );
    check(
        "model M;\nlet x = (a, b);",
        r#"
test.sim:2:11: error: expected `)`, found `,`
  |
2 | let x = (a, b);
  |           ^
  = help: vectors are written in brackets: `[x, y, z]`
"#,
    );
    check(
        "model M;\nlet x = 2(a);",
        r#"
test.sim:2:10: error: `2` cannot be called: only a name can be called
  |
2 | let x = 2(a);
  |          ^
  = help: write `*` to multiply
"#,
    );
    check(
        "model M;\noutput y = ;",
        r#"
test.sim:2:12: error: expected an expression, found `;`
  |
2 | output y = ;
  |            ^
"#,
    );
    check(
        "model M;\nlet x = f(a b);",
        r#"
test.sim:2:13: error: expected `,` or `)`, found `b`
  |
2 | let x = f(a b);
  |             ^
"#,
    );
    check(
        "model M;\nlet z = B.cm.x + B.;",
        r#"
test.sim:2:20: error: expected a name or an index after `.` (such as `B.cm` or `B.1`), found `;`
  |
2 | let z = B.cm.x + B.;
  |                    ^
"#,
    );
}

#[test]
fn block_syntax() {
    check(
        "model M;\nbody B { parent = N }",
        r#"
test.sim:2:17: error: expected `:` after `parent`, found `=`
  |
2 | body B { parent = N }
  |                 ^
  = help: block entries are written `key: value`
"#,
    );
    check(
        "model M;\nbody B { parent: N, small: [translations, rotations] }\nbody C { 3: x }",
        r#"
test.sim:3:10: error: expected a body option such as `parent: ...`, found `3`
  |
3 | body C { 3: x }
  |          ^
"#,
    );
    check(
        "model M;\n\tbody B { q: [x y] }",
        r#"
test.sim:2:17: error: expected `,` or `]`, found `y`
  |
2 | 	body B { q: [x y] }
  | 	               ^
"#,
    );
}

#[test]
fn points() {
    check(
        "model M;\npoint P F at [0, 0, 0];",
        r#"
test.sim:2:9: error: expected `in` and the body the point is fixed in, found `F`
  |
2 | point P F at [0, 0, 0];
  |         ^
  = help: write `point P in B at [x, y, z];`
"#,
    );
}

#[test]
fn doc_comments_and_attributes() {
    check(
        "model M;\n#[derive(Debug)]\nbody B {}",
        r#"
test.sim:2:1: error: unsupported attribute
  |
2 | #[derive(Debug)]
  | ^^^^^^^^^^^^^^^^
  = help: only doc comments (`///`) are allowed here
"#,
    );
    check(
        "model M;\n/// dangling",
        r#"
test.sim:2:13: error: doc comment is not followed by an item
  |
2 | /// dangling
  |             ^
"#,
    );
}

#[test]
fn several_errors_in_one_file_are_all_reported() {
    check(
        "model M\nbody B { rotat: 1 }\nparameter g = 9.81 [m/s^2]\n@ junk;\noutput y = q(B)",
        r#"
test.sim:1:8: error: expected `;` after the model's name
  |
1 | model M
  |        ^
test.sim:2:10: error: unknown body option `rotat`
  |
2 | body B { rotat: 1 }
  |          ^^^^^
  = help: did you mean `rotate`?
  = note: the body options are: parent, joint, translate, rotate, reference, small, lock, mass, inertia, cm, q, u, initial, initial_speeds
test.sim:4:1: error: expected `;` after the parameter, found `@`
  |
4 | @ junk;
  | ^
test.sim:5:16: error: expected `;` after the value of `y`
  |
5 | output y = q(B)
  |                ^
"#,
    );
    check(
        "model M;\nparameters { a = 1, b = , c = 3 [m], d = 4 [ ] }\nbody B { parent: , rotate: 3, rotate: 1, bogus: 2 }\nlet x = 1;",
        r#"
test.sim:2:25: error: expected a number for parameter `b`, found `,`
  |
2 | parameters { a = 1, b = , c = 3 [m], d = 4 [ ] }
  |                         ^
  = help: values are numbers such as `1.5` or `-2`; define derived quantities with `let`
test.sim:2:44: error: empty unit
  |
2 | parameters { a = 1, b = , c = 3 [m], d = 4 [ ] }
  |                                            ^^^
  = help: leave out the brackets for a quantity without a unit
test.sim:3:18: error: expected an expression, found `,`
  |
3 | body B { parent: , rotate: 3, rotate: 1, bogus: 2 }
  |                  ^
test.sim:3:31: error: duplicate body option `rotate`
  |
3 | body B { parent: , rotate: 3, rotate: 1, bogus: 2 }
  |                               ^^^^^^
  = note: `rotate` was first given at 3:20
test.sim:3:42: error: unknown body option `bogus`
  |
3 | body B { parent: , rotate: 3, rotate: 1, bogus: 2 }
  |                                          ^^^^^
  = note: the body options are: parent, joint, translate, rotate, reference, small, lock, mass, inertia, cm, q, u, initial, initial_speeds
"#,
    );
}

#[test]
fn crlf_and_byte_order_mark_keep_columns() {
    check(
        "\u{feff}model M;\r\nbody B {\r\n  rotat: 1 }\r\n",
        r#"
test.sim:3:3: error: unknown body option `rotat`
  |
3 |   rotat: 1 }
  |   ^^^^^
  = help: did you mean `rotate`?
  = note: the body options are: parent, joint, translate, rotate, reference, small, lock, mass, inertia, cm, q, u, initial, initial_speeds
"#,
    );
    check("\u{feff}model M;\r\nlet x = é + 1;\r\n", "OK\n");
    check(
        "model M;\nlet é = ü ^ ;",
        r#"
test.sim:2:13: error: expected an expression, found `;`
  |
2 | let é = ü ^ ;
  |             ^
"#,
    );
}

#[test]
fn token_input_reports_through_syn_errors() {
    let tokens: proc_macro2::TokenStream =
        "model M; body B { rotat: 1, rotate: 2, rotate: 3 } output y = ;"
            .parse()
            .unwrap_or_default();
    let Err(diags) = crate::syntax::parse_tokens(tokens) else {
        panic!("expected errors")
    };
    // Token spans, no file locations.
    assert!(
        diags
            .iter()
            .all(|d| d.span.start().is_none() && d.span.token_range().is_some())
    );
    let messages: Vec<String> = diags
        .to_syn_error()
        .into_iter()
        .flat_map(|e| e.into_iter().map(|e| e.to_string()))
        .collect();
    assert_eq!(
        messages,
        [
            "unknown body option `rotat`\n= help: did you mean `rotate`?\n= note: the body options are: parent, joint, \
             translate, rotate, reference, small, lock, mass, inertia, cm, q, u, initial, initial_speeds",
            "duplicate body option `rotate`\n= note: `rotate` was already given earlier in this block",
            "expected an expression, found `;`",
        ]
    );
}

#[test]
fn file_spans_never_hold_token_spans() {
    let Err(diags) =
        crate::syntax::parse_source(&crate::diag::SourceFile::new("m.sim", "model M; let = 1;"))
    else {
        panic!("expected an error")
    };
    for diagnostic in diags.iter() {
        assert!(diagnostic.span.token_range().is_none());
        assert!(diagnostic.span.start().is_some());
        // Safe to use for generated code after the parse: the call site.
        let _ = diagnostic.to_syn_error();
    }
}

#[test]
fn overlong_expressions_are_refused_before_they_overflow_the_stack() {
    let sum = vec!["x"; 200_000].join("+");
    let rendered = parse_file(&format!("model M;\noutput a = {sum};\nlet b = c d;"))
        .err()
        .unwrap_or_default();
    assert!(
        rendered.starts_with("test.sim:2:20013: error: expression has more than 10000 operators\n"),
        "{}",
        &rendered[..rendered.len().min(300)]
    );
    assert!(rendered.contains("= help: split it into several `let`s"));
    // The parser goes on after it.
    assert!(rendered.contains("test.sim:3:11: error: expected `;` after the value of `b`"));
    // Nested expressions count towards the expression they are in.
    let nested = format!("model M;\noutput a = f({sum});");
    assert!(parse_file(&nested).is_err_and(|r| r.contains("more than 10000 operators")));
}
