//! Stability at the extremes: singular mass matrices. A structure that is
//! singular whatever the state is a compile-time error; masses set at run
//! time and singularities at some states only are typed errors naming the
//! speed (see `extremes/mod.rs`).
//!
//! | case | expected behaviour |
//! | --- | --- |
//! | zero mass and zero inertia on a free degree of freedom | compile-time error naming the speed and the body |
//! | zero masses set at run time (inertia kept) | `ModelError::SingularMassMatrix` naming the cart's speed `vy`; the run stops at t = 0 with `IntegrationError::Model`, state untouched |
//! | zero mass with non-zero inertia on a rotation | passes (the inertia carries the rotation) |
//! | singular only at some states (spherical pendulum at its pole) | `SingularMassMatrix` naming `azimuth_rate` at the pole, nothing elsewhere |
//! | singular with a non-zero diagonal (two parallel translations) | not detectable from the diagonal, so it compiles; `SingularMassMatrix` naming `v1` at run time |

mod extremes;

use autosim::runtime::integrate::Rk4;
use autosim::runtime::{IntegrationError, Model, ModelError};
use extremes::run_to;

mod models {
    autosim::model!(file = "tests/models/extremes/cart_pendulum.sim");
    autosim::model!(file = "tests/models/extremes/spherical_pendulum.sim");
    autosim::model!(file = "tests/models/extremes/double_slider.sim");
}

/// A body without mass or inertia that a degree of freedom moves alone is
/// singular whatever the state: the compiler says so, naming the speed and
/// the body, and suggests a fix.
#[test]
fn zero_mass_and_inertia_on_a_free_degree_of_freedom_is_a_compile_time_error() {
    use autosim_core::diag::SourceFile;
    use autosim_core::pipeline::compile_source;
    let cases = [
        (
            "model MasslessTip;\n\
             body Arm { rotate: 3, mass: 1, cm: [1, 0, 0], inertia: 0 }\n\
             body Tip { parent: Arm, joint: [1, 0, 0], rotate: 1, mass: 0, inertia: 0 }\n",
            "u2",
            "Tip",
        ),
        (
            // Zero mass everywhere, inertia only on the pendulum: nothing
            // resists the cart's translation.
            "model MasslessCart;\n\
             body Cart { translate: 2, mass: 0, inertia: 0 }\n\
             body Pend { parent: Cart, rotate: 1, mass: 0, cm: [0, 0, -1], inertia: diag(1, 1, 1) }\n",
            "u1",
            "Cart",
        ),
    ];
    for (text, speed, body) in cases {
        let file = SourceFile::new("singular.sim", text);
        let diagnostics = match compile_source(&file) {
            Ok(_) => panic!("compiled a singular model:\n{text}"),
            Err(d) => d.render(&file),
        };
        assert!(
            diagnostics.contains(&format!(
                "the mass matrix is singular: nothing resists the acceleration of `{speed}` (a degree of freedom of body `{body}`)"
            )),
            "{diagnostics}"
        );
        assert!(diagnostics.contains("help: give"), "{diagnostics}");
    }
}

/// Masses that are parameters can only be checked at run time: with the
/// cart's and the pendulum's masses set to zero (the pendulum keeping its
/// inertia) `derivatives()` returns `ModelError::SingularMassMatrix` naming
/// the cart's speed `vy`, and a run stops at t = 0 with
/// `IntegrationError::Model`, the state untouched.
#[test]
fn zero_masses_set_at_run_time_name_the_speed() {
    use models::cart_pendulum::{CartPendulum, Parameters};
    let singular = Parameters {
        mc: 0.0,
        mp: 0.0,
        ..Parameters::default()
    };
    let mut model = CartPendulum::with_parameters(singular);
    let x0 = model.initial_state();
    let mut dx = [0.0; 4];
    let expected = ModelError::SingularMassMatrix {
        speed: 0,
        name: "vy",
    };
    assert_eq!(model.derivatives(0.0, &x0, &mut dx), Err(expected));
    let mut x = x0;
    let err = run_to(&mut model, &mut Rk4::new(), &mut x, 1.0, 1e-3, 10_000).unwrap_err();
    assert_eq!(
        err,
        IntegrationError::Model {
            t: 0.0,
            error: expected
        }
    );
    assert_eq!(x, x0);
    assert!(err.to_string().contains("pivot of speed vy"), "{err}");
}

/// Zero mass with non-zero inertia on a rotation is not singular: the
/// inertia resists the rotation. With the pendulum's mass zero the run
/// passes and, with nothing driving it, the pendulum keeps its angle.
#[test]
fn zero_mass_with_inertia_on_a_rotation_passes() {
    use models::cart_pendulum::{CartPendulum, Parameters};
    let mut model = CartPendulum::with_parameters(Parameters {
        mp: 0.0,
        ..Parameters::default()
    });
    let mut x = model.initial_state();
    let x0 = x;
    run_to(&mut model, &mut Rk4::new(), &mut x, 1.0, 1e-3, 10_000).unwrap();
    assert_eq!(x, x0);
}

/// Singular at some states only: the spherical pendulum's azimuth has no
/// inertia at the pole (M = diag(m l² sin²θ, m l²)). The compiler cannot
/// know; `derivatives()` reports `SingularMassMatrix` naming
/// `azimuth_rate` at the pole and works everywhere else.
#[test]
fn a_singularity_at_some_states_is_reported_where_it_happens() {
    let mut model = models::spherical_pendulum::SphericalPendulum::new();
    let mut dx = [0.0; 4];
    assert_eq!(
        model.derivatives(0.0, &[0.3, 0.0, 0.1, 0.0], &mut dx),
        Err(ModelError::SingularMassMatrix {
            speed: 0,
            name: "azimuth_rate"
        })
    );
    let x = model.initial_state();
    assert_eq!(model.derivatives(0.0, &x, &mut dx), Ok(()));
    assert!(dx.iter().all(|v| v.is_finite()));
}

/// Singular with a non-zero diagonal: a block given two translations
/// along the same direction has M = [[m, m], [m, m]]. The compile-time
/// check looks at the diagonal and lets it through; the generated LDLᵀ
/// solve finds the zero pivot. Its elimination runs from the last speed to
/// the first, so the pivot that vanishes, and the speed named, is `v1`.
#[test]
fn a_singular_matrix_with_a_non_zero_diagonal_is_found_at_run_time() {
    use autosim_core::diag::SourceFile;
    use autosim_core::pipeline::compile_source;
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/models/extremes/double_slider.sim"
    );
    let text = std::fs::read_to_string(path).unwrap();
    assert!(compile_source(&SourceFile::new(path, text)).is_ok());

    use models::double_slider::{DoubleSlider, Parameters};
    for m in [1.0, 0.3, 7.0] {
        let mut model = DoubleSlider::with_parameters(Parameters { m, k: 10.0 });
        let mut dx = [0.0; 4];
        assert_eq!(
            model.derivatives(0.0, &model.initial_state(), &mut dx),
            Err(ModelError::SingularMassMatrix {
                speed: 0,
                name: "v1"
            }),
            "m = {m}"
        );
    }
}
