//! Static cases with known answers, the chains' reactions against
//! Pinocchio's RNEA and their energy against SymPy's.

use super::support::{
    close, compile_text, model_text, output_names, outputs_at, outputs_with, parameter_values,
};
use autosim_core::pipeline::Compiled;

/// A pendulum hanging at rest carries its weight at the hinge, straight
/// up, and no moment.
#[test]
fn pendulum_at_rest_carries_its_weight() {
    let c = compile_text(
        "pendulum",
        "model P;
         parameters { m = 1.3 [kg], L = 0.7 [m], g = 9.81 [m/s^2] }
         body Rod { rotate: 1, mass: m, cm: [0, 0, -L], inertia: diag(0.01, 0.02, 0.03) }
         gravity = -g*n3;
         output f1 [N] = dot(reaction_force(Rod), n1);
         output f2 [N] = dot(reaction_force(Rod), n2);
         output f3 [N] = dot(reaction_force(Rod), n3);
         output m1 [N m] = dot(reaction_moment(Rod), n1);
         output m2 [N m] = dot(reaction_moment(Rod), n2);
         output m3 [N m] = dot(reaction_moment(Rod), n3);",
    );
    let y = outputs_at(&c, &[0.0, 0.0], 0.0);
    let expect = [0.0, 0.0, 1.3 * 9.81, 0.0, 0.0, 0.0];
    for (k, (a, b)) in y.iter().zip(expect).enumerate() {
        assert!(close(*a, b, 1e-14), "component {k}: {a} against {b}");
    }
}

/// A block on a horizontal slider held up in part by a vertical spring:
/// at rest the slider carries the weight less the spring's pull, and
/// nothing along its free direction.
#[test]
fn slider_carries_weight_less_spring() {
    let c = compile_text(
        "slider",
        "model S;
         parameters { m = 2 [kg], k = 50 [N/m], h = 1 [m], L0 = 0.6 [m], g = 9.81 [m/s^2] }
         body B { translate: [1], mass: m, inertia: diag(0.1, 0.1, 0.1) }
         point A in N at [0, 0, h];
         force spring { on: B.cm, reaction: A, along: dir(pos(B.cm, A)), magnitude: -k*(mag(pos(B.cm, A)) - L0) }
         gravity = -g*n3;
         output f1 [N] = dot(reaction_force(B), n1);
         output f3 [N] = dot(reaction_force(B), n3);
         output spring_power [W] = power(spring);",
    );
    // Directly below A: the spring pulls up with k (h - L0).
    let y = outputs_at(&c, &[0.0, 0.0], 0.0);
    let pull = 50.0 * (1.0 - 0.6);
    assert!(close(y[0], 0.0, 1e-14), "free direction: {}", y[0]);
    assert!(
        close(y[1], 2.0 * 9.81 - pull, 1e-14),
        "{} against {}",
        y[1],
        2.0 * 9.81 - pull
    );
    // Moving at 0.3 m/s at x = 0.4: the spring's power is F·v.
    let y = outputs_at(&c, &[0.4, 0.3], 0.0);
    let len = (0.4f64 * 0.4 + 1.0).sqrt();
    let f1 = -50.0 * (len - 0.6) * 0.4 / len;
    assert!(
        close(y[2], f1 * 0.3, 1e-14),
        "power {} against {}",
        y[2],
        f1 * 0.3
    );
    assert!(
        close(y[0], 0.0, 1e-13),
        "free direction while moving: {}",
        y[0]
    );
}

/// A carriage held at a height by a rail (a position constraint of the
/// form `dot(pos(P), d) - h`), a pendulum hanging from it, at rest: the
/// rail carries the whole weight, the pendulum's hinge its own, and the
/// carriage's joint (free along n1 and n3) nothing.
#[test]
fn rail_carries_the_weight_of_what_hangs_from_it() {
    let c = compile_text(
        "rail",
        "model Rail;
         parameters { mc = 2 [kg], mp = 0.7 [kg], h = 1.5 [m], L = 0.4 [m], g = 9.81 [m/s^2] }
         body Car { translate: [1, 3], mass: mc, inertia: diag(0.1, 0.1, 0.1), initial: [0.3, 1.5] }
         body Rod { parent: Car, rotate: 2, mass: mp, cm: [0, 0, -L], inertia: diag(0.01, 0.01, 0.01) }
         constraint rail [m] { position: dot(pos(Car), n3) - h }
         gravity = -g*n3;
         output rail_force [N] = constraint_force(rail);
         output car_1 [N] = dot(reaction_force(Car), n1);
         output car_2 [N] = dot(reaction_force(Car), n2);
         output car_3 [N] = dot(reaction_force(Car), n3);
         output car_moment [N m] = mag(reaction_moment(Car));
         output rod_1 [N] = dot(reaction_force(Rod), n1);
         output rod_3 [N] = dot(reaction_force(Rod), n3);",
    );
    // States: x, z, the rod's angle, then the free speeds (x's, the rod's).
    let y = outputs_at(&c, &[0.3, 1.5, 0.0, 0.0, 0.0], 0.0);
    let expect = [(2.0 + 0.7) * 9.81, 0.0, 0.0, 0.0, 0.0, 0.0, 0.7 * 9.81];
    for (k, (a, b)) in y.iter().zip(expect).enumerate() {
        assert!(close(*a, b, 1e-14), "output {k}: {a} against {b} ({y:?})");
    }
}

/// The chains' joint reactions at 50 random states against Pinocchio's
/// RNEA joint forces (less the springs, which the model applies).
#[test]
fn chain_reactions_match_pinocchio() {
    for (kind, file) in [
        ("planar", "chain_planar_5.sim"),
        ("spatial", "chain_spatial_5.sim"),
    ] {
        let mut text = model_text(file);
        for i in 1..=5 {
            for (f, what) in [("reaction_force", "f"), ("reaction_moment", "m")] {
                for a in 1..=3 {
                    let unit = if what == "f" { "N" } else { "N m" };
                    text.push_str(&format!(
                        "output {what}{i}_{a} [{unit}] = dot({f}(B{i}), B{i}.{a});\n"
                    ));
                }
            }
        }
        let c = compile_text(file, &text);
        let data = autosim_test_support::load(&format!("reactions-chain-{kind}-5"));
        let mut worst: f64 = 0.0;
        for s in data["samples"].as_array().expect("samples") {
            let mut x = autosim_test_support::floats(&s["q"]);
            x.extend(autosim_test_support::floats(&s["u"]));
            // The model's own output (tip height) first.
            let y = &outputs_at(&c, &x, 0.0)[1..];
            for i in 0..5 {
                let r = &s["reactions"][i];
                let mut want = autosim_test_support::floats(&r["force"]);
                want.extend(autosim_test_support::floats(&r["moment"]));
                let got = &y[6 * i..6 * i + 6];
                let scale = want.iter().fold(1.0f64, |a, x| a.max(x.abs()));
                let err = autosim_test_support::max_diff(got, &want) / scale;
                worst = autosim_test_support::worst_of(worst, err);
                assert!(
                    err < 1e-10,
                    "{kind} link {}: {got:?} against {want:?}",
                    i + 1
                );
            }
        }
        eprintln!("chain-{kind}-5 reactions against Pinocchio: worst relative error {worst:.2e}");
    }
}

/// Kinetic plus gravitational potential energy (and the springs', written
/// in the model) against SymPy's energy along the undamped chains'
/// reference trajectories.
#[test]
fn chain_energy_matches_sympy() {
    for kind in ["planar", "spatial"] {
        let file = format!("chain_{kind}_3.sim");
        let mut text = model_text(&file);
        text.push_str("output energy [J] = kinetic_energy() + potential_energy() + k*(q1^2 + q2^2 + q3^2)/2;\n");
        text.push_str("output ke [J] = kinetic_energy();\noutput ke_parts [J] = kinetic_energy(B1) + kinetic_energy(B2, B3);\n");
        let c = compile_text(&file, &text);
        let data = autosim_test_support::load(&format!("chain-{kind}-3-trajectory"));
        let params = parameter_values(&c, |p| match p.name.as_str() {
            "c" => 0.0,
            n => data["parameters"][n].as_f64().unwrap_or(p.default),
        });
        let mut worst: f64 = 0.0;
        for r in data["records"].as_array().expect("records") {
            let mut x = autosim_test_support::floats(&r["q"]);
            x.extend(autosim_test_support::floats(&r["u"]));
            let y = outputs_with(&c, &params, &x, 0.0);
            let want = r["energy"].as_f64().expect("energy");
            let err = (y[1] - want).abs() / want.abs().max(1.0);
            worst = autosim_test_support::worst_of(worst, err);
            assert!(err < 1e-12, "{kind}: energy {} against {want}", y[1]);
            assert!(close(y[2], y[3], 1e-14), "kinetic energy by parts");
        }
        eprintln!("chain-{kind}-3 energy against SymPy: worst relative error {worst:.2e}");
    }
}

/// The satellite's boom hinge reaction costs operations only when an
/// output asks for it: with the output left out by the scene's `outputs`,
/// the program's costs are those of the model without it.
#[test]
fn reactions_not_requested_cost_nothing() {
    use autosim_core::diag::SourceFile;
    use autosim_core::model::Scene;
    use autosim_core::opt::BlockKind;
    use autosim_core::pipeline::compile_source_scene;
    let text = model_text("satellite.sim");
    let with = format!(
        "{text}\noutput hinge_force [N] = dot(reaction_force(E), e1);\noutput hinge_moment [N m] = dot(reaction_moment(E), e1);\n"
    );
    let names = output_names(&compile_text("satellite.sim", &text));
    let compile = |text: &str, outputs: Option<&[String]>| {
        let file = SourceFile::new("satellite.sim", text.to_string());
        let scene = Scene {
            outputs: outputs.map(|o| o.iter().map(|n| Scene::name(n)).collect()),
            ..Scene::default()
        };
        match compile_source_scene(&file, &scene) {
            Ok(c) => c,
            Err(d) => panic!("{}", d.render(&file)),
        }
    };
    let ops =
        |c: &Compiled| [BlockKind::Derivatives, BlockKind::Outputs].map(|k| c.program.block(k).ops);
    let base = ops(&compile(&text, None));
    let pruned = ops(&compile(&with, Some(&names)));
    let asked = ops(&compile(&with, None));
    eprintln!("satellite: derivatives, outputs: without {base:?}, asked for {asked:?}");
    assert_eq!(base, pruned, "an output not generated must cost nothing");
    // The reaction's expressions join the arena the derivatives are built
    // in, and the order of a sum's terms follows their ids: the factored
    // form the optimizer finds may differ by an addition or two (470 and
    // 472 additions at the merge of the trig-polynomial simplification).
    let (b, a) = (base[0].total() as f64, asked[0].total() as f64);
    assert!(
        (a - b).abs() <= 0.01 * b,
        "derivatives cost about the same: {b} and {a} operations"
    );
    assert_ne!(base[1], asked[1], "the reaction is computed when asked for");
}
