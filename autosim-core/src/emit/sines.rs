//! Sines and cosines two at a time.
//!
//! The angles a block reads from outside (coordinates, parameters,
//! inputs, time, the common block's values) are all known when it starts,
//! so their sines and cosines can be taken [`LANES`] at a time,
//! `sin_cos_lanes([q1, q2])`: the runtime's branch-free kernel, lane by
//! lane the same operations as its one-angle `sin_cos_inline`, in vector
//! instructions where the target has them, half the instructions of two
//! calls. A group is computed where the first of its angles was; one left
//! over, and angles the block computes itself, keep one call each (libm's
//! in small blocks, the branch-free one in blocks of more than
//! [`MIN_VALUES_FOR_INLINE_SINES`] values). `f32` models take every sine
//! from libm's `sincosf` instead (the kernel computes in `f64`).
//!
//! [`MIN_VALUES_FOR_INLINE_SINES`]: super::block::MIN_VALUES_FOR_INLINE_SINES

use crate::opt::{Block, Ir, Leaf, Nid, Op, Stmt};
use rustc_hash::{FxHashMap, FxHashSet};

/// Angles per group: two lanes were faster than one call per angle in
/// every chain measured, four slower in most (timings:
/// `bench/results/compiler-choices.md`).
pub const LANES: usize = 2;

/// One sine and cosine: the two bound values and the angle.
#[derive(Clone, Copy, Debug)]
pub struct SinCos {
    /// The bound sine.
    pub sin: Nid,
    /// The bound cosine.
    pub cos: Nid,
    /// The angle.
    pub angle: Nid,
}

/// Which statements of a block are emitted as groups of [`LANES`].
#[derive(Default)]
pub struct Groups {
    /// At the index of each group's first statement, the group.
    pub at: FxHashMap<usize, Vec<SinCos>>,
    /// The indices of the groups' other statements (emitted with the first).
    pub skip: FxHashSet<usize>,
}

/// The groups of [`LANES`] of `block`'s sines and cosines whose angles are
/// known at its start (`from_outside(n)`: `n` is read, not computed, by
/// the block), in statement order.
pub fn groups(ir: &Ir, block: &Block, from_outside: &dyn Fn(Nid) -> bool) -> Groups {
    let known_at_start = |angle: Nid| match ir.op(angle) {
        Op::Leaf(l) => matches!(
            l,
            Leaf::State(_) | Leaf::Param(_) | Leaf::Input(_) | Leaf::Time | Leaf::Discrete(_)
        ),
        _ => from_outside(angle),
    };
    let eligible: Vec<(usize, SinCos)> = block
        .stmts
        .iter()
        .enumerate()
        .filter_map(|(i, st)| match *st {
            Stmt::SinCos { sin, cos } => match ir.op(sin) {
                Op::Call(_, args) if args.len() == 1 && known_at_start(args[0]) => Some((
                    i,
                    SinCos {
                        sin,
                        cos,
                        angle: args[0],
                    },
                )),
                _ => None,
            },
            _ => None,
        })
        .collect();
    let mut groups = Groups::default();
    for group in eligible.chunks_exact(LANES) {
        groups
            .at
            .insert(group[0].0, group.iter().map(|g| g.1).collect());
        groups.skip.extend(group[1..].iter().map(|(i, _)| *i));
    }
    groups
}
