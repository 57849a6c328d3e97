//! Joint reactions and the energy and momentum built-ins, through the
//! interpreter of the compiled program: static cases with known answers,
//! the chains against Pinocchio's RNEA (`tests/reference/gen/pinocchio_reactions.py`),
//! and identities of energy, momentum and power.

use autosim_core::diag::SourceFile;
use autosim_core::opt::{At, Interpreter, UserCalls};
use autosim_core::pipeline::{Compiled, compile_source};

fn compile_text(name: &str, text: &str) -> Compiled {
    let file = SourceFile::new(name, text.to_string());
    match compile_source(&file) {
        Ok(c) => c,
        Err(d) => panic!("{}", d.render(&file)),
    }
}

/// The outputs of `c` at state `x` (default parameters, no user code).
fn outputs_at(c: &Compiled, x: &[f64], t: f64) -> Vec<f64> {
    let params: Vec<f64> = c
        .program
        .interface
        .parameters
        .iter()
        .map(|p| p.default)
        .collect();
    outputs_with(c, &params, x, t)
}

fn outputs_with(c: &Compiled, params: &[f64], x: &[f64], t: f64) -> Vec<f64> {
    let it = Interpreter::new(&c.program, params);
    let mut function = |_f: usize, _a: &[f64]| 0.0;
    let mut subroutine = |_s: usize, _a: &[f64]| Vec::new();
    let mut user = UserCalls {
        function: &mut function,
        subroutine: &mut subroutine,
    };
    let at = At { t, x, inputs: &[] };
    it.outputs(at, &mut user).expect("outputs")
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + b.abs())
}

/// A pendulum hanging at rest carries its weight at the hinge, straight
/// up, and no moment.
#[test]
fn pendulum_at_rest_carries_its_weight() {
    let c = compile_text(
        "pendulum",
        "model P;
         parameters { m = 1.3 [kg], L = 0.7 [m], g = 9.81 [m/s^2] }
         body Rod { rotate: 1, mass: m, cm: [0, 0, -L], inertia: diag(0.01, 0.02, 0.03) }
         gravity = -g*n3;
         output f1 [N] = dot(reaction_force(Rod), n1);
         output f2 [N] = dot(reaction_force(Rod), n2);
         output f3 [N] = dot(reaction_force(Rod), n3);
         output m1 [N m] = dot(reaction_moment(Rod), n1);
         output m2 [N m] = dot(reaction_moment(Rod), n2);
         output m3 [N m] = dot(reaction_moment(Rod), n3);",
    );
    let y = outputs_at(&c, &[0.0, 0.0], 0.0);
    let expect = [0.0, 0.0, 1.3 * 9.81, 0.0, 0.0, 0.0];
    for (k, (a, b)) in y.iter().zip(expect).enumerate() {
        assert!(close(*a, b, 1e-14), "component {k}: {a} against {b}");
    }
}
