//! Resolver diagnostics (the file is `test.sim`; the expected text is what
//! a user sees) and models that must resolve without overflowing the stack.

use super::resolve;
use crate::diag::SourceFile;
use crate::syntax::parse_source;

/// The rendered diagnostics of `text`, or `OK`.
fn resolved(text: &str) -> String {
    let file = SourceFile::new("test.sim", text);
    match parse_source(&file).and_then(|model| resolve(&model)) {
        Ok(_) => "OK\n".to_string(),
        Err(d) => d.render(&file),
    }
}

/// Checks that `text` gives exactly one error, and that it contains `message`.
fn check_one_error(text: &str, message: &str) {
    let got = resolved(text);
    assert_eq!(got.matches("error").count(), 1, "{got}");
    assert!(got.contains(message), "{got}");
}

/// Compares the rendered diagnostics (a leading newline in `expect` is ignored).
fn check(text: &str, expect: &str) {
    let got = resolved(text);
    let expect = expect.strip_prefix('\n').unwrap_or(expect);
    assert_eq!(got, expect, "\n--- got:\n{got}");
}

const HEADER: &str = "model M;\nbody B { rotate: 1 }\n";

#[test]
fn models_without_bodies_or_outputs_resolve() {
    check("model M;", "OK\n");
    check("model M;\nparameters { k = 1 }\nbody B {}", "OK\n");
    check(
        "model M;\nbody B { rotate: [] }\npoint P in N at [1, 2, 3];",
        "OK\n",
    );
}

#[test]
fn long_sums_do_not_recurse_per_term() {
    let sum = vec!["q(B)"; 9_000].join(" + ");
    check(&format!("{HEADER}output a = {sum};"), "OK\n");
}

#[test]
fn lets_used_before_a_long_chain_of_definitions_are_refused_once() {
    let mut text = HEADER.to_string();
    for i in 0..1_000 {
        text.push_str(&format!("let a{i} = a{} + q(B);\n", i + 1));
    }
    text.push_str("let a1000 = 1;\noutput o = a0;\n");
    check_one_error(
        &text,
        "error: `a200` is used through more than 200 `let`s or points that are defined after their first use",
    );
    // In source order, a long chain is fine.
    let mut text = HEADER.to_string();
    text.push_str("let a0 = q(B);\n");
    for i in 1..1_000 {
        text.push_str(&format!("let a{i} = a{} + q(B);\n", i - 1));
    }
    text.push_str("output o = a999;\n");
    // Resolving a 1000-deep chain recurses once per level: in an unoptimized
    // build that comes close to a test thread's 2 MB stack (branches that
    // added a frame overflowed it), far from the 8 MB rustc gives proc macros.
    let resolver = std::thread::Builder::new().stack_size(8 << 20);
    let join = resolver.spawn(move || check(&text, "OK\n"));
    join.expect("spawn the resolver's thread")
        .join()
        .expect("the chain resolves");
}

#[test]
fn values_too_large_for_a_float() {
    check(
        "model M;\nparameters { k = 1e999 }\ninput w = -1e400;",
        r#"
test.sim:2:18: error: `1e999` is too large for a floating-point number
  |
2 | parameters { k = 1e999 }
  |                  ^^^^^
  = help: values must be finite: at most about 1.8e308
test.sim:3:11: error: `1e400` is too large for a floating-point number
  |
3 | input w = -1e400;
  |           ^^^^^^
  = help: values must be finite: at most about 1.8e308
"#,
    );
}

#[test]
fn loads_cannot_use_accelerations() {
    check(
        &format!("{HEADER}moment m {{ on: B, about: b1, magnitude: -dxdt(u(B)) }}"),
        r#"
test.sim:3:41: error: a moment cannot use an acceleration (`u1_dot`, the `dxdt` of a speed)
  |
3 | moment m { on: B, about: b1, magnitude: -dxdt(u(B)) }
  |                                         ^^^^^^^^^^^
  = help: accelerations are solved from the forces and moments; use them only in outputs and state derivatives
"#,
    );
    // Outputs and state derivatives may.
    check(
        &format!(
            "{HEADER}state s {{ initial: 0, derivative: dxdt(u(B)) }}\noutput a = dxdt(u(B)) + s/(1 [s]);"
        ),
        "OK\n",
    );
}

#[test]
fn subroutine_arguments_use_earlier_subroutines_only() {
    check(
        &format!("{HEADER}extern sub s(w) -> (y);\nextern sub r(y) -> (w);"),
        r#"
test.sim:3:14: error: an argument of subroutine `s` uses `w`, an output of subroutine `r` declared after it
  |
3 | extern sub s(w) -> (y);
  |              ^
  = help: subroutines are called in the order they are declared: an argument may only use the outputs of subroutines declared before
"#,
    );
    check(
        &format!("{HEADER}extern sub s(2*y) -> (y);"),
        r#"
test.sim:3:14: error: subroutine `s` cannot take its own output `y` as an argument
  |
3 | extern sub s(2*y) -> (y);
  |              ^^^
  = help: subroutines are called in the order they are declared: an argument may only use the outputs of subroutines declared before
"#,
    );
}

#[test]
fn a_failed_reaction_does_not_hide_the_other_mistakes_of_a_load() {
    let got = resolved(&format!(
        "{HEADER}moment m {{ on: B, reaction: C, about: b1, magnitude: kk }}"
    ));
    assert!(got.contains("error: unknown body `C`"), "{got}");
    assert!(got.contains("error: unknown name `kk`"), "{got}");
}

#[test]
fn a_function_named_without_its_arguments_is_pointed_out() {
    for (name, call) in [("vel", "vel(...)"), ("sin", "sin(...)")] {
        let got = resolved(&format!(
            "{HEADER}moment m {{ on: B, about: b1, magnitude: -2*{name} }}"
        ));
        assert!(
            got.contains(&format!("error: unknown name `{name}`")),
            "{got}"
        );
        assert!(
            got.contains(&format!(
                "`{name}` is a function: call it with its arguments, `{call}`"
            )),
            "{got}"
        );
    }
}

#[test]
fn quaternion_body_with_a_locked_translation_does_not_panic() {
    // Locking a translation of a quaternion body indexed its (absent)
    // rotation axes.
    check(
        "model M;\nbody B { translate: [1, 2], rotate: quaternion, lock: [q1], mass: 1, inertia: diag(1, 2, 3) }",
        "OK\n",
    );
    check(
        "model M;\nbody B { translate: [1, 2], rotate: quaternion, q: [x, y, e0, e1, e2, e3], initial: [0, 1, 1, 0, 0, 0], lock: [x] }",
        "OK\n",
    );
}

#[test]
fn quaternion_body_takes_four_coordinate_names() {
    // The names and initial values of a quaternion's coordinates were
    // checked against its three speeds here and against four coordinates
    // in the system: no count satisfied both.
    check(
        "model M;\nbody B { rotate: quaternion, q: [e0, e1, e2, e3], u: [w1, w2, w3], initial: [1, 0, 0, 0] }",
        "OK\n",
    );
    let got = resolved("model M;\nbody B { rotate: quaternion, q: [e1, e2, e3] }");
    assert!(
        got.contains("error: body `B` has 4 coordinates (a quaternion has e0 to e3), but 3 coordinate names were given"),
        "{got}"
    );
}

#[test]
fn long_chains_of_lets_and_points_are_refused_not_a_stack_overflow() {
    // Each `let` wraps the one before: 2000 levels of `sin` overflowed the
    // stack of every pass after the resolver.
    let mut text = HEADER.to_string();
    text.push_str("let r0 = q(B);\n");
    for i in 1..=2_000 {
        text.push_str(&format!("let r{i} = sin(r{});\n", i - 1));
    }
    text.push_str("output y = r2000;\n");
    check_one_error(
        &text,
        "error: `r500` nests operations more than 500 deep, through the `let`s and points it uses",
    );
    // The same through points.
    let mut text = HEADER.to_string();
    text.push_str("point P0 in B at [1, 0, 0];\n");
    for i in 1..=1_000 {
        text.push_str(&format!(
            "point P{i} in B at [sin(dot(pos(P{}), b1) as [1]) as [m], 0, 0];\n",
            i - 1
        ));
    }
    text.push_str("output y = mag(pos(P1000));\n");
    check_one_error(&text, "nests operations more than 500 deep");
    // Shorter chains are fine.
    let mut text = HEADER.to_string();
    text.push_str("let r0 = q(B);\n");
    for i in 1..=400 {
        text.push_str(&format!("let r{i} = sin(r{});\n", i - 1));
    }
    text.push_str("output y = r400;\n");
    check(&text, "OK\n");
}

#[test]
fn a_misspelled_formulation_is_named_and_an_unknown_one_explained() {
    check(
        &format!("{HEADER}settings {{ formulation: recursve }}\n"),
        "
test.sim:3:25: error: `formulation` is `auto`, `mass_matrix` or `recursive`
  |
3 | settings { formulation: recursve }
  |                         ^^^^^^^^
  = help: did you mean `recursive`?
",
    );
    check_one_error(
        &format!("{HEADER}settings {{ formulation: fastest }}\n"),
        "`auto` (the default) generates whichever is estimated faster",
    );
}

/// A setting and the scene option of the same key are checked by one
/// check: the same message for the same mistake, and every mistake of the
/// scene at once.
#[test]
fn settings_and_scene_options_share_their_messages() {
    use crate::model::Scene;
    use crate::syntax::file_arguments;
    let settings = resolved(&format!(
        "{HEADER}settings {{ float: f16, threshold: 30, linearize: yes }}\n"
    ));
    let input: proc_macro2::TokenStream =
        r#"file = "m.sim", float = f16, threshold = 30, linearize = yes"#
            .parse()
            .expect("tokens");
    let arguments = file_arguments(&input)
        .expect("a file argument list")
        .expect("a readable argument list");
    assert!(arguments.diagnostics.is_empty());
    let scene = Scene::from_options(&arguments.options).expect_err("three mistakes");
    let messages: Vec<String> = scene.iter().map(|d| d.message.clone()).collect();
    assert_eq!(messages.len(), 3, "{messages:?}");
    for m in &messages {
        assert!(settings.contains(m.as_str()), "{m} not in\n{settings}");
    }
    assert_eq!(settings.matches("error").count(), 3, "{settings}");
}

/// A quaternion body naming more coordinates than it has, one of them
/// locked (found by the fuzzer: an index past the body's flags).
#[test]
fn a_lock_of_a_coordinate_a_quaternion_does_not_have_is_reported() {
    let got = resolved("model M;\nbody E { rotate: quaternion, q: [a, b, c, d, e, f], lock: f }");
    assert!(got.contains("`f` is not a coordinate of body `E`"), "{got}");
}

/// A body that fails (a misspelled parent, two rotations) reports its own
/// mistake; the uses of its coordinates and speeds add none (they were
/// "unknown names" with a misleading "did you mean").
#[test]
fn a_failed_body_hides_no_mistake_but_adds_none() {
    for body in [
        "body L2 { parent: Lnk1, rotate: 2, q: [th2], u: [w2], mass: 1, inertia: 0 }",
        "body L2 { rotate: [1, 2], q: [th2, ph2], u: [w2, v2], mass: 1, inertia: 0 }",
    ] {
        let got = resolved(&format!(
            "model M;\nbody L1 {{ rotate: 2, q: [th1], u: [w1], mass: 1, inertia: 0 }}\n{body}\n\
             output spin [rad/s] = w2;\noutput tilt [rad] = th2 + th1 + kk;\n"
        ));
        assert_eq!(got.matches("error:").count(), 2, "{got}");
        assert!(got.contains("error: unknown name `kk`"), "{got}");
        assert!(!got.contains("`w2`") && !got.contains("`th2`"), "{got}");
    }
}

/// A body that failed with its coordinates and speeds left to the default
/// names: a use of `u3` or `B_e0` is no second error (a new user's wrong
/// coordinate count brought "unknown name `u3`"); another name still is.
#[test]
fn a_failed_body_with_default_names_adds_no_error_at_them() {
    let got = resolved(
        "model M;
body B { translate: [1, 2, 3], rotate: quaternion, mass: 1, inertia: 0,          initial: [0, 0, 0, 1, 0, 0] }
         output climb [m/s] = u3 + 0*q7 + 0*B_e0 + kk;
",
    );
    assert_eq!(got.matches("error:").count(), 2, "{got}");
    assert!(got.contains("error: body `B` has 7 coordinates"), "{got}");
    assert!(got.contains("error: unknown name `kk`"), "{got}");
}

/// A quaternion's scalar part is a name expressions use: `<Body>_e0`, or
/// the first of the body's `q` names.
#[test]
fn a_quaternions_scalar_part_is_named_in_expressions() {
    check(
        "model M;
body B { rotate: quaternion, mass: 1, inertia: diag(1, 2, 3) }
         output norm [1] = B_e0^2 + q1^2 + q2^2 + q3^2;",
        "OK
",
    );
    check(
        "model M;
body B { rotate: quaternion, q: [e0, e1, e2, e3], u: [w1, w2, w3], mass: 1, inertia: diag(1, 2, 3) }
         output norm [1] = e0^2 + e1^2 + e2^2 + e3^2;",
        "OK
",
    );
}

/// Constants name what varies; gravity's hint is a gravity.
#[test]
fn constant_options_name_what_varies() {
    let got = resolved(
        "model M;\ninput road [m];\nbody W { translate: 3, q: [z], u: [w], mass: 1, inertia: 0, initial: [1 + road] }",
    );
    assert!(
        got.contains("initial coordinates must be constant, but `road` is an input"),
        "{got}"
    );
    let gravity = resolved("model M;\nparameters { g = 9.81 }\ngravity = -g;");
    assert!(gravity.contains("e.g. `-g*n3`"), "{gravity}");
}

/// The unit vectors of a body that failed add no "unknown name" either,
/// and an undeclared name says how to declare it.
#[test]
fn a_failed_bodys_axes_add_no_error() {
    let got = resolved(
        "model M;\nbody P { rotate: 4, q: [th], u: [w], mass: 1, inertia: 0 }\nmoment m { on: P, about: p1, magnitude: 1 }\noutput y = road;",
    );
    assert!(!got.contains("`p1`"), "{got}");
    assert!(got.contains("as `input road [unit];`"), "{got}");
}

/// `partial` and `dxdt` of a quantity the model computes after its
/// equations are refused (they were silently zero, also inside a load).
#[test]
fn derivatives_of_computed_quantities_are_refused() {
    let head = "model M;\nparameters { m = 1 [kg], g = 9.81 [m/s^2] }\ninput tau [N m];\nbody B { rotate: 2, q: [q], u: [w], mass: m, cm: [0, 0, -1], inertia: 0 }\ngravity = -g*n3;\nmoment drive { on: B, about: b2, magnitude: tau }\n";
    for (item, quantity) in [
        (
            "output k [N m] = partial(potential_energy(), q);",
            "`partial` cannot differentiate `potential_energy()`",
        ),
        (
            "output k [W] = dxdt(potential_energy());",
            "`dxdt` cannot differentiate `potential_energy()`",
        ),
        (
            "output k = partial(power(drive), tau);",
            "`partial` cannot differentiate `power(drive)`",
        ),
        (
            "output k = partial(dot(reaction_force(B), n3), tau);",
            "`partial` cannot differentiate `reaction_force(B)`",
        ),
        (
            "moment hold { on: B, about: b2, magnitude: partial(potential_energy(), q) }",
            "`partial` cannot differentiate `potential_energy()`",
        ),
    ] {
        let got = resolved(&format!("{head}{item}"));
        assert!(got.contains(quantity), "{item}\n{got}");
        assert!(!got.contains('#'), "{got}");
    }
    // Of what it is made of, as before.
    let got = resolved(&format!("{head}output k = partial(kinetic_energy(), w);"));
    assert!(!got.contains("error"), "{got}");
}
