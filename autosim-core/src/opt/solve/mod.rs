//! The accelerations: an unrolled LDLᵀ factorization of the mass matrix,
//! built in the IR so it shares the optimizer's naming and counting.
//!
//! Speeds are eliminated leaves first (the reverse of the tree order), which
//! keeps the factor as sparse as the mass matrix for any tree: entries known
//! to be zero at generation time, and their fill-in, are skipped.

pub(super) mod articulated;
pub(super) mod axis_rotation;
pub(super) mod elim;
mod pattern;

pub use pattern::ldlt_varying_products;

use crate::opt::ir::{Ir, Nid};
use crate::opt::solve::articulated::{Articulated, TreeBody};

/// The IR of the solve of `M du = f`.
pub struct Solve {
    /// Pivot `d_k` (for each speed in elimination order) with the speed index.
    pub pivots: Vec<(Nid, usize)>,
    /// du/dt per speed (speed order).
    pub du: Vec<Nid>,
    /// `(name hint, node)` for the factor's entries, for readable code.
    pub hints: Vec<(String, Nid)>,
    /// The factor, for more right-hand sides.
    pub factor: Solver,
}

/// A factored mass matrix: an LDLᵀ of `M`, or the articulated-body
/// recursion (which never forms `M`).
pub enum Solver {
    /// `M = L D Lᵀ`.
    Ldlt(Factor),
    /// The articulated-body recursion.
    Articulated(Box<Articulated>),
}

impl Solver {
    /// `M⁻¹ f` (speed order).
    pub fn solve(&self, ir: &mut Ir, f: &[Nid]) -> Vec<Nid> {
        match self {
            Solver::Ldlt(factor) => factor.solve(ir, f),
            Solver::Articulated(a) => a.solve(ir, f),
        }
    }
}

/// `M du = f` by the articulated-body recursion over `bodies`, `f` the
/// projections of the bodies' bias forces plus `joint_forcing`; with `f`
/// itself, summed by the same recursion.
pub(crate) fn recursive_solve(
    ir: &mut Ir,
    bodies: Vec<TreeBody>,
    joint_forcing: &[Nid],
) -> (Solve, Vec<Nid>) {
    let a = Articulated::new(ir, bodies, joint_forcing.len());
    let du = a.solve_biased(ir, joint_forcing);
    let forcing = a.forcing(ir, joint_forcing);
    let solve = Solve {
        pivots: a.pivots.clone(),
        du,
        hints: Vec::new(),
        factor: Solver::Articulated(Box::new(a)),
    };
    (solve, forcing)
}

/// `M = L D Lᵀ` in the IR, speeds eliminated in `perm` order.
pub struct Factor {
    perm: Vec<usize>,
    /// `L[i][k]` (elimination order), `None` where structurally zero.
    l: Vec<Vec<Option<Nid>>>,
    /// `1 / d_k`.
    d_inv: Vec<Nid>,
}

impl Factor {
    /// `M⁻¹ f` (speed order).
    pub fn solve(&self, ir: &mut Ir, f: &[Nid]) -> Vec<Nid> {
        let (n, perm, l) = (self.perm.len(), &self.perm, &self.l);
        // Forward: y = L⁻¹ f', scale: z = D⁻¹ y, back: x = L⁻ᵀ z.
        let mut y: Vec<Nid> = Vec::with_capacity(n);
        for i in 0..n {
            let mut neg = Vec::new();
            for k in 0..i {
                if let Some(a) = l[i][k] {
                    neg.push(ir.mul(a, y[k]));
                }
            }
            let yi = ir.sum(vec![f[perm[i]]], neg);
            y.push(yi);
        }
        let z: Vec<Nid> = (0..n).map(|i| ir.mul(y[i], self.d_inv[i])).collect();
        let mut x: Vec<Nid> = vec![ir.num(0.0); n];
        for i in (0..n).rev() {
            let mut neg = Vec::new();
            for k in i + 1..n {
                if let Some(a) = l[k][i] {
                    neg.push(ir.mul(a, x[k]));
                }
            }
            x[i] = ir.sum(vec![z[i]], neg);
        }
        let mut du = vec![ir.num(0.0); n];
        for i in 0..n {
            du[perm[i]] = x[i];
        }
        du
    }
}

/// The order `ldlt_solve` eliminates `n` speeds in: the reverse of the
/// speed order (leaves first).
pub fn ldlt_order(n: usize) -> Vec<usize> {
    (0..n).rev().collect()
}

/// Factors `m` (lower triangle used; `None` = structurally zero) and solves
/// for `f`.
pub fn ldlt_solve(ir: &mut Ir, m: &[Vec<Option<Nid>>], f: &[Nid]) -> Solve {
    let n = f.len();
    let perm = ldlt_order(n);
    let entry = |i: usize, j: usize| -> Option<Nid> {
        let (a, b) = (perm[i], perm[j]);
        m[a.max(b)][a.min(b)]
    };
    // Symbolic factorization: nonzero pattern of L with fill-in.
    let nz = pattern::fill(n, |i, j| entry(i, j).is_some());
    let mut l: Vec<Vec<Option<Nid>>> = vec![vec![None; n]; n];
    let mut ld: Vec<Vec<Option<Nid>>> = vec![vec![None; n]; n];
    let mut d_inv: Vec<Nid> = Vec::with_capacity(n);
    let mut pivots = Vec::with_capacity(n);
    let mut hints = Vec::new();
    for j in 0..n {
        // d_j = M_jj - Σ L_jk LD_jk
        let neg = products(ir, &l[j][..j], &ld[j][..j]);
        let mjj = entry(j, j).unwrap_or_else(|| ir.num(0.0));
        let d = ir.sum(vec![mjj], neg);
        pivots.push((d, perm[j]));
        hints.push((format!("d{}", perm[j] + 1), d));
        let one = ir.num(1.0);
        let di = ir.div(one, d);
        hints.push((format!("d{}_inv", perm[j] + 1), di));
        d_inv.push(di);
        for i in j + 1..n {
            if !nz.get(i, j) {
                continue;
            }
            let neg = products(ir, &l[i][..j], &ld[j][..j]);
            let mij = entry(i, j).unwrap_or_else(|| ir.num(0.0));
            let ldij = ir.sum(vec![mij], neg);
            let lij = ir.mul(ldij, di);
            ld[i][j] = Some(ldij);
            l[i][j] = Some(lij);
            hints.push((format!("l{}_{}", perm[i] + 1, perm[j] + 1), lij));
        }
    }
    let factor = Factor { perm, l, d_inv };
    let du = factor.solve(ir, f);
    Solve {
        pivots,
        du,
        hints,
        factor: Solver::Ldlt(factor),
    }
}

/// `a_k b_k` for every `k` where both entries are known (not structurally
/// zero), in order.
fn products(ir: &mut Ir, a: &[Option<Nid>], b: &[Option<Nid>]) -> Vec<Nid> {
    a.iter()
        .zip(b)
        .filter_map(|(x, y)| Some(ir.mul((*x)?, (*y)?)))
        .collect()
}
