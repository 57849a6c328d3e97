//! Static cases with known answers for loads read from speed
//! constraints: a beam on a hinge (that also slides along n1) and a
//! roller at its tip carries half its weight at each; held level by a
//! constraint on its rotation instead, the hinge carries the whole weight
//! and the constraint the moment of it.

use super::support::{close, compile_text, output_names, outputs_at};

/// The beam's model with `support` (a constraint) and the outputs the
/// tests read.
fn beam(support: &str) -> autosim_core::pipeline::Compiled {
    let text = format!(
        "model Beam;
         parameters {{ m = 2 [kg], L = 3 [m], g = 9.81 [m/s^2] }}
         body Beam {{ translate: [1], rotate: 2, mass: m, cm: [L/2, 0, 0], inertia: diag(0.1, 0.2, 0.3) }}
         point Tip in Beam at [L, 0, 0];
         gravity = -g*n3;
         {support}
         output hinge_f1 [N] = dot(reaction_force(Beam), n1);
         output hinge_f3 [N] = dot(reaction_force(Beam), n3);
         output hinge_m2 [N m] = dot(reaction_moment(Beam), n2);
         output support = constraint_force(s);"
    );
    compile_text("beam", &text)
}

/// The outputs at rest, level (every coordinate and speed zero), in the
/// order `hinge_f1, hinge_f3, hinge_m2, support`.
fn at_rest(c: &autosim_core::pipeline::Compiled) -> Vec<f64> {
    let names = output_names(c);
    let y = outputs_at(c, &[0.0; 3], 0.0);
    ["hinge_f1", "hinge_f3", "hinge_m2", "support"]
        .iter()
        .map(|n| y[names.iter().position(|m| m == n).expect(n)])
        .collect()
}

#[test]
fn beam_on_a_roller_carries_half_its_weight_at_each_end() {
    let y = at_rest(&beam("constraint s [m/s] { speed: dot(vel(Tip), n3) }"));
    let half = 2.0 * 9.81 / 2.0;
    let expect = [0.0, half, 0.0, half];
    for (k, (a, b)) in y.iter().zip(expect).enumerate() {
        assert!(close(*a, b, 1e-14), "output {k}: {a} against {b}");
    }
}

#[test]
fn beam_held_level_carries_its_weight_at_the_hinge() {
    // The rotation lock's load is a moment λ n2: it holds gravity's moment
    // about the hinge, (L/2) n1 × (−m g n3) = (L/2) m g n2.
    let y = at_rest(&beam("constraint s { speed: dot(rot(Beam), n2) }"));
    let expect = [0.0, 2.0 * 9.81, 0.0, -1.5 * 2.0 * 9.81];
    for (k, (a, b)) in y.iter().zip(expect).enumerate() {
        assert!(close(*a, b, 1e-14), "output {k}: {a} against {b}");
    }
}
