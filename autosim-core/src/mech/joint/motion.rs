//! What a joint's degrees of freedom do to its body, for the dynamics: the
//! unit motion of each speed (its partial angular and linear velocity),
//! the relative velocity of the joint, and the vector across it.

use super::DofKind;
use super::translation::joint_offset;
use crate::expr::ExprId;
use crate::mech::framevec::Fv;
use crate::mech::system::{BodyId, System};

/// A unit motion of one speed: angular velocity and velocity of the body's
/// origin at unit rate of the speed, in body axes.
#[derive(Clone, Copy, Debug)]
pub struct UnitMotion {
    /// Angular velocity.
    pub w: Fv,
    /// Velocity of the origin.
    pub v: Fv,
    /// Where the unit motion is a unit vector of the body's axes, its
    /// component in `[ω; v]` (0 to 5): a rotation about a body axis (the
    /// joint's `DofKind::Rotation`), or a translation or rotation along a
    /// direction that is a body axis.
    pub axis: Option<usize>,
}

impl System {
    /// The unit motion of speed `k`.
    pub(crate) fn unit_motion(&mut self, k: usize) -> UnitMotion {
        let c = self.coordinates[k].clone();
        let body = self.bodies[c.body.index()].clone();
        let frame = body.frame;
        let zero = Fv::zero(&self.arena, frame);
        match c.kind {
            DofKind::Translation { direction } => {
                let pf = self.bodies[body.parent.unwrap_or(BodyId::N).index()].frame;
                let v = Fv::new(pf, direction).reexpress(&mut self.arena, &mut self.frames, frame);
                let axis = self.unit_component(&v.c).map(|a| 3 + a);
                UnitMotion { w: zero, v, axis }
            }
            DofKind::Rotation { axis } => {
                let mut e = zero;
                e.c[axis.index()] = self.arena.one();
                UnitMotion {
                    w: e,
                    v: zero,
                    axis: Some(axis.index()),
                }
            }
            DofKind::RotationAbout { direction } => UnitMotion {
                w: Fv::new(frame, direction),
                v: zero,
                axis: self.unit_component(&direction),
            },
        }
    }

    /// The axis `a` if the components `c` are exactly the unit vector `e_a`.
    fn unit_component(&self, c: &[ExprId; 3]) -> Option<usize> {
        let one = self.arena.one();
        let a = c.iter().position(|x| *x == one)?;
        c.iter()
            .enumerate()
            .all(|(i, x)| i == a || self.arena.is_zero(*x))
            .then_some(a)
    }

    /// The velocity of body `b`'s origin relative to its parent (parent
    /// axes) and its angular velocity relative to the parent (body axes).
    pub(crate) fn relative_velocity(&mut self, b: BodyId) -> (Fv, Fv) {
        let body = self.bodies[b.index()].clone();
        let pf = self.bodies[body.parent.unwrap_or(BodyId::N).index()].frame;
        let mut v_rel = Fv::zero(&self.arena, pf);
        let mut w_rel = Fv::zero(&self.arena, body.frame);
        for &k in &body.coordinates {
            let c = self.coordinates[k].clone();
            let u = self.arena.sym(c.u);
            match c.kind {
                DofKind::Translation { direction } => {
                    let t = Fv::new(pf, direction).scale(&mut self.arena, u);
                    v_rel = v_rel.add(&mut self.arena, &t);
                }
                DofKind::Rotation { axis } => w_rel.c[axis.index()] = u,
                DofKind::RotationAbout { direction } => {
                    let t = Fv::new(body.frame, direction).scale(&mut self.arena, u);
                    w_rel = w_rel.add(&mut self.arena, &t);
                }
            }
        }
        (v_rel, w_rel)
    }

    /// The vector from a body's parent's origin to the body's origin, in
    /// the parent's axes (joint point plus translations).
    pub(crate) fn joint_vector(&mut self, b: BodyId) -> Fv {
        let body = self.bodies[b.index()].clone();
        let parent = body.parent.unwrap_or(BodyId::N);
        let pf = self.bodies[parent.index()].frame;
        let mut directions = Vec::new();
        let mut qs = Vec::new();
        for &c in &body.coordinates {
            if let DofKind::Translation { direction } = self.coordinates[c].kind {
                directions.push(direction);
                qs.push(self.coordinates[c].q);
            }
        }
        joint_offset(&mut self.arena, pf, &body.joint_point, &directions, &qs)
    }
}
