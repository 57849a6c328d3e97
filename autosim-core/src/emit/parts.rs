//! A block too big for one function, cut into parts of bounded size.
//!
//! LLVM's time on one function grows faster than its size: the Whipple
//! bicycle's `linearize`, 24 404 operations in one function, took 19 s of
//! release build; cut into functions of at most [`MAX_OPS_PER_PART`]
//! operations it takes a fraction of that (README, "Compile cost"). The
//! parts run in order; every value a block binds lives in one array `z`
//! that the caller owns and lends to each part (a value of an earlier part
//! is read as `z[k]`, with a constant index into a fixed-size array: no
//! bounds check, no panic), so a part is a plain sequence of statements
//! like the whole block was.

use crate::opt::{Block, Ir, Leaf, Nid, Op, Program, Stmt};
use std::collections::BTreeSet;

/// Operations per part at most (a statement bigger than this is a part
/// of its own).
pub const MAX_OPS_PER_PART: usize = 1500;

/// One part: its statements as a block (with the leaves and hoisted
/// constants they read), and whether it checks a pivot (returns an error).
pub struct Part {
    /// The statements, and what they read.
    pub block: Block,
    /// Whether a statement checks a pivot.
    pub checks: bool,
    /// Whether it reads or writes the array of bound values.
    pub uses_array: bool,
    /// Whether it stores a result.
    pub stores: bool,
}

/// What the statements of a part read and cost.
#[derive(Default)]
struct Reads {
    leaves: BTreeSet<Leaf>,
    hoisted: BTreeSet<Nid>,
    bound: bool,
    ops: usize,
}

/// The parts of `block`, or `None` when it fits in one, or when a part
/// could not stand alone (a block that calls a subroutine, whose outputs
/// are bound where it is called, or reads the common block). `constant`
/// tells the nodes read from the hoisted constants.
pub fn split(prog: &Program, block: &Block, constant: &dyn Fn(Nid) -> bool) -> Option<Vec<Part>> {
    if block.ops.total() <= MAX_OPS_PER_PART
        || !block.common.is_empty()
        || block.stmts.iter().any(|s| matches!(s, Stmt::CallSub(_)))
    {
        return None;
    }
    let ir = &prog.ir;
    let mut parts: Vec<Part> = Vec::new();
    let mut current: Vec<Stmt> = Vec::new();
    let mut reads = Reads::default();
    for st in &block.stmts {
        let mut one = Reads::default();
        statement_reads(ir, block, st, constant, &mut one);
        if !current.is_empty() && reads.ops + one.ops > MAX_OPS_PER_PART {
            parts.push(part(
                block,
                std::mem::take(&mut current),
                std::mem::take(&mut reads),
            ));
        }
        reads.leaves.extend(one.leaves);
        reads.hoisted.extend(one.hoisted);
        reads.bound |= one.bound;
        reads.ops += one.ops;
        current.push(st.clone());
    }
    if !current.is_empty() {
        parts.push(part(block, current, reads));
    }
    Some(parts)
}

/// The part of statements `stmts`, which read `reads`.
fn part(block: &Block, stmts: Vec<Stmt>, reads: Reads) -> Part {
    let checks = stmts.iter().any(|s| matches!(s, Stmt::Check { .. }));
    let stores = stmts.iter().any(|s| matches!(s, Stmt::Store { .. }));
    let binds = stmts
        .iter()
        .any(|s| matches!(s, Stmt::Let(_) | Stmt::SinCos { .. }));
    Part {
        block: Block {
            stmts,
            names: block.names.clone(),
            hoisted: reads.hoisted,
            common: BTreeSet::new(),
            leaves: reads.leaves,
            ops: Default::default(),
        },
        checks,
        uses_array: binds || reads.bound,
        stores,
    }
}

/// Adds what statement `st` reads: the nodes its printed expressions
/// reach before a bound value, a hoisted constant or a leaf.
fn statement_reads(
    ir: &Ir,
    block: &Block,
    st: &Stmt,
    constant: &dyn Fn(Nid) -> bool,
    out: &mut Reads,
) {
    let roots: Vec<Nid> = match *st {
        Stmt::Let(n) => {
            out.ops += 1;
            ir.children(n)
        }
        Stmt::SinCos { sin, .. } => {
            out.ops += 1;
            ir.children(sin)
        }
        Stmt::Check { pivot, .. } => vec![pivot],
        Stmt::Store { value, .. } => vec![value],
        Stmt::CallSub(_) => Vec::new(),
    };
    let mut stack = roots;
    while let Some(n) = stack.pop() {
        match ir.op(n) {
            Op::Leaf(l) => {
                out.leaves.insert(*l);
            }
            Op::Num(_) => {}
            _ if block.names.contains_key(&n) => out.bound = true,
            _ if constant(n) => {
                out.hoisted.insert(n);
            }
            // An unbound node printed twice is computed twice.
            _ => {
                out.ops += 1;
                stack.extend(ir.children(n));
            }
        }
    }
}
