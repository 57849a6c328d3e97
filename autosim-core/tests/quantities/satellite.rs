//! The satellite's boom hinge reaction, kinetic energy and momenta at the
//! reference's sampled states (`tests/reference/satellite.json`, SymPy)
//! against the Newton–Euler computation of `newton_euler.rs` with the
//! reference's accelerations; the kinetic energy also against the
//! reference's own.

use super::newton_euler::{boom_hinge_reaction, satellite_masses, satellite_motion};
use super::support::{compile_text, model_text, output_names, outputs_calling, parameter_values};
use autosim_core::opt::UserCalls;
use autosim_core::pipeline::Compiled;
use autosim_test_support::{SatelliteSample, load, satellite_samples, worst_of};
use nalgebra::Vector3;

/// The point the angular momentum is taken about (N axes).
const O: [f64; 3] = [0.3, -0.2, 0.5];

/// The satellite with outputs of the quantities, in N's axes.
fn satellite_with_quantities() -> Compiled {
    let mut text = model_text("satellite.sim");
    text.push_str(&format!(
        "point O in N at [{}, {}, {}];\n",
        O[0], O[1], O[2]
    ));
    let vectors = [
        ("hinge_force", "reaction_force(E)", "N"),
        ("hinge_moment", "reaction_moment(E)", "N m"),
        ("hinge_moment_cm", "reaction_moment(E, F.cm)", "N m"),
        ("momentum", "momentum()", "kg m/s"),
        ("momentum_cd", "momentum(C, D)", "kg m/s"),
        ("angular", "angular_momentum(O)", "kg m^2/s"),
        ("angular_f", "angular_momentum(B.cm, F)", "kg m^2/s"),
    ];
    for (name, value, unit) in vectors {
        for a in 1..=3 {
            text.push_str(&format!(
                "output {name}_{a} [{unit}] = dot({value}, n{a});\n"
            ));
        }
    }
    text.push_str("output kinetic [J] = kinetic_energy();\n");
    text.push_str("output kinetic_f [J] = kinetic_energy(F);\n");
    text.push_str("output potential [J] = potential_energy();\n");
    compile_text("satellite.sim", &text)
}

/// The outputs at a reference sample, by name.
fn outputs_at_sample(c: &Compiled, params: &[f64], s: &SatelliteSample) -> impl Fn(&str) -> f64 {
    let mut function = |_f: usize, args: &[f64]| s.thrust[args[1] as usize - 1];
    let mut subroutine = |_s: usize, _a: &[f64]| s.cmd.to_vec();
    let mut user = UserCalls {
        function: &mut function,
        subroutine: &mut subroutine,
    };
    let y = outputs_calling(c, params, &s.state(), s.t, &mut user);
    let names = output_names(c);
    move |name: &str| {
        let k = names.iter().position(|n| n == name);
        y[k.unwrap_or_else(|| panic!("no output {name}"))]
    }
}

fn vector(y: &impl Fn(&str) -> f64, name: &str) -> Vector3<f64> {
    Vector3::new(
        y(&format!("{name}_1")),
        y(&format!("{name}_2")),
        y(&format!("{name}_3")),
    )
}

/// The worst of `|got − want| / max(1, |want|)` over the components of
/// the named vector outputs, each asserted below `tol`.
fn check(y: &impl Fn(&str) -> f64, t: f64, cases: &[(&str, Vector3<f64>)], tol: f64) -> f64 {
    let mut worst: f64 = 0.0;
    for (name, want) in cases {
        let got = vector(y, name);
        let err = (got - want).amax() / want.amax().max(1.0);
        assert!(err < tol, "t = {t}: {name} {got:?} against {want:?}");
        worst = worst_of(worst, err);
    }
    worst
}

#[test]
fn satellite_quantities_match_newton_euler() {
    let data = load("satellite");
    let p = |n: &str| {
        data["parameters"][n]
            .as_f64()
            .unwrap_or_else(|| panic!("no parameter {n}"))
    };
    let c = satellite_with_quantities();
    let params = parameter_values(&c, |q| p(&q.name));
    let masses = satellite_masses(&p);
    let o = Vector3::from(O);
    let (mut worst_reaction, mut worst_momenta, mut worst_energy) = (0.0f64, 0.0f64, 0.0f64);
    let reference = data["samples"].as_array().expect("samples");
    for (s, r) in satellite_samples().iter().zip(reference) {
        let y = outputs_at_sample(&c, &params, s);
        let motion = satellite_motion(&p, &s.q, &s.u, &s.du);
        let [b, cl, d, _, f] = &motion;
        let bodies = [
            (&masses[0], b),
            (&masses[1], cl),
            (&masses[2], d),
            (&masses[3], f),
        ];

        // The boom hinge: force, moment about E's origin and about F's
        // mass center.
        let (force, moment) = boom_hinge_reaction(&p, &s.q, &s.u, &motion);
        let arm = -f.arm(masses[3].cm);
        let moment_cm = moment + arm.cross(&force);
        let reactions = [
            ("hinge_force", force),
            ("hinge_moment", moment),
            ("hinge_moment_cm", moment_cm),
        ];
        worst_reaction = worst_of(worst_reaction, check(&y, s.t, &reactions, 1e-10));

        // Momenta of every body, of some, about a point of N and a body's
        // mass center.
        let total = |which: &[usize], of: &dyn Fn(usize) -> Vector3<f64>| {
            which.iter().map(|&k| of(k)).sum::<Vector3<f64>>()
        };
        let momentum = |k: usize| bodies[k].0.momentum(bodies[k].1);
        let b_cm = b.origin;
        let angular = |k: usize| bodies[k].0.angular_momentum(bodies[k].1, &o);
        let angular_f = |_: usize| masses[3].angular_momentum(f, &b_cm);
        let momenta = [
            ("momentum", total(&[0, 1, 2, 3], &momentum)),
            ("momentum_cd", total(&[1, 2], &momentum)),
            ("angular", total(&[0, 1, 2, 3], &angular)),
            ("angular_f", total(&[3], &angular_f)),
        ];
        worst_momenta = worst_of(worst_momenta, check(&y, s.t, &momenta, 1e-12));

        // Kinetic energy: here, the reference's, and of the boom alone.
        let kinetic: f64 = bodies.iter().map(|(m, x)| m.kinetic_energy(x)).sum();
        let reference_kinetic = r["kinetic_energy"].as_f64().expect("kinetic_energy");
        for (name, got, want) in [
            ("kinetic (this file's)", y("kinetic"), kinetic),
            ("kinetic (reference)", y("kinetic"), reference_kinetic),
            (
                "this file's kinetic (reference)",
                kinetic,
                reference_kinetic,
            ),
            ("kinetic_f", y("kinetic_f"), masses[3].kinetic_energy(f)),
        ] {
            let err = (got - want).abs() / want.abs().max(1.0);
            worst_energy = worst_of(worst_energy, err);
            assert!(err < 1e-12, "t = {}: {name} {got} against {want}", s.t);
        }
        assert_eq!(y("potential"), 0.0, "no gravity");
    }
    eprintln!(
        "satellite at {} reference states: boom hinge reaction worst relative error {worst_reaction:.2e}, momenta {worst_momenta:.2e}, kinetic energy {worst_energy:.2e}",
        reference.len()
    );
}
