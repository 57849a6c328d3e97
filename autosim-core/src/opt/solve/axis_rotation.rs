//! `C B Cᵀ` for a rotation `C` about a coordinate axis, by double angles.
//!
//! A joint turning about one of its body's axes (`mech`'s
//! `BodyKinetics::turn`) has a direction cosine
//! matrix with a 1 on that axis and `[[c, −s], [s, c]]` (`c = cos q`,
//! `s = ±sin q`) in the other two. Rotating a 3×3 block with it leaves the
//! axis's own entry alone, turns the axis's row and column as vectors, and
//! acts on the remaining 2×2 part `P` as `R P Rᵀ`. Written in the basis
//! `I, J` (unchanged by the rotation) and `Z = diag(1, −1)`,
//! `X = [[0, 1], [1, 0]]` (turned by the double angle, with
//! `cos 2q = 2c² − 1`, `sin 2q = 2cs`), the 2×2 part costs 11 operations
//! when symmetric and 16 in general, against 21 and 24 as two matrix
//! products; the double-angle terms are shared by every block the joint
//! turns.

use crate::expr::Func;
use crate::opt::ir::{Ir, Nid, Op};

/// Three by three matrices of IR nodes.
pub(crate) type M3 = [[Nid; 3]; 3];

/// A rotation about coordinate axis `k`: `C[i][i] = C[j][j] = c`,
/// `C[j][i] = s`, `C[i][j] = −s`, with `c` and `±s` the cosine and sine of
/// one angle (so `c² + s² = 1`).
pub(crate) struct AxisRotation {
    k: usize,
    i: usize,
    j: usize,
    /// `c` and `s`.
    cos_sin: (Nid, Nid),
    /// `cos 2q`, `cos 2q / 2`, `sin 2q`, `sin 2q / 2`.
    double: [Nid; 4],
}

impl AxisRotation {
    /// The rotation `c` about axis `k`, which the joint turns about (the
    /// matrix is such a rotation: checked in debug builds).
    pub fn about(ir: &mut Ir, c: &M3, k: usize) -> AxisRotation {
        let (i, j) = match k {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let (cos, s) = (c[i][i], c[j][i]);
        let cc = ir.mul(cos, cos);
        let cs = ir.mul(cos, s);
        let half = ir.num(0.5);
        let one = ir.num(1.0);
        let c2_half = ir.sum(vec![cc], vec![half]);
        let c2 = ir.sum(vec![cc, cc], vec![one]);
        let s2 = ir.sum(vec![cs, cs], Vec::new());
        AxisRotation {
            k,
            i,
            j,
            cos_sin: (cos, s),
            double: [c2, c2_half, s2, cs],
        }
    }

    /// `C b Cᵀ`; `symmetric`: `b` is, and so is the result.
    pub fn rotate(&self, ir: &mut Ir, b: &M3, symmetric: bool) -> M3 {
        let (k, i, j) = (self.k, self.i, self.j);
        let [c2, c2_half, s2, s2_half] = self.double;
        let mut out = *b;
        // The axis's row and column turn as vectors.
        let (c, s) = self.cos_sin;
        let turn = |ir: &mut Ir, u: Nid, v: Nid| -> (Nid, Nid) {
            let (cu, sv, su, cv) = (ir.mul(c, u), ir.mul(s, v), ir.mul(s, u), ir.mul(c, v));
            (ir.sum(vec![cu], vec![sv]), ir.sum(vec![su, cv], Vec::new()))
        };
        (out[i][k], out[j][k]) = turn(ir, b[i][k], b[j][k]);
        if symmetric {
            (out[k][i], out[k][j]) = (out[i][k], out[j][k]);
        } else {
            (out[k][i], out[k][j]) = turn(ir, b[k][i], b[k][j]);
        }
        let (p, q, r, t) = (b[i][i], b[i][j], b[j][i], b[j][j]);
        let trace = ir.sum(vec![p, t], Vec::new());
        let diff = ir.sum(vec![p], vec![t]);
        let half = ir.num(0.5);
        let mean = ir.mul(half, trace);
        if symmetric {
            // t' = d cos 2q − y sin 2q, y' = d sin 2q + y cos 2q, d = diff/2.
            let (a, bq) = (ir.mul(diff, c2_half), ir.mul(q, s2));
            let turned = ir.sum(vec![a], vec![bq]);
            let (a, bq) = (ir.mul(diff, s2_half), ir.mul(q, c2));
            out[i][j] = ir.sum(vec![a, bq], Vec::new());
            out[j][i] = out[i][j];
            out[i][i] = ir.sum(vec![mean, turned], Vec::new());
            out[j][j] = ir.sum(vec![mean], vec![turned]);
        } else {
            let sym = ir.sum(vec![q, r], Vec::new());
            let anti = ir.sum(vec![q], vec![r]);
            let anti_half = ir.mul(half, anti);
            let (a, e) = (ir.mul(diff, c2_half), ir.mul(sym, s2_half));
            let z = ir.sum(vec![a], vec![e]);
            let (a, e) = (ir.mul(diff, s2_half), ir.mul(sym, c2_half));
            let x = ir.sum(vec![a, e], Vec::new());
            out[i][i] = ir.sum(vec![mean, z], Vec::new());
            out[j][j] = ir.sum(vec![mean], vec![z]);
            out[i][j] = ir.sum(vec![x, anti_half], Vec::new());
            out[j][i] = ir.sum(vec![x], vec![anti_half]);
        }
        out
    }
}

/// The axis `c` turns about, read from its literal entries (what `mech`
/// says of the joint, checked in debug builds).
pub(crate) fn literal_turn(ir: &Ir, c: &M3) -> Option<usize> {
    [(0, 1, 2), (1, 0, 2), (2, 0, 1)]
        .into_iter()
        .find(|&axes| is_turn(ir, c, axes))
        .map(|(k, _, _)| k)
}

/// Whether `c` is 1 on axis `k`, 0 beside it, and turns the other two
/// axes `i`, `j` by the cosine and sine of one angle (literal entries).
fn is_turn(ir: &Ir, c: &M3, (k, i, j): (usize, usize, usize)) -> bool {
    let zero = |n: Nid| ir.as_num(n) == Some(0.0);
    ir.as_num(c[k][k]) == Some(1.0)
        && [c[k][i], c[k][j], c[i][k], c[j][k]].into_iter().all(zero)
        && c[j][j] == c[i][i]
        && same_angle(ir, c[i][i], c[j][i])
}

/// `cos` is `cos(x)` and `s` is `sin(x)` or `−sin(x)` of the same `x`.
fn same_angle(ir: &Ir, cos: Nid, s: Nid) -> bool {
    let sin = match ir.op(s) {
        Op::Neg(x) => *x,
        _ => s,
    };
    match (ir.op(cos), ir.op(sin)) {
        (Op::Call(Func::Cos, a), Op::Call(Func::Sin, b)) => a == b,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::opt::ir::Leaf;

    /// The value of `n` with state `k` equal to `x[k]`.
    fn eval(ir: &Ir, n: Nid, x: &[f64]) -> f64 {
        let v = |m: &Nid| eval(ir, *m, x);
        match ir.op(n) {
            Op::Num(b) => f64::from_bits(*b),
            Op::Leaf(Leaf::State(k)) => x[*k],
            Op::Sum { pos, neg } => pos.iter().map(v).sum::<f64>() - neg.iter().map(v).sum::<f64>(),
            Op::Mul(a, b) => v(a) * v(b),
            Op::Neg(a) => -v(a),
            Op::Powi(a, 2) => v(a) * v(a),
            Op::Call(Func::Sin, a) => v(&a[0]).sin(),
            Op::Call(Func::Cos, a) => v(&a[0]).cos(),
            other => panic!("not expected here: {other:?}"),
        }
    }

    /// `C b Cᵀ` by double angles equals the matrix product, for rotations
    /// about each axis (both signs of the sine) and general and symmetric
    /// blocks.
    #[test]
    fn double_angles_match_the_matrix_product() {
        let x = [0.7, 0.3, -1.1, 2.0, 0.25, -0.4, 0.9, 1.3, -0.6, 0.45];
        for k in 0..3 {
            for flip in [false, true] {
                let mut ir = Ir::new();
                let q = ir.leaf(Leaf::State(0));
                let (cos, sin) = (ir.call(Func::Cos, vec![q]), ir.call(Func::Sin, vec![q]));
                let s = if flip { ir.neg(sin) } else { sin };
                let (i, j) = [(1, 2), (0, 2), (0, 1)][k];
                let (zero, one) = (ir.num(0.0), ir.num(1.0));
                let mut c = [[zero; 3]; 3];
                c[k][k] = one;
                (c[i][i], c[j][j], c[j][i]) = (cos, cos, s);
                c[i][j] = ir.neg(s);
                let leaf = |ir: &mut Ir, r: usize, col: usize, sym: bool| {
                    let (r, col) = if sym && r > col { (col, r) } else { (r, col) };
                    ir.leaf(Leaf::State(1 + 3 * r + col))
                };
                assert_eq!(literal_turn(&ir, &c), Some(k));
                let rotation = AxisRotation::about(&mut ir, &c, k);
                for symmetric in [false, true] {
                    let b: M3 = std::array::from_fn(|r| {
                        std::array::from_fn(|col| leaf(&mut ir, r, col, symmetric))
                    });
                    let fast = rotation.rotate(&mut ir, &b, symmetric);
                    for r in 0..3 {
                        for col in 0..3 {
                            let want: f64 = (0..3)
                                .flat_map(|a| (0..3).map(move |d| (a, d)))
                                .map(|(a, d)| {
                                    eval(&ir, c[r][a], &x)
                                        * eval(&ir, b[a][d], &x)
                                        * eval(&ir, c[col][d], &x)
                                })
                                .sum();
                            let got = eval(&ir, fast[r][col], &x);
                            assert!(
                                (got - want).abs() < 1e-14,
                                "k {k} flip {flip} ({r},{col}): {got} vs {want}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn a_general_matrix_is_not_an_axis_rotation() {
        let mut ir = Ir::new();
        let m: M3 =
            std::array::from_fn(|r| std::array::from_fn(|c| ir.leaf(Leaf::State(3 * r + c))));
        assert_eq!(literal_turn(&ir, &m), None);
    }
}
