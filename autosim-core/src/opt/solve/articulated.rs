//! `M u̇ = f` solved in O(n) by the articulated-body recursion
//! (Featherstone's), unrolled in the IR so the optimizer's zero folding,
//! hoisting and naming apply. Kane's forcing `f` enters as each body's
//! own bias force (its applied and velocity-dependent inertia forces,
//! summed into the subtrees by the inward pass, as Featherstone's `p^A`)
//! plus joint forces `τ` for what is not a body's (moving-point terms).
//! Spatial quantities are `[angular; linear]` in each body's axes about
//! its origin.
//!
//! Inward, each body's articulated inertia `I^A` (its own inertia plus its
//! children's, each less what its joint lets move): `U = I^A S`,
//! `D = Sᵀ U`, `W = U D⁻¹`, `I^a = I^A − W Uᵀ`, carried to the parent as
//! `Xᵀ I^a X`. A solve for `τ` goes inward with the bias
//! `p^a = p^A + W (τ − Sᵀ p^A)` and outward with the accelerations
//! `u̇ = D⁻¹ (τ − Sᵀ p^A) − Wᵀ a'`, `a = a' + S u̇` (`a' = X a_parent`).
//! The mass matrix is never formed; each `D`'s pivots are checked as the
//! mass matrix's are.

use crate::opt::ir::{Ir, Nid};
use crate::opt::solve::axis_rotation::{AxisRotation, M3, literal_turn};

/// Spatial vectors `[angular; linear]`.
type V6 = [Nid; 6];
/// Spatial inertias, blocks `[[A, B], [Bᵀ, C]]`.
type M6 = [[Nid; 6]; 6];

/// One body as the recursion reads it (its data lowered to the IR).
pub(crate) struct TreeBody {
    /// Parent's position in the list (`None`: N).
    pub parent: Option<usize>,
    /// `C[i][j] = p_i · b_j`.
    pub rotation: M3,
    /// Origin from the parent's origin, parent axes.
    pub offset: [Nid; 3],
    /// Rigid inertia about the origin, body axes.
    pub inertia: M6,
    /// Speed index and unit motion of each of its speeds.
    pub speeds: Vec<(usize, V6)>,
    /// For each speed, the component of `[ω; v]` its unit motion is the
    /// unit vector of, where it is one (from `mech`'s joint).
    pub unit_axes: Vec<Option<usize>>,
    /// The axis the body turns about relative to its parent, where its
    /// rotation is one turn about an axis the two share.
    pub turn: Option<usize>,
    /// Its bias force (applied plus velocity-dependent inertia forces,
    /// negated), body axes.
    pub bias: V6,
}

/// What the inward pass leaves for solves: per body `W` and the
/// factor of `D`.
struct Joint {
    w: Vec<V6>,
    d: SmallLdlt,
    /// The coordinate axis of each speed's unit motion, where it is one.
    axes: Vec<Option<usize>>,
}

/// The factored recursion: solves `M x = τ` for any `τ` in O(n).
pub struct Articulated {
    bodies: Vec<TreeBody>,
    joints: Vec<Joint>,
    /// Pivots of every `D` with their speed, in elimination order.
    pub pivots: Vec<(Nid, usize)>,
    speeds: usize,
}

impl Articulated {
    /// The inward pass over `bodies` (parent-first order), `n` speeds.
    pub(crate) fn new(ir: &mut Ir, bodies: Vec<TreeBody>, n: usize) -> Articulated {
        let mut ia: Vec<M6> = bodies.iter().map(|b| b.inertia).collect();
        let mut joints: Vec<Option<Joint>> = (0..bodies.len()).map(|_| None).collect();
        let mut pivots = Vec::new();
        for i in (0..bodies.len()).rev() {
            let b = &bodies[i];
            let s: Vec<V6> = b.speeds.iter().map(|(_, s)| *s).collect();
            let u: Vec<V6> = s.iter().map(|sk| mat6_vec(ir, &ia[i], sk)).collect();
            let k = s.len();
            let dm: Vec<Vec<Nid>> = (0..k)
                .map(|a| (0..k).map(|c| dot6(ir, &s[a], &u[c])).collect())
                .collect();
            let d = SmallLdlt::new(ir, &dm);
            for (j, p) in d.pivots.iter().enumerate() {
                pivots.push((*p, b.speeds[j].0));
            }
            // W = U D⁻¹, row by row.
            let mut w: Vec<V6> = vec![[ir.num(0.0); 6]; k];
            for row in 0..6 {
                let rhs: Vec<Nid> = (0..k).map(|c| u[c][row]).collect();
                let x = d.solve(ir, &rhs);
                for c in 0..k {
                    w[c][row] = x[c];
                }
            }
            // Where a unit motion is a coordinate axis `e_a`, `Sᵀ W = 1`
            // gives row `a` of `W` and `I^a S = U − W Sᵀ U = 0` row and
            // column `a` of `I^a`: exact values the algebra would only
            // reach as `x − x D D⁻¹`.
            let axes = b.unit_axes.clone();
            debug_assert!(
                s.iter()
                    .zip(&axes)
                    .all(|(sk, a)| coordinate_axis(ir, sk) == *a),
                "the unit motions are not the coordinate axes the joint says"
            );
            for (c2, axis) in axes.iter().enumerate() {
                if let Some(a) = *axis {
                    for (c, wc) in w.iter_mut().enumerate() {
                        wc[a] = ir.num(if c == c2 { 1.0 } else { 0.0 });
                    }
                }
            }
            let annulled = |x: usize| axes.contains(&Some(x));
            let mut articulated = ia[i];
            for r in 0..6 {
                for c in r..6 {
                    let v = if annulled(r) || annulled(c) {
                        ir.num(0.0)
                    } else {
                        let terms: Vec<Nid> = (0..k).map(|j| ir.mul(w[j][r], u[j][c])).collect();
                        ir.sum(vec![articulated[r][c]], terms)
                    };
                    articulated[r][c] = v;
                    articulated[c][r] = v;
                }
            }
            if let Some(p) = b.parent {
                let moved = inertia_to_parent(ir, &articulated, b);
                for r in 0..6 {
                    for c in r..6 {
                        let v = ir.sum(vec![ia[p][r][c], moved[r][c]], Vec::new());
                        ia[p][r][c] = v;
                        ia[p][c][r] = v;
                    }
                }
            }
            joints[i] = Some(Joint { w, d, axes });
        }
        Articulated {
            joints: joints
                .into_iter()
                .map(|j| j.expect("every body visited"))
                .collect(),
            bodies,
            pivots,
            speeds: n,
        }
    }

    /// `M⁻¹ τ` (`τ` and the result by speed index).
    pub fn solve(&self, ir: &mut Ir, tau: &[Nid]) -> Vec<Nid> {
        let zero = ir.num(0.0);
        self.solve_from(ir, tau, vec![[zero; 6]; self.bodies.len()])
    }

    /// `M⁻¹ f` for `f` the projections of every subtree's bias forces (the
    /// bodies' `bias`, negated) plus `tau`: Kane's forcing, summed once
    /// inside the recursion.
    pub fn solve_biased(&self, ir: &mut Ir, tau: &[Nid]) -> Vec<Nid> {
        let bias = self.bodies.iter().map(|b| b.bias).collect();
        self.solve_from(ir, tau, bias)
    }

    /// The inward and outward passes, each body's bias force starting at
    /// `pa`.
    fn solve_from(&self, ir: &mut Ir, tau: &[Nid], mut pa: Vec<V6>) -> Vec<Nid> {
        let nb = self.bodies.len();
        let zero = ir.num(0.0);
        let mut own: Vec<Vec<Nid>> = vec![Vec::new(); nb];
        for i in (0..nb).rev() {
            let (b, j) = (&self.bodies[i], &self.joints[i]);
            let e: Vec<Nid> = b
                .speeds
                .iter()
                .map(|(k, s)| {
                    let sp = dot6(ir, s, &pa[i]);
                    ir.sum(vec![tau[*k]], vec![sp])
                })
                .collect();
            let mut bias = pa[i];
            for (c, ec) in e.iter().enumerate() {
                for r in 0..6 {
                    let t = ir.mul(j.w[c][r], *ec);
                    bias[r] = ir.sum(vec![bias[r], t], Vec::new());
                }
            }
            // Along a coordinate axis, `Sᵀ p^a = Sᵀ p^A + e = τ` exactly.
            for ((k, _), axis) in b.speeds.iter().zip(&j.axes) {
                if let Some(a) = *axis {
                    bias[a] = tau[*k];
                }
            }
            own[i] = j.d.solve(ir, &e);
            if let Some(p) = b.parent {
                let moved = force_to_parent(ir, &bias, &b.rotation, &b.offset);
                for r in 0..6 {
                    pa[p][r] = ir.sum(vec![pa[p][r], moved[r]], Vec::new());
                }
            }
        }
        let mut acc: Vec<V6> = vec![[zero; 6]; nb];
        let mut out = vec![zero; self.speeds];
        for i in 0..nb {
            let (b, j) = (&self.bodies[i], &self.joints[i]);
            let a_in = match b.parent {
                Some(p) => motion_to_child(ir, &acc[p], &b.rotation, &b.offset),
                None => [zero; 6],
            };
            let mut a = a_in;
            for (c, (k, s)) in b.speeds.iter().enumerate() {
                let wa = dot6(ir, &j.w[c], &a_in);
                let udot = ir.sum(vec![own[i][c]], vec![wa]);
                out[*k] = udot;
                for r in 0..6 {
                    let t = ir.mul(s[r], udot);
                    a[r] = ir.sum(vec![a[r], t], Vec::new());
                }
            }
            acc[i] = a;
        }
        out
    }

    /// Kane's forcing `f` (by speed index) without the mass matrix: every
    /// subtree's bias forces summed inward and projected on the speeds'
    /// unit motions, plus the joint forces `tau`.
    pub fn forcing(&self, ir: &mut Ir, tau: &[Nid]) -> Vec<Nid> {
        let mut force: Vec<V6> = self.bodies.iter().map(|b| b.bias).collect();
        let mut out = tau.to_vec();
        for i in (0..self.bodies.len()).rev() {
            let b = &self.bodies[i];
            for (k, s) in &b.speeds {
                let projected = dot6(ir, s, &force[i]);
                out[*k] = ir.sum(vec![tau[*k]], vec![projected]);
            }
            if let Some(p) = b.parent {
                let moved = force_to_parent(ir, &force[i], &b.rotation, &b.offset);
                for r in 0..6 {
                    force[p][r] = ir.sum(vec![force[p][r], moved[r]], Vec::new());
                }
            }
        }
        out
    }

    /// `M v` (by speed index) without forming `M`: outward accelerations
    /// at rest, inward forces of the rigid inertias, projected on the
    /// speeds' unit motions.
    pub fn times_mass(&self, ir: &mut Ir, v: &[Nid]) -> Vec<Nid> {
        let nb = self.bodies.len();
        let zero = ir.num(0.0);
        let mut acc: Vec<V6> = vec![[zero; 6]; nb];
        for i in 0..nb {
            let b = &self.bodies[i];
            let mut a = match b.parent {
                Some(p) => motion_to_child(ir, &acc[p], &b.rotation, &b.offset),
                None => [zero; 6],
            };
            for (k, s) in &b.speeds {
                for r in 0..6 {
                    let t = ir.mul(s[r], v[*k]);
                    a[r] = ir.sum(vec![a[r], t], Vec::new());
                }
            }
            acc[i] = a;
        }
        let mut force: Vec<V6> = (0..nb)
            .map(|i| mat6_vec(ir, &self.bodies[i].inertia, &acc[i]))
            .collect();
        let mut out = vec![zero; self.speeds];
        for i in (0..nb).rev() {
            let b = &self.bodies[i];
            for (k, s) in &b.speeds {
                out[*k] = dot6(ir, s, &force[i]);
            }
            if let Some(p) = b.parent {
                let moved = force_to_parent(ir, &force[i], &b.rotation, &b.offset);
                for r in 0..6 {
                    force[p][r] = ir.sum(vec![force[p][r], moved[r]], Vec::new());
                }
            }
        }
        out
    }
}

/// A small symmetric positive definite `D = L diag(d) Lᵀ`, unrolled.
struct SmallLdlt {
    l: Vec<Vec<Nid>>,
    d_inv: Vec<Nid>,
    pivots: Vec<Nid>,
}

impl SmallLdlt {
    fn new(ir: &mut Ir, m: &[Vec<Nid>]) -> SmallLdlt {
        let k = m.len();
        let zero = ir.num(0.0);
        let mut l = vec![vec![zero; k]; k];
        let mut d = vec![zero; k];
        let mut d_inv = vec![zero; k];
        for j in 0..k {
            let terms: Vec<Nid> = (0..j)
                .map(|c| {
                    let x = ir.mul(l[j][c], l[j][c]);
                    ir.mul(x, d[c])
                })
                .collect();
            d[j] = ir.sum(vec![m[j][j]], terms);
            let one = ir.num(1.0);
            d_inv[j] = ir.div(one, d[j]);
            for i in j + 1..k {
                let terms: Vec<Nid> = (0..j)
                    .map(|c| {
                        let x = ir.mul(l[i][c], l[j][c]);
                        ir.mul(x, d[c])
                    })
                    .collect();
                let s = ir.sum(vec![m[i][j]], terms);
                l[i][j] = ir.mul(s, d_inv[j]);
            }
        }
        SmallLdlt {
            l,
            d_inv,
            pivots: d,
        }
    }

    fn solve(&self, ir: &mut Ir, b: &[Nid]) -> Vec<Nid> {
        let k = b.len();
        let mut y: Vec<Nid> = Vec::with_capacity(k);
        for i in 0..k {
            let terms: Vec<Nid> = (0..i).map(|c| ir.mul(self.l[i][c], y[c])).collect();
            y.push(ir.sum(vec![b[i]], terms));
        }
        let mut x = vec![ir.num(0.0); k];
        for i in (0..k).rev() {
            let z = ir.mul(y[i], self.d_inv[i]);
            let terms: Vec<Nid> = (i + 1..k).map(|c| ir.mul(self.l[c][i], x[c])).collect();
            x[i] = ir.sum(vec![z], terms);
        }
        x
    }
}

/// `Some(a)` if `s` is the coordinate axis `e_a` (literal ones and
/// zeros; what `mech` says of the joint, checked in debug builds).
fn coordinate_axis(ir: &Ir, s: &V6) -> Option<usize> {
    let mut axis = None;
    for (r, x) in s.iter().enumerate() {
        match ir.as_num(*x) {
            Some(0.0) => {}
            Some(v) if v == 1.0 && axis.is_none() => axis = Some(r),
            _ => return None,
        }
    }
    axis
}

fn dot(ir: &mut Ir, a: &[Nid], b: &[Nid]) -> Nid {
    let terms: Vec<Nid> = a.iter().zip(b).map(|(x, y)| ir.mul(*x, *y)).collect();
    ir.sum(terms, Vec::new())
}

fn dot6(ir: &mut Ir, a: &V6, b: &V6) -> Nid {
    dot(ir, a, b)
}

fn mat6_vec(ir: &mut Ir, m: &M6, v: &V6) -> V6 {
    std::array::from_fn(|r| dot(ir, &m[r], v))
}

/// `C v` (body axes to parent axes).
fn rotate(ir: &mut Ir, c: &M3, v: &[Nid]) -> [Nid; 3] {
    std::array::from_fn(|i| dot(ir, &c[i], v))
}

/// `Cᵀ v` (parent axes to body axes).
fn rotate_back(ir: &mut Ir, c: &M3, v: &[Nid]) -> [Nid; 3] {
    std::array::from_fn(|j| {
        let col = [c[0][j], c[1][j], c[2][j]];
        dot(ir, &col, v)
    })
}

/// `a × b`.
fn cross(ir: &mut Ir, a: &[Nid], b: &[Nid]) -> [Nid; 3] {
    let mut term = |i: usize, j: usize| {
        let x = ir.mul(a[i], b[j]);
        let y = ir.mul(a[j], b[i]);
        ir.sum(vec![x], vec![y])
    };
    [term(1, 2), term(2, 0), term(0, 1)]
}

/// A parent's spatial acceleration in a child's axes at its origin:
/// `[Cᵀ α; Cᵀ (a − r × α)]`.
fn motion_to_child(ir: &mut Ir, m: &V6, c: &M3, r: &[Nid; 3]) -> V6 {
    let rxa = cross(ir, r, &m[..3]);
    let lin: Vec<Nid> = (0..3)
        .map(|i| ir.sum(vec![m[3 + i]], vec![rxa[i]]))
        .collect();
    let w = rotate_back(ir, c, &m[..3]);
    let v = rotate_back(ir, c, &lin);
    [w[0], w[1], w[2], v[0], v[1], v[2]]
}

/// A child's spatial force in its parent's axes about the parent's
/// origin: `[C n + r × C f; C f]`.
fn force_to_parent(ir: &mut Ir, f: &V6, c: &M3, r: &[Nid; 3]) -> V6 {
    let n = rotate(ir, c, &f[..3]);
    let force = rotate(ir, c, &f[3..]);
    let rxf = cross(ir, r, &force);
    let moment: Vec<Nid> = (0..3)
        .map(|i| ir.sum(vec![n[i], rxf[i]], Vec::new()))
        .collect();
    [
        moment[0], moment[1], moment[2], force[0], force[1], force[2],
    ]
}

/// `C b Cᵀ` (a block in body axes to parent axes); `symmetric`: the upper
/// triangle computed, mirrored.
fn rotate_block(ir: &mut Ir, c: &M3, b: &M3, symmetric: bool) -> M3 {
    // T = b Cᵀ, row i: C b_i.
    let t: M3 = std::array::from_fn(|i| rotate(ir, c, &b[i]));
    let mut out = *b;
    for j in 0..3 {
        let col = [t[0][j], t[1][j], t[2][j]];
        for i in 0..3 {
            if symmetric && i > j {
                continue;
            }
            out[i][j] = dot(ir, &c[i], &col);
            if symmetric {
                out[j][i] = out[i][j];
            }
        }
    }
    out
}

fn mul3(ir: &mut Ir, x: &M3, y: &M3) -> M3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let col = [y[0][j], y[1][j], y[2][j]];
            dot(ir, &x[i], &col)
        })
    })
}

/// `Xᵀ I X` for a child's articulated inertia `I`: rotated to the
/// parent's axes (`C A Cᵀ` per block), then moved from the child's origin
/// to the parent's (`A − B r̃ + r̃ Bᵀ − r̃ C r̃`, `B + r̃ C`, `C`).
fn inertia_to_parent(ir: &mut Ir, m: &M6, body: &TreeBody) -> M6 {
    let (c, r) = (&body.rotation, &body.offset);
    let part = |row: usize, col: usize| -> M3 {
        std::array::from_fn(|i| std::array::from_fn(|j| m[row + i][col + j]))
    };
    debug_assert_eq!(
        literal_turn(ir, c),
        body.turn,
        "the rotation is not the turn the joint says"
    );
    let axis = body.turn.map(|k| AxisRotation::about(ir, c, k));
    let turn = |ir: &mut Ir, b: &M3, symmetric: bool| match &axis {
        Some(axis) => axis.rotate(ir, b, symmetric),
        None => rotate_block(ir, c, b, symmetric),
    };
    let a = turn(ir, &part(0, 0), true);
    let b = turn(ir, &part(0, 3), false);
    let cm = turn(ir, &part(3, 3), true);
    let zero = ir.num(0.0);
    let (n1, n2, n3) = (ir.neg(r[0]), ir.neg(r[1]), ir.neg(r[2]));
    let skew: M3 = [[zero, n3, r[1]], [r[2], zero, n1], [n2, r[0], zero]];
    let bt: M3 = std::array::from_fn(|i| std::array::from_fn(|j| b[j][i]));
    let b_r = mul3(ir, &b, &skew);
    let r_bt = mul3(ir, &skew, &bt);
    let r_c = mul3(ir, &skew, &cm);
    let r_c_r = mul3(ir, &r_c, &skew);
    let mut out: M6 = [[zero; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            if j >= i {
                let v = ir.sum(vec![a[i][j], r_bt[i][j]], vec![b_r[i][j], r_c_r[i][j]]);
                out[i][j] = v;
                out[j][i] = v;
                out[3 + i][3 + j] = cm[i][j];
                out[3 + j][3 + i] = cm[i][j];
            }
            let bo = ir.sum(vec![b[i][j], r_c[i][j]], Vec::new());
            out[i][3 + j] = bo;
            out[3 + j][i] = bo;
        }
    }
    out
}
