//! The recursive (articulated-body) formulation equals the mass-matrix
//! formulation at random states (derivatives; `mass_matrix`, which the
//! recursion computes a column at a time; `forcing`, which it sums body
//! by body and the other form takes as derived), for every tree model of
//! `examples/models` (the constrained ones have only the mass-matrix
//! form): a differential test of the O(n) solve. (The formulation chosen
//! by default is the cheaper one; this forces each.) Where the mass
//! matrix is ill conditioned, both are measured against exact
//! accelerations instead (chain-spatial-20, at the end).

use autosim::runtime::Model;
use autosim_test_support::{Rng, features_user, floats, load, rel_err, worst_of};

macro_rules! both {
    ($module:ident, $file:literal) => {
        mod $module {
            autosim::model!(file = $file, name = Matrix, formulation = mass_matrix);
            autosim::model!(file = $file, name = Recursive, formulation = recursive);
        }
    };
}
both!(planar1, "examples/models/chain_planar_1.sim");
both!(planar2, "examples/models/chain_planar_2.sim");
both!(planar2_f32, "examples/models/chain_planar_2_f32.sim");
both!(planar3, "examples/models/chain_planar_3.sim");
both!(planar5, "examples/models/chain_planar_5.sim");
both!(planar10, "examples/models/chain_planar_10.sim");
both!(spatial1, "examples/models/chain_spatial_1.sim");
both!(spatial2, "examples/models/chain_spatial_2.sim");
both!(spatial3, "examples/models/chain_spatial_3.sim");
both!(spatial3_stiff, "examples/models/chain_spatial_3_stiff.sim");
both!(spatial5, "examples/models/chain_spatial_5.sim");
both!(spatial7, "examples/models/chain_spatial_7.sim");
both!(spatial10, "examples/models/chain_spatial_10.sim");
both!(spatial20, "examples/models/chain_spatial_20.sim");
both!(features, "examples/models/features.sim");
both!(satellite, "examples/models/satellite.sim");
both!(satellite_small, "examples/models/satellite_small.sim");
both!(satellite_sampled, "examples/models/satellite_sampled.sim");
both!(pendulum, "examples/models/pendulum.sim");
both!(quarter_car, "examples/models/quarter_car.sim");

/// Deterministic user code: the same arguments give the same values in
/// both formulations.
#[derive(Clone, Copy)]
struct User;
/// The same user code for every listed `Externs` trait.
macro_rules! user {
    ($($externs:path),+ => $body:tt) => {$(
        impl $externs for User $body
    )+};
}
user!(
    satellite::matrix::Externs,
    satellite::recursive::Externs,
    satellite_small::matrix::Externs,
    satellite_small::recursive::Externs => {
        fn thrust(&mut self, _t: f64, axis: f64, error: f64) -> f64 {
            (axis * error).sin()
        }
        fn cmd(&mut self, t: f64) -> [f64; 2] {
            [t.sin(), t.cos()]
        }
    }
);
user!(satellite_sampled::matrix::Externs, satellite_sampled::recursive::Externs => {
    fn cmd(&mut self, t: f64) -> [f64; 2] {
        [t.sin(), t.cos()]
    }
});
user!(features::matrix::Externs, features::recursive::Externs => {
    fn friction(&mut self, speed: f64, normal: f64) -> f64 {
        features_user::friction(speed, normal)
    }
    fn sensor(&mut self, t: f64, x: f64) -> [f64; 2] {
        features_user::sensor(t, x)
    }
});

/// A random state, entries uniform in [-2, 2], those in `small` scaled
/// by 1e-6.
fn random_state<const N: usize>(rng: &mut Rng, small: &[usize]) -> [f64; N] {
    let mut x: [f64; N] = std::array::from_fn(|_| rng.uniform(-2.0, 2.0));
    for k in small {
        x[*k] *= 1e-6;
    }
    x
}

/// How closely the two forms' derivatives agree at random states.
struct Agreement {
    /// The largest difference, relative to the derivatives' size.
    worst: f64,
    /// The same over the states where f64 determines the solution to
    /// 1e-12 (κ(M)·ε ≤ 1e-12).
    worst_where_determined: f64,
    /// The largest ratio of the difference to `max(1e-12, κ(M) ε)`.
    worst_ratio: f64,
    /// How many states had κ(M)·ε > 1e-12.
    ill_conditioned: usize,
}

/// The two forms' derivatives at `cases` random states (the states in
/// `small` at 1e-6 scale: with small variables each formulation truncates
/// a different model, equal to first order), with random inputs, and the
/// conditioning κ(M) = λmax/λmin of the mass matrix at each. A mass-matrix
/// solution is only determined to about κ(M)·ε (its entries' rounding
/// alone moves it that much), so where M is that ill conditioned the
/// forms may differ by that (chain-spatial-20 at 2.5 % of random states;
/// the last test shows the recursion is the accurate one there).
fn compare<A, B, const N: usize, const S: usize>(
    mut a: A,
    mut b: B,
    mass_matrix: fn(&mut B, f64, &[f64; N], &mut [[f64; S]; S]),
    cases: usize,
    small: &[usize],
) -> Agreement
where
    A: Model<Float = f64, State = [f64; N]>,
    B: Model<Float = f64, State = [f64; N]>,
{
    let mut rng = Rng::new(0x0bad_cafe_1234_5678);
    let mut agreement = Agreement {
        worst: 0.0,
        worst_where_determined: 0.0,
        worst_ratio: 0.0,
        ill_conditioned: 0,
    };
    let mut evaluated = 0;
    for _ in 0..cases {
        let x: [f64; N] = random_state(&mut rng, small);
        let t = rng.uniform(0.0, 5.0);
        let inputs: Vec<f64> = A::INPUT_NAMES
            .iter()
            .map(|_| rng.uniform(-1.0, 1.0))
            .collect();
        a.set_input_values(&inputs);
        b.set_input_values(&inputs);
        let (mut da, mut db) = ([0.0; N], [0.0; N]);
        let (ra, rb) = (a.derivatives(t, &x, &mut da), b.derivatives(t, &x, &mut db));
        assert_eq!(ra.is_ok(), rb.is_ok());
        if ra.is_err() {
            continue;
        }
        evaluated += 1;
        let mut m = [[0.0; S]; S];
        mass_matrix(&mut b, t, &x, &mut m);
        let difference = relative_difference(&da, &db);
        let determined = conditioning(&m) * f64::EPSILON;
        agreement.worst = worst_of(agreement.worst, difference);
        agreement.worst_ratio = worst_of(agreement.worst_ratio, difference / determined.max(1e-12));
        match determined > 1e-12 {
            true => agreement.ill_conditioned += 1,
            false => {
                agreement.worst_where_determined =
                    worst_of(agreement.worst_where_determined, difference)
            }
        }
    }
    // A state may fail a pivot check in both forms alike; most must not.
    assert!(
        evaluated * 10 >= cases * 9,
        "only {evaluated} of {cases} states evaluated"
    );
    agreement
}

/// How many inputs `M` has.
fn input_count<M: Model>(_: &M) -> usize {
    M::INPUT_NAMES.len()
}

/// κ(M) = λmax/λmin of a symmetric positive definite matrix (finite:
/// the eigenvalue iteration would not end on a NaN).
fn conditioning<const S: usize>(m: &[[f64; S]; S]) -> f64 {
    assert!(
        m.iter().flatten().all(|v| v.is_finite()),
        "mass matrix not finite"
    );
    let eigenvalues = nalgebra::DMatrix::from_fn(S, S, |i, j| m[i][j]).symmetric_eigenvalues();
    eigenvalues.max() / eigenvalues.min()
}

/// The largest difference of `b` from `a`, relative to the largest entry
/// of `a` (or to 1 if all are smaller).
fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |w, (p, q)| worst_of(w, (p - q).abs() / scale))
}

/// The largest entry of `M du - f`, relative to the largest force.
fn residual<const S: usize>(m: &[[f64; S]; S], du: &[f64], f: &[f64; S]) -> f64 {
    let scale = f.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    m.iter().zip(f).fold(0.0f64, |w, (row, fi)| {
        let m_du: f64 = row.iter().zip(du).map(|(mk, duk)| mk * duk).sum();
        worst_of(w, (m_du - fi).abs() / scale)
    })
}

/// Largest difference of two functions of the state, relative to the
/// largest entry of the first, at `cases` random states (`small` as in
/// [`compare`]).
fn compare_at<const N: usize>(
    mut a: impl FnMut(&[f64; N]) -> Vec<f64>,
    mut b: impl FnMut(&[f64; N]) -> Vec<f64>,
    cases: usize,
    small: &[usize],
) -> f64 {
    let mut rng = Rng::new(0x5eed_0f4a_5500);
    let mut worst = 0.0f64;
    for _ in 0..cases {
        let x: [f64; N] = random_state(&mut rng, small);
        let (va, vb) = (a(&x), b(&x));
        let scale = va.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (ea, eb) in va.iter().zip(&vb) {
            worst = worst_of(worst, (ea - eb).abs() / scale);
        }
    }
    worst
}

/// `mass_matrix`, row by row, as one vector.
fn mass<M: Model<Float = f64, State = [f64; N]>, const N: usize, const S: usize>(
    model: &mut M,
    entries: fn(&mut M, f64, &[f64; N], &mut [[f64; S]; S]),
) -> impl FnMut(&[f64; N]) -> Vec<f64> + '_ {
    move |x| {
        let mut m = [[0.0; S]; S];
        entries(model, 0.0, x, &mut m);
        m.concat()
    }
}

/// `forcing` as a function of the state.
fn vector<M: Model<Float = f64, State = [f64; N]>, const N: usize, const S: usize>(
    model: &mut M,
    values: fn(&mut M, f64, &[f64; N], &mut [f64; S]),
) -> impl FnMut(&[f64; N]) -> Vec<f64> + '_ {
    move |x| {
        let mut f = [0.0; S];
        values(model, 0.0, x, &mut f);
        f.to_vec()
    }
}

/// Largest difference of `forcing` and `M du/dt` (with `du/dt` from
/// `derivatives`, the speeds' rates following the coordinates' in the
/// state), relative to the largest force, at `cases` random states
/// (`small` as in [`compare`]).
fn forcing_against_mass<M, const N: usize, const S: usize>(
    model: &mut M,
    forcing: fn(&mut M, f64, &[f64; N], &mut [f64; S]),
    entries: fn(&mut M, f64, &[f64; N], &mut [[f64; S]; S]),
    cases: usize,
    small: &[usize],
) -> f64
where
    M: Model<Float = f64, State = [f64; N]>,
{
    let mut rng = Rng::new(0xf0_5c1e);
    let (mut worst, mut evaluated) = (0.0f64, 0);
    for _ in 0..cases {
        let x: [f64; N] = random_state(&mut rng, small);
        let (mut f, mut m, mut dx) = ([0.0; S], [[0.0; S]; S], [0.0; N]);
        if model.derivatives(0.0, &x, &mut dx).is_err() {
            continue;
        }
        evaluated += 1;
        forcing(model, 0.0, &x, &mut f);
        entries(model, 0.0, &x, &mut m);
        worst = worst_of(worst, residual(&m, &dx[S..], &f));
    }
    assert!(
        evaluated * 10 >= cases * 9,
        "only {evaluated} of {cases} states evaluated"
    );
    worst
}

/// Which agreement of the derivatives a model is held to.
#[derive(PartialEq)]
enum Bound {
    /// 1e-12 at every state.
    Strict,
    /// 1e-12 where κ(M)·ε ≤ 1e-12, κ(M)·ε elsewhere: for a model whose
    /// mass-matrix form is less accurate than that at some states.
    Conditioned,
}

macro_rules! check {
    ($test:ident, $module:ident, $bound:expr, $small:expr, $($user:expr)?) => {
        #[test]
        fn $test() {
            use $module::*;
            let report = |what: &str, worst: f64, tolerance: f64| {
                eprintln!("{}: {what} {worst:e}", stringify!($module));
                assert!(worst < tolerance, "{what}: {worst:e}");
            };
            let (mut a, mut b) = (matrix::Matrix::new($($user)?), recursive::Recursive::new($($user)?));
            let agreement =
                compare(a.clone(), b.clone(), recursive::Recursive::mass_matrix, 50, &$small);
            eprintln!(
                "{}: recursive vs mass matrix {:e}, {} of 50 states with κ(M) ε > 1e-12",
                stringify!($module), agreement.worst, agreement.ill_conditioned
            );
            report("recursive vs mass matrix where κ(M) ε ≤ 1e-12", agreement.worst_where_determined, 1e-12);
            report("recursive vs mass matrix / max(1e-12, κ(M) ε)", agreement.worst_ratio, 1.0);
            if $bound == Bound::Strict {
                report("recursive vs mass matrix", agreement.worst, 1e-12);
            }
            // The remaining checks with inputs too (the same in both).
            let inputs: Vec<f64> = (0..input_count(&a)).map(|k| 0.7 - 0.3 * k as f64).collect();
            a.set_input_values(&inputs);
            b.set_input_values(&inputs);
            // With small variables the mass-matrix form truncates `M`
            // term by term and the recursion does not: they differ at
            // second order in the small states (1e-6 here).
            let small: &[usize] = &$small;
            let tolerance = if small.is_empty() { 1e-12 } else { 1e-10 };
            let ma = mass(&mut a, matrix::Matrix::mass_matrix);
            let mb = mass(&mut b, recursive::Recursive::mass_matrix);
            report("mass matrices", compare_at(ma, mb, 20, small), tolerance);
            // The recursion sums each subtree's forces for `forcing`, the
            // other form lowers Kane's forcing as derived; each is also
            // `M du/dt` of its own mass matrix and derivatives.
            let fa = vector(&mut a, matrix::Matrix::forcing);
            let fb = vector(&mut b, recursive::Recursive::forcing);
            report("forcing", compare_at(fa, fb, 20, small), tolerance);
            let worst = forcing_against_mass(&mut a, matrix::Matrix::forcing, matrix::Matrix::mass_matrix, 20, small);
            let worst = worst_of(worst, forcing_against_mass(&mut b, recursive::Recursive::forcing, recursive::Recursive::mass_matrix, 20, small));
            report("forcing against M du/dt", worst, 1e-11);
        }
    };
}
check!(planar_1, planar1, Bound::Strict, [],);
check!(planar_2, planar2, Bound::Strict, [],);
check!(planar_3, planar3, Bound::Strict, [],);
check!(planar_5, planar5, Bound::Strict, [],);
check!(planar_10, planar10, Bound::Strict, [],);
check!(spatial_1, spatial1, Bound::Strict, [],);
check!(spatial_2, spatial2, Bound::Strict, [],);
check!(spatial_3, spatial3, Bound::Strict, [],);
check!(spatial_3_stiff, spatial3_stiff, Bound::Strict, [],);
check!(spatial_5, spatial5, Bound::Strict, [],);
check!(spatial_7, spatial7, Bound::Strict, [],);
check!(spatial_10, spatial10, Bound::Strict, [],);
// Both forms share work between `derivatives` and `forcing` here. The
// mass matrix is ill conditioned at some states (κ(M) up to 1.5e5), where
// the mass-matrix form's own rounding error passes 1e-12 (at 2.5 % of
// random states, up to 4.4e-12): the bound there is κ(M) ε, and the last
// test measures both forms against exact accelerations.
check!(spatial_20, spatial20, Bound::Conditioned, [],);
// The bead's slide `s` and its speed are small.
check!(every_feature, features, Bound::Strict, [2, 10], User);
check!(the_satellite, satellite, Bound::Strict, [], User);
check!(
    the_sampled_satellite,
    satellite_sampled,
    Bound::Strict,
    [],
    User
);
check!(the_pendulum, pendulum, Bound::Strict, [],);
check!(the_quarter_car, quarter_car, Bound::Strict, [],);
// The bus's six and the boom's two degrees of freedom are small.
check!(
    the_small_satellite,
    satellite_small,
    Bound::Strict,
    [0, 1, 2, 3, 4, 5, 8, 9, 10, 11, 12, 13, 14, 15, 18, 19],
    User
);

/// The `f32` chain: the two forms agree to the precision of `f32` (ε =
/// 1.2e-7; measured 8.8e-7, 7 ε: the two round differently, and
/// chain-planar-2's mass matrix is well conditioned, so 1e-5 = 80 ε
/// leaves room for other targets' rounding and nothing for a wrong term,
/// which shows at 1e-2 and above).
#[test]
fn planar_2_in_f32() {
    let mut a = planar2_f32::matrix::Matrix::new();
    let mut b = planar2_f32::recursive::Recursive::new();
    let mut rng = Rng::new(0x0bad_cafe_1234_5678);
    let mut worst = 0.0f64;
    for _ in 0..50 {
        let x: [f32; 4] = random_state::<4>(&mut rng, &[]).map(|v| v as f32);
        let (mut da, mut db) = ([0.0f32; 4], [0.0f32; 4]);
        a.derivatives(0.0, &x, &mut da)
            .expect("no pivot check fails");
        b.derivatives(0.0, &x, &mut db)
            .expect("no pivot check fails");
        let (da, db) = (da.map(f64::from), db.map(f64::from));
        worst = worst_of(worst, relative_difference(&da, &db));
    }
    eprintln!("planar2_f32: recursive vs mass matrix {worst:e}");
    assert!(worst < 1e-5, "{worst:e}");
}

/// Against the exact accelerations of chain-spatial-20 (40-digit
/// arithmetic, `tests/reference/gen/chain_exact.py`, written from the
/// model's definition) at 200 random states. Beyond the 50 states above
/// the two forms differ by up to 4.2e-12 here (4.4e-12 over 2 000 states
/// of `compare`'s generator), and this says which is right: the recursion
/// stays within 8.1e-14 of the exact value, while the mass-matrix form is
/// limited by the conditioning of `M` (κ(M) = λmax/λmin up to 1.5e5 at
/// these states): rounding `M`'s entries to f64 alone moves the exact
/// solution of `M du = f` by up to 1.1e-12, and the LDLᵀ's own rounding
/// brings it to 4.2e-12. So the recursion is held to 2e-13 of the exact
/// value, the mass-matrix form to κ(M)·ε of it (measured 0.30 of that),
/// and each satisfies `M du/dt = f` to 1e-12 of the largest force
/// (backward error; measured 3.2e-14).
#[test]
fn spatial_20_against_its_exact_accelerations() {
    let data = load("chain-spatial-20-exact");
    let samples = data["samples"].as_array().expect("samples");
    assert_eq!(samples.len(), 200);
    let mut matrix = spatial20::matrix::Matrix::new();
    let mut recursive = spatial20::recursive::Recursive::new();
    let (mut recursive_error, mut matrix_ratio, mut worst_residual) = (0.0f64, 0.0f64, 0.0f64);
    for s in samples {
        let mut x = [0.0; 40];
        x[..20].copy_from_slice(&floats(&s["q"]));
        x[20..].copy_from_slice(&floats(&s["u"]));
        let exact = floats(&s["du"]);
        let (mut da, mut db) = ([0.0f64; 40], [0.0f64; 40]);
        matrix
            .derivatives(0.0, &x, &mut da)
            .expect("no pivot check fails");
        recursive
            .derivatives(0.0, &x, &mut db)
            .expect("no pivot check fails");
        let (mut m, mut f) = ([[0.0; 20]; 20], [0.0; 20]);
        recursive.mass_matrix(0.0, &x, &mut m);
        recursive.forcing(0.0, &x, &mut f);
        let conditioning = conditioning(&m);
        recursive_error = worst_of(recursive_error, rel_err(&db[20..], &exact));
        let matrix_error = rel_err(&da[20..], &exact);
        matrix_ratio = worst_of(matrix_ratio, matrix_error / (conditioning * f64::EPSILON));
        for d in [&da, &db] {
            worst_residual = worst_of(worst_residual, residual(&m, &d[20..], &f));
        }
    }
    eprintln!(
        "spatial20 against exact: recursive {recursive_error:e}, \
         mass matrix / (κ ε) {matrix_ratio}, backward error {worst_residual:e}"
    );
    assert!(recursive_error < 2e-13, "recursive: {recursive_error:e}");
    assert!(matrix_ratio < 1.0, "mass matrix: {matrix_ratio} κ(M) ε");
    assert!(worst_residual < 1e-12, "backward error {worst_residual:e}");
}
