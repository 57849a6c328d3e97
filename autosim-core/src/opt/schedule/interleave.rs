//! Ordering a big block's statements for instruction-level parallelism.
//!
//! A block is one straight line of code, and a processor overlaps only
//! the operations within a window of a few hundred instructions. Scheduled
//! task by task, a recursive solve computes one long dependent chain after
//! another (all articulated inertias inward, then all velocities outward),
//! so the window holds dependent operations and the processor waits on
//! latencies. Here statements are reordered by list scheduling, the one
//! with the longest path of latencies still ahead of it first, so that
//! independent chains advance together, unless too many values are live,
//! when the one that frees the most goes first. Effects keep their order: user
//! calls, subroutine calls and pivot checks stay in sequence (a model that
//! fails reports the same error and calls user code the same way), and
//! only pure values move across them. Values are unchanged, so results
//! are bit for bit the same; only the order of the `let`s differs.

use crate::expr::Func;
use crate::opt::ir::{Ir, Leaf, Nid, Op};
use crate::opt::schedule::Stmt;
use crate::opt::schedule::cost::latency;
use rustc_hash::FxHashMap;
use std::cmp::Reverse;
use std::collections::BTreeSet;

/// Blocks with fewer statements fit in the processor's window as they
/// are; they keep the order that reads best (each result with what it
/// needs just before it).
pub const MIN_STATEMENTS: usize = 200;

/// Past this many live values (about the registers of a target) the
/// statement that frees the most is taken first instead of the longest
/// chain, so that interleaving does not turn into spilling. Measured on
/// the chains of `bench/peers` (x86-64 with AVX-512, 32 vector registers):
/// 24 and 64 both beat no limit; 24 spills least.
pub const MAX_LIVE: usize = 24;

/// Reorders `stmts` (a topological order) as described in the module
/// documentation. `sub_args`: each subroutine's arguments; `bound(n)`: `n` is computed by a statement of the block
/// (`Let`, `SinCos`); `opaque(n)`: `n` is read, not computed.
pub fn interleave(
    ir: &Ir,
    stmts: Vec<Stmt>,
    sub_args: &[Vec<Nid>],
    bound: &dyn Fn(Nid) -> bool,
    opaque: &dyn Fn(Nid) -> bool,
) -> Vec<Stmt> {
    if stmts.len() < MIN_STATEMENTS {
        return stmts;
    }
    let graph = Graph::new(ir, &stmts, sub_args, bound, opaque);
    let order = graph.list_schedule();
    let mut slots: Vec<Option<Stmt>> = stmts.into_iter().map(Some).collect();
    order.into_iter().filter_map(|i| slots[i].take()).collect()
}

/// The statements' dependencies: what each reads (statements whose
/// values it uses, and the previous effect for an effect), who reads it,
/// and the longest latency path from it to the block's end.
struct Graph {
    reads: Vec<Vec<usize>>,
    readers: Vec<Vec<usize>>,
    height: Vec<u32>,
}

impl Graph {
    fn new(
        ir: &Ir,
        stmts: &[Stmt],
        sub_args: &[Vec<Nid>],
        bound: &dyn Fn(Nid) -> bool,
        opaque: &dyn Fn(Nid) -> bool,
    ) -> Graph {
        let mut defined_by: FxHashMap<Nid, usize> = FxHashMap::default();
        let mut calls: FxHashMap<usize, usize> = FxHashMap::default();
        for (i, st) in stmts.iter().enumerate() {
            match st {
                Stmt::CallSub(sub) => {
                    calls.insert(*sub, i);
                }
                Stmt::Let(n) => {
                    defined_by.insert(*n, i);
                }
                Stmt::SinCos { sin, cos } => {
                    defined_by.insert(*sin, i);
                    defined_by.insert(*cos, i);
                }
                _ => {}
            }
        }
        let inputs = Inputs {
            defined_by: &defined_by,
            calls: &calls,
            bound,
            opaque,
        };
        let count = stmts.len();
        let mut reads: Vec<Vec<usize>> = vec![Vec::new(); count];
        let mut readers: Vec<Vec<usize>> = vec![Vec::new(); count];
        let mut own = vec![0u32; count];
        let mut last_effect: Option<usize> = None;
        for (i, st) in stmts.iter().enumerate() {
            // What the statement computes (or reads, for checks, stores
            // and subroutine calls).
            let (roots, effect) = match st {
                Stmt::Let(n) => (
                    std::slice::from_ref(n),
                    matches!(ir.op(*n), Op::Call(Func::User(_), _)),
                ),
                Stmt::SinCos { sin, .. } => (std::slice::from_ref(sin), false),
                Stmt::Check { pivot, .. } => (std::slice::from_ref(pivot), true),
                Stmt::Store { value, .. } => (std::slice::from_ref(value), false),
                Stmt::CallSub(sub) => (sub_args.get(*sub).map_or(&[][..], Vec::as_slice), true),
            };
            for &r in roots {
                let l = inputs.latency(ir, r, i, &mut reads[i]);
                own[i] = own[i].max(l);
            }
            if effect {
                reads[i].extend(last_effect);
                last_effect = Some(i);
            }
            reads[i].sort_unstable();
            reads[i].dedup();
            for &p in &reads[i] {
                readers[p].push(i);
            }
        }
        let mut height = vec![0u32; count];
        for i in (0..count).rev() {
            let after = readers[i].iter().map(|s| height[*s]).max().unwrap_or(0);
            height[i] = own[i] + after;
        }
        Graph {
            reads,
            readers,
            height,
        }
    }

    /// The order: among the statements whose inputs are ready, the
    /// highest first, or while more than [`MAX_LIVE`] values are live, the
    /// one that leaves the fewest live.
    fn list_schedule(&self) -> Vec<usize> {
        let count = self.reads.len();
        let mut waiting_on: Vec<usize> = self.reads.iter().map(Vec::len).collect();
        let mut unread: Vec<usize> = self.readers.iter().map(Vec::len).collect();
        let mut scheduled = vec![false; count];
        // For a ready statement: how many of the values it reads it is the
        // last to read (kept up to date as readers are scheduled).
        let mut frees = vec![0usize; count];
        let mut ready = Ready::default();
        for i in (0..count).filter(|i| waiting_on[*i] == 0) {
            ready.insert(i, self.key(i, 0));
        }
        let mut live = 0usize;
        let mut out = Vec::with_capacity(count);
        while let Some(i) = ready.pop(live > MAX_LIVE) {
            live = live.saturating_add_signed(self.key(i, frees[i]).growth);
            scheduled[i] = true;
            out.push(i);
            for &p in &self.reads[i] {
                unread[p] -= 1;
                if unread[p] == 1 {
                    // Its one reader left, if ready, now frees it.
                    let last = self.readers[p].iter().find(|r| !scheduled[**r]);
                    if let Some(&r) = last.filter(|r| waiting_on[**r] == 0) {
                        frees[r] += 1;
                        ready.insert(r, self.key(r, frees[r]));
                    }
                }
            }
            for &s in &self.readers[i] {
                waiting_on[s] -= 1;
                if waiting_on[s] == 0 {
                    frees[s] = self.reads[s].iter().filter(|p| unread[**p] == 1).count();
                    ready.insert(s, self.key(s, frees[s]));
                }
            }
        }
        out
    }

    /// What the choice among ready statements compares for statement `i`
    /// reading `frees` values last.
    fn key(&self, i: usize, frees: usize) -> Key {
        Key {
            // Live values the statement adds less those it reads last.
            growth: isize::from(!self.readers[i].is_empty()) - frees as isize,
            height: self.height[i],
        }
    }
}

/// A ready statement's priorities.
#[derive(Clone, Copy)]
struct Key {
    growth: isize,
    height: u32,
}

/// The ready statements, ordered both ways the choice needs (the highest
/// first; the one leaving the fewest live first), so that each choice
/// costs a logarithm of their number rather than a pass over them (which
/// made scheduling quadratic in a block's size).
#[derive(Default)]
struct Ready {
    /// `(height, Reverse(i))`: the last is the highest, the first of equals.
    by_height: BTreeSet<(u32, Reverse<usize>)>,
    /// `(growth, Reverse(height), i)`: the first leaves the fewest live.
    by_growth: BTreeSet<(isize, Reverse<u32>, usize)>,
    /// Each ready statement's key as entered.
    keys: FxHashMap<usize, Key>,
}

impl Ready {
    /// Enters statement `i` with key `k`, or updates its key.
    fn insert(&mut self, i: usize, k: Key) {
        self.remove(i);
        self.by_height.insert((k.height, Reverse(i)));
        self.by_growth.insert((k.growth, Reverse(k.height), i));
        self.keys.insert(i, k);
    }

    fn remove(&mut self, i: usize) {
        if let Some(k) = self.keys.remove(&i) {
            self.by_height.remove(&(k.height, Reverse(i)));
            self.by_growth.remove(&(k.growth, Reverse(k.height), i));
        }
    }

    /// Takes the next statement: by growth while too many values are live
    /// (`crowded`), by height otherwise.
    fn pop(&mut self, crowded: bool) -> Option<usize> {
        let i = match crowded {
            true => self.by_growth.first().map(|e| e.2)?,
            false => self.by_height.last().map(|e| e.1.0)?,
        };
        self.remove(i);
        Some(i)
    }
}

/// How a statement's expression reads other statements' values.
struct Inputs<'a> {
    defined_by: &'a FxHashMap<Nid, usize>,
    /// The statement calling each subroutine (its outputs are leaves).
    calls: &'a FxHashMap<usize, usize>,
    bound: &'a dyn Fn(Nid) -> bool,
    opaque: &'a dyn Fn(Nid) -> bool,
}

impl Inputs<'_> {
    /// The latency of statement `me`'s expression `root` (computed inline
    /// unless another statement binds it), collecting the statements whose
    /// values it reads.
    fn latency(&self, ir: &Ir, root: Nid, me: usize, reads: &mut Vec<usize>) -> u32 {
        let mut memo: FxHashMap<Nid, u32> = FxHashMap::default();
        let mut stack = vec![(root, false)];
        while let Some((n, expanded)) = stack.pop() {
            if memo.contains_key(&n) {
                continue;
            }
            let elsewhere = self.defined_by.get(&n).filter(|s| **s != me);
            if let Op::Leaf(Leaf::SubOut(sub, _)) = ir.op(n) {
                reads.extend(self.calls.get(sub));
            }
            if (self.opaque)(n) || ((self.bound)(n) && elsewhere.is_some()) {
                reads.extend(elsewhere);
                memo.insert(n, 0);
                continue;
            }
            let children = ir.children(n);
            if expanded {
                let ahead = children.iter().map(|c| memo[c]).max().unwrap_or(0);
                memo.insert(n, latency(ir.op(n)) + ahead);
            } else {
                stack.push((n, true));
                stack.extend(children.into_iter().map(|c| (c, false)));
            }
        }
        memo[&root]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::opt::schedule::Guard;
    use rustc_hash::FxHashSet;

    /// Two independent chains of `len` products, each with a check part
    /// way: statements as the task-by-task schedule writes them.
    fn two_chains(ir: &mut Ir, len: usize) -> (Vec<Stmt>, Vec<Nid>, Vec<Nid>) {
        let chain = |ir: &mut Ir, leaf: usize| {
            let x = ir.leaf(Leaf::State(leaf));
            let mut v = x;
            (0..len)
                .map(|k| {
                    let p = ir.mul(v, x);
                    let c = ir.num(k as f64 + 2.0);
                    v = ir.sum(vec![p, c], Vec::new());
                    v
                })
                .collect::<Vec<Nid>>()
        };
        let (a, b) = (chain(ir, 0), chain(ir, 1));
        let mut stmts: Vec<Stmt> = a.iter().map(|n| Stmt::Let(*n)).collect();
        stmts.insert(
            len / 3,
            Stmt::Check {
                pivot: a[len / 3 - 1],
                guard: Guard::Positive { speed: 0 },
            },
        );
        stmts.extend(b.iter().map(|n| Stmt::Let(*n)));
        stmts.push(Stmt::Check {
            pivot: b[len / 2],
            guard: Guard::Positive { speed: 1 },
        });
        stmts.push(Stmt::Store {
            slot: 0,
            value: a[len - 1],
        });
        stmts.push(Stmt::Store {
            slot: 1,
            value: b[len - 1],
        });
        (stmts, a, b)
    }

    #[test]
    fn chains_advance_together_and_effects_keep_their_order() {
        let mut ir = Ir::new();
        let (stmts, a, b) = two_chains(&mut ir, 150);
        let named: FxHashSet<Nid> = a.iter().chain(&b).copied().collect();
        let bound = |n: Nid| named.contains(&n);
        let opaque = |n: Nid| matches!(ir.op(n), Op::Num(_) | Op::Leaf(_));
        let out = interleave(&ir, stmts.clone(), &[], &bound, &opaque);
        assert_eq!(out.len(), stmts.len());
        // Every value is defined before it is read.
        let mut defined: FxHashSet<Nid> = FxHashSet::default();
        for st in &out {
            let reads = match st {
                Stmt::Let(n) => ir
                    .children(*n)
                    .iter()
                    .flat_map(|c| ir.children(*c))
                    .collect(),
                Stmt::Check { pivot, .. } => vec![*pivot],
                Stmt::Store { value, .. } => vec![*value],
                _ => Vec::new(),
            };
            for r in reads.into_iter().filter(|r| named.contains(r)) {
                assert!(defined.contains(&r), "{r:?} read before it is defined");
            }
            if let Stmt::Let(n) = st {
                defined.insert(*n);
            }
        }
        // The checks keep their order.
        let checks: Vec<&Stmt> = out
            .iter()
            .filter(|s| matches!(s, Stmt::Check { .. }))
            .collect();
        assert!(matches!(
            checks[..],
            [
                Stmt::Check {
                    guard: Guard::Positive { speed: 0 },
                    ..
                },
                Stmt::Check {
                    guard: Guard::Positive { speed: 1 },
                    ..
                }
            ]
        ));
        // The second chain starts before the first ends.
        let first_b = out.iter().position(|s| *s == Stmt::Let(b[0])).unwrap();
        assert!(first_b < 10, "chain b starts at statement {first_b}");
    }

    #[test]
    fn small_blocks_keep_their_order() {
        let mut ir = Ir::new();
        let (stmts, _, _) = two_chains(&mut ir, 20);
        let out = interleave(&ir, stmts.clone(), &[], &|_| true, &|_| false);
        assert_eq!(out, stmts);
    }
}
