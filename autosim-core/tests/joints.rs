//! Joint kinds beyond the axis rotations: a rotation about a constant
//! direction of the parent (the paper's `d_rot`, with and without its
//! reference direction `d_ref`, Eq. 8) against rotation matrices built
//! independently with nalgebra, and a pendulum on a tilted axis against its
//! equation of motion derived by hand.

use autosim_core::diag::SourceFile;
use autosim_core::expr::{Bindings, NoUserFunctions};
use autosim_core::mech::{BodyId, System};
use autosim_core::pipeline::{Compiled, compile_source};
use autosim_test_support::Rng;
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};

fn compile(text: &str) -> Compiled {
    let src = SourceFile::new("joints.sim", text.to_string());
    compile_source(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)))
}

fn pendulum(reference: &str) -> String {
    format!(
        "model Tilted;
         parameters {{ m = 1.3 [kg], rho = 0.7 [m], g = 9.81 [m/s^2], lambda = 0.4 [rad] }}
         body B {{ rotate: [[0, sin(lambda), cos(lambda)]], {reference} mass: m, cm: [rho, 0, 0], inertia: 0 }}
         gravity = -g*n3;"
    )
}

/// `C_BN` from the model at `q`, with the parameters' defaults.
fn cosine_matrix(c: &mut Compiled, q: f64) -> Matrix3<f64> {
    let sys: &mut System = &mut c.model.system;
    let b = sys.body_named("B").expect("body B");
    let m = sys.cosine_matrix(b, BodyId::N);
    let mut env = Bindings::with_defaults(&sys.arena);
    env.set(sys.coordinates()[0].q, q);
    Matrix3::from_fn(|i, j| sys.arena.eval(m[i][j], &env, &mut NoUserFunctions))
}

/// The axis of the tilted pendulum, unit.
fn axis(lambda: f64) -> Unit<Vector3<f64>> {
    Unit::new_normalize(Vector3::new(0.0, lambda.sin(), lambda.cos()))
}

#[test]
fn rotation_about_a_direction_is_the_rotation_matrix_about_it() {
    let mut c = compile(&pendulum(""));
    let mut rng = Rng::new(5);
    for _ in 0..20 {
        let q = rng.uniform(-4.0, 4.0);
        // C_ij = b_i · a_j = R(d, q)ᵀ for the active rotation R.
        let want = Rotation3::from_axis_angle(&axis(0.4), q)
            .matrix()
            .transpose();
        let got = cosine_matrix(&mut c, q);
        assert!((got - want).abs().max() < 1e-14, "q = {q}: {got} vs {want}");
    }
}

#[test]
fn a_reference_direction_fixes_the_nominal_axes_of_eq_8() {
    // b3 = d, b2 = d × r / |d × r|, b1 = b2 × b3, then a turn about b3.
    let mut c = compile(&pendulum("reference: [1, 0, 0],"));
    let d = axis(0.4).into_inner();
    let b2 = d.cross(&Vector3::x()).normalize();
    let nominal = Matrix3::from_rows(&[b2.cross(&d).transpose(), b2.transpose(), d.transpose()]);
    let mut rng = Rng::new(6);
    for _ in 0..20 {
        let q = rng.uniform(-4.0, 4.0);
        let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), q)
            .matrix()
            .transpose();
        let want = turn * nominal;
        let got = cosine_matrix(&mut c, q);
        assert!((got - want).abs().max() < 1e-14, "q = {q}: {got} vs {want}");
    }
}

#[test]
fn a_pendulum_on_a_tilted_axis_follows_its_hand_derived_equation() {
    // A point mass at rho from the axis d = (0, sin λ, cos λ), starting along
    // n1: its height is -rho sin λ sin θ, so m rho² θ'' = m g rho sin λ cos θ.
    for reference in ["", "reference: [1, 0, 0],"] {
        let c = compile(&pendulum(reference));
        let sys = &c.model.system;
        let eqs = &c.equations;
        let mut rng = Rng::new(7);
        for _ in 0..20 {
            let (q, u) = (rng.uniform(-3.0, 3.0), rng.uniform(-2.0, 2.0));
            let mut env = Bindings::with_defaults(&sys.arena);
            env.set(eqs.coordinates[0], q);
            env.set(eqs.speeds[0], u);
            let ev = |e| sys.arena.eval(e, &env, &mut NoUserFunctions);
            let du = ev(eqs.forcing[0]) / ev(eqs.mass_matrix[0][0]);
            let want = 9.81 * 0.4f64.sin() * q.cos() / 0.7;
            assert!(
                (du - want).abs() < 1e-12 * want.abs().max(1.0),
                "{reference}: {du} vs {want}"
            );
            assert_eq!(ev(eqs.kinematics[0]), u);
        }
    }
}

#[test]
fn an_axis_direction_is_a_simple_rotation() {
    // `rotate: [[0, 0, 2]]` is `rotate: 3`: the same generated program.
    let about =
        compile("model A; body B { rotate: [[0, 0, 2]], cm: [1, 0, 0] } gravity = -9.81*n2;");
    let simple = compile("model A; body B { rotate: 3, cm: [1, 0, 0] } gravity = -9.81*n2;");
    assert_eq!(about.program.to_string(), simple.program.to_string());
}
