//! The structural dependencies of derivatives and outputs (`opt::dependencies`)
//! on models whose equations are known by hand. Every exported FMU's
//! dependencies are also checked numerically through FMPy (`tests/fmi.rs`).

use autosim_core::diag::SourceFile;
use autosim_core::opt::dependencies::{Dependencies, Depends};
use autosim_core::pipeline::compile_source;

fn dependencies(file: &str) -> Dependencies {
    let path = format!("{}/../examples/models/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("example model");
    let compiled = compile_source(&SourceFile::new(&path, text)).expect("compiles");
    Dependencies::of(&compiled.program)
}

fn on(states: &[usize], inputs: &[usize]) -> (Vec<usize>, Vec<usize>) {
    (states.to_vec(), inputs.to_vec())
}

fn of(d: &Depends) -> (Vec<usize>, Vec<usize>) {
    (d.states.clone(), d.inputs.clone())
}

#[test]
fn quarter_car_reads_what_its_equations_say() {
    // States zu, zs, vu, vs; input road (the tire force, on the wheel only).
    let d = dependencies("quarter_car.sim");
    assert_eq!(of(&d.derivatives[0]), on(&[2], &[]));
    assert_eq!(of(&d.derivatives[1]), on(&[3], &[]));
    assert_eq!(of(&d.derivatives[2]), on(&[0, 1, 2, 3], &[0]));
    assert_eq!(of(&d.derivatives[3]), on(&[0, 1, 2, 3], &[]));
    // deflection = Ls - (zs - zu); body_acceleration = dvs/dt.
    assert_eq!(of(&d.outputs[0]), on(&[0, 1], &[]));
    assert_eq!(of(&d.outputs[1]), on(&[0, 1, 2, 3], &[]));
    assert!(d.dependent.is_empty());
    // Parameters ms, mu, ks, cs, kt, Ls, Lt, g: the body's acceleration
    // reads all but the tire's (kt, Lt) and the wheel's mass.
    assert_eq!(d.derivatives[3].parameters, [0, 2, 3, 5, 7]);
}

#[test]
fn four_bar_depends_on_its_independent_states_only() {
    // States q1, q2, q3, u1; q2 and q3 are solved from q1 by the loop.
    let d = dependencies("four_bar.sim");
    assert_eq!(d.dependent, [1, 2]);
    assert_eq!(of(&d.derivatives[0]), on(&[3], &[]));
    assert_eq!(of(&d.derivatives[3]), on(&[0, 3], &[]));
    // The residuals read q1 only through the dependent coordinates'
    // solution: zero at every assembled state, but structurally q1's.
    for output in &d.outputs {
        assert!(
            output.states.iter().all(|s| [0, 3].contains(s)),
            "{output:?}"
        );
    }
    assert_eq!(of(&d.outputs[0]), on(&[0, 3], &[]));
}

#[test]
fn initial_values_read_the_parameters_they_are_written_with() {
    let text = "model Start;\n\
                parameters { m = 1 [kg], g = 9.81 [m/s^2], k = 100 [N/m], lift = 0.1 [m] }\n\
                body B { translate: 3, q: [z], u: [w], mass: m, inertia: 0, initial: [lift - m*g/k], initial_speeds: [2] }\n\
                body C { translate: 1, q: [y], u: [v], mass: m, inertia: 0, initial: [0.5] }\n\
                gravity = -g*n3;\n";
    let compiled =
        compile_source(&SourceFile::new("start.sim", text.to_string())).expect("compiles");
    let d = Dependencies::of(&compiled.program);
    // States z, y, w, v: z from lift, m, g and k; the others numbers.
    assert_eq!(d.initial, [vec![0, 1, 2, 3], vec![], vec![], vec![]]);
}
