//! The Whipple bicycle's linearization about upright, straight running
//! reproduces the benchmark of Meijaard, Papadopoulos, Ruina & Schwab
//! (2007): M, C1, K0, K2 of `M q̈ + v C1 q̇ + (g K0 + v² K2) q = f` in roll
//! and steer, and the weave and capsize speeds (their Table 2 and
//! eq. (A23)-(A25), as published).

use autosim::runtime::analysis::{LinearSystem, find_crossing};

autosim::model!(file = "examples/models/bicycle.sim", linearize = true);
use bicycle::Bicycle;

const G: f64 = 9.81;
const R_REAR: f64 = 0.3;

/// The published matrices (roll, steer).
const M: [[f64; 2]; 2] = [
    [80.81722, 2.31941332208709],
    [2.31941332208709, 0.29784188199686],
];
const C1: [[f64; 2]; 2] = [
    [0.0, 33.86641391492494],
    [-0.85035641456978, 1.68540397397560],
];
const K0: [[f64; 2]; 2] = [
    [-80.95, -2.59951685249872],
    [-2.59951685249872, -0.80329488458618],
];
const K2: [[f64; 2]; 2] = [[0.0, 76.59734589573222], [0.0, 2.65431523794604]];

/// Upright, straight running at `v`.
fn upright(v: f64) -> [f64; 11] {
    let mut x = [0.0; 11];
    x[9] = v / R_REAR;
    x
}

/// The roll-steer system at `v`: [phi, delta, u_phi, u_delta].
fn roll_steer(v: f64) -> LinearSystem {
    let mut model = Bicycle::new();
    let full = LinearSystem::of(&mut model, 0.0, &upright(v)).unwrap();
    full.restricted(&["phi", "delta", "u_phi", "u_delta"])
        .unwrap()
}

/// The mass matrix of the roll and steer speeds (the independent speeds
/// are u_phi, u_thetaR, u_delta).
fn mass() -> [[f64; 2]; 2] {
    let mut model = Bicycle::new();
    let mut m = [[0.0; 3]; 3];
    model.mass_matrix(0.0, &upright(0.0), &mut m);
    [[m[0][0], m[0][2]], [m[2][0], m[2][2]]]
}

fn mul(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2]) -> [[f64; 2]; 2] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j]))
}

/// `−M A_block` for the 2×2 block of `A` at rows u_phi, u_delta and
/// columns `first..first + 2` (0: the angles, 2: the rates).
fn times_mass(sys: &LinearSystem, first: usize) -> [[f64; 2]; 2] {
    let block: [[f64; 2]; 2] =
        std::array::from_fn(|i| std::array::from_fn(|j| -sys.a[(2 + i, first + j)]));
    mul(&mass(), &block)
}

fn assert_close(name: &str, got: &[[f64; 2]; 2], want: &[[f64; 2]; 2]) {
    for i in 0..2 {
        for j in 0..2 {
            let (g, w) = (got[i][j], want[i][j]);
            let err = if w == 0.0 {
                g.abs()
            } else {
                (g - w).abs() / w.abs()
            };
            // Published to 14 significant digits (M11, K0_11 exact).
            assert!(
                err < 1e-10,
                "{name}[{i}][{j}]: {g} vs published {w} ({err:e})"
            );
        }
    }
    eprintln!("{name} = {got:?}");
}

#[test]
fn the_benchmark_matrices_are_reproduced() {
    assert_close("M", &mass(), &M);
    let v = 5.0;
    let k_at_rest = times_mass(&roll_steer(0.0), 0);
    let k0 = k_at_rest.map(|r| r.map(|x| x / G));
    let k_at_v = times_mass(&roll_steer(v), 0);
    let k2: [[f64; 2]; 2] =
        std::array::from_fn(|i| std::array::from_fn(|j| (k_at_v[i][j] - G * k0[i][j]) / (v * v)));
    let c1 = times_mass(&roll_steer(v), 2).map(|r| r.map(|x| x / v));
    assert_close("K0", &k0, &K0);
    assert_close("K2", &k2, &K2);
    assert_close("C1", &c1, &C1);
}

/// The largest real part among the oscillatory eigenvalues (the weave).
fn weave(v: f64) -> f64 {
    roll_steer(v)
        .eigenvalues()
        .iter()
        .filter(|l| l.im.abs() > 1e-9)
        .map(|l| l.re)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The largest real eigenvalue (the capsize mode near the stable range).
fn capsize(v: f64) -> f64 {
    roll_steer(v)
        .eigenvalues()
        .iter()
        .filter(|l| l.im.abs() <= 1e-9)
        .map(|l| l.re)
        .fold(f64::NEG_INFINITY, f64::max)
}

#[test]
fn weave_and_capsize_speeds_match_the_benchmark() {
    let v_weave =
        find_crossing(weave, 3.0, 5.0, 1e-13).expect("the weave stabilizes between 3 and 5 m/s");
    let v_capsize = find_crossing(capsize, 5.0, 7.0, 1e-13).expect("capsize between 5 and 7 m/s");
    let (weave_published, capsize_published) = (4.29238253634111, 6.02426201538837);
    eprintln!("weave {v_weave:.14} m/s, capsize {v_capsize:.14} m/s");
    assert!(
        (v_weave - weave_published).abs() < 1e-10 * weave_published,
        "weave {v_weave}"
    );
    assert!(
        (v_capsize - capsize_published).abs() < 1e-10 * capsize_published,
        "capsize {v_capsize}"
    );
}

#[test]
fn self_stable_between_the_two_speeds() {
    for v in [4.5, 5.0, 5.5, 6.0] {
        let modes = roll_steer(v).modes();
        assert!(
            modes.iter().all(|m| !m.is_unstable()),
            "unstable at {v} m/s: {modes:?}"
        );
    }
    assert!(
        roll_steer(3.0)
            .modes()
            .iter()
            .any(|m| m.is_unstable() && m.time_constant.is_none()),
        "weave at 3 m/s"
    );
}
