//! The nonzero pattern of the LDLᵀ factor of a mass matrix, fill-in
//! included, and from it a lower bound on what the factorization costs per
//! call, known before it is built (the `auto` formulation skips the mass
//! matrix's route when the bound already exceeds the recursion's cost).
//!
//! Patterns are rows of bits (`u64` words): a few lines, where a bit-set
//! crate would be a dependency for one loop; the fill of a 400-speed
//! matrix is then 7 words per pair of rows instead of 400 booleans.

use crate::opt::ir::{Ir, Nid};

/// A strictly lower triangular pattern: bit `k` of row `i` (`k < i`).
pub(super) struct Rows {
    words: usize,
    bits: Vec<u64>,
}

impl Rows {
    fn new(n: usize) -> Rows {
        let words = n.div_ceil(64);
        Rows {
            words,
            bits: vec![0; n * words],
        }
    }

    fn row(&self, i: usize) -> &[u64] {
        &self.bits[i * self.words..(i + 1) * self.words]
    }

    /// Whether entry `(i, k)` is set.
    pub(super) fn get(&self, i: usize, k: usize) -> bool {
        self.row(i)[k / 64] >> (k % 64) & 1 == 1
    }

    fn set(&mut self, i: usize, k: usize) {
        self.bits[i * self.words + k / 64] |= 1 << (k % 64);
    }
}

/// How many `k` have bit `k` set in all of `rows` (each a row's words).
fn common<const N: usize>(rows: [&[u64]; N]) -> usize {
    (0..rows[0].len())
        .map(|w| rows.iter().fold(!0u64, |acc, r| acc & r[w]).count_ones() as usize)
        .sum()
}

/// The factor's pattern for `entry(i, j)` (`i > j`, elimination order)
/// known nonzero: an entry is nonzero where the matrix's is, or where an
/// earlier column has both rows nonzero (fill-in).
pub(super) fn fill(n: usize, entry: impl Fn(usize, usize) -> bool) -> Rows {
    let mut nz = Rows::new(n);
    for i in 0..n {
        for j in 0..i {
            if entry(i, j) {
                nz.set(i, j);
            }
        }
    }
    for j in 0..n {
        for i in j + 1..n {
            // Row j has bits below j only, so the common bits are k < j.
            if !nz.get(i, j) && common([nz.row(i), nz.row(j)]) > 0 {
                nz.set(i, j);
            }
        }
    }
    nz
}

/// A lower bound on the operations the LDLᵀ solve of `mass` (lower
/// triangle, `None` structurally zero; speeds eliminated in `perm` order)
/// adds to every call of `derivatives`: its products `L_ik LD_jk` of two
/// factor entries that both vary with the state. Such a product is an
/// operation of its own (the IR folds only literals and never cancels
/// terms) computed per call (it is not a constant). An entry is counted
/// as varying only where that is certain: where `mass`'s entry varies, or
/// a product of two varying entries enters it. Products of different
/// entries are different operations unless two entries coincide as
/// expressions, which is why the caller allows a margin.
pub fn ldlt_varying_products(ir: &Ir, mass: &[Vec<Option<Nid>>], perm: &[usize]) -> usize {
    let n = perm.len();
    let entry = |i: usize, j: usize| {
        let (a, b) = (perm[i], perm[j]);
        mass[a.max(b)][a.min(b)]
    };
    let varies = |i: usize, j: usize| entry(i, j).is_some_and(|e| !ir.is_constant(e));
    let nz = fill(n, |i, j| entry(i, j).is_some());
    // `LD_ij = M_ij − Σ_k L_ik LD_jk` and `L_ij = LD_ij / d_j`: with the
    // same pattern, and varying where `LD` does, both in `varying`.
    let mut varying = Rows::new(n);
    let mut count = 0;
    for j in 0..n {
        for i in j + 1..n {
            if !nz.get(i, j) {
                continue;
            }
            let products = common([varying.row(i), varying.row(j)]);
            count += products;
            if varies(i, j) || products > 0 {
                varying.set(i, j);
            }
        }
    }
    // The pivots `d_j = M_jj − Σ_k L_jk LD_jk`.
    count + (0..n).map(|j| common([varying.row(j)])).sum::<usize>()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::opt::ir::{Leaf, Op};
    use crate::opt::solve::{ldlt_order, ldlt_solve};

    /// A lower triangle of leaves: `State` (varying) where `varying(i, j)`,
    /// `Param` (constant) elsewhere, `None` where `zero(i, j)`.
    fn matrix(
        ir: &mut Ir,
        n: usize,
        zero: impl Fn(usize, usize) -> bool,
        varying: impl Fn(usize, usize) -> bool,
    ) -> Vec<Vec<Option<Nid>>> {
        let mut k = 0;
        (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        k += 1;
                        (j <= i && !zero(i, j)).then(|| match varying(i, j) {
                            true => ir.leaf(Leaf::State(k)),
                            false => ir.leaf(Leaf::Param(k)),
                        })
                    })
                    .collect()
            })
            .collect()
    }

    /// The multiplications `ldlt_solve` adds to `ir` that vary.
    fn varying_products_built(ir: &mut Ir, m: &[Vec<Option<Nid>>]) -> usize {
        let before = ir.len();
        let f: Vec<Nid> = (0..m.len()).map(|i| ir.leaf(Leaf::Input(i))).collect();
        ldlt_solve(ir, m, &f);
        (before..ir.len())
            .map(|k| Nid(k as u32))
            .filter(|&n| matches!(ir.op(n), Op::Mul(..) | Op::Powi(..)) && !ir.is_constant(n))
            .count()
    }

    #[test]
    fn a_dense_varying_matrix_counts_every_product_of_its_factorization() {
        let mut ir = Ir::new();
        let m = matrix(&mut ir, 5, |_, _| false, |_, _| true);
        // Σ_j (n − j) j products: (n³ − n) / 6.
        assert_eq!(ldlt_varying_products(&ir, &m, &ldlt_order(5)), 20);
    }

    #[test]
    fn a_constant_matrix_costs_nothing_per_call() {
        let mut ir = Ir::new();
        let m = matrix(&mut ir, 6, |_, _| false, |_, _| false);
        assert_eq!(ldlt_varying_products(&ir, &m, &ldlt_order(6)), 0);
    }

    #[test]
    fn the_bound_never_exceeds_the_varying_products_built() {
        // Sparse, partly constant patterns of several shapes.
        for seed in 0..40usize {
            let n = 3 + seed % 9;
            let hash = |i: usize, j: usize, s: usize| (i * 31 + j * 17 + seed * 7 + s) % 5;
            let mut ir = Ir::new();
            let m = matrix(
                &mut ir,
                n,
                |i, j| i != j && hash(i, j, 0) < 2,
                |i, j| hash(i, j, 3) < 3,
            );
            let bound = ldlt_varying_products(&ir, &m, &ldlt_order(n));
            let built = varying_products_built(&mut ir, &m);
            assert!(bound <= built, "seed {seed}: bound {bound} > built {built}");
            if seed % 9 == 8 {
                assert!(bound > 0, "seed {seed}: a bound of 0 tests nothing");
            }
        }
    }
}
