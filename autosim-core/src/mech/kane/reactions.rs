//! Joint reactions by a Newton–Euler pass from the leaves: each body's
//! applied plus inertia forces with the complete accelerations (those of
//! the composite-body form at du/dt = 0 plus each speed's unit motion
//! times its rate), summed into the subtrees as `subtrees` sums them.
//!
//! Why this and not Kane's method with auxiliary speeds: the subtree
//! resultants are what the composite-body form already builds, so a
//! reaction costs one more inward sum of O(1)-sized terms per body, all
//! six components at once, with no new partial velocities; auxiliary
//! speeds would add six speeds per joint asked for and re-derive the
//! partial velocities of its subtree.
//!
//! The joint holds the subtree of `B` in equilibrium with everything else
//! that acts on it: the force and moment (about `B`'s origin) that the
//! parent exerts on `B` through the joint are minus the subtree's applied
//! plus inertia forces. The model's own forces and moments (a joint
//! spring, a motor) are applied loads, so the reaction is what the joint
//! itself carries: zero along its free directions unless a motion
//! prescribes them (then the force that enforces the motion).

use super::recursion::{Accelerations, Resultants};
use crate::expr::ExprId;
use crate::mech::constraint::ConstraintLoad;
use crate::mech::framevec::Fv;
use crate::mech::system::{BodyId, System};
use crate::mech::vector::Vector;

/// The load a joint transmits from the parent to its body: the force and
/// the moment about the body's origin.
#[derive(Clone, Debug)]
pub struct JointReaction {
    /// The force.
    pub force: Vector,
    /// The moment about the body's origin.
    pub moment: Vector,
}

impl System {
    /// The reaction of every body's joint (index by body; N's is zero),
    /// using the symbols of the speeds' rates (`du/dt`) for the
    /// accelerations.
    pub fn joint_reactions(&mut self) -> Vec<JointReaction> {
        self.joint_reactions_with(&ConstraintLoad::default())
    }

    /// The reactions with these forces and moments added to the applied
    /// loads: the loads the constraints carry (each constraint's load
    /// times its multiplier).
    pub fn joint_reactions_with(&mut self, extra: &ConstraintLoad) -> Vec<JointReaction> {
        let mut loads = self.applied_loads();
        for (p, f) in &extra.forces {
            self.add_point_force(&mut loads.force, &mut loads.moment, *p, f, false);
        }
        for (b, m) in &extra.moments {
            let b = b.index();
            loads.moment[b] = loads.moment[b].add(&mut self.arena, m);
        }
        let acc = self.accelerations();
        let acc = self.with_rates(acc);
        let mut res = self.body_resultants(&loads, &acc);
        for b in (1..self.bodies.len()).rev() {
            for ch in self.bodies[b].children.clone() {
                let _ = self.carry_resultant(BodyId(b as u32), ch, &mut res);
            }
        }
        let m1 = self.arena.int(-1);
        (0..self.bodies.len())
            .map(|b| {
                let f = res.force[b].scale(&mut self.arena, m1);
                let m = res.moment[b].scale(&mut self.arena, m1);
                JointReaction {
                    force: f.to_vector(&mut self.arena, &self.frames),
                    moment: m.to_vector(&mut self.arena, &self.frames),
                }
            })
            .collect()
    }

    /// The accelerations at du/dt = 0 plus each speed's unit motion times
    /// its rate, outward.
    fn with_rates(&mut self, acc: Accelerations) -> Accelerations {
        let nb = self.bodies.len();
        let zero = |s: &Self, b: usize| Fv::zero(&s.arena, s.bodies[b].frame);
        let mut d_alpha: Vec<Fv> = vec![zero(self, 0)];
        let mut d_a0: Vec<Fv> = vec![zero(self, 0)];
        for b in 1..nb {
            let body = self.bodies[b].clone();
            let a = body.parent.unwrap_or(BodyId::N).index();
            let r = self.joint_vector(BodyId(b as u32));
            let axr = d_alpha[a].cross(&mut self.arena, &r);
            let lin = d_a0[a].add(&mut self.arena, &axr);
            let mut lin = lin.reexpress(&mut self.arena, &mut self.frames, body.frame);
            let mut ang = d_alpha[a].reexpress(&mut self.arena, &mut self.frames, body.frame);
            for &k in &body.coordinates {
                let um = self.unit_motion(k);
                let du: ExprId = self.arena.sym(self.coordinates[k].du);
                let w = um.w.scale(&mut self.arena, du);
                let v = um.v.scale(&mut self.arena, du);
                ang = ang.add(&mut self.arena, &w);
                lin = lin.add(&mut self.arena, &v);
            }
            d_alpha.push(ang);
            d_a0.push(lin);
        }
        let mut alpha = Vec::with_capacity(nb);
        let mut a0 = Vec::with_capacity(nb);
        for b in 0..nb {
            alpha.push(acc.alpha[b].add(&mut self.arena, &d_alpha[b]));
            a0.push(acc.a0[b].add(&mut self.arena, &d_a0[b]));
        }
        Accelerations { alpha, a0 }
    }

    /// Adds the resultants of child `ch`'s subtree to those of its parent
    /// `b` (moved to `b`'s origin and axes); returns the joint vector of
    /// `ch` (from `b`'s origin, `b`'s axes).
    pub(super) fn carry_resultant(&mut self, b: BodyId, ch: BodyId, res: &mut Resultants) -> Fv {
        let (b, ci) = (b.index(), ch.index());
        let fr = self.bodies[b].frame;
        let r = self.joint_vector(ch);
        let rc = res.force[ci].reexpress(&mut self.arena, &mut self.frames, fr);
        let hc = res.moment[ci].reexpress(&mut self.arena, &mut self.frames, fr);
        let rxr = r.cross(&mut self.arena, &rc);
        res.force[b] = res.force[b].add(&mut self.arena, &rc);
        let h = hc.add(&mut self.arena, &rxr);
        res.moment[b] = res.moment[b].add(&mut self.arena, &h);
        r
    }
}
