//! The paper's Table 12 operations (`pos`, `vel`, `rot`), time derivatives
//! of vectors, and partial velocities, all basis-free.

use super::error::ModelError;
use super::framevec::Fv;
use super::joint::Axis;
use super::system::{BodyId, PointId, System};
use super::vector::Vector;
use crate::expr::ExprId;
use rustc_hash::FxHashMap;

impl System {
    /// The chain of bodies from `b` up to N (inclusive of both).
    fn ancestors(&self, b: BodyId) -> Vec<BodyId> {
        let mut out = vec![b];
        let mut cur = b;
        while let Some(p) = self.bodies[cur.index()].parent {
            out.push(p);
            cur = p;
        }
        out
    }

    /// Position of a point relative to the origin of an ancestor body.
    fn position_from(&mut self, ancestor: BodyId, p: PointId) -> Vector {
        let point = self.points[p.index()].clone();
        let frame = self.bodies[point.body.index()].frame;
        let mut acc = self
            .frames
            .vector_in(&mut self.arena, frame, point.coordinates);
        let mut cur = point.body;
        while cur != ancestor {
            let j = self.joint_vector(cur);
            let jv = j.to_vector(&mut self.arena, &self.frames);
            acc = acc.add(&mut self.arena, &jv);
            cur = match self.bodies[cur.index()].parent {
                Some(p) => p,
                None => break,
            };
        }
        acc
    }

    /// The paper's `pos`: the vector from point `p2` to point `p1`
    /// (`r(p1) - r(p2)`). With `p2 = None`, from the origin of N.
    pub fn pos(&mut self, p1: PointId, p2: Option<PointId>) -> Vector {
        let b1 = self.points[p1.index()].body;
        let Some(p2) = p2 else {
            return self.position_from(BodyId::N, p1);
        };
        let b2 = self.points[p2.index()].body;
        let a1 = self.ancestors(b1);
        let a2 = self.ancestors(b2);
        let common = a1
            .iter()
            .find(|b| a2.contains(b))
            .copied()
            .unwrap_or(BodyId::N);
        let r1 = self.position_from(common, p1);
        let r2 = self.position_from(common, p2);
        r1.sub(&mut self.arena, &r2)
    }

    /// The paper's `rot`: the absolute angular velocity of a body.
    pub fn rot(&mut self, b: BodyId) -> Vector {
        let w = self.bodies[b.index()].w;
        w.to_vector(&mut self.arena, &self.frames)
    }

    /// Absolute velocity of a point (Eq. 11): `v(B0) + w × r + d/dt in B of
    /// the point's coordinates`.
    pub fn velocity(&mut self, p: PointId) -> Result<Vector, ModelError> {
        let point = self.points[p.index()].clone();
        let body = self.bodies[point.body.index()].clone();
        let r = Fv::new(body.frame, point.coordinates);
        let mut v = body.w.cross(&mut self.arena, &r);
        if point
            .coordinates
            .iter()
            .any(|c| !self.arena.is_constant(*c))
        {
            let mut rel = [self.arena.zero(); 3];
            for k in 0..3 {
                rel[k] = self.arena.dxdt(point.coordinates[k])?;
            }
            v = v.add(&mut self.arena, &Fv::new(body.frame, rel));
        }
        let v = v.to_vector(&mut self.arena, &self.frames);
        Ok(body.v0.add(&mut self.arena, &v))
    }

    /// Velocity of the material point of `p`'s body where `p` is:
    /// `v(B0) + w × r`, without the motion of `p` in its body (what a
    /// force at `p` acts through).
    pub fn material_velocity(&mut self, p: PointId) -> Vector {
        let point = self.points[p.index()].clone();
        let body = self.bodies[point.body.index()].clone();
        let r = Fv::new(body.frame, point.coordinates);
        let wxr = body.w.cross(&mut self.arena, &r);
        let wxr = wxr.to_vector(&mut self.arena, &self.frames);
        body.v0.add(&mut self.arena, &wxr)
    }

    /// The paper's `vel`: `v(p1) - v(p2)` (with `p2 = None`, absolute).
    pub fn vel(&mut self, p1: PointId, p2: Option<PointId>) -> Result<Vector, ModelError> {
        let v1 = self.velocity(p1)?;
        match p2 {
            None => Ok(v1),
            Some(p2) => {
                let v2 = self.velocity(p2)?;
                Ok(v1.sub(&mut self.arena, &v2))
            }
        }
    }

    /// Time derivative of a vector in N: coefficients differentiated, and
    /// `d/dt u = w × u` for each unit vector (Eq. 5).
    pub fn dxdt_vector(&mut self, v: &Vector) -> Result<Vector, ModelError> {
        let mut acc = Vector::zero();
        for &(u, c) in v.terms() {
            let dc = self.arena.dxdt(c)?;
            let t = Vector::term(&mut self.arena, u, dc);
            acc = acc.add(&mut self.arena, &t);
            let home = self.frames.uv(u).home;
            let w = self.frame_w[home.index()].clone();
            if !w.is_zero() {
                let uv = Vector::term(&mut self.arena, u, c);
                let wxu = self.frames.cross_vec(&mut self.arena, &w, &uv);
                acc = acc.add(&mut self.arena, &wxu);
            }
        }
        Ok(acc)
    }

    /// Coefficient-wise partial derivative of a vector.
    pub fn partial_vector(
        &mut self,
        v: &Vector,
        x: crate::expr::SymId,
    ) -> Result<Vector, ModelError> {
        let mut memo = FxHashMap::default();
        let mut terms = Vec::new();
        for &(u, c) in v.terms() {
            let d = self.arena.partial_memo(c, x, &mut memo)?;
            terms.push((u, d));
        }
        let mut acc = Vector::zero();
        for (u, d) in terms {
            let t = Vector::term(&mut self.arena, u, d);
            acc = acc.add(&mut self.arena, &t);
        }
        Ok(acc)
    }

    /// The partial velocity of a point with respect to generalized speed
    /// `k` (0-based): `∂v/∂u_k`.
    pub fn partial_velocity(&mut self, p: PointId, k: usize) -> Result<Vector, ModelError> {
        let v = self.velocity(p)?;
        let u = self.coordinates[k].u;
        self.partial_vector(&v, u)
    }

    /// The partial angular velocity of a body with respect to speed `k`.
    pub fn partial_angular_velocity(&mut self, b: BodyId, k: usize) -> Result<Vector, ModelError> {
        let w = self.rot(b);
        let u = self.coordinates[k].u;
        self.partial_vector(&w, u)
    }

    /// The direction-cosine matrix `C_ij = b_i · a_j` of body `b` relative to
    /// body `a` (the paper's Eq. 7, `cos-matrix` when `a` is the parent).
    pub fn cosine_matrix(&mut self, b: BodyId, a: BodyId) -> [[ExprId; 3]; 3] {
        let fb = self.bodies[b.index()].frame;
        let fa = self.bodies[a.index()].frame;
        self.frames.cosine_matrix(&mut self.arena, fb, fa)
    }

    /// The paper's `convert-coordinates`: components `coordinates` along the
    /// axes of body `from` converted to components along the axes of `to`.
    pub fn convert_coordinates(
        &mut self,
        coordinates: [ExprId; 3],
        from: BodyId,
        to: BodyId,
    ) -> [ExprId; 3] {
        let ff = self.bodies[from.index()].frame;
        let ft = self.bodies[to.index()].frame;
        Fv::new(ff, coordinates)
            .reexpress(&mut self.arena, &mut self.frames, ft)
            .c
    }

    /// A unit vector of a body.
    pub fn unit_vector(&mut self, b: BodyId, axis: Axis) -> Vector {
        let f = self.bodies[b.index()].frame;
        let u = self.frames.frame(f).triad[axis.index()];
        Vector::uv(&mut self.arena, u)
    }
}
