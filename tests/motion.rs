//! Prescribed motion: a pendulum on a cart driven back and forth, against
//! its equations derived by hand (Lagrange, below) and integrated here; and
//! a four-bar whose crank is driven (no free speed left), against the
//! power balance: the driving torque's power is the energy's rate.

use autosim::runtime::integrate::{DormandPrince, Rk4};
use autosim::runtime::{Model, RunSettings, Stepper, run};
use autosim_test_support::worst_of;

autosim::model! {
    /// A cart on a rail along n2, driven as `x = A sin(omega t)`, carrying
    /// a pendulum (a point mass on a massless rod) swinging about n1.
    model DrivenCart;
    parameters { M = 2 [kg], m = 0.5 [kg], L = 0.8 [m], A = 0.1 [m], omega = 3 [rad/s], g = 9.81 [m/s^2] }
    body Cart { translate: 2, q: [x], u: [v], mass: M, inertia: 0 }
    body Bob { parent: Cart, rotate: 1, q: [theta], u: [w], initial: [0.4], mass: m, cm: [0, 0, -L], inertia: 0 }
    gravity = -g*n3;
    motion drive { coordinate: x, value: A*sin(omega*t) }
}
use driven_cart::DrivenCart;

/// The cart-pendulum by hand: with `T = ½ M ẋ² + ½ m ((ẋ + L cos θ θ̇)² +
/// (L sin θ θ̇)²)` and `V = −m g L cos θ`, Lagrange's equations give
/// `θ̈ = −(g sin θ + ẍ cos θ)/L` and the force on the cart
/// `F = (M + m) ẍ + m L (cos θ θ̈ − sin θ θ̇²)`.
fn by_hand(t: f64, theta: f64, w: f64) -> (f64, f64) {
    let (mass_cart, m, l, a, omega, g) = (2.0, 0.5, 0.8, 0.1, 3.0, 9.81);
    let xdd = -a * omega * omega * (omega * t).sin();
    let (s, c) = theta.sin_cos();
    let theta_dd = -(g * s + xdd * c) / l;
    let force = (mass_cart + m) * xdd + m * l * (c * theta_dd - s * w * w);
    (theta_dd, force)
}

#[test]
fn the_driven_coordinate_is_no_state_and_its_force_is_an_output() {
    assert_eq!(DrivenCart::STATE_NAMES, ["theta", "w"]);
    assert_eq!(DrivenCart::OUTPUT_NAMES, ["drive"]);
    assert_eq!(DrivenCart::OUTPUT_UNITS, ["N"]);
}

#[test]
fn the_pendulum_and_the_driving_force_match_the_hand_derivation() {
    let mut model = DrivenCart::new();
    let h = 1e-3;
    let mut x = model.initial_state();
    let mut hand = [x[0], x[1]];
    let mut rk4 = Rk4::new();
    let mut worst = (0.0f64, 0.0f64);
    for k in 0..3000 {
        let t = k as f64 * h;
        let mut y = [0.0];
        model.outputs(t, &x, &mut y).unwrap();
        let mut dx = [0.0; 2];
        model.derivatives(t, &x, &mut dx).unwrap();
        let (theta_dd, force) = by_hand(t, x[0], x[1]);
        worst.0 = worst.0.max((dx[1] - theta_dd).abs());
        worst.1 = worst.1.max((y[0] - force).abs());
        rk4.step(&mut model, t, &mut x, h).unwrap();
        hand = rk4_by_hand(t, hand, h);
    }
    let along = (x[0] - hand[0]).abs().max((x[1] - hand[1]).abs());
    eprintln!(
        "driven cart: theta'' {:e}, force {:e}, trajectory {along:e}",
        worst.0, worst.1
    );
    assert!(worst.0 < 1e-12 && worst.1 < 1e-12, "{worst:?}");
    assert!(along < 1e-12, "{along:e}");
}

/// One classic RK4 step of the hand-derived equations.
fn rk4_by_hand(t: f64, s: [f64; 2], h: f64) -> [f64; 2] {
    let f = |t: f64, s: [f64; 2]| [s[1], by_hand(t, s[0], s[1]).0];
    let k1 = f(t, s);
    let k2 = f(
        t + h / 2.0,
        [s[0] + h / 2.0 * k1[0], s[1] + h / 2.0 * k1[1]],
    );
    let k3 = f(
        t + h / 2.0,
        [s[0] + h / 2.0 * k2[0], s[1] + h / 2.0 * k2[1]],
    );
    let k4 = f(t + h, [s[0] + h * k3[0], s[1] + h * k3[1]]);
    [0, 1].map(|i| s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

autosim::model! {
    /// The four-bar of `examples/models/four_bar.sim` with its crank driven
    /// at a varying rate: no free speed is left.
    model DrivenFourBar;
    parameters { L0 = 1.0 [m], L1 = 0.3 [m], L2 = 1.0 [m], L3 = 0.8 [m], m1 = 1.0 [kg], m2 = 2.0 [kg], m3 = 1.5 [kg], g = 9.81 [m/s^2] }
    body C { rotate: 1, q: [q1], u: [u1], mass: m1, cm: [0, L1/2, 0], inertia: diag(m1*L1^2/12, 0, m1*L1^2/12) }
    body K { parent: C, joint: [0, L1, 0], rotate: 1, q: [q2], u: [u2], initial: [0.9], mass: m2, cm: [0, L2/2, 0], inertia: diag(m2*L2^2/12, 0, m2*L2^2/12) }
    body R { joint: [0, L0, 0], rotate: 1, q: [q3], u: [u3], initial: [1.7], mass: m3, cm: [0, L3/2, 0], inertia: diag(m3*L3^2/12, 0, m3*L3^2/12) }
    point E in K at [0, L2, 0];
    point T in R at [0, L3, 0];
    constraint loop_n2 [m] { position: dot(pos(E, T), n2) }
    constraint loop_n3 [m] { position: dot(pos(E, T), n3) }
    motion crank { coordinate: q1, value: 2 [rad/s]*t + 0.5*sin(3 [rad/s]*t) }
    gravity = -g*n3;
    output energy [J] = kinetic_energy() + potential_energy();
    output crank_rate [rad/s] = u1;
}
use driven_four_bar::DrivenFourBar;

#[test]
fn a_fully_driven_mechanism_balances_power() {
    assert_eq!(DrivenFourBar::STATE_NAMES, ["q2", "q3"]);
    assert_eq!(
        DrivenFourBar::OUTPUT_NAMES,
        ["energy", "crank_rate", "loop_n2", "loop_n3", "crank"]
    );
    assert_eq!(DrivenFourBar::OUTPUT_UNITS[4], "N m");
    let mut model = DrivenFourBar::new();
    let mut x = model.initial_state();
    let mut dopri = DormandPrince::<DrivenFourBar>::with_tolerances(1e-12, 1e-12).unwrap();
    let dt = 1e-3;
    let settings = RunSettings::new(0.0, 3.0, 1e-4, dt);
    let mut out: Vec<[f64; 5]> = Vec::new();
    run(
        &mut model,
        &mut dopri,
        &mut x,
        &settings,
        &mut |_t, _x: &[f64; 2], y: &[f64; 5]| {
            out.push(*y);
        },
    )
    .unwrap();
    // dE/dt (fourth-order central differences, error ~ dt^4 E(5)/30)
    // against the torque's power.
    let peak = out.iter().map(|y| (y[4] * y[1]).abs()).fold(0.0, worst_of);
    let mut worst = 0.0f64;
    for k in 2..out.len() - 2 {
        let e = |j: usize| out[j][0];
        let rate = (e(k - 2) - 8.0 * e(k - 1) + 8.0 * e(k + 1) - e(k + 2)) / (12.0 * dt);
        worst = worst_of(worst, (rate - out[k][4] * out[k][1]).abs());
    }
    let closure = out
        .iter()
        .map(|y| y[2].abs().max(y[3].abs()))
        .fold(0.0, worst_of);
    eprintln!(
        "driven four-bar: power balance {:e} of the peak {peak:.3} W, loop {closure:e}",
        worst / peak
    );
    assert!(
        worst < 1e-8 * peak,
        "power balance off by {worst:e} W (peak {peak} W)"
    );
    assert!(closure < 1e-9, "loop residual {closure:e}");
}
