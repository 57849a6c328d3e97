//! Scheduling a block of the program: which IR nodes get a name (used more
//! than once, user calls, pivots), in what order they are computed
//! (subroutines first, then user functions in model order, then each result
//! with what it needs just before it), and what the block costs.

pub(super) mod common;
pub(super) mod cost;
pub(super) mod interleave;
pub(super) mod naming;

use crate::expr::Func;
use crate::opt::ir::{Ir, Leaf, Nid, Op};
use crate::opt::schedule::interleave::interleave;
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::BTreeSet;
use std::fmt;

use crate::limits::MAX_INLINE_DEPTH;

/// What a block must produce.
#[derive(Clone, Debug, PartialEq)]
pub enum Task {
    /// Write `value` into output slot `slot`.
    Store {
        /// Output slot.
        slot: usize,
        /// The value.
        value: Nid,
    },
    /// Stop with the guard's error unless the pivot passes it.
    Check {
        /// The pivot.
        pivot: Nid,
        /// What the pivot must be, and what to report when it is not.
        guard: Guard,
    },
}

/// A run-time test of a pivot, and the error it reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Guard {
    /// A pivot of the mass matrix's LDLᵀ: positive, or
    /// `SingularMassMatrix` naming speed `speed` (index in the state's
    /// speeds).
    Positive {
        /// Speed index.
        speed: usize,
    },
    /// A pivot of a constraint solve: away from zero, or
    /// `SingularConstraints` naming constraint `constraint` (declaration
    /// order).
    Regular {
        /// Constraint index.
        constraint: usize,
    },
}

/// One statement of a scheduled block.
#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    /// `let <name> = <expression of node>;`
    Let(Nid),
    /// Call user subroutine `sub` (its outputs become available).
    CallSub(usize),
    /// `let (<sin name>, <cos name>) = sin_cos(x);` for a `sin(x)` and a
    /// `cos(x)` of the same block.
    SinCos {
        /// The `sin(x)` node.
        sin: Nid,
        /// The `cos(x)` node.
        cos: Nid,
    },
    /// The pivot check.
    Check {
        /// The pivot.
        pivot: Nid,
        /// Its test.
        guard: Guard,
    },
    /// Write an output slot.
    Store {
        /// Output slot.
        slot: usize,
        /// The value.
        value: Nid,
    },
}

/// Operation counts of a block (what one call costs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Ops {
    /// Additions and subtractions.
    pub adds: usize,
    /// Multiplications.
    pub muls: usize,
    /// Divisions.
    pub divs: usize,
    /// Calls of built-in functions (sin, cos, sqrt, ...).
    pub funcs: usize,
    /// Calls of user functions and subroutines.
    pub user_calls: usize,
}

impl Ops {
    /// Arithmetic operations and built-in function calls.
    pub fn total(&self) -> usize {
        self.adds + self.muls + self.divs + self.funcs
    }
}

impl std::ops::AddAssign for Ops {
    fn add_assign(&mut self, o: Ops) {
        self.adds += o.adds;
        self.muls += o.muls;
        self.divs += o.divs;
        self.funcs += o.funcs;
        self.user_calls += o.user_calls;
    }
}

impl fmt::Display for Ops {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // "1 divide", "2 divides": counts read as English.
        let counted = |n: usize, one: &str, many: &str| match n {
            1 => format!("1 {one}"),
            n => format!("{n} {many}"),
        };
        write!(
            f,
            "{}, {}, {}, {}",
            counted(self.adds, "add", "adds"),
            counted(self.muls, "multiply", "multiplies"),
            counted(self.divs, "divide", "divides"),
            counted(self.funcs, "function", "functions")
        )?;
        if self.user_calls > 0 {
            write!(
                f,
                ", {}",
                counted(self.user_calls, "user call", "user calls")
            )?;
        }
        Ok(())
    }
}

/// A scheduled block.
#[derive(Clone, Debug, Default)]
pub struct Block {
    /// Statements in order.
    pub stmts: Vec<Stmt>,
    /// Names of the nodes bound by `Stmt::Let`.
    pub names: FxHashMap<Nid, String>,
    /// Constant nodes read from the precomputed constants.
    pub hoisted: BTreeSet<Nid>,
    /// Nodes read from the common block (computed once for the blocks
    /// that share them: `common.rs`).
    pub common: BTreeSet<Nid>,
    /// Leaves the block reads.
    pub leaves: BTreeSet<Leaf>,
    /// Cost of one execution.
    pub ops: Ops,
}

impl Block {
    /// Whether the block reads the time.
    pub fn reads_time(&self) -> bool {
        self.leaves.contains(&Leaf::Time)
    }

    /// Whether the block reads a state.
    pub fn reads_state(&self) -> bool {
        self.leaves.iter().any(|l| matches!(l, Leaf::State(_)))
    }

    /// Whether the block reads a parameter.
    pub fn reads_parameters(&self) -> bool {
        self.leaves.iter().any(|l| matches!(l, Leaf::Param(_)))
    }
}

/// How to schedule a block.
#[derive(Clone, Copy)]
pub struct Options<'a> {
    /// Read non-trivial constants from the constants block instead of
    /// computing them.
    pub hoist_constants: bool,
    /// Preferred names for some nodes.
    pub hints: &'a FxHashMap<Nid, String>,
    /// User-function call nodes in the order they must be called.
    pub call_order: &'a [Nid],
    /// Arguments of each user subroutine (declaration order).
    pub sub_args: &'a [Vec<Nid>],
    /// Names that generated names must avoid.
    pub reserved: &'a FxHashSet<String>,
    /// Nodes the common block computes: read, not computed, here.
    pub common: &'a FxHashSet<Nid>,
}

struct Sched<'a> {
    ir: &'a Ir,
    opts: &'a Options<'a>,
    /// `sin(x)` ↔ `cos(x)` pairs computed together.
    partner: FxHashMap<Nid, Nid>,
    named: FxHashSet<Nid>,
    emitted: FxHashSet<Nid>,
    block: Block,
    /// What the tasks read: roots, then everything reachable from them.
    roots: Vec<Nid>,
    reach: FxHashSet<Nid>,
    /// Reachable nodes in the order they were found.
    order: Vec<Nid>,
    /// Subroutines whose outputs are read.
    subs_used: BTreeSet<usize>,
}

impl Sched<'_> {
    /// Nodes read as values rather than computed here.
    fn opaque(&self, n: Nid) -> bool {
        match self.ir.op(n) {
            Op::Num(_) | Op::Leaf(_) => true,
            _ if self.opts.common.contains(&n) => true,
            _ => self.opts.hoist_constants && self.ir.is_constant(n),
        }
    }

    /// Emits `root`'s named dependencies (children first, left to right)
    /// and `root` itself if it is named. Iterative: dependency chains of
    /// big models are thousands deep.
    fn emit_node(&mut self, root: Nid) {
        let mut stack: Vec<(Nid, bool)> = vec![(root, false)];
        while let Some((n, expanded)) = stack.pop() {
            if self.opaque(n) || self.emitted.contains(&n) {
                continue;
            }
            if expanded {
                if self.named.contains(&n) {
                    self.emitted.insert(n);
                    match self.partner.get(&n).copied() {
                        Some(other) => {
                            // Both share the argument, already computed.
                            self.emitted.insert(other);
                            let (sin, cos) = match self.ir.op(n) {
                                Op::Call(Func::Sin, _) => (n, other),
                                _ => (other, n),
                            };
                            self.block.stmts.push(Stmt::SinCos { sin, cos });
                        }
                        None => self.block.stmts.push(Stmt::Let(n)),
                    }
                }
                continue;
            }
            stack.push((n, true));
            for c in self.ir.children(n).into_iter().rev() {
                stack.push((c, false));
            }
        }
    }
}

/// The arguments of subroutine `sub`.
fn sub_args<'a>(opts: &'a Options<'_>, sub: usize) -> &'a [Nid] {
    opts.sub_args.get(sub).map_or(&[], Vec::as_slice)
}

/// Schedules the tasks of one block.
pub fn schedule(ir: &Ir, tasks: &[Task], opts: &Options<'_>) -> Block {
    let mut s = Sched {
        ir,
        opts,
        partner: FxHashMap::default(),
        named: FxHashSet::default(),
        emitted: FxHashSet::default(),
        block: Block::default(),
        roots: Vec::new(),
        reach: FxHashSet::default(),
        order: Vec::new(),
        subs_used: BTreeSet::new(),
    };
    s.reachable(tasks);
    s.name_shared_values(tasks);
    s.bound_nesting();
    s.pair_sines_and_cosines();
    s.order_statements(tasks);
    s.interleave_statements();
    s.choose_names();
    s.count_operations();
    s.block
}

impl Sched<'_> {
    /// Reachable computed nodes; subroutine arguments join the roots when
    /// one of the subroutine's outputs is used.
    fn reachable(&mut self, tasks: &[Task]) {
        self.roots = tasks
            .iter()
            .map(|t| match t {
                Task::Store { value, .. } => *value,
                Task::Check { pivot, .. } => *pivot,
            })
            .collect();
        loop {
            let mut stack = self.roots.clone();
            while let Some(n) = stack.pop() {
                if !self.reach.insert(n) {
                    continue;
                }
                self.order.push(n);
                if let Op::Leaf(l) = self.ir.op(n) {
                    self.block.leaves.insert(*l);
                    if let Leaf::SubOut(sub, _) = l {
                        self.subs_used.insert(*sub);
                    }
                }
                if self.opaque(n) {
                    if self.opts.common.contains(&n) {
                        self.block.common.insert(n);
                    } else if !matches!(self.ir.op(n), Op::Num(_) | Op::Leaf(_)) {
                        self.block.hoisted.insert(n);
                    }
                    continue;
                }
                stack.extend(self.ir.children(n));
            }
            let before = self.roots.len();
            for &sub in &self.subs_used {
                for a in sub_args(self.opts, sub) {
                    if !self.roots.contains(a) {
                        self.roots.push(*a);
                    }
                }
            }
            if self.roots.len() == before {
                break;
            }
        }
    }

    /// Values used more than once, user calls, computed bases of small
    /// powers (written as products) and pivots get a name.
    fn name_shared_values(&mut self, tasks: &[Task]) {
        let mut uses: FxHashMap<Nid, usize> = FxHashMap::default();
        for &r in &self.roots {
            *uses.entry(r).or_default() += 1;
        }
        for &n in &self.order {
            if self.opaque(n) {
                continue;
            }
            for c in self.ir.children(n) {
                *uses.entry(c).or_default() += 1;
            }
        }
        for i in 0..self.order.len() {
            let n = self.order[i];
            if self.opaque(n) {
                continue;
            }
            let multi = uses.get(&n).copied().unwrap_or(0) >= 2;
            let user_call = matches!(self.ir.op(n), Op::Call(Func::User(_), _));
            if multi || user_call {
                self.named.insert(n);
            }
            if let Op::Powi(b, k) = self.ir.op(n)
                && *k <= 3
                && !self.opaque(*b)
            {
                self.named.insert(*b);
            }
        }
        for t in tasks {
            if let Task::Check { pivot, .. } = t
                && !self.opaque(*pivot)
            {
                self.named.insert(*pivot);
            }
        }
    }

    /// Bounds how deeply expressions nest when printed (and the recursion
    /// of the printers): a value nested deeper than [`MAX_INLINE_DEPTH`] is
    /// named.
    fn bound_nesting(&mut self) {
        let mut sorted: Vec<Nid> = self
            .order
            .iter()
            .copied()
            .filter(|n| !self.opaque(*n))
            .collect();
        sorted.sort();
        let mut depth: FxHashMap<Nid, usize> = FxHashMap::default();
        for &n in &sorted {
            let d = 1 + self
                .ir
                .children(n)
                .iter()
                .filter(|c| !self.opaque(**c) && !self.named.contains(c))
                .map(|c| depth.get(c).copied().unwrap_or(0))
                .max()
                .unwrap_or(0);
            if d > MAX_INLINE_DEPTH {
                self.named.insert(n);
            }
            depth.insert(n, if self.named.contains(&n) { 0 } else { d });
        }
    }

    /// Sine and cosine of the same argument are computed together.
    fn pair_sines_and_cosines(&mut self) {
        for i in 0..self.order.len() {
            let n = self.order[i];
            if self.opaque(n) {
                continue;
            }
            if let Op::Call(Func::Sin, args) = self.ir.op(n)
                && let Some(c) = self.ir.find(&Op::Call(Func::Cos, args.clone()))
                && self.reach.contains(&c)
                && !self.opaque(c)
            {
                self.named.insert(n);
                self.named.insert(c);
                self.partner.insert(n, c);
                self.partner.insert(c, n);
            }
        }
    }

    /// Statements in order: subroutines, user functions, then the tasks,
    /// each with what it needs just before it.
    fn order_statements(&mut self, tasks: &[Task]) {
        for sub in self.subs_used.clone() {
            for a in sub_args(self.opts, sub) {
                self.emit_node(*a);
            }
            self.block.stmts.push(Stmt::CallSub(sub));
        }
        for &c in self.opts.call_order {
            if self.reach.contains(&c) {
                self.emit_node(c);
            }
        }
        for t in tasks {
            match *t {
                Task::Store { slot, value } => {
                    self.emit_node(value);
                    self.block.stmts.push(Stmt::Store { slot, value });
                }
                Task::Check { pivot, guard } => {
                    self.emit_node(pivot);
                    self.block.stmts.push(Stmt::Check { pivot, guard });
                }
            }
        }
    }

    /// Big blocks: independent chains of computation advance together
    /// (`interleave.rs`).
    fn interleave_statements(&mut self) {
        let stmts = std::mem::take(&mut self.block.stmts);
        let bound = |n: Nid| self.named.contains(&n);
        let opaque = |n: Nid| self.opaque(n);
        self.block.stmts = interleave(self.ir, stmts, self.opts.sub_args, &bound, &opaque);
    }

    /// Names: hints where free, otherwise `z1`, `z2`, ... in order of use.
    fn choose_names(&mut self) {
        let mut used_names: FxHashSet<String> = self.opts.reserved.clone();
        let mut counter = 0;
        let lets: Vec<Nid> = self
            .block
            .stmts
            .iter()
            .flat_map(|st| match st {
                Stmt::Let(n) => vec![*n],
                Stmt::SinCos { sin, cos } => vec![*sin, *cos],
                _ => Vec::new(),
            })
            .collect();
        for n in lets {
            let name = match self.opts.hints.get(&n) {
                Some(h) if !used_names.contains(h) => h.clone(),
                _ => loop {
                    counter += 1;
                    let z = format!("z{counter}");
                    if !used_names.contains(&z) {
                        break z;
                    }
                },
            };
            used_names.insert(name.clone());
            self.block.names.insert(n, name);
        }
    }

    /// The cost: every computed node once; a sine-cosine pair is one call.
    fn count_operations(&mut self) {
        let mut ops = Ops {
            user_calls: self.subs_used.len(),
            ..Ops::default()
        };
        for &n in &self.order {
            if self.opaque(n) {
                continue;
            }
            match self.ir.op(n) {
                Op::Sum { pos, neg } => ops.adds += pos.len() + neg.len() - 1,
                Op::Mul(..) => ops.muls += 1,
                Op::Div(..) => ops.divs += 1,
                Op::Powi(_, k) => ops.muls += (*k as usize).saturating_sub(1),
                Op::Sqrt(_) | Op::Powf(..) => ops.funcs += 1,
                Op::Call(Func::User(_), _) => ops.user_calls += 1,
                Op::Call(..) => ops.funcs += 1,
                Op::Neg(_) | Op::Num(_) | Op::Leaf(_) => {}
            }
        }
        ops.funcs -= self.partner.len() / 2;
        self.block.ops = ops;
    }
}
