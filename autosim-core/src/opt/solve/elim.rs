//! Linear systems of the constraints in the IR: an unrolled LU
//! factorization (Doolittle) with the row order and the pivot column of
//! each row chosen at compile time (`mech` chooses them by complete
//! pivoting at the initial state, preferring entries with a constant part).
//! Entries known to be zero, and their fill-in, are skipped; literal
//! pivots fold away. One factorization serves several right-hand sides.

use crate::opt::ir::{Ir, Nid};

/// A factored square matrix.
pub struct Elimination {
    /// Row of each step.
    rows: Vec<usize>,
    /// Column (unknown) of each step.
    cols: Vec<usize>,
    /// `1 / U[s][s]`.
    inverse_pivots: Vec<Nid>,
    /// `L[i][s]`, `i > s` (steps).
    lower: Vec<Vec<Option<Nid>>>,
    /// `U[s][t]`, `t > s` (steps).
    upper: Vec<Vec<Option<Nid>>>,
    /// `(U[s][s], row)` of every step whose pivot is not a literal, to be
    /// checked at run time.
    pub checks: Vec<(Nid, usize)>,
}

impl Elimination {
    /// Factors `a[row][col]` (`None`: structurally zero), eliminating the
    /// rows in `order`, row `r` on column `col_of[r]`.
    pub fn factor(
        ir: &mut Ir,
        a: &[Vec<Option<Nid>>],
        order: &[usize],
        col_of: &[usize],
    ) -> Elimination {
        let m = order.len();
        let rows = order.to_vec();
        let cols: Vec<usize> = order.iter().map(|&r| col_of[r]).collect();
        let entry = |s: usize, t: usize| a[rows[s]][cols[t]];
        let mut lower: Vec<Vec<Option<Nid>>> = vec![vec![None; m]; m];
        let mut upper: Vec<Vec<Option<Nid>>> = vec![vec![None; m]; m];
        let mut inverse_pivots = Vec::with_capacity(m);
        let mut checks = Vec::new();
        for s in 0..m {
            // U[s][t] = B[s][t] − Σ_{k<s} L[s][k] U[k][t], t ≥ s.
            for t in s..m {
                let terms: Vec<Nid> = (0..s)
                    .filter_map(|k| Some(ir.mul(lower[s][k]?, upper[k][t]?)))
                    .collect();
                upper[s][t] = reduced(ir, entry(s, t), terms);
            }
            let pivot = upper[s][s].unwrap_or_else(|| ir.num(0.0));
            if ir.as_num(pivot).is_none() {
                checks.push((pivot, rows[s]));
            }
            let one = ir.num(1.0);
            let inv = ir.div(one, pivot);
            inverse_pivots.push(inv);
            // L[i][s] = (B[i][s] − Σ_{k<s} L[i][k] U[k][s]) / U[s][s], i > s.
            for i in s + 1..m {
                let terms: Vec<Nid> = (0..s)
                    .filter_map(|k| Some(ir.mul(lower[i][k]?, upper[k][s]?)))
                    .collect();
                lower[i][s] = reduced(ir, entry(i, s), terms).map(|d| ir.mul(d, inv));
            }
        }
        Elimination {
            rows,
            cols,
            inverse_pivots,
            lower,
            upper,
            checks,
        }
    }

    /// The unknowns (by column) of `A x = rhs` (`rhs` by row).
    pub fn solve(&self, ir: &mut Ir, rhs: &[Nid]) -> Vec<Nid> {
        let m = self.rows.len();
        let mut y: Vec<Nid> = Vec::with_capacity(m);
        for s in 0..m {
            let terms: Vec<Nid> = (0..s)
                .filter_map(|k| Some(ir.mul(self.lower[s][k]?, y[k])))
                .collect();
            y.push(ir.sum(vec![rhs[self.rows[s]]], terms));
        }
        let mut x_step: Vec<Nid> = vec![ir.num(0.0); m];
        for s in (0..m).rev() {
            let terms: Vec<Nid> = (s + 1..m)
                .filter_map(|t| Some(ir.mul(self.upper[s][t]?, x_step[t])))
                .collect();
            let d = ir.sum(vec![y[s]], terms);
            x_step[s] = ir.mul(d, self.inverse_pivots[s]);
        }
        let mut x = vec![ir.num(0.0); m];
        for s in 0..m {
            x[self.cols[s]] = x_step[s];
        }
        x
    }
}

/// `b − Σ terms` (`b` absent: zero), or `None` where both are absent
/// (a structural zero).
fn reduced(ir: &mut Ir, b: Option<Nid>, terms: Vec<Nid>) -> Option<Nid> {
    if b.is_none() && terms.is_empty() {
        return None;
    }
    let b = b.unwrap_or_else(|| ir.num(0.0));
    Some(ir.sum(vec![b], terms))
}
