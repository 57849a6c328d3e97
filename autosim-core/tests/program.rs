//! The program IR: every example model's program satisfies the verifier's
//! invariants, the verifier catches broken programs, and the text form of a
//! small program is a snapshot (so an optimizer change shows up here, apart
//! from the emitter's snapshots in `emit.rs`).

use autosim_core::diag::SourceFile;
use autosim_core::opt::{BlockKind, Program, Stmt};
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

#[test]
fn verifier_catches_a_value_read_before_it_is_bound() {
    let mut p = chain_planar_2();
    let stmts = derivatives_mut(&mut p);
    let first_let = stmts
        .iter()
        .position(|s| matches!(s, Stmt::Let(_)))
        .expect("a let");
    let st = stmts.remove(first_let);
    stmts.push(st);
    let e = p.verify().expect_err("a use before the binding");
    assert!(e.contains("before it is bound"), "{e}");
}

#[test]
fn verifier_catches_a_missing_and_a_doubled_store() {
    let mut p = chain_planar_2();
    let stmts = derivatives_mut(&mut p);
    let last = stmts
        .iter()
        .rposition(|s| matches!(s, Stmt::Store { .. }))
        .expect("a store");
    let st = stmts.remove(last);
    assert!(
        p.verify()
            .expect_err("a slot never written")
            .contains("never written")
    );
    let stmts = derivatives_mut(&mut p);
    stmts.push(st.clone());
    stmts.push(st);
    assert!(
        p.verify()
            .expect_err("a slot written twice")
            .contains("twice")
    );
}

#[test]
fn text_form_of_a_small_program() {
    insta::assert_snapshot!("chain_planar_2_program", chain_planar_2().to_string());
}
