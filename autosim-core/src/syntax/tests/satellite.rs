//! The paper's satellite (Figure 6) in the model language: it parses, from
//! a file and from tokens, and the AST keeps what was written.

use std::fmt::Write as _;

use super::parse_file;
use crate::syntax::ast::{Item, Model, Opt, OptionKey, Unit, Value};
use crate::syntax::parse_tokens;

pub(crate) const SATELLITE: &str = r#"/// The paper's spacecraft.
model Satellite;
settings { threshold: 2, float: f64 }          // small-term order threshold
parameters {
    /// Boom torsional stiffness.
    KB = 2000 [N m/rad],
    DB = 10 [N m s/rad],
    L1 = 1.5 [m],
    PI = 3.1415926,
}
parameter g = 9.81 [m/s^2];
body B "bus" { translate: [1, 2, 3], rotate: [1, 2, 3], small: [translations, rotations],
               q: [x, y, z, roll, pitch, yaw], u: [vx, vy, vz, wx, wy, wz] }
body C "clock" { parent: B, rotate: 3, inertia: diag(IC, IC, 0), cm: [0, 0, -L2], initial: [4 - PI] }
body D "camera" { parent: C, joint: [0, L3, -L1], cm: [0, -L5, -L6], rotate: 1 }
body E "boom hinge" { parent: B, joint: [0, -L7, 0], rotate: 3, mass: 0, inertia: 0, small: rotations }
body F "boom" { parent: E, rotate: 1, inertia: [[IF1, 0, 0], [0, IF2, 0], [0, 0, IF1]], cm: [0, -L8, 0], small: all }
body W { parent: N, translate: [[0.6, 0.8, 0], 3] }
point P "tip" in F at [0, -L8, 0];
point Q in B at [x1, 0, 0];
let r = pos(P, Q);
force spring "boom spring" { on: P, reaction: Q, along: dir(r), magnitude: -k*(mag(r) - L0) }
force push { on: B.cm, vector: F1*b1 + F2*b3 }
moment boom1 { on: F, reaction: B, about: e3, magnitude: -KB*q(E) - DB*u(E) }
moment tt1 { on: B, vector: LTT1*thrust(t, 1, G*u(B, 4) + q(B, 4))*b1 }
gravity = -g*n3;
input clkcmd [rad], camcmd [rad] = -0.5;
extern fn thrust(t, axis, error);
extern sub cmd(t) -> (clkcmd2 [rad], camcmd2 [rad]);
state lag [N] { initial: 0, derivative: (F1 - lag)/tau }
output clock_angle [rad] = q(C);
output tip_speed [m/s] = mag(vel(P));
"#;

const SUMMARY: &str = r#"model Satellite docs [" The paper's spacecraft."]
settings { threshold: 2, float: f64 }
parameters KB = 2000 [N m/rad] docs [" Boom torsional stiffness."], DB = 10 [N m s/rad], L1 = 1.5 [m], PI = 3.1415926
parameters g = 9.81 [m/s^2]
body B "bus" { translate: [1, 2, 3], rotate: [1, 2, 3], small: [translations, rotations], q: [x, y, z, roll, pitch, yaw], u: [vx, vy, vz, wx, wy, wz] }
body C "clock" { parent: B, rotate: 3, inertia: diag(IC, IC, 0), cm: [0, 0, -L2], initial: [4 - PI] }
body D "camera" { parent: C, joint: [0, L3, -L1], cm: [0, -L5, -L6], rotate: 1 }
body E "boom hinge" { parent: B, joint: [0, -L7, 0], rotate: 3, mass: 0, inertia: 0, small: rotations }
body F "boom" { parent: E, rotate: 1, inertia: [[IF1, 0, 0], [0, IF2, 0], [0, 0, IF1]], cm: [0, -L8, 0], small: all }
body W { parent: N, translate: [[0.6, 0.8, 0], 3] }
point P "tip" in F at [0, -L8, 0]
point Q in B at [x1, 0, 0]
let r = pos(P, Q)
force spring "boom spring" { on: P, reaction: Q, along: dir(r), magnitude: -k*(mag(r) - L0) }
force push { on: B.cm, vector: F1*b1 + F2*b3 }
moment boom1 { on: F, reaction: B, about: e3, magnitude: -KB*q(E) - DB*u(E) }
moment tt1 { on: B, vector: LTT1*thrust(t, 1, G*u(B, 4) + q(B, 4))*b1 }
gravity = -g*n3
input clkcmd [rad], camcmd [rad] = -0.5
extern fn thrust(t, axis, error)
extern sub cmd(t) -> (clkcmd2 [rad], camcmd2 [rad])
state lag [N] { initial: 0, derivative: (F1 - lag)/tau }
output clock_angle [rad] = q(C)
output tip_speed [m/s] = mag(vel(P))
"#;

fn unit(unit: &Option<Unit>) -> String {
    unit.as_ref()
        .map(|u| format!(" [{}]", u.text))
        .unwrap_or_default()
}

fn value(value: &Value) -> String {
    format!(
        "{}{}",
        if value.negative { "-" } else { "" },
        value.number.text
    )
}

fn label(label: &Option<crate::syntax::ast::Label>) -> String {
    label
        .as_ref()
        .map(|l| format!(" {:?}", l.text))
        .unwrap_or_default()
}

/// `<kind> <name> "<label>" { options }`.
fn labelled<K: OptionKey>(
    kind: &str,
    name: &crate::syntax::ast::Name,
    l: &Option<crate::syntax::ast::Label>,
    entries: &[Opt<K>],
) -> String {
    format!("{kind} {}{} {}", name.text, label(l), opts(entries))
}

fn opts<K: OptionKey>(entries: &[Opt<K>]) -> String {
    let parts: Vec<String> = entries
        .iter()
        .map(|o| format!("{}: {}", o.key.as_str(), o.value))
        .collect();
    if parts.is_empty() {
        "{ }".to_string()
    } else {
        format!("{{ {} }}", parts.join(", "))
    }
}

/// One line per item, in the model language (what a user would recognize).
pub(crate) fn summary(model: &Model) -> String {
    let mut out = format!("model {} docs {:?}\n", model.name.text, model.docs);
    for item in &model.items {
        let line = match item {
            Item::Settings(s) => format!("settings {}", opts(&s.options.entries)),
            Item::Parameters(p) => {
                let params: Vec<String> = p
                    .params
                    .iter()
                    .map(|p| {
                        let docs = if p.docs.is_empty() {
                            String::new()
                        } else {
                            format!(" docs {:?}", p.docs)
                        };
                        format!(
                            "{} = {}{}{docs}",
                            p.name.text,
                            value(&p.value),
                            unit(&p.unit)
                        )
                    })
                    .collect();
                format!("parameters {}", params.join(", "))
            }
            Item::Body(b) => labelled("body", &b.name, &b.label, &b.options.entries),
            Item::Point(p) => format!(
                "point {}{} in {} at {}",
                p.name.text,
                label(&p.label),
                p.body.text,
                p.at
            ),
            Item::Let(l) => format!("let {} = {}", l.name.text, l.value),
            Item::Force(f) => labelled("force", &f.name, &f.label, &f.options.entries),
            Item::Moment(m) => labelled("moment", &m.name, &m.label, &m.options.entries),
            Item::Gravity(g) => format!("gravity = {}", g.value),
            Item::Inputs(i) | Item::Discrete(i) => {
                let keyword = match item {
                    Item::Discrete(_) => "discrete",
                    _ => "input",
                };
                let inputs: Vec<String> = i
                    .inputs
                    .iter()
                    .map(|i| {
                        let default = i
                            .default
                            .as_ref()
                            .map(|d| format!(" = {}", value(d)))
                            .unwrap_or_default();
                        format!("{}{}{default}", i.name.text, unit(&i.unit))
                    })
                    .collect();
                format!("{keyword} {}", inputs.join(", "))
            }
            Item::ExternFn(f) => {
                let params: Vec<&str> = f.params.iter().map(|p| p.text.as_str()).collect();
                format!("extern fn {}({})", f.name.text, params.join(", "))
            }
            Item::ExternSub(s) => {
                let args: Vec<String> = s.args.iter().map(|a| a.to_string()).collect();
                let outs: Vec<String> = s
                    .outputs
                    .iter()
                    .map(|o| format!("{}{}", o.name.text, unit(&o.unit)))
                    .collect();
                format!(
                    "extern sub {}({}) -> ({})",
                    s.name.text,
                    args.join(", "),
                    outs.join(", ")
                )
            }
            Item::State(s) => format!(
                "state {}{} {}",
                s.name.text,
                unit(&s.unit),
                opts(&s.options.entries)
            ),
            Item::Output(o) => format!("output {}{} = {}", o.name.text, unit(&o.unit), o.value),
            Item::Constraint(c) => format!(
                "constraint {}{}{} {}",
                c.name.text,
                unit(&c.unit),
                label(&c.label),
                opts(&c.options.entries)
            ),
            Item::Motion(m) => labelled("motion", &m.name, &m.label, &m.options.entries),
            Item::Event(e) => {
                let assigned = |list: &Option<(_, Vec<crate::syntax::ast::Assignment>)>, key| {
                    list.as_ref().map_or(String::new(), |(_, list)| {
                        let parts: Vec<String> = list
                            .iter()
                            .map(|a| format!("{}: {}", a.target.text, a.value))
                            .collect();
                        format!(" {key} {{ {} }}", parts.join(", "))
                    })
                };
                format!(
                    "event {}{}{} {}{}{}",
                    e.name.text,
                    unit(&e.unit),
                    label(&e.label),
                    opts(&e.options.entries),
                    assigned(&e.set, "set"),
                    assigned(&e.reset, "reset")
                )
            }
        };
        let _ = writeln!(out, "{line}");
    }
    out
}

#[test]
fn satellite_from_file() {
    assert_eq!(summary_of(SATELLITE), SUMMARY);
}

#[test]
fn satellite_from_tokens() {
    let tokens: proc_macro2::TokenStream = SATELLITE.parse().unwrap_or_default();
    let model = parse_tokens(tokens).unwrap_or_else(|diags| panic!("{diags:?}"));
    assert_eq!(summary(&model), SUMMARY);
}

#[test]
fn satellite_spans_are_file_locations() {
    let model = parse_file(SATELLITE).unwrap_or_else(|rendered| panic!("{rendered}"));
    let at = |span: crate::diag::Span| span.start().map(|s| (s.line, s.col));
    assert_eq!(at(model.name.span), Some((2, 7)));
    let Some(Item::Body(c)) = model.items.get(4) else {
        panic!("item 3 is not body C")
    };
    assert_eq!(at(c.name.span), Some((14, 6)));
    assert_eq!(at(c.options.entries[2].key_span), Some((14, 40)));
    let inertia = &c.options.entries[2].value;
    assert_eq!(at(inertia.span()), Some((14, 49)));
    assert_eq!(
        inertia.span().end().map(|e| (e.line, e.col)),
        Some((14, 64))
    );
    // A file span holds no token span: generated code gets the call site.
    assert!(inertia.span().token_range().is_none());
}

/// The summary of a model text that parses.
pub(super) fn summary_of(text: &str) -> String {
    summary(&parse_file(text).unwrap_or_else(|r| panic!("{r}")))
}

#[test]
fn items_in_any_order_and_stray_semicolons() {
    assert_eq!(
        summary_of("output y = x; ; body B { }; model M;"),
        "model M docs []\noutput y = x\nbody B { }\n"
    );
}

#[test]
fn inner_docs_and_numbers_as_written() {
    let text = "//! Model docs.\nmodel M;\nparameters { a = 1_000, b = -2.50, c = 1e-3, d = 0.1 }";
    assert_eq!(
        summary_of(text),
        "model M docs [\" Model docs.\"]\nparameters a = 1000, b = -2.50, c = 1e-3, d = 0.1\n"
    );
}

#[test]
fn units_are_normalized() {
    let text = "model M; input a [ N * m / rad ], b [kg m ^ 2], c [m/s^-2], d [N-m], e [(kg m)/s], f [1/s], g [%];";
    assert_eq!(
        summary_of(text),
        "model M docs []\ninput a [N*m/rad], b [kg m^2], c [m/s^-2], d [N-m], e [(kg m)/s], f [1/s], g [%]\n"
    );
}
