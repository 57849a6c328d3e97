//! The generated linearization (`linearize = true`) against central
//! finite differences of the generated derivatives and outputs, at random
//! states and inputs: the reference chains, the satellite, and the
//! constrained models (in their independent states: a perturbed
//! independent coordinate is re-assembled before differencing), and a
//! constrained chain whose outputs read the constraints' loads and joint
//! reactions (their `C`, `D` rows against differences of the generated
//! `outputs`: a consistency check of the generated functions with each
//! other, the values themselves are checked against Newton–Euler in
//! `autosim-core/tests/quantities`).

use autosim::runtime::{Linearize, Model, StateArray};
use autosim_test_support::{Rng, worst_of};

mod chains {
    use autosim_test_support::models_from;
    models_from! { "examples/models/chain_planar_1.sim": Planar1, linearize = true; }
    models_from! { "examples/models/chain_planar_5.sim": Planar5, linearize = true; }
    models_from! { "examples/models/chain_planar_10.sim": Planar10, linearize = true; }
    models_from! { "examples/models/chain_spatial_1.sim": Spatial1, linearize = true; }
    models_from! { "examples/models/chain_spatial_3.sim": Spatial3, linearize = true; }
    models_from! { "examples/models/chain_spatial_10.sim": Spatial10, linearize = true; }
}
mod satellite {
    autosim::model!(file = "examples/models/satellite.sim", linearize = true);
}
mod constrained {
    autosim::model!(file = "examples/models/four_bar.sim", linearize = true);
    autosim::model!(file = "examples/models/rolling_disc.sim", linearize = true);
    autosim::model!(file = "examples/models/bicycle.sim", linearize = true);
}

/// Three hinged links, the last one's tip sliding on a wall (a position
/// constraint), the second and third joints coupled by a belt (a speed
/// constraint through the links' rotations), pushed at the tip by an
/// input; the outputs read both constraints' loads and joint reactions.
mod loaded {
    autosim::model! {
        model LoadedChain;
        settings { linearize: true }
        parameters { m = 1 [kg], L = 0.5 [m], g = 9.81 [m/s^2], k = 2 [N m/rad], c = 0.1 [N m s/rad], a = 0.2 [m] }
        input push [N] = 0.5;
        body B1 { parent: N, rotate: 1, mass: m, cm: [0, 0, -L/2], inertia: diag(0.03, 0.03, 0.002), q: [q1], u: [u1], initial: [0.6] }
        moment spring { on: B1, reaction: N, about: N.1, magnitude: -k*q1 - c*u1 }
        body B2 { parent: B1, joint: [0, 0, -L], rotate: 1, mass: m, cm: [0, 0, -L/2], inertia: diag(0.03, 0.03, 0.002), q: [q2], u: [u2], initial: [-1.2] }
        body B3 { parent: B2, joint: [0, 0, -L], rotate: 1, mass: m, cm: [0, 0, -L/2], inertia: diag(0.03, 0.03, 0.002), q: [q3], u: [u3], initial: [1.0] }
        point Tip in B3 at [0, 0, -L];
        force tip_push { on: Tip, along: n3, magnitude: push }
        constraint wall [m] { position: dot(pos(Tip), n2) - a, dependent: q3 }
        constraint belt [rad/s] { speed: dot(rot(B1) - rot(B3), n1), dependent: u2 }
        gravity = -g*n3;
        output wall_force [N] = constraint_force(wall);
        output belt_moment [N m] = constraint_force(belt);
        output hinge_n2 [N] = dot(reaction_force(B1), n2);
        output hinge_n3 [N] = dot(reaction_force(B1), n3);
        output knee_n3 [N] = dot(reaction_force(B3), n3);
    }
}

/// A cart on a spring and damper written in user code, pushed by an
/// input; an output reads the user function too.
mod tire {
    autosim::model! {
        model UserSpring;
        settings { linearize: true }
        parameters { m = 2 [kg] }
        input push [N] = 0.5;
        extern fn spring(x [m], v [m/s]) -> [N];
        body Cart { parent: N, translate: 1, mass: m, inertia: 0, q: [x], u: [v], initial: [0.1] }
        force restoring { on: Cart, along: n1, magnitude: push - spring(x, v) }
        output load [N] = spring(x, v);
    }
}

/// `A`, `B`, `C`, `D` as row-major vectors.
type Matrices = [Vec<f64>; 4];

fn generated<M: Linearize<Float = f64>>(m: &mut M, x: &M::State) -> Matrices {
    let (nl, nw, ny) = (
        M::LINEAR_STATES.len(),
        M::INPUT_NAMES.len(),
        M::OUTPUT_NAMES.len(),
    );
    let mut out = [
        vec![0.0; nl * nl],
        vec![0.0; nl * nw],
        vec![0.0; ny * nl],
        vec![0.0; ny * nw],
    ];
    let [a, b, c, d] = &mut out;
    m.linearize_into(0.0, x, a, b, c, d).expect("regular state");
    out
}

/// Derivatives and outputs at `x` (re-assembled) and `w`.
fn evaluate<M: Model<Float = f64>>(m: &mut M, x: &M::State, w: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let mut x = *x;
    m.assemble(0.0, &mut x).expect("assembles");
    m.set_input_values(w);
    let mut dx = x;
    m.derivatives(0.0, &x, &mut dx).expect("regular state");
    let mut y = M::Outputs::zeros();
    m.outputs(0.0, &x, &mut y).expect("regular state");
    (dx.as_ref().to_vec(), y.as_ref().to_vec())
}

/// Central differences, in the same layout.
fn differenced<M: Linearize<Float = f64>>(m: &mut M, x: &M::State, w: &[f64]) -> Matrices {
    let states = M::LINEAR_STATES;
    let (nl, nw, ny) = (states.len(), w.len(), M::OUTPUT_NAMES.len());
    let mut out = [
        vec![0.0; nl * nl],
        vec![0.0; nl * nw],
        vec![0.0; ny * nl],
        vec![0.0; ny * nw],
    ];
    let columns = nl + nw;
    for j in 0..columns {
        let (mut xp, mut xm, mut wp, mut wm) = (*x, *x, w.to_vec(), w.to_vec());
        let h = if j < nl {
            let s = states[j];
            let h = 1e-6 * (1.0 + x.as_ref()[s].abs());
            xp.as_mut()[s] += h;
            xm.as_mut()[s] -= h;
            h
        } else {
            let h = 1e-6 * (1.0 + w[j - nl].abs());
            wp[j - nl] += h;
            wm[j - nl] -= h;
            h
        };
        let (fp, yp) = evaluate(m, &xp, &wp);
        let (fm, ym) = evaluate(m, &xm, &wm);
        let (rates, outs) = if j < nl { (0, 2) } else { (1, 3) };
        let (col, width) = if j < nl { (j, nl) } else { (j - nl, nw) };
        for (i, &s) in states.iter().enumerate() {
            out[rates][i * width + col] = (fp[s] - fm[s]) / (2.0 * h);
        }
        for i in 0..ny {
            out[outs][i * width + col] = (yp[i] - ym[i]) / (2.0 * h);
        }
    }
    m.set_input_values(w);
    out
}

/// Compares at `cases` random states (from `state`) and inputs.
fn check<M: Linearize<Float = f64>>(
    name: &str,
    mut m: M,
    cases: usize,
    state: impl Fn(&mut Rng) -> M::State,
) {
    let mut rng = Rng::new(0x5eed_1234_abcd_0001);
    let mut worst = 0.0f64;
    for _ in 0..cases {
        let mut x = state(&mut rng);
        m.assemble(0.0, &mut x).expect("assembles");
        let w: Vec<f64> = M::INPUT_NAMES
            .iter()
            .map(|_| rng.uniform(-2.0, 2.0))
            .collect();
        m.set_input_values(&w);
        let got = generated(&mut m, &x);
        let want = differenced(&mut m, &x, &w);
        for (k, label) in ["A", "B", "C", "D"].iter().enumerate() {
            let scale = want[k].iter().fold(1.0f64, |s, v| s.max(v.abs()));
            let err = got[k]
                .iter()
                .zip(&want[k])
                .map(|(g, w)| (g - w).abs())
                .fold(0.0, worst_of)
                / scale;
            worst = worst_of(worst, err);
            assert!(
                err < 1e-6,
                "{name}: {label} differs from finite differences by {err:e}\n got {:?}\nwant {:?}",
                got[k],
                want[k]
            );
        }
    }
    eprintln!("{name}: linearization vs central differences {worst:.1e}");
}

fn uniform<const N: usize>(rng: &mut Rng, lo: f64, hi: f64) -> [f64; N] {
    std::array::from_fn(|_| rng.uniform(lo, hi))
}

/// [`check`] of a chain, at states uniform in [-1.5, 1.5].
fn check_chain<M, const N: usize>(name: &str, m: M, cases: usize)
where
    M: Linearize<Float = f64, State = [f64; N]>,
{
    check(name, m, cases, |r| uniform(r, -1.5, 1.5));
}

#[test]
fn chains_match_finite_differences() {
    use chains::*;
    check_chain("chain-planar-1", planar1::Planar1::new(), 5);
    check_chain("chain-planar-5", planar5::Planar5::new(), 5);
    check_chain("chain-planar-10", planar10::Planar10::new(), 3);
    check_chain("chain-spatial-1", spatial1::Spatial1::new(), 5);
    check_chain("chain-spatial-3", spatial3::Spatial3::new(), 5);
    check_chain("chain-spatial-10", spatial10::Spatial10::new(), 3);
}

/// Thrusters on a dead band wide enough not to switch under the
/// differences; constant commands.
struct Quiet;
impl satellite::satellite::Externs for Quiet {
    fn thrust(&mut self, _t: f64, _axis: f64, _error: f64) -> f64 {
        0.0
    }
    fn cmd(&mut self, _t: f64) -> [f64; 2] {
        [0.3, -0.2]
    }
}

/// A stiffening spring with a saturating damper: `k x + k3 x³ + c tanh(v)`.
struct Stiffening;
impl Stiffening {
    const K: f64 = 40.0;
    const K3: f64 = 900.0;
    const C: f64 = 3.0;
}
impl tire::user_spring::Externs for Stiffening {
    fn spring(&mut self, x: f64, v: f64) -> f64 {
        Self::K * x + Self::K3 * x.powi(3) + Self::C * v.tanh()
    }
}

/// User functions are differentiated (central differences in the
/// generated code), not held: `A`, `B`, `C`, `D` of the cart against
/// their closed forms, `∂f/∂x = k + 3 k3 x²`, `∂f/∂v = c / cosh² v`.
#[test]
fn user_functions_are_differentiated() {
    use tire::user_spring::UserSpring;
    let mut m = UserSpring::new(Stiffening);
    let mass = 2.0;
    let mut rng = Rng::new(7);
    let mut worst = 0.0f64;
    for _ in 0..20 {
        let x = [rng.uniform(-0.3, 0.3), rng.uniform(-3.0, 3.0)];
        m.set_input_values(&[rng.uniform(-2.0, 2.0)]);
        let [a, b, c, d] = generated(&mut m, &x);
        let fx = Stiffening::K + 3.0 * Stiffening::K3 * x[0] * x[0];
        let fv = Stiffening::C / x[1].cosh().powi(2);
        let want = [
            vec![0.0, 1.0, -fx / mass, -fv / mass],
            vec![0.0, 1.0 / mass],
            vec![fx, fv],
            vec![0.0],
        ];
        for (got, want) in [a, b, c, d].iter().zip(&want) {
            for (g, w) in got.iter().zip(want) {
                let err = (g - w).abs() / w.abs().max(1.0);
                worst = worst_of(worst, err);
                assert!(err < 1e-8, "{got:?} against {want:?} at {x:?}");
            }
        }
    }
    eprintln!("user function's partials vs closed form {worst:.1e}");
}

#[test]
fn satellite_matches_finite_differences() {
    check(
        "satellite",
        satellite::satellite::Satellite::new(Quiet),
        5,
        |r| uniform(r, -0.5, 0.5),
    );
}

#[test]
fn constrained_models_match_finite_differences_in_their_independent_states() {
    use constrained::*;
    check("four-bar", four_bar::FourBar::new(), 5, |r| {
        [r.uniform(-0.5, 0.5), 0.9, 1.7, r.uniform(-3.0, 3.0)]
    });
    check("rolling disc", rolling_disc::RollingDisc::new(), 5, |r| {
        let mut x: [f64; 9] = uniform(r, -1.0, 1.0);
        x[6..].copy_from_slice(&[
            r.uniform(-3.0, 3.0),
            r.uniform(-8.0, 8.0),
            r.uniform(-3.0, 3.0),
        ]);
        x
    });
    check("bicycle", bicycle::Bicycle::new(), 5, |r| {
        let mut x = [0.0; 11];
        x[3] = r.uniform(-0.3, 0.3);
        x[6] = r.uniform(-0.5, 0.5);
        x[8..].copy_from_slice(&[
            r.uniform(-1.0, 1.0),
            r.uniform(5.0, 20.0),
            r.uniform(-1.0, 1.0),
        ]);
        x
    });
}

#[test]
fn outputs_reading_constraint_loads_match_finite_differences() {
    use loaded::loaded_chain::LoadedChain;
    check("loaded chain", LoadedChain::new(), 5, |r| {
        [
            0.6 + r.uniform(-0.2, 0.2),
            -1.2 + r.uniform(-0.2, 0.2),
            1.0,
            r.uniform(-1.0, 1.0),
        ]
    });
    // Not a comparison of zeros: the loads move with the state and input.
    let mut m = LoadedChain::new();
    let mut x = [0.6, -1.2, 1.0, 0.3];
    m.assemble(0.0, &mut x).expect("assembles");
    let [_, _, c, d] = generated(&mut m, &x);
    let largest = |v: &[f64]| v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    eprintln!(
        "loaded chain: largest |C| {:.2e}, |D| {:.2e}",
        largest(&c),
        largest(&d)
    );
    assert!(largest(&c) > 0.1 && largest(&d) > 0.1);
}

/// Entries zero by structure are exactly `0.0` at any state: the bicycle
/// never reads its rear contact's position (`A` and `C` columns `x`, `y`),
/// its coordinates' rates and its outputs never read the torques (`B`
/// rows of the coordinates, `D`).
#[test]
fn structurally_zero_entries_are_exact_zeros() {
    use constrained::bicycle::Bicycle;
    type B = Bicycle;
    let states = B::LINEAR_STATES;
    let (nl, nw, ny) = (states.len(), B::INPUT_NAMES.len(), B::OUTPUT_NAMES.len());
    let col = |name: &str| {
        states
            .iter()
            .position(|k| B::STATE_NAMES[*k] == name)
            .expect("a linear state")
    };
    let (x, y) = (col("x"), col("y"));
    let nq = constrained::bicycle::N_STATES - constrained::bicycle::N_SPEEDS;
    let coordinates = states.iter().filter(|k| **k < nq).count();
    let mut rng = Rng::new(26);
    let mut m = B::new();
    for _ in 0..5 {
        let mut s = [0.0; 11];
        for v in &mut s {
            *v = rng.uniform(-0.4, 0.4);
        }
        // The pitch follows (assembly), the rear wheel rolls.
        s[4] = 0.0;
        s[9] = rng.uniform(5.0, 20.0);
        m.set_input_values(&[rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)]);
        m.assemble(0.0, &mut s).expect("assembles");
        let [a, b, c, d] = generated(&mut m, &s);
        let mut zeros: Vec<f64> = (0..nl)
            .flat_map(|i| [a[i * nl + x], a[i * nl + y]])
            .collect();
        zeros.extend((0..ny).flat_map(|i| [c[i * nl + x], c[i * nl + y]]));
        zeros.extend(&b[..coordinates * nw]);
        zeros.extend(&d);
        assert!(zeros.iter().all(|v| *v == 0.0), "{zeros:?} at {s:?}");
    }
}
