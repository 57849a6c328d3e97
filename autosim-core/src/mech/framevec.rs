//! Vectors and matrices held as components in one frame: the working form
//! of the recursive kinematics and of the composite-body dynamics, where
//! every quantity is kept in its own body's axes and moved one frame at a
//! time (so expressions stay small).

use super::frames::{FrameId, Frames};
use super::vector::Vector;
use crate::expr::{Arena, ExprId};

/// A vector given by its components along the unit vectors of `frame`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fv {
    /// The frame whose axes the components refer to.
    pub frame: FrameId,
    /// Components along the frame's unit vectors 1, 2, 3.
    pub c: [ExprId; 3],
}

/// A 3×3 matrix of expressions (row-major).
pub type Mat3 = [[ExprId; 3]; 3];

impl Fv {
    /// The zero vector in `frame`.
    pub fn zero(arena: &Arena, frame: FrameId) -> Fv {
        Fv {
            frame,
            c: [arena.zero(); 3],
        }
    }

    /// A vector from components.
    pub fn new(frame: FrameId, c: [ExprId; 3]) -> Fv {
        Fv { frame, c }
    }

    /// `true` if all components are zero.
    pub fn is_zero(&self, arena: &Arena) -> bool {
        self.c.iter().all(|x| arena.is_zero(*x))
    }

    /// `self + other` (same frame).
    pub fn add(&self, arena: &mut Arena, other: &Fv) -> Fv {
        debug_assert_eq!(self.frame, other.frame);
        Fv::new(
            self.frame,
            [0, 1, 2].map(|k| arena.add(self.c[k], other.c[k])),
        )
    }

    /// `self - other` (same frame).
    pub fn sub(&self, arena: &mut Arena, other: &Fv) -> Fv {
        debug_assert_eq!(self.frame, other.frame);
        Fv::new(
            self.frame,
            [0, 1, 2].map(|k| arena.sub(self.c[k], other.c[k])),
        )
    }

    /// `s self`.
    pub fn scale(&self, arena: &mut Arena, s: ExprId) -> Fv {
        Fv::new(self.frame, self.c.map(|x| arena.mul(x, s)))
    }

    /// `self · other` (same frame).
    pub fn dot(&self, arena: &mut Arena, other: &Fv) -> ExprId {
        debug_assert_eq!(self.frame, other.frame);
        let t = [0, 1, 2].map(|k| arena.mul(self.c[k], other.c[k]));
        arena.sum(&t)
    }

    /// `self × other` (same frame).
    pub fn cross(&self, arena: &mut Arena, other: &Fv) -> Fv {
        debug_assert_eq!(self.frame, other.frame);
        let (a, b) = (self.c, other.c);
        let comp = |arena: &mut Arena, i: usize, j: usize| {
            let p = arena.mul(a[i], b[j]);
            let q = arena.mul(a[j], b[i]);
            arena.sub(p, q)
        };
        Fv::new(
            self.frame,
            [comp(arena, 1, 2), comp(arena, 2, 0), comp(arena, 0, 1)],
        )
    }

    /// The same vector with components in frame `to`.
    pub fn reexpress(&self, arena: &mut Arena, frames: &mut Frames, to: FrameId) -> Fv {
        if to == self.frame {
            return *self;
        }
        let r = frames.cosine_matrix(arena, to, self.frame);
        Fv::new(to, mat_vec(arena, &r, &self.c))
    }

    /// The basis-free vector.
    pub fn to_vector(&self, arena: &mut Arena, frames: &Frames) -> Vector {
        frames.vector_in(arena, self.frame, self.c)
    }

    /// Components of a basis-free vector in `frame`.
    pub fn from_vector(arena: &mut Arena, frames: &mut Frames, v: &Vector, frame: FrameId) -> Fv {
        Fv::new(frame, frames.express_in(arena, v, frame))
    }
}

/// `m v`.
pub fn mat_vec(arena: &mut Arena, m: &Mat3, v: &[ExprId; 3]) -> [ExprId; 3] {
    [0, 1, 2].map(|i| {
        let t = [0, 1, 2].map(|j| arena.mul(m[i][j], v[j]));
        arena.sum(&t)
    })
}

/// The zero matrix.
pub fn mat_zero(arena: &Arena) -> Mat3 {
    [[arena.zero(); 3]; 3]
}

/// `a + b`.
pub fn mat_add(arena: &mut Arena, a: &Mat3, b: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| arena.add(a[i][j], b[i][j])))
}

/// `r m rᵀ` for a symmetric `m`, computed on the upper triangle and mirrored.
pub fn mat_rotate_symmetric(arena: &mut Arena, r: &Mat3, m: &Mat3) -> Mat3 {
    // t = r m
    let t: Mat3 = [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let p = [0, 1, 2].map(|k| arena.mul(r[i][k], m[k][j]));
            arena.sum(&p)
        })
    });
    let mut out = mat_zero(arena);
    for i in 0..3 {
        for j in i..3 {
            let p = [0, 1, 2].map(|k| arena.mul(t[i][k], r[j][k]));
            let s = arena.sum(&p);
            out[i][j] = s;
            out[j][i] = s;
        }
    }
    out
}

/// The symmetric matrix of `m (r·r) 1 - m r rᵀ` (a point mass `m` at `r`).
pub fn point_inertia(arena: &mut Arena, m: ExprId, r: &[ExprId; 3]) -> Mat3 {
    let sq = r.map(|x| arena.powi(x, 2));
    let mut out = mat_zero(arena);
    for i in 0..3 {
        for j in i..3 {
            let v = if i == j {
                let others: Vec<ExprId> = (0..3).filter(|k| *k != i).map(|k| sq[k]).collect();
                arena.sum(&others)
            } else {
                let p = arena.mul(r[i], r[j]);
                arena.neg(p)
            };
            let v = arena.mul(m, v);
            out[i][j] = v;
            out[j][i] = v;
        }
    }
    out
}

/// The symmetric matrix `2 (r·s) 1 - r sᵀ - s rᵀ` (the cross term of the
/// parallel-axis shift with first moment `s`).
pub fn shift_cross_term(arena: &mut Arena, r: &[ExprId; 3], s: &[ExprId; 3]) -> Mat3 {
    let rs = [0, 1, 2].map(|k| arena.mul(r[k], s[k]));
    let mut out = mat_zero(arena);
    for i in 0..3 {
        for j in i..3 {
            let v = if i == j {
                // 2 (r·s) - 2 r_i s_i = 2 Σ_{k≠i} r_k s_k
                let others: Vec<ExprId> = (0..3).filter(|k| *k != i).map(|k| rs[k]).collect();
                let t = arena.sum(&others);
                arena.scale(crate::expr::Number::int(2), t)
            } else {
                let a = arena.mul(r[i], s[j]);
                let b = arena.mul(s[i], r[j]);
                let t = arena.add(a, b);
                arena.neg(t)
            };
            out[i][j] = v;
            out[j][i] = v;
        }
    }
    out
}
