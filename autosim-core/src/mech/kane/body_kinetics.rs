//! What an articulated-body (recursive, O(n)) solve of `M u̇ = f` needs of
//! each body: how it sits in its parent (rotation and offset), its rigid
//! inertia about its origin, and the unit motions of its speeds, all in
//! its own axes, and the forces the recursion carries inward: each body's
//! applied plus velocity-dependent inertia forces (with du/dt = 0 and N
//! accelerating at -g, as Kane's forcing has them), so the recursion
//! needs no velocities or gravity of its own and sums each subtree's
//! forces once, not again for Kane's forcing.

use super::recursion::Resultants;
use crate::expr::ExprId;
use crate::mech::framevec::Mat3;
use crate::mech::joint::{Axis, UnitMotion};
use crate::mech::system::{BodyId, System};

/// One body's data for the recursive solve (bodies in parent-first order;
/// N is not listed).
#[derive(Clone, Debug)]
pub struct BodyKinetics {
    /// The body.
    pub body: BodyId,
    /// The parent's position in the list (`None`: N).
    pub parent: Option<usize>,
    /// `C[i][j] = p_i · b_j`: the body's axes in the parent's.
    pub rotation: Mat3,
    /// The body's origin from the parent's origin, parent axes.
    pub offset: [ExprId; 3],
    /// Mass.
    pub mass: ExprId,
    /// First moment `m c` about the origin, body axes.
    pub first_moment: [ExprId; 3],
    /// Inertia about the origin, body axes.
    pub inertia: Mat3,
    /// Each of the body's speeds: its index and its unit motion
    /// `[ω; v_origin]` in body axes.
    pub speeds: Vec<(usize, [ExprId; 6])>,
    /// For each speed, the component of `[ω; v_origin]` its unit motion
    /// is the unit vector of, where it is one (`UnitMotion::axis`).
    pub unit_axes: Vec<Option<usize>>,
    /// The axis the body turns about relative to its parent, where its
    /// rotation is one turn about an axis the two share (a simple
    /// rotation by an angle that is not small, with no constant turn
    /// before it): `rotation` is then 1 on
    /// that axis and `[[c, −s], [s, c]]` in the other two.
    pub turn: Option<Axis>,
    /// The body's applied plus velocity-dependent inertia forces, negated
    /// (the bias force of the recursion): `[−moment about the origin;
    /// −force]`, body axes.
    pub bias: [ExprId; 6],
}

/// The recursive solve's data: `M du/dt = f` with `f` the projections of
/// every subtree's bias forces plus `joint_forcing`.
#[derive(Clone, Debug)]
pub struct TreeKinetics {
    /// The bodies, parent first (N not listed).
    pub bodies: Vec<BodyKinetics>,
    /// The generalized forces not carried by the bodies' resultants (of
    /// forces at points moving in their body), per speed.
    pub joint_forcing: Vec<ExprId>,
}

impl System {
    /// The bodies' data for the recursive solve, given the unit motion of
    /// every speed, each body's own resultants and the rest of the forcing.
    pub(super) fn tree_kinetics(
        &mut self,
        motions: &[UnitMotion],
        own: &Resultants,
        joint_forcing: Vec<ExprId>,
    ) -> TreeKinetics {
        let mut out = Vec::with_capacity(self.bodies.len().saturating_sub(1));
        for b in 1..self.bodies.len() {
            let body = self.bodies[b].clone();
            let parent = body.parent.unwrap_or(BodyId::N);
            let pf = self.bodies[parent.index()].frame;
            let rotation = self.frames.cosine_matrix(&mut self.arena, pf, body.frame);
            let offset = self.joint_vector(BodyId(b as u32)).c;
            let (m, c) = (body.mass, body.cm);
            let first_moment = c.map(|x| self.arena.mul(m, x));
            let inertia = self.inertia_about_origin(m, &c, &body.inertia);
            let speeds = body
                .coordinates
                .iter()
                .map(|&k| {
                    let um = &motions[k];
                    let (w, v) = (um.w.c, um.v.c);
                    (k, [w[0], w[1], w[2], v[0], v[1], v[2]])
                })
                .collect();
            let unit_axes = body.coordinates.iter().map(|&k| motions[k].axis).collect();
            let (f, t) = (own.force[b].c, own.moment[b].c);
            let bias = [t[0], t[1], t[2], f[0], f[1], f[2]].map(|x| self.arena.neg(x));
            out.push(BodyKinetics {
                body: BodyId(b as u32),
                parent: body
                    .parent
                    .filter(|p| *p != BodyId::N)
                    .map(|p| p.index() - 1),
                rotation,
                offset,
                mass: m,
                first_moment,
                inertia,
                speeds,
                unit_axes,
                turn: self.frames.turn_axis(&self.arena, pf, body.frame),
                bias,
            });
        }
        TreeKinetics {
            bodies: out,
            joint_forcing,
        }
    }

    /// `J_O = J_C + m (|c|² 1 − c cᵀ)` (parallel axes).
    fn inertia_about_origin(&mut self, m: ExprId, c: &[ExprId; 3], jc: &Mat3) -> Mat3 {
        let a = &mut self.arena;
        let squares: Vec<ExprId> = c.iter().map(|x| a.mul(*x, *x)).collect();
        let c2 = a.sum(&squares);
        let mut out = *jc;
        for i in 0..3 {
            for j in 0..3 {
                let cc = a.mul(c[i], c[j]);
                let shift = if i == j { a.sub(c2, cc) } else { a.neg(cc) };
                let ms = a.mul(m, shift);
                out[i][j] = a.add(jc[i][j], ms);
            }
        }
        out
    }
}
