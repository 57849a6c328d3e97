//! What engineers read off a model besides its motion: kinetic and
//! gravitational potential energy, linear and angular momentum, and the
//! power of a load, each of a set of bodies (all but N when none is
//! named), as basis-free expressions of the state.

use super::error::ModelError;
use super::framevec::{Fv, mat_vec};
use super::system::{BodyId, PointId, System};
use super::vector::Vector;
use crate::expr::ExprId;

impl System {
    /// Every body but N.
    pub fn moving_bodies(&self) -> Vec<BodyId> {
        (1..self.bodies.len()).map(|b| BodyId(b as u32)).collect()
    }

    /// The kinetic energy of all bodies: `Σ ½ m v*·v* + ½ w·I·w`.
    pub fn kinetic_energy(&mut self) -> ExprId {
        let all = self.moving_bodies();
        self.kinetic_energy_of(&all)
    }

    /// The kinetic energy of `bodies`: `Σ ½ m v*·v* + ½ w·I·w`, with `v*`
    /// the velocity of the mass center and `I` the inertia about it.
    pub fn kinetic_energy_of(&mut self, bodies: &[BodyId]) -> ExprId {
        let mut terms = Vec::new();
        for &b in bodies {
            let body = self.bodies[b.index()].clone();
            if b == BodyId::N {
                continue;
            }
            let v = self.cm_velocity(b);
            let vv = self.frames.dot_vec(&mut self.arena, &v, &v);
            let iw = Fv::new(
                body.frame,
                mat_vec(&mut self.arena, &body.inertia, &body.w.c),
            );
            let wiw = body.w.dot(&mut self.arena, &iw);
            let mv = self.arena.mul(body.mass, vv);
            let t = self.arena.add(mv, wiw);
            let half = self.arena.rational(1, 2);
            terms.push(self.arena.mul(half, t));
        }
        self.arena.sum(&terms)
    }

    /// The velocity of body `b`'s mass center in N (basis-free, like the
    /// body's origin velocity it adds to).
    fn cm_velocity(&mut self, b: BodyId) -> Vector {
        let body = self.bodies[b.index()].clone();
        let c = Fv::new(body.frame, body.cm);
        let wxc = body.w.cross(&mut self.arena, &c);
        let wxc = wxc.to_vector(&mut self.arena, &self.frames);
        body.v0.add(&mut self.arena, &wxc)
    }

    /// The gravitational potential energy of `bodies`, zero with every
    /// mass center at N's origin: `−Σ m g·r*` (`g` the model's gravity,
    /// `r*` the position of the mass center from N's origin); 0 without
    /// gravity.
    pub fn gravitational_energy(&mut self, bodies: &[BodyId]) -> ExprId {
        let Some(g) = self.gravity.clone() else {
            return self.arena.zero();
        };
        let mut terms = Vec::new();
        for &b in bodies {
            if b == BodyId::N {
                continue;
            }
            let body = self.bodies[b.index()].clone();
            let r = self.pos(body.cm_point, None);
            let gr = self.frames.dot_vec(&mut self.arena, &g, &r);
            let m = self.arena.neg(body.mass);
            terms.push(self.arena.mul(m, gr));
        }
        self.arena.sum(&terms)
    }

    /// The linear momentum of `bodies`: `Σ m v*`.
    pub fn momentum(&mut self, bodies: &[BodyId]) -> Vector {
        let mut p = Vector::zero();
        for &b in bodies {
            if b == BodyId::N {
                continue;
            }
            let mass = self.bodies[b.index()].mass;
            let v = self.cm_velocity(b).scale(&mut self.arena, mass);
            p = p.add(&mut self.arena, &v);
        }
        p
    }

    /// The angular momentum of `bodies` about point `about`:
    /// `Σ I·w + r × m v*`, with `r` the position of the mass center from
    /// `about` and `v*` its velocity in N.
    pub fn angular_momentum(&mut self, about: PointId, bodies: &[BodyId]) -> Vector {
        let mut h = Vector::zero();
        for &b in bodies {
            if b == BodyId::N {
                continue;
            }
            let body = self.bodies[b.index()].clone();
            let iw = Fv::new(
                body.frame,
                mat_vec(&mut self.arena, &body.inertia, &body.w.c),
            );
            let iw = iw.to_vector(&mut self.arena, &self.frames);
            let mv = self.cm_velocity(b).scale(&mut self.arena, body.mass);
            let r = self.pos(body.cm_point, Some(about));
            let rxmv = self.frames.cross_vec(&mut self.arena, &r, &mv);
            h = h.add(&mut self.arena, &iw).add(&mut self.arena, &rxmv);
        }
        h
    }

    /// The power of the force or moment named `name`: `F·v(P) − F·v(Q)`
    /// for a force `F` on point `P` with its reaction on `Q`, `M·w(A) −
    /// M·w(B)` for a moment on body `A` with its reaction on `B` (the
    /// reaction's term only when it has one); `None` when no force or
    /// moment has that name.
    pub fn power_of(&mut self, name: &str) -> Option<Result<ExprId, ModelError>> {
        if let Some(f) = self.forces.iter().find(|f| f.name == name).cloned() {
            return Some(self.force_power(&f.vector, f.at, f.reaction));
        }
        let m = self.moments.iter().find(|m| m.name == name).cloned()?;
        let w = self.rot(m.at);
        let mut p = self.frames.dot_vec(&mut self.arena, &m.vector, &w);
        if let Some(c) = m.reaction {
            let w = self.rot(c);
            let q = self.frames.dot_vec(&mut self.arena, &m.vector, &w);
            p = self.arena.sub(p, q);
        }
        Some(Ok(p))
    }

    fn force_power(
        &mut self,
        f: &Vector,
        at: PointId,
        reaction: Option<PointId>,
    ) -> Result<ExprId, ModelError> {
        let v = self.vel(at, reaction)?;
        Ok(self.frames.dot_vec(&mut self.arena, f, &v))
    }
}
