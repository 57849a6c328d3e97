//! The four-bar's loop-closing pin force (`constraint_force` of its two
//! loop constraints) and its joints' reactions at the reference's sampled
//! states
//! (`tests/reference/four-bar.json`, SymPy) against a planar Newton–Euler
//! computation written here with the reference's accelerations.
//!
//! The loop constraints are `dot(pos(E, T), n2)` and `dot(pos(E, T), n3)`:
//! their power is `λ·(v_E − v_T)`, so `(λ2, λ3)` is the force the pin
//! exerts on the coupler at E (and minus it on the rocker at T).

use super::support::{compile_text, model_text, outputs_with, parameter_values};
use autosim_test_support::{floats, load, max_diff, worst_of};
use nalgebra::{Matrix2, Vector2};

/// The unit vector at angle `a` from n2 towards n3, and the one square to
/// it (a quarter turn further).
fn along(a: f64) -> (Vector2<f64>, Vector2<f64>) {
    let (s, c) = a.sin_cos();
    (Vector2::new(c, s), Vector2::new(-s, c))
}

/// The n1 component of `r × f` for vectors in the (n2, n3) plane.
fn cross(r: &Vector2<f64>, f: &Vector2<f64>) -> f64 {
    r.x * f.y - r.y * f.x
}

/// A bar turning about one end at angle `a`, rate `w`, acceleration
/// `alpha`: the acceleration of its point at distance `r`, relative to
/// that end.
fn relative_acceleration(a: f64, w: f64, alpha: f64, r: f64) -> Vector2<f64> {
    let (e, n) = along(a);
    (n * alpha - e * (w * w)) * r
}

/// The four pins' forces in the (n2, n3) plane.
struct Pins {
    /// On the rocker at T, from the coupler.
    loop_pin: Vector2<f64>,
    /// On the crank at O, from N.
    crank: Vector2<f64>,
    /// On the coupler at B, from the crank.
    coupler: Vector2<f64>,
    /// On the rocker at D, from N.
    rocker: Vector2<f64>,
    /// The residual of the crank's moment balance (a check of this
    /// computation with the reference's accelerations).
    balance: f64,
}

fn pin_forces(p: &dyn Fn(&str) -> f64, q: &[f64], u: &[f64], du: &[f64]) -> Pins {
    let (l1, l2, l3) = (p("L1"), p("L2"), p("L3"));
    let (m1, m2, m3) = (p("m1"), p("m2"), p("m3"));
    let gravity = Vector2::new(0.0, -p("g"));
    // Absolute angles, rates and accelerations of crank, coupler, rocker.
    let a = [q[0], q[0] + q[1], q[2]];
    let w = [u[0], u[0] + u[1], u[2]];
    let alpha = [du[0], du[0] + du[1], du[2]];
    let e: Vec<Vector2<f64>> = a.iter().map(|&x| along(x).0).collect();
    let crank_tip = relative_acceleration(a[0], w[0], alpha[0], l1);
    let a_crank = relative_acceleration(a[0], w[0], alpha[0], l1 / 2.0);
    let a_coupler = crank_tip + relative_acceleration(a[1], w[1], alpha[1], l2 / 2.0);
    let a_rocker = relative_acceleration(a[2], w[2], alpha[2], l3 / 2.0);
    let inertia = [
        m1 * l1 * l1 / 12.0,
        m2 * l2 * l2 / 12.0,
        m3 * l3 * l3 / 12.0,
    ];
    // Rocker about its pivot D: (T − D) × F = I α + r* × m (a* − g).
    let rocker = inertia[2] * alpha[2] + cross(&(e[2] * (l3 / 2.0)), &((a_rocker - gravity) * m3));
    // Coupler about the crank tip B, with −F at E: (E − B) × F = −(...).
    let coupler =
        -(inertia[1] * alpha[1] + cross(&(e[1] * (l2 / 2.0)), &((a_coupler - gravity) * m2)));
    let (r_t, r_e) = (e[2] * l3, e[1] * l2);
    // r × F = r.x F.y − r.y F.x, one row per arm.
    let m = Matrix2::new(-r_t.y, r_t.x, -r_e.y, r_e.x);
    let f = m
        .lu()
        .solve(&Vector2::new(rocker, coupler))
        .expect("the arms are not parallel");
    // The crank about O: the coupler pushes on it at B with −(m2 (a* − g) + F).
    let on_coupler_at_b = (a_coupler - gravity) * m2 + f;
    let spring = -p("k") * (q[0] - p("q10"));
    let lhs = inertia[0] * alpha[0] + cross(&(e[0] * (l1 / 2.0)), &((a_crank - gravity) * m1));
    let rhs = spring + cross(&(e[0] * l1), &(-on_coupler_at_b));
    Pins {
        loop_pin: f,
        crank: (a_crank - gravity) * m1 + on_coupler_at_b,
        coupler: on_coupler_at_b,
        rocker: (a_rocker - gravity) * m3 - f,
        balance: lhs - rhs,
    }
}

#[test]
fn four_bar_pin_forces_match_newton_euler() {
    let data = load("four-bar");
    let p = |n: &str| {
        data["parameters"][n]
            .as_f64()
            .unwrap_or_else(|| panic!("no parameter {n}"))
    };
    let mut text = model_text("four_bar.sim");
    text.push_str("output pin_n2 [N] = constraint_force(loop_n2);\n");
    text.push_str("output pin_n3 [N] = constraint_force(loop_n3);\n");
    for body in ["C", "K", "R"] {
        for a in 1..=3 {
            text.push_str(&format!(
                "output f_{body}{a} [N] = dot(reaction_force({body}), n{a});\n\
                 output m_{body}{a} [N m] = dot(reaction_moment({body}), n{a});\n"
            ));
        }
    }
    let c = compile_text("four_bar.sim", &text);
    let params = parameter_values(&c, |x| p(&x.name));
    let (mut worst, mut worst_balance) = (0.0f64, 0.0f64);
    let samples = data["samples"].as_array().expect("samples");
    for s in samples {
        let (q, u, du) = (floats(&s["q"]), floats(&s["u"]), floats(&s["du"]));
        let pins = pin_forces(&p, &q, &u, &du);
        let scale = [pins.loop_pin, pins.crank, pins.coupler, pins.rocker]
            .iter()
            .fold(1.0f64, |a, f| a.max(f.amax()));
        worst_balance = worst_of(worst_balance, pins.balance.abs() / scale);
        assert!(
            pins.balance.abs() < 1e-10 * scale,
            "the crank's balance: {:e}",
            pins.balance
        );
        let y = outputs_with(&c, &params, &[q[0], q[1], q[2], u[0]], 0.0);
        // The model's output (energy) first, then ours: the multipliers
        // (the force on the coupler at E), then per body the reaction
        // force and moment, interleaved by component.
        let mut got = vec![y[1], y[2]];
        let mut want = vec![-pins.loop_pin.x, -pins.loop_pin.y];
        for (k, f) in [pins.crank, pins.coupler, pins.rocker].iter().enumerate() {
            let at = 3 + 6 * k;
            // n1 (out of the plane) is 0 for force and moment; n2, n3 of
            // the moment too (planar loads); the moment along n1 is the
            // joint's free direction.
            got.extend([y[at], y[at + 2], y[at + 4]]);
            want.extend([0.0, f.x, f.y]);
            got.extend([y[at + 1], y[at + 3], y[at + 5]]);
            want.extend([0.0, 0.0, 0.0]);
        }
        let err = max_diff(&got, &want) / scale;
        worst = worst_of(worst, err);
        assert!(err < 1e-10, "{got:?} against {want:?}");
    }
    eprintln!(
        "four-bar at {} reference states: pin forces and joint reactions worst relative error {worst:.2e} (the crank's moment balance with them: {worst_balance:.2e})",
        samples.len()
    );
}
