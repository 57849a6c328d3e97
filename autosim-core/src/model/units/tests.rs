//! The algebra of dimensions, the unit table, and the check on small
//! models, data-driven: each case is its input and what it must give.

use super::dim::{Dim, Ratio};
use super::infer::{Affine, Solver};
use super::table::parse_unit;
use crate::diag::SourceFile;
use crate::model::resolve;
use crate::syntax::parse_source;

/// Unit text → its dimension as printed, and its factor.
const UNITS: &[(&str, &str, f64)] = &[
    ("N m/rad", "N m/rad", 1.0),
    ("N m s/rad", "N m s/rad", 1.0),
    ("kg m^2", "kg m^2", 1.0),
    ("m/s^2", "m/s^2", 1.0),
    ("N/m", "N/m", 1.0),
    ("N s/m", "N s/m", 1.0),
    ("J", "N m", 1.0),
    ("W", "N m/s", 1.0),
    ("Pa", "N/m^2", 1.0),
    ("Hz", "1/s", 1.0),
    ("1/s", "1/s", 1.0),
    ("1", "1", 1.0),
    ("rad", "rad", 1.0),
    ("deg", "rad", std::f64::consts::PI / 180.0),
    ("mm", "m", 1e-3),
    ("km/h", "m/s", 1000.0 / 3600.0),
    ("g", "kg", 1e-3),
    ("kN", "N", 1e3),
    ("min", "s", 60.0),
    ("m^-1", "1/m", 1.0),
    ("m^(1/2)", "m^(1/2)", 1.0),
    ("J/(kg K)", "m^2/(s^2 K)", 1.0),
    ("kg*m/s^2", "N", 1.0),
    ("V A", "N m/s", 1.0),
    ("%", "1", 0.01),
];

#[test]
fn units_read_as_their_dimension_and_factor() {
    for &(text, dim, factor) in UNITS {
        let u = parse_unit(text).unwrap_or_else(|e| panic!("{text}: {e:?}"));
        assert_eq!(u.dim.to_string(), dim, "{text}");
        assert!(
            (u.factor - factor).abs() <= 1e-15 * factor,
            "{text}: {}",
            u.factor
        );
    }
}

/// Unit text that does not read → the start of its message.
const BAD_UNITS: &[(&str, &str)] = &[
    ("furlong", "unknown unit `furlong`"),
    ("m/s/s", "`m/s/s` has more than one `/`"),
    ("m^x", "a unit's power must be a number"),
    ("(m", "unclosed `(`"),
    ("N m/", "a unit ends where a symbol is needed"),
    ("kkg", "unknown unit `kkg`"),
];

#[test]
fn bad_units_say_what_is_wrong() {
    for &(text, message) in BAD_UNITS {
        let e = parse_unit(text).expect_err(text);
        assert!(e.message.starts_with(message), "{text}: {}", e.message);
    }
}

#[test]
fn exponents_are_exact_ratios() {
    let half = Ratio::new(1, 2).unwrap();
    let m = Dim::base(1);
    let area = m.pow(Ratio::int(2)).unwrap();
    assert_eq!(area.pow(half), Some(m));
    assert_eq!(m.times(m.recip()), Some(Dim::ONE));
    assert_eq!(Ratio::new(2, -4), Ratio::new(-1, 2));
    assert_eq!(Ratio::new(1, 0), None);
    assert_eq!(Ratio::int(1 << 39).times(Ratio::int(4)), None);
    // The radian is tracked but dimensionless.
    let rad = Dim::base(super::dim::RAD);
    assert!(rad.is_dimensionless() && rad.compatible(Dim::ONE) && !rad.is_one());
    assert!(!m.compatible(Dim::ONE));
}

#[test]
fn unknowns_are_solved_by_the_first_equation_and_checked_by_the_next() {
    let mut s = Solver::default();
    let k = s.fresh("k");
    let newton = Affine::known(parse_unit("N").unwrap().dim);
    let metre = Affine::known(Dim::base(1));
    // k * m = N: k is N/m.
    let km = Affine::var(k).times(&metre).unwrap();
    assert!(s.unify(&km, &newton).is_ok());
    assert_eq!(s.known(&Affine::var(k)).unwrap().to_string(), "N/m");
    // k = N/m now: k * m = kg fails.
    let kg = Affine::known(Dim::base(0));
    assert!(s.unify(&km, &kg).is_err());
    // An unknown that no equation fixes stays unknown.
    let c = s.fresh("c");
    assert_eq!(s.known(&Affine::var(c)), None);
}

/// The diagnostics of a model (the file is `test.sim`), or `OK`.
fn resolved(text: &str) -> String {
    let file = SourceFile::new("test.sim", text);
    match parse_source(&file).and_then(|model| resolve(&model)) {
        Ok(_) => "OK".to_string(),
        Err(d) => d.render(&file),
    }
}

const HEAD: &str = "model M;\nparameters { m = 2 [kg], k = 10 [N/m], c = 1 [N s/m], L = 1 [m], g = 9.81 [m/s^2] }\nbody B { translate: 1, q: [x], u: [v], mass: m, inertia: 0 }\nbody R { parent: B, rotate: 3, q: [th], u: [w], cm: [L, 0, 0] }\n";

/// Model items (after [`HEAD`]) → `OK` or the start of the first message.
const MODELS: &[(&str, &str)] = &[
    // Loads, gravity, outputs with declared units.
    ("force f { on: B, along: n1, magnitude: -k*x - c*v }", "OK"),
    (
        "force f { on: B, along: n1, magnitude: m + x }",
        "error: `m + x` adds kg to m",
    ),
    ("force f { on: B, vector: -k*pos(B)*2 }", "OK"),
    (
        "force f { on: B, vector: -k*pos(B)*x }",
        "error: a force's vector must be in N, but",
    ),
    ("moment mt { on: R, about: r3, magnitude: -k*L*L*th }", "OK"),
    (
        "moment mt { on: R, about: r3, magnitude: -c*w }",
        "error: the magnitude of a moment must be in N m, but `-c*w` is in N rad/m",
    ),
    ("gravity = -g*n3;", "OK"),
    (
        "body Lk { parent: R, rotate: 1, lock: all, q: [ql], u: [ul] }\nmoment ml { on: Lk, about: lk1, magnitude: -k*L*L*q(Lk) - c*L*L*u(Lk) - c*L*L*ul }",
        "OK",
    ),
    (
        "moment mt { on: R, about: r3, magnitude: -k*L*L*q(R) - c*L*L*u(R) }",
        "OK",
    ),
    ("gravity = -9.81*n3;", "OK"),
    (
        "gravity = -L*n3;",
        "error: gravity must be in m/s^2, but `-L*n3` is in m",
    ),
    ("output e [J] = m*v^2/2 + k*x^2/2;", "OK"),
    ("output e [J] = x + v;", "error: `x + v` adds m to m/s"),
    (
        "output p [m] = pos(R.cm);",
        "error: an output needs a scalar",
    ),
    ("output a [rad] = th + 0.1;", "OK"),
    ("output a [deg] = th;", "OK"),
    (
        "input ai [deg];",
        "error: `deg` is not a coherent SI unit (1 deg = 0.017453292519943295 rad)",
    ),
    ("output s [m/s] = mag(vel(R.cm)) + L*mag(rot(R));", "OK"),
    ("output s [m/s^2] = dxdt(v);", "OK"),
    (
        "output s = dxdt(v) + x;",
        "error: `dxdt(v) + x` adds m/s^2 to m",
    ),
    // Functions.
    ("output y = sin(th) + cos(x/L);", "OK"),
    (
        "output y = sin(x);",
        "error: the argument of `sin` must be dimensionless, but `x` is in m",
    ),
    ("output y [m] = sqrt(x*x + L^2);", "OK"),
    (
        "output y [m] = sqrt(x);",
        "error: the output `y` [m] must be in m, but `sqrt(x)` is in m^(1/2)",
    ),
    ("output y [m] = min(x, L) + max(x, 0);", "OK"),
    (
        "output y = min(x, m);",
        "error: `min(x, m)` compares m with kg",
    ),
    ("output y [rad] = atan2(x, L);", "OK"),
    (
        "output y = x^m;",
        "error: an exponent must be dimensionless",
    ),
    (
        "output y = x^th;",
        "error: `x^th` raises m to a power that is not a constant number",
    ),
    ("output y [m/s^2] = -9.81*dot(n3, r2);", "OK"),
    ("output y [m^3] = x^(3/2)*L^1.5;", "OK"),
    // Lets are inferred; numbers take the unit they need.
    ("let r = pos(R.cm, B);\noutput d [m] = mag(r) - 0.5;", "OK"),
    (
        "let r = pos(R.cm, B);\noutput d [s] = mag(r);",
        "error: the output `d` [s] must be in s, but `mag(r)` is in m",
    ),
    // The escape, and numbers with units.
    (
        "output y [N] = (x + m) as [N];",
        "error: `x + m` adds m to kg",
    ),
    ("output y [N] = (k*m) as [N];", "OK"),
    ("output y [m] = x + 5 [mm];", "OK"),
    (
        "output y [m] = x + 5 [kg];",
        "error: `x + 5 [kg]` adds m to kg",
    ),
    // Unknown units are inferred from their uses.
    (
        "parameter kk = 3;\nforce f { on: B, along: n1, magnitude: -kk*x }\noutput y [N] = kk*x;",
        "OK",
    ),
    (
        "parameter kk = 3;\nforce f { on: B, along: n1, magnitude: -kk*x }\noutput y [m] = kk*x;",
        "error: the output `y` [m] must be in m, but `kk*x` is in N",
    ),
    // States, constraints, user functions.
    (
        "input F [N];\nstate lag [N] { initial: 0, derivative: (F - lag)/(0.1 [s]) }",
        "OK",
    ),
    (
        "input F [N];\nstate lag [N] { initial: 0, derivative: F - lag }",
        "error: the derivative of `lag` must be in N/s, but `F - lag` is in N",
    ),
    (
        "extern fn fr(speed [m/s]) -> [N];\nforce f { on: B, along: n1, magnitude: fr(v) }",
        "OK",
    ),
    (
        "extern fn fr(speed [m/s]) -> [N];\nforce f { on: B, along: n1, magnitude: fr(x) }",
        "error: argument 1 of `fr` must be in m/s, but `x` is in m",
    ),
    (
        "extern fn fr(speed);\nforce f { on: B, along: n1, magnitude: fr(v) }",
        "error: the magnitude of a force must be in N, but `fr(v)` is dimensionless",
    ),
    ("constraint cc [m] { position: x - L*cos(th) }", "OK"),
    (
        "constraint cc [m] { position: x - th }",
        "error: `x - th` subtracts rad from m",
    ),
    // A constraint's force: W per the unit of its speed-level expression.
    (
        "constraint cc [m] { position: x - L*cos(th) }\noutput y [N] = constraint_force(cc);",
        "OK",
    ),
    (
        "constraint cc [rad] { position: th - x/L }\noutput y [N m/rad] = constraint_force(cc);",
        "OK",
    ),
    (
        "constraint cs [m/s] { speed: v - L*w }\noutput y [N] = constraint_force(cs);",
        "OK",
    ),
    (
        "constraint cc [m] { position: x - L*cos(th) }\noutput y [N m] = constraint_force(cc);",
        "error: the output `y` [N m] must be in N m, but `constraint_force(cc)` is in N",
    ),
    // Bodies.
    (
        "body W { parent: R, mass: 2 [g], inertia: diag(1, 1, L), joint: [L, 0, 0] }",
        "error: an inertia must be in kg m^2, but `L` is in m",
    ),
    (
        "body W { parent: R, translate: 2, rotate: 1, initial: [L, 0.1], initial_speeds: [0, 1 [rad/s]] }",
        "OK",
    ),
    (
        "body W { parent: R, translate: 2, rotate: 1, initial: [0.1, L] }",
        "error: an initial coordinate must be in rad, but `L` is in m",
    ),
    (
        "motion mo { coordinate: x, value: L*sin(t) }",
        "error: the argument of `sin` must be dimensionless, but `t` is in s",
    ),
    (
        "parameter om = 2 [rad/s];\nmotion mo { coordinate: th, value: om*t }",
        "OK",
    ),
];

#[test]
fn models_are_checked() {
    let mut wrong = String::new();
    for &(items, expect) in MODELS {
        let got = resolved(&format!("{HEAD}{items}\n"));
        let ok = match expect {
            "OK" => got == "OK",
            _ => got.contains(expect) && got.matches("error").count() == 1,
        };
        if !ok {
            wrong += &format!("{items}\n  expected: {expect}\n--- got:\n{got}\n");
        }
    }
    assert!(wrong.is_empty(), "{wrong}");
}

/// In a sum of more than two terms the message names the term whose unit
/// differs from the terms before it.
#[test]
fn a_long_sum_names_its_odd_term() {
    let got = resolved(&format!(
        "{HEAD}force f {{ on: B, along: n1, magnitude: -k*x - c*v + m }}"
    ));
    assert!(
        got.contains("error: `-k*x - c*v + m` adds N to kg"),
        "{got}"
    );
    assert!(
        got.contains("help: the term `m` is in kg, the terms before it in N"),
        "{got}"
    );
    let two = resolved(&format!(
        "{HEAD}force f {{ on: B, along: n1, magnitude: m + x }}"
    ));
    assert!(!two.contains("the terms before it"), "{two}");
}

#[test]
fn a_parameter_in_a_unit_with_a_factor_is_converted() {
    let file = SourceFile::new(
        "test.sim",
        "model M;\nparameter a = 30 [deg];\nparameter d = 5 [mm];\n",
    );
    let model = parse_source(&file).unwrap();
    let r = resolve(&model).unwrap();
    let arena = &r.system.arena;
    let value = |name: &str| {
        let s = arena.symbol_named(name).unwrap();
        match arena.symbol(s).kind {
            crate::expr::SymbolKind::Parameter { default } => {
                (default, arena.symbol(s).unit.clone())
            }
            _ => unreachable!(),
        }
    };
    assert_eq!(
        value("a"),
        (30.0 * std::f64::consts::PI / 180.0, Some("rad".to_string()))
    );
    assert_eq!(value("d"), (5.0 * 1e-3, Some("m".to_string())));
}

/// docs/language.md lists every unit of the table, with its factor.
#[test]
fn the_language_reference_lists_every_unit() {
    let doc = include_str!("../../../../docs/language.md");
    for u in super::table::UNITS {
        let row = format!("| `{}` | ", u.symbol);
        let line = doc.lines().find(|l| l.starts_with(&row));
        let line = line.unwrap_or_else(|| panic!("docs/language.md has no row for `{}`", u.symbol));
        let factor = if u.factor == 1.0 {
            "| 1 |".to_string()
        } else {
            String::new()
        };
        assert!(factor.is_empty() || line.contains(&factor), "{line}");
        assert!(
            line.contains(if u.prefixable { "| yes |" } else { "| no |" }),
            "{line}"
        );
    }
    for (prefix, _) in super::table::PREFIXES {
        assert!(doc.contains(&format!("`{prefix}`")), "prefix {prefix}");
    }
}

#[test]
fn an_output_in_a_unit_with_a_factor_is_converted() {
    use crate::expr::{Bindings, NoUserFunctions};
    let text = format!("{HEAD}output a [deg] = th;\noutput d [mm] = x;\n");
    let file = SourceFile::new("test.sim", &text);
    let model = parse_source(&file).unwrap();
    let r = resolve(&model).unwrap();
    let arena = &r.system.arena;
    let mut b = Bindings::with_defaults(arena);
    b.set(arena.symbol_named("x").unwrap(), 0.25);
    b.set(
        arena.symbol_named("th").unwrap(),
        std::f64::consts::FRAC_PI_2,
    );
    let y: Vec<f64> = r
        .system
        .outputs()
        .iter()
        .map(|o| arena.eval(o.expr, &b, &mut NoUserFunctions))
        .collect();
    assert!(
        (y[0] - 90.0).abs() < 1e-12 && (y[1] - 250.0).abs() < 1e-12,
        "{y:?}"
    );
}

/// A load whose direction has a unit: the message says the direction
/// scales it (its fix is `dir(...)`, not `as` on the magnitude).
#[test]
fn a_direction_with_a_unit_is_named_as_the_scale() {
    let got = resolved(&format!(
        "{HEAD}moment mt {{ on: R, about: pos(R), magnitude: -k*L*L*th }}"
    ));
    assert!(
        got.contains("note: `about` is in m, not a unit vector"),
        "{got}"
    );
    assert!(got.contains("write `about: dir(...)`"), "{got}");
    // A spring written along its vector is right as it stands.
    let spring = resolved(&format!(
        "{HEAD}force f {{ on: B, along: pos(B), magnitude: -k }}"
    ));
    assert_eq!(spring, "OK");
}

/// A user function called with the wrong number of arguments is reported
/// once: its arguments' units are not checked against other positions.
#[test]
fn a_call_with_the_wrong_arity_adds_no_unit_error() {
    let got = resolved(&format!(
        "{HEAD}extern fn tire(k [N/m], d [m]) -> [N];\nforce f {{ on: B, along: n1, magnitude: tire(x) }}"
    ));
    assert!(got.contains("`tire` takes 2 arguments"), "{got}");
    assert!(!got.contains("argument 1 of `tire`"), "{got}");
}
