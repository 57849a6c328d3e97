//! The rolling disc's friction force (`constraint_force` of its two
//! no-slip constraints `dot(slip, n1)`, `dot(slip, n2)`, with `slip` the
//! velocity of the disc's material point at the contact: the force along
//! n1, n2 on the disc there) at the reference's sampled states
//! (`tests/reference/rolling-disc.json`, SymPy) against Newton's second
//! law with the reference's accelerations: gravity is along n3, so the
//! contact's horizontal force is the mass times the centre's horizontal
//! acceleration (`du_x`, `du_y`: the translation speeds are `dq/dt` in N).

use super::support::{compile_text, model_text, outputs_with};
use autosim_test_support::{floats, load, max_diff, program_parameters, worst_of};

/// The model's state at a reference sample: the coordinates, then the
/// independent speeds (the reference's last three).
fn state(q: &[f64], u: &[f64]) -> Vec<f64> {
    q.iter().chain(&u[3..]).copied().collect()
}

#[test]
fn rolling_disc_friction_matches_newton() {
    let data = load("rolling-disc");
    let m = data["parameters"]["m"].as_f64().expect("m");
    let mut text = model_text("rolling_disc.sim");
    text.push_str("output friction_n1 [N] = constraint_force(roll_n1);\n");
    text.push_str("output friction_n2 [N] = constraint_force(roll_n2);\n");
    let c = compile_text("rolling_disc.sim", &text);
    let params = program_parameters(&c.program, &data);
    let mut worst = 0.0f64;
    let samples = data["samples"].as_array().expect("samples");
    for s in samples {
        let (q, u, du) = (floats(&s["q"]), floats(&s["u"]), floats(&s["du"]));
        let y = outputs_with(&c, &params, &state(&q, &u), 0.0);
        // The model's outputs (energy, yaw_rate, speed), then ours.
        let got = [y[3], y[4]];
        let want = [m * du[0], m * du[1]];
        let scale = want.iter().fold(1.0f64, |a, f| a.max(f.abs()));
        let err = max_diff(&got, &want) / scale;
        worst = worst_of(worst, err);
        assert!(err < 1e-10, "{got:?} against {want:?}");
    }
    eprintln!(
        "rolling disc at {} reference states: friction force worst relative error {worst:.2e}",
        samples.len()
    );
}

/// The rolling disc with its ground contact written through the contact
/// point `C` (a point of the disc that moves in it: the rim's lowest
/// point): `dot(pos(C), n3)`, the same constraint as the example's
/// `dot(pos(D), n3) - r*cos(phi)` where the lean is under a right angle.
fn disc_with_contact_point(outputs: &str) -> String {
    let text = model_text("rolling_disc.sim");
    let touch = "constraint touch [m] { position: dot(pos(D), n3) - r*cos(phi), dependent: z }";
    assert!(text.contains(touch), "rolling_disc.sim's contact changed");
    let through_c = "point C \"contact\" in D at [dot(contact, d1), dot(contact, d2), dot(contact, d3)];\n\
                     constraint touch [m] { position: dot(pos(C), n3), dependent: z }";
    text.replace(touch, through_c) + outputs
}

/// `[x, y, z]` in N of `v` in the disc's axes: body-fixed 3-1-2 (yaw `psi`
/// about n3, lean `phi` about the yawed axis 1, spin `theta` about D.2).
fn disc_axes(q: &[f64]) -> nalgebra::Rotation3<f64> {
    use nalgebra::{Rotation3, Vector3};
    Rotation3::from_axis_angle(&Vector3::z_axis(), q[3])
        * Rotation3::from_axis_angle(&Vector3::x_axis(), q[4])
        * Rotation3::from_axis_angle(&Vector3::y_axis(), q[5])
}

/// The contact force (`constraint_force` of `touch`, `roll_n1`,
/// `roll_n2`: along n3, n1, n2 at the contact) against the Newton–Euler
/// equations of the disc written here with the reference's accelerations
/// (SymPy): `m a* = F + m g` and, about the centre, `I α + ω × I ω =
/// r_C × F` (`r_C = −r l3`, the lean frame's axis 3; `ω = u4 d1 + u5 d2 +
/// u6 d3` in the disc's axes, `α` its rates); and the reaction of the
/// disc's free joint, zero when the contact loads are put where they act.
#[test]
fn rolling_disc_contact_force_matches_newton_euler() {
    use nalgebra::{Matrix3, Rotation3, Vector3};
    let data = load("rolling-disc");
    let (m, r, g) = ["m", "r", "g"]
        .map(|k| data["parameters"][k].as_f64().expect(k))
        .into();
    let outputs = "output lambda_n3 [N] = constraint_force(touch);\n\
                   output lambda_n1 [N] = constraint_force(roll_n1);\n\
                   output lambda_n2 [N] = constraint_force(roll_n2);\n\
                   output joint_f1 [N] = dot(reaction_force(D), n1);\n\
                   output joint_f2 [N] = dot(reaction_force(D), n2);\n\
                   output joint_f3 [N] = dot(reaction_force(D), n3);\n\
                   output joint_m1 [N*m] = dot(reaction_moment(D), n1);\n\
                   output joint_m2 [N*m] = dot(reaction_moment(D), n2);\n\
                   output joint_m3 [N*m] = dot(reaction_moment(D), n3);\n";
    let c = compile_text("rolling_disc.sim", &disc_with_contact_point(outputs));
    let names = super::support::output_names(&c);
    let at = |name: &str| names.iter().position(|n| n == name).expect(name);
    let params = program_parameters(&c.program, &data);
    let inertia = Matrix3::from_diagonal(&Vector3::new(
        m * r * r / 4.0,
        m * r * r / 2.0,
        m * r * r / 4.0,
    ));
    let (mut worst_force, mut worst_moment, mut worst_joint) = (0.0f64, 0.0f64, 0.0f64);
    let samples = data["samples"].as_array().expect("samples");
    for s in samples {
        let (q, u, du) = (floats(&s["q"]), floats(&s["u"]), floats(&s["du"]));
        let y = outputs_with(&c, &params, &state(&q, &u), 0.0);
        let f = Vector3::new(y[at("lambda_n1")], y[at("lambda_n2")], y[at("lambda_n3")]);
        let scale = m * g;
        let newton = Vector3::new(du[0], du[1], du[2]) * m - f - Vector3::new(0.0, 0.0, -m * g);
        worst_force = worst_of(worst_force, newton.amax() / scale);
        let lean: Rotation3<f64> = Rotation3::from_axis_angle(&Vector3::z_axis(), q[3])
            * Rotation3::from_axis_angle(&Vector3::x_axis(), q[4]);
        let r_c = lean * Vector3::new(0.0, 0.0, -r);
        let to_disc = disc_axes(&q).inverse();
        let (w, alpha) = (
            Vector3::new(u[3], u[4], u[5]),
            Vector3::new(du[3], du[4], du[5]),
        );
        let euler = inertia * alpha + w.cross(&(inertia * w)) - to_disc * r_c.cross(&f);
        worst_moment = worst_of(worst_moment, euler.amax() / (scale * r));
        let joint: Vec<f64> = ["f1", "f2", "f3", "m1", "m2", "m3"]
            .iter()
            .map(|k| y[at(&format!("joint_{k}"))])
            .collect();
        let joint = joint[..3]
            .iter()
            .map(|v| v / scale)
            .chain(joint[3..].iter().map(|v| v / (scale * r)));
        worst_joint = joint.fold(worst_joint, |a, v| worst_of(a, v.abs()));
    }
    eprintln!(
        "rolling disc at {} reference states, contact written through its point: m a* = F + m g worst {worst_force:.2e} (of m g), \
         I α + ω × I ω = r_C × F worst {worst_moment:.2e} (of m g r), the free joint's reaction worst {worst_joint:.2e}",
        samples.len()
    );
    assert!(worst_force < 1e-10 && worst_moment < 1e-10 && worst_joint < 1e-10);
}

/// The example's contact `dot(pos(D), n3) - r*cos(phi)` does not say where
/// its load acts (its rate `ż + r sin(phi) dphi/dt` is not a velocity of
/// the contact point as written): a reaction is refused, naming it and
/// only it (the no-slip constraints are read from `slip`).
#[test]
fn rolling_disc_contact_as_a_height_is_refused() {
    let text =
        model_text("rolling_disc.sim") + "output joint_f3 [N] = dot(reaction_force(D), n3);\n";
    let file = autosim_core::diag::SourceFile::new("rolling_disc.sim", text);
    let Err(d) = autosim_core::pipeline::compile_source(&file) else {
        panic!("the reaction was computed");
    };
    let message = d.render(&file);
    assert!(
        message.contains("the constraint `touch` does not say where its load acts"),
        "{message}"
    );
}
