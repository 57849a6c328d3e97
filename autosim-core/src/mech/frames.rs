//! Reference frames and unit vectors, with memoized dot and cross products
//! that climb the frame tree (the paper's Eqs. 4 and 6-10).
//!
//! Every frame but N is its parent rotated about one of the parent's axes; a
//! body with three rotations owns a chain of three such frames. The axis of
//! rotation is shared: a frame rotated about `a3` has unit vectors
//! `(b1, b2, a3)`, as in the paper's Table 8 (`c1, c2, b3`).

use super::joint::Axis;
use super::vector::Vector;
use crate::expr::{Arena, ExprId};
use rustc_hash::FxHashMap;

crate::ids::id_type!(
    /// A reference frame; `FrameId::N` is the inertial frame.
    FrameId,
    "frame table"
);

impl FrameId {
    /// The inertial frame N.
    pub const N: FrameId = FrameId(0);
}

crate::ids::id_type!(
    /// A unit vector fixed in some frame.
    UvId,
    "unit-vector table"
);

/// A reference frame.
#[derive(Clone, Debug)]
pub struct Frame {
    /// Name (the body's name, or `B'`/`B''` for intermediate frames).
    pub name: String,
    /// The frame it is rotated from (`None` for N).
    pub parent: Option<FrameId>,
    /// Number of rotations between N and this frame.
    pub depth: u32,
    /// The three unit vectors, in axis order.
    pub triad: [UvId; 3],
    /// Rotation relative to the parent: the axis and the angle.
    pub rotation: Option<(Axis, ExprId)>,
}

/// A unit vector.
#[derive(Clone, Debug)]
pub struct Uv {
    /// Name, e.g. `b1`.
    pub name: String,
    /// The frame that introduced it.
    pub home: FrameId,
    /// Axis index within that frame (0-based).
    pub axis: usize,
    /// The unit vector in terms of the home frame's parent's unit vectors.
    pub in_parent: Option<Vec<(UvId, ExprId)>>,
}

/// The frame tree with its unit vectors and product tables.
#[derive(Clone, Debug)]
pub struct Frames {
    frames: Vec<Frame>,
    uvs: Vec<Uv>,
    dot_memo: FxHashMap<(UvId, UvId), ExprId>,
    cross_memo: FxHashMap<(UvId, UvId), Vector>,
}

impl Frames {
    /// The tree with only the inertial frame N (unit vectors n1, n2, n3).
    pub fn new() -> Frames {
        let mut f = Frames {
            frames: Vec::new(),
            uvs: Vec::new(),
            dot_memo: FxHashMap::default(),
            cross_memo: FxHashMap::default(),
        };
        let triad = [0, 1, 2].map(|k| {
            f.uvs.push(Uv {
                name: format!("n{}", k + 1),
                home: FrameId::N,
                axis: k,
                in_parent: None,
            });
            UvId(k as u32)
        });
        f.frames.push(Frame {
            name: "N".to_string(),
            parent: None,
            depth: 0,
            triad,
            rotation: None,
        });
        f
    }

    /// A frame.
    pub fn frame(&self, id: FrameId) -> &Frame {
        &self.frames[id.index()]
    }

    /// A unit vector.
    pub fn uv(&self, id: UvId) -> &Uv {
        &self.uvs[id.index()]
    }

    /// Number of frames.
    pub fn len(&self) -> usize {
        self.frames.len()
    }

    /// Always false: N exists.
    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    /// Adds a frame rotated from `parent` by `angle` about the parent's axis
    /// `axis`. `uv_prefix` names the new unit vectors
    /// (`prefix1`...).
    pub fn add_rotated(
        &mut self,
        arena: &mut Arena,
        parent: FrameId,
        axis: Axis,
        angle: ExprId,
        name: &str,
        uv_prefix: &str,
    ) -> FrameId {
        let p = self.frames[parent.index()].triad;
        let (i, j) = axis.others();
        let (i, j) = (i.index(), j.index());
        let s = arena.sin(angle);
        let c = arena.cos(angle);
        let ms = arena.neg(s);
        // b_i = c a_i + s a_j ;  b_j = -s a_i + c a_j
        let new_axes = vec![
            (i, vec![(p[i], c), (p[j], s)]),
            (j, vec![(p[i], ms), (p[j], c)]),
        ];
        self.add_child(parent, (name, uv_prefix), Some((axis, angle)), new_axes)
    }

    /// The axis `b` is rotated about from `a`, where `b` is one exact
    /// rotation about an axis of `a` (`add_rotated` by an angle that is
    /// not small: a small angle's cosine and sine are truncated to 1 and
    /// the angle).
    pub fn turn_axis(&self, arena: &Arena, a: FrameId, b: FrameId) -> Option<Axis> {
        let frame = &self.frames[b.index()];
        let (axis, angle) = frame.rotation?;
        (frame.parent == Some(a) && arena.order(angle) == 0).then_some(axis)
    }

    /// Adds a frame oriented by a general direction-cosine matrix relative
    /// to `parent`: `c[i][j] = b_i · a_j` (all three unit vectors new).
    pub fn add_general(
        &mut self,
        arena: &mut Arena,
        parent: FrameId,
        c: [[ExprId; 3]; 3],
        name: &str,
        uv_prefix: &str,
    ) -> FrameId {
        let p = self.frames[parent.index()].triad;
        let new_axes = c
            .iter()
            .enumerate()
            .map(|(i, row)| {
                let parts = (0..3)
                    .filter(|j| !arena.is_zero(row[*j]))
                    .map(|j| (p[j], row[j]))
                    .collect();
                (i, parts)
            })
            .collect();
        self.add_child(parent, (name, uv_prefix), None, new_axes)
    }

    /// Adds a frame under `parent` named `name`, with a new unit vector
    /// (`uv_prefix` and its axis number) for each of `new_axes`, given in
    /// the parent's unit vectors; the other axes are the parent's.
    fn add_child(
        &mut self,
        parent: FrameId,
        (name, uv_prefix): (&str, &str),
        rotation: Option<(Axis, ExprId)>,
        new_axes: Vec<(usize, Vec<(UvId, ExprId)>)>,
    ) -> FrameId {
        let id = FrameId(self.frames.len() as u32);
        let p = &self.frames[parent.index()];
        let (mut triad, depth) = (p.triad, p.depth + 1);
        for (axis, parts) in new_axes {
            triad[axis] = UvId(self.uvs.len() as u32);
            self.uvs.push(Uv {
                name: format!("{uv_prefix}{}", axis + 1),
                home: id,
                axis,
                in_parent: Some(parts),
            });
        }
        self.frames.push(Frame {
            name: name.to_string(),
            parent: Some(parent),
            depth,
            triad,
            rotation,
        });
        id
    }

    fn home_depth(&self, u: UvId) -> u32 {
        self.frames[self.uvs[u.index()].home.index()].depth
    }

    /// Orders a pair so the first has the deeper home frame.
    fn deeper_first(&self, u: UvId, v: UvId) -> (UvId, UvId) {
        let (du, dv) = (self.home_depth(u), self.home_depth(v));
        if du > dv || (du == dv && u > v) {
            (u, v)
        } else {
            (v, u)
        }
    }

    /// Position of `v` in the triad of `u`'s home frame, if it is there.
    fn in_home_triad(&self, u: UvId, v: UvId) -> Option<usize> {
        let home = self.uvs[u.index()].home;
        self.frames[home.index()].triad.iter().position(|t| *t == v)
    }

    /// `u · v` for unit vectors.
    pub fn dot(&mut self, arena: &mut Arena, u: UvId, v: UvId) -> ExprId {
        if u == v {
            return arena.one();
        }
        let key = if u < v { (u, v) } else { (v, u) };
        if let Some(r) = self.dot_memo.get(&key) {
            return *r;
        }
        let (deep, other) = self.deeper_first(u, v);
        let r = if self.in_home_triad(deep, other).is_some() {
            arena.zero()
        } else {
            match self.uvs[deep.index()].in_parent.clone() {
                Some(parts) => {
                    let mut terms = Vec::with_capacity(2);
                    for (a, coef) in parts {
                        let d = self.dot(arena, a, other);
                        terms.push(arena.mul(coef, d));
                    }
                    arena.sum(&terms)
                }
                // Both in N: distinct axes.
                None => arena.zero(),
            }
        };
        self.dot_memo.insert(key, r);
        r
    }

    /// `u × v` for unit vectors.
    pub fn cross(&mut self, arena: &mut Arena, u: UvId, v: UvId) -> Vector {
        if u == v {
            return Vector::zero();
        }
        if u > v {
            let r = self.cross(arena, v, u);
            return r.neg(arena);
        }
        if let Some(r) = self.cross_memo.get(&(u, v)) {
            return r.clone();
        }
        let (deep, other) = self.deeper_first(u, v);
        let r = if let Some(pos_other) = self.in_home_triad(deep, other) {
            let home = self.uvs[deep.index()].home;
            let triad = self.frames[home.index()].triad;
            let pos_u = triad.iter().position(|t| *t == u).unwrap_or(0);
            let pos_v = if u == deep {
                pos_other
            } else {
                triad.iter().position(|t| *t == v).unwrap_or(0)
            };
            let w = triad[3 - pos_u - pos_v];
            if (pos_u + 1) % 3 == pos_v {
                Vector::uv(arena, w)
            } else {
                Vector::uv(arena, w).neg(arena)
            }
        } else {
            match self.uvs[deep.index()].in_parent.clone() {
                Some(parts) => {
                    let mut acc = Vector::zero();
                    for (a, coef) in parts {
                        let c = if deep == u {
                            self.cross(arena, a, other)
                        } else {
                            self.cross(arena, other, a)
                        };
                        let scaled = c.scale(arena, coef);
                        acc = acc.add(arena, &scaled);
                    }
                    acc
                }
                None => Vector::zero(),
            }
        };
        self.cross_memo.insert((u, v), r.clone());
        r
    }

    /// `a · b` for vectors.
    pub fn dot_vec(&mut self, arena: &mut Arena, a: &Vector, b: &Vector) -> ExprId {
        let mut terms = Vec::with_capacity(a.terms().len() * b.terms().len());
        for &(u, cu) in a.terms() {
            for &(v, cv) in b.terms() {
                let d = self.dot(arena, u, v);
                if !arena.is_zero(d) {
                    terms.push(arena.product(&[cu, cv, d]));
                }
            }
        }
        arena.sum(&terms)
    }

    /// `a × b` for vectors.
    pub fn cross_vec(&mut self, arena: &mut Arena, a: &Vector, b: &Vector) -> Vector {
        let mut acc = Vector::zero();
        for &(u, cu) in a.terms() {
            for &(v, cv) in b.terms() {
                let c = self.cross(arena, u, v);
                if c.is_zero() {
                    continue;
                }
                let k = arena.mul(cu, cv);
                let scaled = c.scale(arena, k);
                acc = acc.add(arena, &scaled);
            }
        }
        acc
    }

    /// The components of `v` along the unit vectors of `frame`.
    pub fn express_in(&mut self, arena: &mut Arena, v: &Vector, frame: FrameId) -> [ExprId; 3] {
        let triad = self.frames[frame.index()].triad;
        triad.map(|t| {
            let tv = Vector::uv(arena, t);
            self.dot_vec(arena, v, &tv)
        })
    }

    /// The vector with components `c` along the unit vectors of `frame`.
    pub fn vector_in(&self, arena: &mut Arena, frame: FrameId, c: [ExprId; 3]) -> Vector {
        let triad = self.frames[frame.index()].triad;
        let mut v = Vector::zero();
        for k in 0..3 {
            let t = Vector::uv(arena, triad[k]).scale(arena, c[k]);
            v = v.add(arena, &t);
        }
        v
    }

    /// Direction cosine matrix `C_ij = a_i · b_j` between two frames (the
    /// paper's Eq. 7 with `a` the first frame).
    pub fn cosine_matrix(&mut self, arena: &mut Arena, a: FrameId, b: FrameId) -> [[ExprId; 3]; 3] {
        let ta = self.frames[a.index()].triad;
        let tb = self.frames[b.index()].triad;
        ta.map(|u| tb.map(|v| self.dot(arena, u, v)))
    }
}

impl Default for Frames {
    fn default() -> Self {
        Frames::new()
    }
}

impl Frames {
    /// `v · D` for a vector and a dyadic.
    pub fn dot_vec_dyadic(
        &mut self,
        arena: &mut Arena,
        v: &Vector,
        d: &super::vector::Dyadic,
    ) -> Vector {
        self.dyadic_product(arena, d, v, true)
    }

    /// `D · v` for a dyadic and a vector.
    pub fn dot_dyadic_vec(
        &mut self,
        arena: &mut Arena,
        d: &super::vector::Dyadic,
        v: &Vector,
    ) -> Vector {
        self.dyadic_product(arena, d, v, false)
    }

    /// `v · D` (`vector_first`) or `D · v`: each term `c l r` dots `v`
    /// into `l` (or `r`) and keeps the other unit vector.
    fn dyadic_product(
        &mut self,
        arena: &mut Arena,
        d: &super::vector::Dyadic,
        v: &Vector,
        vector_first: bool,
    ) -> Vector {
        let mut acc = Vector::zero();
        for &((l, r), c) in d.terms() {
            let (dotted, kept) = if vector_first { (l, r) } else { (r, l) };
            let u = Vector::uv(arena, dotted);
            let k = match vector_first {
                true => self.dot_vec(arena, v, &u),
                false => self.dot_vec(arena, &u, v),
            };
            if arena.is_zero(k) {
                continue;
            }
            let k = arena.mul(k, c);
            let t = Vector::term(arena, kept, k);
            acc = acc.add(arena, &t);
        }
        acc
    }
}
