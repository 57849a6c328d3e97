//! The program IR: every example model's program satisfies the verifier's
//! invariants, the verifier catches broken programs, and the text form of a
//! small program is a snapshot (so an optimizer change shows up here, apart
//! from the emitter's snapshots in `emit.rs`).

use autosim_core::diag::SourceFile;
use autosim_core::opt::{At, BlockKind, Interpreter, Program, Stmt, UserCalls};
use autosim_core::pipeline::compile_source;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn program(path: &Path) -> Program {
    let text = std::fs::read_to_string(path).expect("model file");
    let src = SourceFile::new(path, text);
    compile_source(&src)
        .unwrap_or_else(|d| panic!("{}", d.render(&src)))
        .program
}

fn model_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for dir in ["examples/models", "tests/models/extremes"] {
        for e in std::fs::read_dir(root().join(dir)).expect("model folder") {
            let p = e.expect("entry").path();
            if p.extension().is_some_and(|x| x == "sim") {
                files.push(p);
            }
        }
    }
    files.sort();
    files
}

#[test]
fn every_example_program_verifies() {
    let files = model_files();
    assert!(files.len() > 20, "found only {} models", files.len());
    for f in files {
        if let Err(e) = program(&f).verify() {
            panic!("{}: {e}", f.display());
        }
    }
}

fn chain_planar_2() -> Program {
    program(&root().join("examples/models/chain_planar_2.sim"))
}

fn derivatives_mut(p: &mut Program) -> &mut Vec<Stmt> {
    let (_, b) = p
        .blocks
        .iter_mut()
        .find(|(k, _)| *k == BlockKind::Derivatives)
        .expect("a derivatives block");
    &mut b.stmts
}

/// What the verifier says of chain-planar-2's program once `edit` has
/// changed its derivatives block's statements.
fn verify_edited(edit: impl FnOnce(&mut Vec<Stmt>)) -> String {
    let mut p = chain_planar_2();
    edit(derivatives_mut(&mut p));
    p.verify().expect_err("the edit breaks an invariant")
}

#[test]
fn verifier_catches_a_value_read_before_it_is_bound() {
    let e = verify_edited(|stmts| {
        let first_let = stmts.iter().position(|s| matches!(s, Stmt::Let(_)));
        let st = stmts.remove(first_let.expect("a let"));
        stmts.push(st);
    });
    assert!(e.contains("before it is bound"), "{e}");
}

#[test]
fn verifier_catches_a_missing_and_a_doubled_store() {
    let last_store = |stmts: &[Stmt]| {
        let last = stmts.iter().rposition(|s| matches!(s, Stmt::Store { .. }));
        last.expect("a store")
    };
    let e = verify_edited(|stmts| {
        stmts.remove(last_store(stmts));
    });
    assert!(e.contains("never written"), "{e}");
    let e = verify_edited(|stmts| {
        let st = stmts[last_store(stmts)].clone();
        stmts.push(st);
    });
    assert!(e.contains("twice"), "{e}");
}

#[test]
fn text_form_of_a_small_program() {
    insta::assert_snapshot!("chain_planar_2_program", chain_planar_2().to_string());
}

/// A spatial chain of `n` equal links hinged about axes 1, 2, 3, 1, ...,
/// with its accelerations solved by `formulation`.
fn spatial_chain(n: usize, formulation: &str) -> Program {
    let mut text = format!(
        "model Chain;\nsettings {{ formulation: {formulation} }}\nparameters {{ m = 1.2 [kg], L = 0.4 [m], k = 2 [N m/rad] }}\n"
    );
    for i in 1..=n {
        let (parent, joint) = match i {
            1 => ("N".to_string(), String::new()),
            _ => (format!("B{}", i - 1), ", joint: [0, 0, -L]".to_string()),
        };
        let axis = (i - 1) % 3 + 1;
        text += &format!(
            "body B{i} {{ parent: {parent}{joint}, rotate: {axis}, mass: m, cm: [0, 0, -L/2], inertia: [[0.02, 0.0005, 0], [0.0005, 0.03, 0], [0, 0, 0.004]], q: [q{i}], u: [u{i}] }}\nmoment spring{i} {{ on: B{i}, reaction: {parent}, about: {parent}.{axis}, magnitude: -k*q{i} }}\n"
        );
    }
    text += "gravity = -9.81*n3;\n";
    let src = SourceFile::new("chain.sim", text);
    compile_source(&src)
        .unwrap_or_else(|d| panic!("{}", d.render(&src)))
        .program
}

/// A state of `n_states` values from a simple generator (angles and
/// rates of order one).
fn state(n_states: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    (0..n_states)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

/// In a model too big for one `let` per value, `derivatives` and
/// `forcing` read what both compute from one common block: the program
/// verifies, each call's cost counts the common block, and the values
/// equal the other formulation's (whose common block holds different
/// values) at random states.
#[test]
fn big_models_compute_the_shared_terms_once() {
    let n = 40;
    let recursive = spatial_chain(n, "recursive");
    let matrix = spatial_chain(n, "mass_matrix");
    for p in [&recursive, &matrix] {
        p.verify().expect("the program verifies");
        let common = p.block(BlockKind::Common);
        assert_eq!(
            common
                .stmts
                .iter()
                .filter(|s| matches!(s, Stmt::Store { .. }))
                .count(),
            p.common.len()
        );
        for kind in [BlockKind::Derivatives, BlockKind::Forcing] {
            let b = p.block(kind);
            assert!(
                !b.common.is_empty(),
                "{} reads the common block",
                kind.name()
            );
            assert!(
                b.ops.total() >= common.ops.total(),
                "{} counts the common block",
                kind.name()
            );
        }
    }
    let params: Vec<f64> = recursive
        .interface
        .model
        .parameters
        .iter()
        .map(|q| q.default)
        .collect();
    let (rec, mat) = (
        Interpreter::new(&recursive, &params),
        Interpreter::new(&matrix, &params),
    );
    let mut function = |_: usize, _: &[f64]| f64::NAN;
    let mut subroutine = |_: usize, _: &[f64]| Vec::new();
    let mut user = UserCalls {
        function: &mut function,
        subroutine: &mut subroutine,
    };
    for seed in 1..=5 {
        let x = state(2 * n, seed);
        let at = At {
            t: 0.0,
            x: &x,
            inputs: &[],
            discrete: &[],
        };
        let dr = rec.derivatives(at, &mut user).expect("regular");
        let dm = mat.derivatives(at, &mut user).expect("regular");
        let (_, fr) = rec.mass_matrix_and_forcing(at, &mut user);
        let (_, fm) = mat.mass_matrix_and_forcing(at, &mut user);
        for (a, b) in dr.iter().zip(&dm).chain(fr.iter().zip(&fm)) {
            assert!(
                (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
                "{a} against {b} (seed {seed})"
            );
        }
    }
}

/// A Jacobian entry that does not depend on its variable is the literal
/// zero in the program, not a computed value that rounds to zero: the
/// bicycle's equations never read the rear contact's position `x`, `y`,
/// no coordinate's rate reads the inputs, and no output reads the inputs.
#[test]
fn structural_zeros_of_the_linearization_are_literal() {
    use autosim_core::model::Scene;
    use autosim_core::pipeline::compile_source_scene;
    let path = root().join("examples/models/bicycle.sim");
    let text = std::fs::read_to_string(&path).expect("model file");
    let src = SourceFile::new(&path, text);
    let scene = Scene {
        linearize: Some(true),
        ..Scene::default()
    };
    let program = compile_source_scene(&src, &scene)
        .unwrap_or_else(|d| panic!("{}", d.render(&src)))
        .program;
    let states = program.interface.linear_states.clone().expect("linearized");
    let layout = &program.interface.states;
    let names = |k: usize| layout.state(k).name.as_str();
    let (nl, nw, ny) = (states.len(), 2, 3);
    let col = |name: &str| {
        states
            .iter()
            .position(|k| names(*k) == name)
            .expect("a linear state")
    };
    let (x, y) = (col("x"), col("y"));
    let coordinates = states
        .iter()
        .filter(|k| **k < layout.coordinates.len())
        .count();
    let (b0, c0) = (nl * nl, nl * nl + nl * nw);
    let d0 = c0 + ny * nl;
    let mut zero: Vec<usize> = (0..nl).flat_map(|i| [i * nl + x, i * nl + y]).collect();
    zero.extend((0..ny).flat_map(|i| [c0 + i * nl + x, c0 + i * nl + y]));
    zero.extend(b0..b0 + coordinates * nw);
    zero.extend(d0..d0 + ny * nw);
    let block = &program
        .blocks
        .iter()
        .find(|(k, _)| *k == BlockKind::Linearize)
        .expect("a linearize block")
        .1;
    let computed: Vec<usize> = block
        .stmts
        .iter()
        .filter_map(|s| match s {
            Stmt::Store { slot, value }
                if zero.contains(slot) && program.ir.as_num(*value) != Some(0.0) =>
            {
                Some(*slot)
            }
            _ => None,
        })
        .collect();
    assert!(
        computed.is_empty(),
        "structurally zero slots computed: {computed:?}"
    );
}
