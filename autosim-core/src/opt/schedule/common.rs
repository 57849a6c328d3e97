//! Work two generated functions share, computed once: `derivatives` and
//! `forcing` of a big model both compute the body velocities and the
//! velocity-dependent forces (on the recursive route four fifths of what
//! `forcing` computes; on the mass-matrix route all of it). The shared
//! part becomes a common block, a private function both call, and its
//! values are read from the array it fills: the generated module shrinks
//! by the shared part and no call does more work than before.
//!
//! Where: in blocks too big for one `let` per value (their intermediates
//! live in an array anyway), and in big blocks bound by throughput rather
//! than latency, where it is also faster: scheduled apart, the shared
//! values and the rest each keep fewer values live. A latency-bound block
//! would wait for the shared part instead, so it keeps one function
//! (timings: `bench/results/compiler-choices.md`).

use crate::limits::MAX_LETS_IN_FUNCTION;
use crate::opt::ir::{Ir, Nid, Op};
use crate::opt::schedule::cost::critical_path;
use crate::opt::schedule::{Block, Options, Task, schedule};
use rustc_hash::FxHashSet;

/// Blocks with more bound values than this share for speed when they are
/// throughput-bound; smaller ones were slower shared
/// (`bench/results/compiler-choices.md`).
pub const MIN_VALUES_TO_SHARE: usize = 1000;

/// The common block of `first` and `second` (scheduled from `tasks`
/// with `opts`), or `None` when they do not gain from one: `first` small
/// or latency-bound (module docs), either block calling user code (whose
/// calls must stay where the model puts them), or nothing shared.
///
/// On `Some((common, values))` both blocks are rescheduled to read the
/// shared values (slot `k` of the common block computes `values[k]`),
/// and each block's cost includes the common block's.
pub fn share(
    ir: &Ir,
    (first, first_tasks): (&mut Block, &[Task]),
    (second, second_tasks): (&mut Block, &[Task]),
    opts: &Options<'_>,
) -> Option<(Block, Vec<Nid>)> {
    let calls_user_code = |b: &Block| b.ops.user_calls > 0;
    let bound = first.names.len();
    let throughput_bound = || 2 * critical_path(ir, first) as usize <= first.ops.total();
    let worth = bound > MAX_LETS_IN_FUNCTION || (bound > MIN_VALUES_TO_SHARE && throughput_bound());
    if !worth || calls_user_code(first) || calls_user_code(second) {
        return None;
    }
    let opaque = |n: Nid| match ir.op(n) {
        Op::Num(_) | Op::Leaf(_) => true,
        _ => opts.hoist_constants && ir.is_constant(n),
    };
    let a = computed(ir, first_tasks, &opaque);
    let b = computed(ir, second_tasks, &opaque);
    let values = frontier(ir, (&a, first_tasks), (&b, second_tasks), &opaque);
    if values.is_empty() {
        return None;
    }
    let common_set: FxHashSet<Nid> = values.iter().copied().collect();
    let stores: Vec<Task> = values
        .iter()
        .enumerate()
        .map(|(slot, &value)| Task::Store { slot, value })
        .collect();
    let common = schedule(ir, &stores, opts);
    let reading = Options {
        common: &common_set,
        ..*opts
    };
    for (block, tasks) in [(first, first_tasks), (second, second_tasks)] {
        *block = schedule(ir, tasks, &reading);
        block.ops += common.ops;
    }
    Some((common, values))
}

/// The values a task reads.
fn roots(tasks: &[Task]) -> impl Iterator<Item = Nid> + '_ {
    tasks.iter().map(|t| match t {
        Task::Store { value, .. } => *value,
        Task::Check { pivot, .. } => *pivot,
    })
}

/// The nodes the tasks compute (not those read as values).
fn computed(ir: &Ir, tasks: &[Task], opaque: &dyn Fn(Nid) -> bool) -> FxHashSet<Nid> {
    let mut seen = FxHashSet::default();
    let mut stack: Vec<Nid> = roots(tasks).collect();
    while let Some(n) = stack.pop() {
        if !opaque(n) && seen.insert(n) {
            stack.extend(ir.children(n));
        }
    }
    seen
}

/// The shared nodes either block reads directly: a task's value, or an
/// operand of a node only that block computes (in IR order, operands
/// first). Everything they depend on is shared too.
fn frontier(
    ir: &Ir,
    (a, a_tasks): (&FxHashSet<Nid>, &[Task]),
    (b, b_tasks): (&FxHashSet<Nid>, &[Task]),
    opaque: &dyn Fn(Nid) -> bool,
) -> Vec<Nid> {
    let shared = |n: &Nid| a.contains(n) && b.contains(n);
    let mut read: FxHashSet<Nid> = roots(a_tasks)
        .chain(roots(b_tasks))
        .filter(shared)
        .collect();
    for n in a.iter().chain(b.iter()).filter(|n| !shared(n)) {
        read.extend(
            ir.children(*n)
                .into_iter()
                .filter(|c| !opaque(*c) && shared(c)),
        );
    }
    let mut values: Vec<Nid> = read.into_iter().collect();
    values.sort();
    values
}
