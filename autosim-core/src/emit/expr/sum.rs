//! Printing sums, and which of their products become fused multiply-adds.
//!
//! `acc + a * b` printed `a.fma(b, acc)` is one instruction where the
//! target has fused multiply-adds instead of two; big generated functions
//! are limited by how fast the processor reads their instructions, so that
//! pays there. But a fused multiply-add takes a multiply's latency where an
//! add is shorter: when the sum so far is ready later than the product's
//! factors, the separate add finishes first (fusing everything made chains
//! of such sums slower: `bench/results/compiler-choices.md`). So a sum is printed
//! left to right as the IR orders it, and each product after the first term
//! is fused only where that does not make the sum ready later, by rough
//! latencies from the block's inputs. Without fused instructions
//! `a.fma(b, acc)` is `a * b + acc`: the same bits as the sum unfused.

use super::{ExprPrinter, Prec, magnitude_literal};
use crate::opt::{Nid, Op};
use proc_macro2::TokenStream;
use quote::quote;
use rustc_hash::FxHashMap;
use std::cell::RefCell;

/// Cycles of an add, a multiply and a fused multiply-add (Intel's; an
/// estimate that only has to rank).
const ADD: u32 = 2;
const MUL: u32 = 4;
const FMA: u32 = 4;

/// What the printer of one block knows of its timing: when each value is
/// ready, in rough cycles from the block's start, and each sum's terms in
/// printing order (both filled once, as sums are printed).
#[derive(Default)]
pub struct Timing {
    ready: RefCell<FxHashMap<Nid, u32>>,
    plans: RefCell<FxHashMap<Nid, Vec<Term>>>,
}

/// One term of a sum in printing order.
#[derive(Clone, Copy, Debug)]
enum Term {
    /// `± node`.
    Plain { negative: bool, node: Nid },
    /// `± a * b`, fused with the sum before it.
    Fused { negative: bool, a: Nid, b: Nid },
}

impl ExprPrinter<'_> {
    /// The sum `n` (terms `pos`, `neg`), printed left to right with its
    /// fused products.
    pub(super) fn sum(&self, n: Nid, pos: &[Nid], neg: &[Nid]) -> TokenStream {
        let terms = self.terms(n, pos, neg);
        let mut out = TokenStream::new();
        // How tightly `out` binds: whether it needs parentheses as a receiver.
        let mut out_prec = Prec::Atom;
        for (i, term) in terms.iter().enumerate() {
            let fused_next = matches!(terms.get(i + 1), Some(Term::Fused { .. }));
            (out, out_prec) = match *term {
                Term::Plain { negative, node } if i == 0 => {
                    self.first_term(negative, node, fused_next)
                }
                Term::Plain { negative, node } => {
                    let (e, op) = match negative {
                        false => (self.wrap(node, Prec::Sum), quote!(+)),
                        true => (self.wrap(node, Prec::Prod), quote!(-)),
                    };
                    (quote!(#out #op #e), Prec::Sum)
                }
                Term::Fused { negative, a, b } => {
                    let acc = if out_prec < Prec::Atom {
                        quote!((#out))
                    } else {
                        out
                    };
                    let method = if negative {
                        quote!(sub_mul)
                    } else {
                        quote!(add_mul)
                    };
                    let (a, b) = (self.expr(a), self.expr(b));
                    (quote!(#acc.#method(#a, #b)), Prec::Atom)
                }
            };
        }
        out
    }

    /// How tightly the sum `n` binds as printed: a method call if it ends
    /// with a fused product.
    pub(super) fn sum_prec(&self, n: Nid, pos: &[Nid], neg: &[Nid]) -> Prec {
        match self.terms(n, pos, neg)[..] {
            [.., Term::Fused { .. }] => Prec::Atom,
            _ => Prec::Sum,
        }
    }

    /// The terms of the sum `n` in printing order, planned once.
    fn terms(&self, n: Nid, pos: &[Nid], neg: &[Nid]) -> Vec<Term> {
        if let Some(terms) = self.timing.plans.borrow().get(&n) {
            return terms.clone();
        }
        // A sum computed outside the block is not timed; plan it from its
        // terms' times.
        self.ready_at(pos.iter().chain(neg).copied());
        let (terms, _) = self.plan(pos, neg, &self.timing.ready.borrow());
        self.timing.plans.borrow_mut().insert(n, terms.clone());
        terms
    }

    /// The first term of a sum and how tightly it binds; a literal that
    /// receives `add_mul` is typed (`0.5f64`): an untyped one is ambiguous.
    fn first_term(&self, negative: bool, node: Nid, receiver: bool) -> (TokenStream, Prec) {
        if receiver
            && self.lanes.is_none()
            && !self.is_name(node)
            && let Some(x) = self.ir().as_num(node)
            && let Some(lit) = magnitude_literal(x, self.float, true)
        {
            let x = if negative { -x } else { x };
            return match x < 0.0 {
                true => (quote!(-#lit), Prec::Unary),
                false => (quote!(#lit), Prec::Atom),
            };
        }
        match negative {
            false => {
                let prec = match self.prec(node) {
                    p if p < Prec::Sum => Prec::Atom,
                    p => p,
                };
                (self.wrap(node, Prec::Sum), prec)
            }
            true => {
                let e = self.wrap(node, Prec::Prod);
                (quote!(-#e), Prec::Unary)
            }
        }
    }

    /// The terms of a sum in printing order, and when the sum is ready
    /// (`ready` holds every term and its factors).
    fn plan(&self, pos: &[Nid], neg: &[Nid], ready: &FxHashMap<Nid, u32>) -> (Vec<Term>, u32) {
        let mut terms: Vec<(bool, Nid)> = pos.iter().map(|&t| (false, t)).collect();
        terms.extend(neg.iter().map(|&t| (true, t)));
        let at = |n: Nid| ready.get(&n).copied().unwrap_or(0);
        let factors_at = |(a, b): (Nid, Nid)| at(a).max(at(b));
        // `a * b + c` is `c + a * b` exactly: start from `c` to fuse (not
        // for `a * b - c`: `(-c).add_mul(a, b)` reads badly).
        if let [(false, first), (false, second), ..] = terms[..]
            && let Some(f) = self.product(first)
            && self.product(second).is_none()
            && fuses(at(second), factors_at(f))
        {
            terms.swap(0, 1);
        }
        let mut planned = Vec::with_capacity(terms.len());
        let mut acc = 0;
        for (i, (negative, node)) in terms.into_iter().enumerate() {
            let product = self.product(node);
            let term_at = product.map_or(at(node), |f| factors_at(f) + MUL);
            match product {
                _ if i == 0 => {
                    acc = term_at;
                    planned.push(Term::Plain { negative, node });
                }
                Some((a, b)) if fuses(acc, factors_at((a, b))) => {
                    acc = acc.max(factors_at((a, b))) + FMA;
                    planned.push(Term::Fused { negative, a, b });
                }
                _ => {
                    acc = acc.max(term_at) + ADD;
                    planned.push(Term::Plain { negative, node });
                }
            }
        }
        (planned, acc)
    }

    /// Computes (once) when each of `roots` is ready, planning the sums on
    /// the way: iterative, chains of big models are thousands deep.
    fn ready_at(&self, roots: impl Iterator<Item = Nid>) {
        let mut ready = self.timing.ready.borrow_mut();
        let mut stack: Vec<(Nid, bool)> = roots.map(|n| (n, false)).collect();
        while let Some((n, expanded)) = stack.pop() {
            if ready.contains_key(&n) {
                continue;
            }
            let ir = self.ir();
            let from_outside = matches!(ir.op(n), Op::Num(_) | Op::Leaf(_))
                || ir.is_constant(n)
                || self.is_outside(n);
            if from_outside {
                ready.insert(n, 0);
            } else if expanded {
                let at = self.ready_after_operands(n, &ready);
                ready.insert(n, at);
            } else {
                stack.push((n, true));
                stack.extend(ir.children(n).into_iter().map(|c| (c, false)));
            }
        }
    }

    /// When `n` is ready, its operands' times known.
    fn ready_after_operands(&self, n: Nid, ready: &FxHashMap<Nid, u32>) -> u32 {
        let ir = self.ir();
        let operands = || ir.children(n).iter().map(|c| ready[c]).max().unwrap_or(0);
        match ir.op(n) {
            Op::Sum { pos, neg } => {
                let (terms, at) = self.plan(pos, neg, ready);
                self.timing.plans.borrow_mut().insert(n, terms);
                at
            }
            Op::Num(_) | Op::Leaf(_) => 0,
            Op::Neg(_) => operands() + 1,
            Op::Mul(..) | Op::Powi(_, 2) => operands() + MUL,
            Op::Powi(_, 3) => operands() + 2 * MUL,
            Op::Div(..) | Op::Sqrt(_) => operands() + 15,
            Op::Powi(..) | Op::Powf(..) | Op::Call(..) => operands() + 40,
        }
    }

    /// The factors `(a, b)` of an unnamed product `a * b` (or `a * a`),
    /// which can be fused into a sum.
    fn product(&self, n: Nid) -> Option<(Nid, Nid)> {
        if self.is_name(n) || self.array.contains_key(&n) {
            return None;
        }
        match *self.ir().op(n) {
            Op::Mul(a, b) => Some((a, b)),
            Op::Powi(a, 2) => Some((a, a)),
            _ => None,
        }
    }
}

/// Whether adding a product whose factors are ready at `factors` to a sum
/// ready at `acc` is done no later fused than as a multiply and an add.
fn fuses(acc: u32, factors: u32) -> bool {
    acc.max(factors) + FMA <= acc.max(factors + MUL) + ADD
}

#[cfg(test)]
mod tests {
    use super::fuses;

    #[test]
    fn a_product_fuses_unless_the_sum_so_far_is_the_late_operand() {
        assert!(fuses(0, 0));
        assert!(fuses(3, 10));
        // A tie fuses: as soon, one instruction fewer.
        assert!(fuses(12, 10));
        assert!(!fuses(13, 10));
        assert!(!fuses(40, 0));
    }
}
