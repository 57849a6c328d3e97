//! The rolling disc's friction force (`constraint_force` of its two
//! no-slip constraints `dot(slip, n1)`, `dot(slip, n2)`, with `slip` the
//! velocity of the disc's material point at the contact: the force along
//! n1, n2 on the disc there) at the reference's sampled states
//! (`tests/reference/rolling-disc.json`, SymPy) against Newton's second
//! law with the reference's accelerations: gravity is along n3, so the
//! contact's horizontal force is the mass times the centre's horizontal
//! acceleration (`du_x`, `du_y`: the translation speeds are `dq/dt` in N).

use super::support::{compile_text, model_text, outputs_with, parameter_values};
use autosim_test_support::{floats, load, max_diff, worst_of};

#[test]
fn rolling_disc_friction_matches_newton() {
    let data = load("rolling-disc");
    let m = data["parameters"]["m"].as_f64().expect("m");
    let mut text = model_text("rolling_disc.sim");
    text.push_str("output friction_n1 [N] = constraint_force(roll_n1);\n");
    text.push_str("output friction_n2 [N] = constraint_force(roll_n2);\n");
    let c = compile_text("rolling_disc.sim", &text);
    let params = parameter_values(&c, |p| {
        data["parameters"][&p.name].as_f64().expect("parameter")
    });
    let mut worst = 0.0f64;
    let samples = data["samples"].as_array().expect("samples");
    for s in samples {
        let (q, u, du) = (floats(&s["q"]), floats(&s["u"]), floats(&s["du"]));
        let mut x = q.clone();
        x.extend(&u[3..]);
        let y = outputs_with(&c, &params, &x, 0.0);
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
