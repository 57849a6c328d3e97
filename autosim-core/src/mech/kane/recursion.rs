//! The recursions of the composite-body form: accelerations outward with
//! du/dt = 0 (N accelerating at -g), each body's applied plus inertia
//! forces, and inward the resultants of every subtree with its composite
//! mass, first moment and inertia, each body's in its own axes.

use super::loads::AppliedLoads;
use crate::expr::ExprId;
use crate::mech::frames::FrameId;
use crate::mech::framevec::{
    Fv, Mat3, mat_add, mat_rotate_symmetric, mat_vec, point_inertia, shift_cross_term,
};
use crate::mech::system::{BodyId, System};

/// Angular acceleration and acceleration of the origin of each body with
/// du/dt = 0, body axes.
pub(super) struct Accelerations {
    pub alpha: Vec<Fv>,
    pub a0: Vec<Fv>,
}

/// Applied plus (velocity-dependent) inertia forces: the resultant force
/// and moment about the origin, per body (then per subtree), body axes.
#[derive(Clone)]
pub(super) struct Resultants {
    pub force: Vec<Fv>,
    pub moment: Vec<Fv>,
}

/// The composite body of each subtree: mass, first moment and inertia
/// about the subtree root's origin, in its axes.
pub(super) struct Composite {
    pub mass: Vec<ExprId>,
    pub first: Vec<Fv>,
    pub inertia: Vec<Mat3>,
}

impl System {
    /// Accelerations with du/dt = 0, body axes; N accelerates at -g.
    pub(super) fn accelerations(&mut self) -> Accelerations {
        let nb = self.bodies.len();
        let mut alpha: Vec<Fv> = Vec::with_capacity(nb);
        let mut a0: Vec<Fv> = Vec::with_capacity(nb);
        alpha.push(Fv::zero(&self.arena, FrameId::N));
        let a_n = match self.gravity.clone() {
            Some(g) => {
                let gn = Fv::from_vector(&mut self.arena, &mut self.frames, &g, FrameId::N);
                let m1 = self.arena.int(-1);
                gn.scale(&mut self.arena, m1)
            }
            None => Fv::zero(&self.arena, FrameId::N),
        };
        a0.push(a_n);
        for b in 1..nb {
            let body = self.bodies[b].clone();
            let a = body.parent.unwrap_or(BodyId::N).index();
            let r = self.joint_vector(BodyId(b as u32));
            let (v_rel, w_rel) = self.relative_velocity(BodyId(b as u32));
            let w_a = self.bodies[a].w;
            let alpha_a = alpha[a];
            // a0_B = a0_A + α_A × r + w_A × (w_A × r) + 2 w_A × v_rel
            let t1 = alpha_a.cross(&mut self.arena, &r);
            let wxr = w_a.cross(&mut self.arena, &r);
            let t2 = w_a.cross(&mut self.arena, &wxr);
            let wxv = w_a.cross(&mut self.arena, &v_rel);
            let two = self.arena.int(2);
            let t3 = wxv.scale(&mut self.arena, two);
            let acc = a0[a]
                .add(&mut self.arena, &t1)
                .add(&mut self.arena, &t2)
                .add(&mut self.arena, &t3);
            a0.push(acc.reexpress(&mut self.arena, &mut self.frames, body.frame));
            // α_B = α_A + w_A × w_rel
            let alpha_b = alpha_a.reexpress(&mut self.arena, &mut self.frames, body.frame);
            let w_a_b = w_a.reexpress(&mut self.arena, &mut self.frames, body.frame);
            let wxw = w_a_b.cross(&mut self.arena, &w_rel);
            alpha.push(alpha_b.add(&mut self.arena, &wxw));
        }

        Accelerations { alpha, a0 }
    }

    /// Applied plus inertia forces per body (body axes, about the origin).
    pub(super) fn body_resultants(
        &mut self,
        loads: &AppliedLoads,
        acc: &Accelerations,
    ) -> Resultants {
        let (alpha, a0) = (&acc.alpha, &acc.a0);
        let nb = self.bodies.len();
        let (f_app, t_app) = (&loads.force, &loads.moment);
        let mut res: Vec<Fv> = Vec::with_capacity(nb);
        let mut mom: Vec<Fv> = Vec::with_capacity(nb);
        for b in 0..nb {
            let body = self.bodies[b].clone();
            let fr = body.frame;
            let f = Fv::from_vector(&mut self.arena, &mut self.frames, &f_app[b], fr);
            let t = Fv::from_vector(&mut self.arena, &mut self.frames, &t_app[b], fr);
            if b == 0 {
                res.push(Fv::zero(&self.arena, fr));
                mom.push(Fv::zero(&self.arena, fr));
                continue;
            }
            let c = Fv::new(fr, body.cm);
            let w = body.w;
            // a_cm = a0 + α × c + w × (w × c)
            let axc = alpha[b].cross(&mut self.arena, &c);
            let wxc = w.cross(&mut self.arena, &c);
            let wwxc = w.cross(&mut self.arena, &wxc);
            let a_cm = a0[b].add(&mut self.arena, &axc).add(&mut self.arena, &wwxc);
            let m_neg = self.arena.neg(body.mass);
            let inertia_force = a_cm.scale(&mut self.arena, m_neg);
            let iw = Fv::new(fr, mat_vec(&mut self.arena, &body.inertia, &w.c));
            let ia = Fv::new(fr, mat_vec(&mut self.arena, &body.inertia, &alpha[b].c));
            let wxiw = w.cross(&mut self.arena, &iw);
            let cxf = c.cross(&mut self.arena, &inertia_force);
            res.push(f.add(&mut self.arena, &inertia_force));
            let torque = t
                .sub(&mut self.arena, &ia)
                .sub(&mut self.arena, &wxiw)
                .add(&mut self.arena, &cxf);
            mom.push(torque);
        }

        Resultants {
            force: res,
            moment: mom,
        }
    }

    /// Inward accumulation: subtree resultants (in place) and composite
    /// bodies.
    pub(super) fn subtrees(&mut self, res: &mut Resultants) -> Composite {
        let nb = self.bodies.len();
        let zero = self.arena.zero();
        let mut cmass: Vec<ExprId> = vec![zero; nb];
        let mut cfirst: Vec<Fv> = (0..nb)
            .map(|b| Fv::zero(&self.arena, self.bodies[b].frame))
            .collect();
        let mut cinertia: Vec<Mat3> = vec![[[zero; 3]; 3]; nb];
        for b in (1..nb).rev() {
            let body = self.bodies[b].clone();
            let fr = body.frame;
            let c = Fv::new(fr, body.cm);
            let mut m = body.mass;
            let mut s = c.scale(&mut self.arena, body.mass);
            let pi = point_inertia(&mut self.arena, body.mass, &body.cm);
            let mut j = mat_add(&mut self.arena, &body.inertia, &pi);
            for &ch in &body.children {
                let ci = ch.index();
                let r = self.carry_resultant(BodyId(b as u32), ch, res);
                // Composite mass properties of the child's subtree, moved to
                // this body's origin and axes.
                let mc = cmass[ci];
                let sc = cfirst[ci].reexpress(&mut self.arena, &mut self.frames, fr);
                let rot = self
                    .frames
                    .cosine_matrix(&mut self.arena, fr, self.bodies[ci].frame);
                let jc = mat_rotate_symmetric(&mut self.arena, &rot, &cinertia[ci]);
                let jp = point_inertia(&mut self.arena, mc, &r.c);
                let jx = shift_cross_term(&mut self.arena, &r.c, &sc.c);
                j = mat_add(&mut self.arena, &j, &jc);
                j = mat_add(&mut self.arena, &j, &jp);
                j = mat_add(&mut self.arena, &j, &jx);
                m = self.arena.add(m, mc);
                let mr = r.scale(&mut self.arena, mc);
                s = s.add(&mut self.arena, &mr).add(&mut self.arena, &sc);
            }
            cmass[b] = m;
            cfirst[b] = s;
            cinertia[b] = j;
        }

        Composite {
            mass: cmass,
            first: cfirst,
            inertia: cinertia,
        }
    }
}
