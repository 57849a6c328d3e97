//! What a block costs a processor: its operations, and the longest chain
//! of latencies through them (the cycles no parallelism hides). The
//! choice between the two ways of solving a tree weighs both.

use crate::opt::ir::{Ir, Nid, Op};
use crate::opt::schedule::{Block, Stmt};
use rustc_hash::FxHashMap;

/// Rough latencies in cycles, enough to rank chains.
pub fn latency(op: &Op) -> u32 {
    match op {
        Op::Num(_) | Op::Leaf(_) => 0,
        Op::Neg(_) => 1,
        Op::Sum { .. } | Op::Mul(..) | Op::Powi(..) => 3,
        Op::Div(..) | Op::Sqrt(_) => 13,
        Op::Powf(..) | Op::Call(..) => 40,
    }
}

/// The estimated cycles of one execution of `block`: its operations (one
/// a cycle) plus its critical path: neither alone ranks the two
/// formulations the way they time (a recursion with fewer operations can
/// be slower for its one long chain); the sum ranks every pair timed as
/// measured (`bench/results/compiler-choices.md`).
pub fn estimated_cycles(ir: &Ir, block: &Block) -> usize {
    block.ops.total() + critical_path(ir, block) as usize
}

/// The longest chain of latencies from the values the block reads to
/// what it stores and checks (values of a common block included: the
/// call computes them).
pub fn critical_path(ir: &Ir, block: &Block) -> u32 {
    let mut depth: FxHashMap<Nid, u32> = FxHashMap::default();
    let roots = block.stmts.iter().filter_map(|st| match st {
        Stmt::Store { value, .. } => Some(*value),
        Stmt::Check { pivot, .. } => Some(*pivot),
        _ => None,
    });
    roots
        .map(|r| depth_of(ir, r, &mut depth))
        .max()
        .unwrap_or(0)
}

/// The latency from the block's inputs to `root` (iterative: chains of
/// big models are thousands deep). Constants are computed once per
/// parameter set and cost nothing here.
fn depth_of(ir: &Ir, root: Nid, depth: &mut FxHashMap<Nid, u32>) -> u32 {
    let mut stack = vec![(root, false)];
    while let Some((n, expanded)) = stack.pop() {
        if depth.contains_key(&n) {
            continue;
        }
        if matches!(ir.op(n), Op::Num(_) | Op::Leaf(_)) || ir.is_constant(n) {
            depth.insert(n, 0);
        } else if expanded {
            let below = ir.children(n).iter().map(|c| depth[c]).max();
            depth.insert(n, latency(ir.op(n)) + below.unwrap_or(0));
        } else {
            stack.push((n, true));
            stack.extend(ir.children(n).into_iter().map(|c| (c, false)));
        }
    }
    depth[&root]
}
