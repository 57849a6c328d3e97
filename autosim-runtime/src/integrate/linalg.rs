//! Dense LU factorization with partial pivoting on fixed `[[F; N]; N]`
//! arrays, for the Newton iterations of implicit methods.

use crate::Float;

/// The matrix given to [`LuFactors::factor`] is singular to working
/// precision (or holds NaN or infinity).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SingularMatrix {
    /// The elimination column whose best pivot was (numerically) zero.
    pub column: usize,
}

impl core::fmt::Display for SingularMatrix {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "matrix is singular: no usable pivot in column {}",
            self.column
        )
    }
}

impl core::error::Error for SingularMatrix {}

/// `P·A = L·U` of an `N × N` matrix, with row pivoting, stored in place:
/// the strict lower triangle holds `L` (unit diagonal implied), the upper
/// triangle `U`.
///
/// Use it to solve several systems with one matrix (the Newton stages of an
/// implicit step share theirs); it never allocates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LuFactors<F, const N: usize> {
    lu: [[F; N]; N],
    perm: [usize; N],
}

impl<F: Float, const N: usize> LuFactors<F, N> {
    /// Factors `a`.
    ///
    /// # Errors
    /// [`SingularMatrix`] if a pivot is zero, below `N·ε·max|aᵢⱼ|`, or not
    /// finite.
    pub fn factor(a: &[[F; N]; N]) -> Result<Self, SingularMatrix> {
        let mut f = Self::identity();
        f.refactor(a)?;
        Ok(f)
    }

    /// The factors of the identity matrix: a starting value for a workspace
    /// that [`LuFactors::refactor`] fills later.
    pub fn identity() -> Self {
        let mut lu = [[F::ZERO; N]; N];
        let mut perm = [0usize; N];
        for (i, (row, p)) in lu.iter_mut().zip(perm.iter_mut()).enumerate() {
            row[i] = F::ONE;
            *p = i;
        }
        Self { lu, perm }
    }

    /// Factors `a` into `self`, reusing its storage (no large temporaries on
    /// the stack). On error `self` holds garbage until the next successful
    /// call.
    ///
    /// # Errors
    /// As [`LuFactors::factor`].
    pub fn refactor(&mut self, a: &[[F; N]; N]) -> Result<(), SingularMatrix> {
        let lu = &mut self.lu;
        let perm = &mut self.perm;
        *lu = *a;
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        let mut scale = F::ZERO;
        for row in a.iter() {
            for v in row.iter() {
                if !v.is_finite() {
                    return Err(SingularMatrix { column: 0 });
                }
                scale = scale.max(v.abs());
            }
        }
        let tiny = scale * F::EPSILON * F::from_f64(N as f64);
        for k in 0..N {
            // Partial pivoting: the largest entry of column k on or below the diagonal.
            let mut p = k;
            let mut best = lu[k][k].abs();
            for (i, row) in lu.iter().enumerate().skip(k + 1) {
                if row[k].abs() > best {
                    best = row[k].abs();
                    p = i;
                }
            }
            let usable = best > tiny && best.is_finite();
            if !usable {
                return Err(SingularMatrix { column: k });
            }
            if p != k {
                lu.swap(p, k);
                perm.swap(p, k);
            }
            let pivot_row = lu[k];
            let pivot = pivot_row[k];
            for row in lu.iter_mut().skip(k + 1) {
                let factor = row[k] / pivot;
                row[k] = factor;
                for (v, u) in row.iter_mut().zip(pivot_row.iter()).skip(k + 1) {
                    *v -= factor * *u;
                }
            }
        }
        Ok(())
    }

    /// Solves `A·x = b` in place (`b` becomes `x`).
    pub fn solve(&self, b: &mut [F; N]) {
        let mut y = [F::ZERO; N];
        for (yi, &p) in y.iter_mut().zip(self.perm.iter()) {
            *yi = b[p];
        }
        // Forward substitution with the unit lower triangle.
        for i in 0..N {
            let row = &self.lu[i];
            let mut s = y[i];
            for (l, yj) in row.iter().zip(y.iter()).take(i) {
                s -= *l * *yj;
            }
            y[i] = s;
        }
        // Back substitution with the upper triangle.
        for i in (0..N).rev() {
            let row = &self.lu[i];
            let mut s = y[i];
            for (u, yj) in row.iter().zip(y.iter()).skip(i + 1) {
                s -= *u * *yj;
            }
            y[i] = s / row[i];
        }
        *b = y;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_system_that_needs_pivoting() {
        // Zero in the (0, 0) position forces a row exchange.
        let a = [[0.0, 2.0, 1.0], [1.0, 1.0, 1.0], [2.0, 1.0, 3.0]];
        let x_true = [1.0, -2.0, 3.0];
        let mut b = [0.0; 3];
        for (bi, row) in b.iter_mut().zip(a.iter()) {
            *bi = row.iter().zip(x_true.iter()).map(|(a, x)| a * x).sum();
        }
        let lu = LuFactors::factor(&a).unwrap();
        lu.solve(&mut b);
        for (x, t) in b.iter().zip(x_true.iter()) {
            assert!((x - t).abs() < 1e-14, "{b:?}");
        }
    }

    #[test]
    fn reports_the_singular_column() {
        let a = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [1.0, 0.0, 1.0]];
        assert_eq!(LuFactors::factor(&a), Err(SingularMatrix { column: 2 }));
        let nan = [[f64::NAN, 0.0], [0.0, 1.0]];
        assert!(LuFactors::factor(&nan).is_err());
    }
}
