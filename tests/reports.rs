//! Reports are written for people: no negative zeros, an unstable mode
//! said to be unstable, repeated zero eigenvalues grouped, counts in the
//! singular where there is one, no `h []` for a quantity without a unit,
//! and the mass matrix never printed under a parameter's name.

use autosim::runtime::OpCount;
use autosim::runtime::analysis::LinearSystem;
use autosim::runtime::io::CsvWriter;
use autosim::runtime::{RunSettings, integrate::Rk4, run};

autosim::model!(file = "examples/models/pendulum.sim");

autosim::model! {
    /// Two masses on a line joined by a spring, free of any wall: the
    /// pair translates freely (a double zero eigenvalue).
    model FreePair;
    settings { linearize: true }
    parameters { m = 2 [kg], k = 50 [N/m] }
    body B1 { translate: 1, q: [x1], u: [v1], mass: m, inertia: 0 }
    body B2 { translate: 1, q: [x2], u: [v2], mass: m, inertia: 0 }
    force s12 { on: B2, reaction: B1, along: n1, magnitude: -k*(x2 - x1) }
    /// A ratio: no unit.
    output stretch = (x2 - x1)/1;
}

#[test]
fn an_unstable_mode_is_said_to_be_unstable() {
    let mut m = pendulum::Pendulum::new();
    let up = LinearSystem::of(&mut m, 0.0, &[std::f64::consts::PI, 0.0]).unwrap();
    let report = up.modes_report();
    // λ = ±sqrt(g/L) = ±3.7436: the growing one was "time constant
    // -0.267 s" with no word of instability.
    assert!(
        report.contains("λ = 3.743566 1/s, unstable: grows by a factor e every 0.267125 s"),
        "{report}"
    );
    assert!(
        report.contains("λ = -3.743566 1/s, time constant 0.267125 s"),
        "{report}"
    );
    assert!(!report.contains("-0.000000"), "{report}");
}

#[test]
fn zero_eigenvalues_are_one_line_and_zeros_print_as_zero() {
    let mut m = free_pair::FreePair::new();
    let sys = LinearSystem::of(&mut m, 0.0, &[0.0; 4]).unwrap();
    let report = sys.modes_report();
    let lines: Vec<&str> = report.lines().collect();
    assert_eq!(lines.len(), 2, "{report}");
    assert!(
        lines[0].starts_with("λ = 0, 2 times (rigid-body or ignorable motions"),
        "{report}"
    );
    // The oscillation: ωn = sqrt(2k/m) = sqrt(50), undamped; its ζ is
    // exactly zero and must not print as -0.000000.
    assert!(
        lines[1].contains("ωn = 7.071068 rad/s, ζ = 0.000000"),
        "{report}"
    );
    let md = sys.to_markdown();
    assert!(
        !md.contains("-0.000000") && !md.contains("0.000000e0"),
        "{md}"
    );
    assert!(md.contains("| `x1`′ | 0 | 0 | 1.000000e0 | 0 |"), "{md}");
}

#[test]
fn counts_read_as_english() {
    let ops = OpCount {
        adds: 1,
        muls: 2,
        divs: 1,
        funcs: 1,
        user_calls: 0,
    };
    assert_eq!(
        ops.to_string(),
        "1 add, 2 multiplies, 1 divide, 1 function, 0 user calls"
    );
}

#[test]
fn a_column_without_a_unit_has_no_brackets() {
    let mut model = free_pair::FreePair::new();
    let mut x = [0.0, 0.1, 0.0, 0.0];
    let mut csv = CsvWriter::<free_pair::FreePair, _>::new(Vec::new()).unwrap();
    let settings = RunSettings::new(0.0, 0.1, 0.01, 0.1);
    run(&mut model, &mut Rk4::new(), &mut x, &settings, &mut csv).unwrap();
    let text = String::from_utf8(csv.into_inner().unwrap()).unwrap();
    assert_eq!(
        text.lines().next(),
        Some("time [s],x1 [m],x2 [m],v1 [m/s],v2 [m/s],stretch")
    );
}

#[test]
fn the_mass_matrix_is_not_named_after_a_parameter() {
    use autosim_core::diag::SourceFile;
    use autosim_core::pipeline::compile_source;
    let text = "model Cart;\nsettings { formulation: mass_matrix }\n\
                parameters { M = 2 [kg], f = 1 [N] }\n\
                body C { translate: 1, mass: M, inertia: 0 }\n\
                force push { on: C, along: n1, magnitude: f }\n";
    let c = compile_source(&SourceFile::new("cart.sim", text)).unwrap();
    let listing = c.program.to_string();
    assert!(listing.contains("MassMatrix[1,1] = M"), "{listing}");
    assert!(listing.contains("forcing[1] = f"), "{listing}");
    assert!(!listing.contains("M[1,1]"), "{listing}");
}
