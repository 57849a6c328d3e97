//! Linear analysis against analytic results: the pendulum's and a
//! spring-mass chain's eigenvalues, the quarter car's static deflections
//! (trim), a steady turn of the bicycle (trim from a rough start), an
//! impossible trim (a typed error), and the exports read back.

use autosim::runtime::analysis::{Complex, LinearSystem, Mode, Trim, TrimError, trim};
use autosim::runtime::{Model, RunSettings, integrate::DormandPrince, run};
use autosim_test_support::worst_of;

autosim::model!(file = "examples/models/pendulum.sim");

autosim::model! {
    /// Three equal masses in a row between two walls, joined by equal
    /// springs (fixed-fixed).
    model SpringChain;
    settings { linearize: true }
    parameters { m = 2 [kg], k = 50 [N/m] }
    body B1 { translate: 1, q: [x1], u: [v1], mass: m, inertia: 0 }
    body B2 { translate: 1, q: [x2], u: [v2], mass: m, inertia: 0 }
    body B3 { translate: 1, q: [x3], u: [v3], mass: m, inertia: 0 }
    force wall1 { on: B1, along: n1, magnitude: -k*x1 }
    force s12 { on: B2, reaction: B1, along: n1, magnitude: -k*(x2 - x1) }
    force s23 { on: B3, reaction: B2, along: n1, magnitude: -k*(x3 - x2) }
    force wall3 { on: B3, along: n1, magnitude: -k*x3 }
}

autosim::model!(file = "examples/models/quarter_car.sim");

mod bike {
    autosim::model!(file = "examples/models/bicycle.sim", linearize = true);
}

#[test]
fn pendulum_eigenvalues_are_analytic() {
    let mut m = pendulum::Pendulum::new();
    let sys = LinearSystem::of(&mut m, 0.0, &[0.0, 0.0]).unwrap();
    let w = (9.81f64 / 0.7).sqrt();
    let ev = sys.eigenvalues();
    assert!(
        ev[0].re.abs() < 1e-12 && (ev[0].im.abs() - w).abs() < 1e-12 * w,
        "{ev:?}"
    );
    let mode = &sys.modes()[0];
    assert!((mode.natural_frequency - w).abs() < 1e-12 * w && mode.damping_ratio.abs() < 1e-12);
    // B: the torque's angular acceleration per N m, 1/(m L²).
    assert!((sys.b[(1, 0)] - 1.0 / (1.3 * 0.49)).abs() < 1e-12);
    // Upside down it is unstable: λ = ±sqrt(g/L).
    let up = LinearSystem::of(&mut m, 0.0, &[std::f64::consts::PI, 0.0]).unwrap();
    let ev = up.eigenvalues();
    assert!(
        (ev[1].re - w).abs() < 1e-12 * w && ev[1].im == 0.0,
        "{ev:?}"
    );
}

#[test]
fn spring_chain_eigenvalues_are_analytic() {
    let mut m = spring_chain::SpringChain::new();
    let sys = LinearSystem::of(&mut m, 0.0, &[0.0; 6]).unwrap();
    let modes = sys.modes();
    // Fixed-fixed chain of N = 3: ω_j = 2 sqrt(k/m) sin(j π / (2 (N + 1))).
    let mut want: Vec<f64> = (1..=3)
        .map(|j| 2.0 * (50.0f64 / 2.0).sqrt() * (j as f64 * std::f64::consts::PI / 8.0).sin())
        .collect();
    want.sort_by(f64::total_cmp);
    let mut got: Vec<f64> = modes.iter().map(|m| m.natural_frequency).collect();
    got.sort_by(f64::total_cmp);
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() < 1e-12 * w, "{got:?} vs {want:?}");
    }
    // The lowest mode moves the masses in phase, the middle one most:
    // x1 : x2 : x3 = 1 : √2 : 1.
    let low = modes
        .iter()
        .min_by(|a, b| a.natural_frequency.total_cmp(&b.natural_frequency))
        .unwrap();
    let (x1, x2, x3) = (low.shape[0].1, low.shape[1].1, low.shape[2].1);
    let (r1, r3) = (x1 / x2, x3 / x2);
    let half = 1.0 / 2f64.sqrt();
    assert!(
        (r1.re - half).abs() < 1e-9 && r1.im.abs() < 1e-9 && (r3.re - half).abs() < 1e-9,
        "{:?}",
        low.shape
    );
}

#[test]
fn quarter_car_static_deflection_is_analytic() {
    let mut m = quarter_car::QuarterCar::new();
    let mut x = m.initial_state();
    let spec = Trim::new(&["zu", "zs"], &[], &["vu", "vs"]);
    let report = trim(&mut m, 0.0, &mut x, &spec).unwrap();
    let (ms, mu, ks, kt, g) = (300.0, 40.0, 20000.0, 200000.0, 9.81);
    let zu = 0.3 - (ms + mu) * g / kt;
    let zs = zu + 0.4 - ms * g / ks;
    eprintln!(
        "quarter car: zu {} zs {} in {} iterations",
        x[0], x[1], report.iterations
    );
    assert!(
        (x[0] - zu).abs() < 1e-12 && (x[1] - zs).abs() < 1e-12,
        "{x:?} vs {zu} {zs}"
    );
    assert!(report.residual < 1e-10);
}

#[test]
fn an_impossible_trim_is_a_typed_error() {
    // A hinge torque above m g L cannot be held by gravity at any angle.
    let mut m = pendulum::Pendulum::new();
    m.inputs.torque = 2.0 * 1.3 * 9.81 * 0.7;
    let mut x = [0.1, 0.0];
    let r = trim(&mut m, 0.0, &mut x, &Trim::new(&["q"], &[], &["u"]));
    match r {
        Err(TrimError::NotConverged { residuals, .. } | TrimError::Singular { residuals }) => {
            assert_eq!(residuals[0].0, "u");
            assert!(residuals[0].1.abs() > 1.0);
        }
        other => panic!("expected a typed failure, got {other:?}"),
    }
    let bad = trim(&mut m, 0.0, &mut x, &Trim::new(&["nope"], &[], &["u"]));
    assert!(matches!(bad, Err(TrimError::Invalid(_))), "{bad:?}");
}

#[test]
fn trim_limits_its_step_and_names_a_singular_jacobian() {
    // Held by gravity alone (no torque): the equilibria are q = k pi.
    // From q = 1.5 a full Newton step (-tan 1.5 = -14.1) would jump to the
    // equilibrium at -4 pi; the step limit (max(1, |q|) = 1.5 rad) keeps
    // the trim on the nearest one, q = 0.
    let mut m = pendulum::Pendulum::new();
    let mut x = [1.5, 0.0];
    trim(&mut m, 0.0, &mut x, &Trim::new(&["q"], &[], &["u"])).unwrap();
    assert!(x[0].abs() < 1e-12, "{x:?}");
    // At q = pi/2 the Jacobian d(u')/dq = -(g/L) cos q is zero to rounding:
    // the Newton step would be 2e16 rad. That is a singular Jacobian, said
    // so (it was a step to -2.18e16 and `NotConverged`).
    let mut x = [std::f64::consts::FRAC_PI_2, 0.0];
    let r = trim(&mut m, 0.0, &mut x, &Trim::new(&["q"], &[], &["u"]));
    match r {
        Err(TrimError::Singular { ref residuals }) => assert_eq!(residuals[0].0, "u"),
        ref other => panic!("expected a singular Jacobian, got {other:?}"),
    }
    assert!(r.unwrap_err().to_string().contains("singular Jacobian"));
    assert_eq!(x[0], std::f64::consts::FRAC_PI_2, "left where it was");
}

#[test]
fn fewer_unknowns_than_residuals_is_invalid() {
    // One unknown (the torque), two residuals (q' and u'): over-determined.
    let mut m = pendulum::Pendulum::new();
    let mut x = [0.5, 0.0];
    let r = trim(
        &mut m,
        0.0,
        &mut x,
        &Trim::new(&[], &["torque"], &["q", "u"]),
    );
    let Err(TrimError::Invalid(why)) = r else {
        panic!("expected Invalid, got {r:?}");
    };
    assert_eq!(
        why,
        "2 steady derivatives but 1 free unknown: over-determined (free as many states or inputs as there are steady states)"
    );
}

#[test]
fn bicycle_steady_turn_trims_from_a_rough_start() {
    use bike::bicycle::Bicycle;
    let mut m = Bicycle::new();
    // 5 m/s, leaning 0.1 rad: find the steer angle and the steer torque
    // that hold it, from straight running.
    let mut x = [0.0; 11];
    x[3] = 0.1;
    x[9] = 5.0 / 0.3;
    let spec = Trim::new(&["delta"], &["T_delta"], &["u_phi", "u_delta"]);
    let report = trim(&mut m, 0.0, &mut x, &spec).unwrap();
    let mut dx = x;
    m.derivatives(0.0, &x, &mut dx).unwrap();
    eprintln!(
        "steady turn: steer {} rad, torque {} N m, {} iterations, residual {:e}",
        x[6], m.inputs.T_delta, report.iterations, report.residual
    );
    assert!(report.residual < 1e-10 && dx[8].abs() < 1e-10 && dx[10].abs() < 1e-10);
    // The wheel speed holds too (no drive needed in a steady turn).
    assert!(dx[9].abs() < 1e-9, "rear wheel acceleration {}", dx[9]);
    // And the nonlinear model keeps turning with the lean held.
    let mut dopri = DormandPrince::<Bicycle>::with_tolerances(1e-11, 1e-11).unwrap();
    let mut worst = 0.0f64;
    let settings = RunSettings::new(0.0, 2.0, 1e-3, 0.1);
    run(
        &mut m,
        &mut dopri,
        &mut x,
        &settings,
        &mut |_t, x: &[f64; 11], _y: &[f64; 3]| {
            worst = worst_of(worst, (x[3] - 0.1).abs());
        },
    )
    .unwrap();
    assert!(worst < 1e-8, "lean drifted by {worst:e}");
}

/// The numbers of `name = [ ... ];` in a MATLAB script, row by row.
fn matlab_matrix(script: &str, name: &str) -> Vec<Vec<f64>> {
    let start = script
        .find(&format!("{name} = ["))
        .expect("matrix in the script")
        + name.len()
        + 4;
    let end = start + script[start..].find("];").expect("closed");
    script[start..end]
        .split(';')
        .map(|row| {
            row.split(',')
                .filter_map(|v| v.trim().parse().ok())
                .collect::<Vec<f64>>()
        })
        .filter(|r| !r.is_empty())
        .collect()
}

#[test]
fn exports_read_back_to_the_same_eigenvalues() {
    let mut m = bike::bicycle::Bicycle::new();
    let mut x = [0.0; 11];
    x[9] = 4.0 / 0.3;
    let sys = LinearSystem::of(&mut m, 0.0, &x)
        .unwrap()
        .restricted(&["phi", "delta", "u_phi", "u_delta"])
        .unwrap();
    let script = sys.to_matlab("Bicycle");
    let a = matlab_matrix(&script, "A");
    let n = a.len();
    let back = LinearSystem::from_matrices(
        autosim::runtime::analysis::DMatrix::from_fn(n, n, |i, j| a[i][j]),
        &["phi", "delta", "u_phi", "u_delta"],
    );
    assert_eq!(back.a, sys.a, "the script holds every digit");
    assert!(script.contains("state_names = {'phi', 'delta', 'u_phi', 'u_delta'};"));
    let json = sys.to_json();
    assert!(json.contains("\"name\": \"u_delta\"") && json.contains("\"a\": [["));
    let python = sys.to_python("Bicycle");
    assert!(python.contains("STATES = [\"phi\", \"delta\", \"u_phi\", \"u_delta\"]"));
    let md = sys.to_markdown();
    assert!(md.contains("| `u_phi`′ |") && md.contains("**Modes**"));
    // Where NumPy is installed, the Python module reproduces the eigenvalues.
    let dir = std::env::temp_dir().join(format!("autosim-export-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bike_linear.py"), &python).unwrap();
    let check = "import sys; sys.path.insert(0, sys.argv[1]); import numpy as np, bike_linear as b; \
                 ev = sorted(np.linalg.eigvals(b.A), key=lambda z: (z.real, z.imag)); \
                 print(' '.join(f'{z.real:.17e} {z.imag:.17e}' for z in ev))";
    let env = match autosim_test_support::python::python_env(&["numpy"]) {
        Ok(env) => env,
        Err(why) => {
            autosim_test_support::python::skip("the NumPy check of the Python export", &why);
            let _ = std::fs::remove_dir_all(&dir);
            return;
        }
    };
    let out = env
        .command()
        .arg("-c")
        .arg(check)
        .arg(&dir)
        .output()
        .expect("the environment's python runs");
    assert!(
        out.status.success(),
        "the exported module fails in NumPy: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let nums: Vec<f64> = String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    for (k, l) in sys.eigenvalues().iter().enumerate() {
        assert!(
            (nums[2 * k] - l.re).abs() < 1e-9 && (nums[2 * k + 1] - l.im).abs() < 1e-9,
            "NumPy {nums:?} vs {l}"
        );
    }
    eprintln!("NumPy reproduces the eigenvalues");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn runs_record_the_inputs() {
    use autosim::runtime::integrate::Rk4;
    use autosim::runtime::io::{CsvWriter, Recording};
    let mut car = quarter_car::QuarterCar::new();
    car.inputs.road = 0.02;
    let mut x = car.initial_state();
    let settings = RunSettings::new(0.0, 0.1, 1e-3, 0.05);
    let mut recording = Recording::new();
    run(&mut car, &mut Rk4::new(), &mut x, &settings, &mut recording).unwrap();
    let road = recording.column("road").unwrap();
    assert_eq!(
        (road.unit, road.values.as_slice()),
        ("m", &[0.02, 0.02, 0.02][..])
    );
    let mut csv = CsvWriter::<quarter_car::QuarterCar, Vec<u8>>::new(Vec::new()).unwrap();
    let mut x = car.initial_state();
    run(&mut car, &mut Rk4::new(), &mut x, &settings, &mut csv).unwrap();
    let text = String::from_utf8(csv.into_inner().unwrap()).unwrap();
    let header = text.lines().next().unwrap();
    assert_eq!(
        header,
        "time [s],zu [m],zs [m],vu [m/s],vs [m/s],road [m],deflection [m],body_acceleration [m/s^2]"
    );
    assert!(text.lines().nth(1).unwrap().contains(",0.02,"));
}

/// An undamped mode's damping ratio is zero, never `-0` (which prints as
/// `-0.0` in a `Debug` listing of the modes).
#[test]
fn an_undamped_mode_has_a_damping_ratio_of_plain_zero() {
    let a = nalgebra::DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, 0.0]);
    let modes = LinearSystem::from_matrices(a, &["x", "v"]).modes();
    assert_eq!(modes.len(), 1);
    assert_eq!(modes[0].eigenvalue.re, 0.0);
    assert_eq!(modes[0].natural_frequency, 2.0);
    let zeta = modes[0].damping_ratio;
    assert!(zeta == 0.0 && zeta.is_sign_positive(), "{:?}", modes[0]);
}

/// A sleeping top on two massless gimbals spinning below its critical
/// rate (a new user's model): nalgebra's Schur iteration looped forever
/// on this `A`. Its characteristic polynomial, with `K = 218 I` and the
/// gyroscopic `G = [[0, -25], [25, 0]]`, is `(λ² - 218)² + (25 λ)²`, so
/// `λ = ±12.5 i ± sqrt(247)/2`, and the decoupled spin adds two zeros.
#[test]
fn a_sleeping_top_below_its_critical_spin_has_its_four_roots_and_two_zeros() {
    #[rustfmt::skip]
    let a = nalgebra::DMatrix::from_row_slice(6, 6, &[
        0.0, 0.0, 0.0, 1.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
        0.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        218.0, 0.0, 0.0, 0.0, -25.0, 0.0,
        0.0, 218.0, 0.0, 25.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ]);
    let system = LinearSystem::from_matrices(a, &["a1", "a2", "spin", "v1", "v2", "w"]);
    let ev = system.eigenvalues();
    let re = 247f64.sqrt() / 2.0;
    let expected = [
        (-re, -12.5),
        (-re, 12.5),
        (0.0, 0.0),
        (0.0, 0.0),
        (re, -12.5),
        (re, 12.5),
    ];
    for (l, (r, i)) in ev.iter().zip(expected) {
        assert!(
            (l.re - r).abs() < 1e-12 && (l.im - i).abs() < 1e-12,
            "{ev:?}"
        );
    }
    let unstable = system.modes().iter().filter(|m| m.is_unstable()).count();
    assert_eq!(unstable, 1, "one unstable pair: {}", system.modes_report());
}

/// A neutral oscillation's real part is rounding (±1e-16 here): the
/// mode is reported undamped, not unstable.
#[test]
fn rounding_does_not_make_a_neutral_mode_unstable() {
    // The sleeping top above spinning at 300 rad/s, its spin dropped: a
    // gyroscopically stable pair of undamped oscillations.
    #[rustfmt::skip]
    let a = nalgebra::DMatrix::from_row_slice(4, 4, &[
        0.0, 0.0, 1.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
        218.0, 0.0, 0.0, -50.0,
        0.0, 218.0, 50.0, 0.0,
    ]);
    let system = LinearSystem::from_matrices(a, &["a1", "a2", "v1", "v2"]);
    // λ² ± 50 i λ - 218 = 0: λ = i (±25 ± sqrt(625 - 218)).
    let root = 407f64.sqrt();
    let modes = system.modes();
    assert_eq!(modes.len(), 2);
    for (m, w) in modes.iter().zip([25.0 - root, 25.0 + root]) {
        assert!((m.natural_frequency - w).abs() < 1e-12 * w, "{m:?}");
        assert!(
            !m.is_unstable() && m.damping_ratio == 0.0,
            "{}",
            system.modes_report()
        );
    }
}

/// `(A − λI) v` for a mode's shape, largest entry's magnitude.
fn residual(a: &nalgebra::DMatrix<f64>, mode: &Mode) -> f64 {
    let v: Vec<Complex<f64>> = mode.shape.iter().map(|(_, c)| *c).collect();
    (0..a.nrows())
        .map(|i| {
            let av: Complex<f64> = (0..a.ncols()).map(|j| v[j] * a[(i, j)]).sum();
            (av - mode.eigenvalue * v[i]).norm()
        })
        .fold(0.0, f64::max)
}

/// The rank of the shapes of `modes`, as columns (tolerance 1e-9).
fn rank_of_shapes(modes: &[&Mode]) -> usize {
    let n = modes[0].shape.len();
    let m = nalgebra::DMatrix::from_fn(n, modes.len(), |i, j| modes[j].shape[i].1);
    m.svd(false, false)
        .singular_values
        .iter()
        .filter(|s| **s > 1e-9)
        .count()
}

/// Two identical uncoupled oscillators (`ẍ = -4x`, `ÿ = -4y`): `λ = 2i`
/// twice, and its two copies are the two independent motions, not one
/// motion twice (inverse iteration from one start gave both the same).
#[test]
fn a_repeated_eigenvalue_has_independent_shapes() {
    #[rustfmt::skip]
    let a = nalgebra::DMatrix::from_row_slice(4, 4, &[
        0.0, 0.0, 1.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
        -4.0, 0.0, 0.0, 0.0,
        0.0, -4.0, 0.0, 0.0,
    ]);
    let modes = LinearSystem::from_matrices(a.clone(), &["x", "y", "vx", "vy"]).modes();
    assert_eq!(modes.len(), 2, "{modes:?}");
    for m in &modes {
        assert!(
            (m.eigenvalue - Complex::new(0.0, 2.0)).norm() < 1e-12,
            "{m:?}"
        );
        assert!(residual(&a, m) < 1e-12, "{m:?}");
    }
    assert_eq!(
        rank_of_shapes(&modes.iter().collect::<Vec<_>>()),
        2,
        "{modes:?}"
    );
}

/// A free particle in the plane (`ẋ = v`, `v̇ = 0`, twice): `λ = 0` four
/// times with two eigenvectors (the positions); the other two copies are
/// generalized eigenvectors, `A w` the position's shape, so the four
/// shapes span the state space.
#[test]
fn a_defective_zero_has_generalized_eigenvectors() {
    #[rustfmt::skip]
    let a = nalgebra::DMatrix::from_row_slice(4, 4, &[
        0.0, 0.0, 1.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
        0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0,
    ]);
    let modes = LinearSystem::from_matrices(a.clone(), &["x", "y", "vx", "vy"]).modes();
    assert_eq!(modes.len(), 4, "{modes:?}");
    let eigen: Vec<_> = modes.iter().filter(|m| residual(&a, m) < 1e-12).collect();
    assert_eq!(eigen.len(), 2, "{modes:?}");
    for m in &eigen {
        // An eigenvector is a position: no velocity.
        assert!(m.shape[2].1.norm() + m.shape[3].1.norm() < 1e-12, "{m:?}");
    }
    assert_eq!(
        rank_of_shapes(&modes.iter().collect::<Vec<_>>()),
        4,
        "{modes:?}"
    );
}

/// A report prints a real mode's entries with their signs: the robot's
/// yaw mode turns its wheels against each other.
#[test]
fn a_reported_real_mode_keeps_its_signs() {
    // ẋ = -x, with y following -x: the mode is (x, y) = (1, -1).
    #[rustfmt::skip]
    let a = nalgebra::DMatrix::from_row_slice(2, 2, &[
        -1.0, 0.0,
        1.0, -2.0,
    ]);
    let report = LinearSystem::from_matrices(a, &["uL", "uR"]).modes_report();
    // λ = -1: (A + I) v = 0 gives v = (1, 1); λ = -2: v = (0, 1).
    assert!(
        report.contains("λ = -1.000000 1/s, time constant 1.000000 s [uL 1.000, uR 1.000]"),
        "{report}"
    );
    #[rustfmt::skip]
    let b = nalgebra::DMatrix::from_row_slice(2, 2, &[
        -1.0, 0.0,
        -1.0, -2.0,
    ]);
    let report = LinearSystem::from_matrices(b, &["uL", "uR"]).modes_report();
    // λ = -1: v = (1, -1).
    assert!(report.contains("[uL 1.000, uR -1.000]"), "{report}");
}
