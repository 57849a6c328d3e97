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

/// A load hung from a trolley by a cable written as a distance,
/// `mag(pos(Load, Trolley)) - L`: its multiplier is the cable's pull
/// along the line (Newton along the cable:
/// `T = −m g r̂₃ − m ẍ r̂₁ + m |v_rel|²/L`, `λ = −T`), the rail carries
/// `M g − T r̂₃`, and the trolley, free along n1, is pulled by `T r̂₁`.
#[test]
fn a_cable_written_as_a_distance_pulls_along_its_line() {
    let c = compile_text(
        "crane",
        "model Crane;
         parameters { M = 5 [kg], m = 2 [kg], L = 1.5 [m], g = 9.81 [m/s^2] }
         body Trolley { translate: 1, q: [x], u: [v], mass: M, inertia: 0 }
         body Load { parent: Trolley, translate: [1, 3], q: [xl, zl], u: [vxl, vzl], mass: m, inertia: 0, initial: [0.9, -1.2] }
         gravity = -g*n3;
         constraint cable [m] { position: mag(pos(Load, Trolley)) - L, dependent: zl }
         output pull [N] = constraint_force(cable);
         output rail [N] = dot(reaction_force(Trolley), n3);
         output a [m/s^2] = dxdt(v);",
    );
    let names = output_names(&c);
    // On the cable's circle, moving along it: r̂ = (0.6, 0, −0.8).
    let y = outputs_at(&c, &[0.0, 0.9, -1.2, 0.3, 0.8, 0.6], 0.0);
    let get = |n: &str| y[names.iter().position(|m| m == n).expect(n)];
    let (m, big_m, g, l) = (2.0, 5.0, 9.81, 1.5);
    let (r1, r3) = (0.6, -0.8);
    let a = get("a");
    let tension = -m * g * r3 - m * a * r1 + m * 1.0 / l;
    assert!(
        close(get("pull"), -tension, 1e-12),
        "{} against {}",
        get("pull"),
        -tension
    );
    assert!(
        close(get("rail"), big_m * g - tension * r3, 1e-12),
        "{}",
        get("rail")
    );
    assert!(
        close(big_m * a, tension * r1, 1e-12),
        "M a = {} against T r̂₁ = {}",
        big_m * a,
        tension * r1
    );
}
