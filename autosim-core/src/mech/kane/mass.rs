//! The mass matrix: `M_kl = d_k · P_l + e_k · H_l` with the momentum of the
//! subtree of speed `l` moving at unit rate `u_l` (composite mass, first
//! moment and inertia), carried inward body by body.

use super::recursion::Composite;
use crate::expr::ExprId;
use crate::mech::framevec::{Fv, mat_vec};
use crate::mech::joint::UnitMotion;
use crate::mech::system::{BodyId, System};

impl System {
    /// The mass matrix from the unit motions and the composite bodies.
    pub(super) fn mass_matrix(
        &mut self,
        motions: &[UnitMotion],
        c: &Composite,
    ) -> Vec<Vec<ExprId>> {
        let n = motions.len();
        let zero = self.arena.zero();
        let (cmass, cfirst, cinertia) = (&c.mass, &c.first, &c.inertia);
        let mut mass = vec![vec![zero; n]; n];
        for l in 0..n {
            let lb = self.coordinates[l].body;
            let um = &motions[l];
            let li = lb.index();
            let fr = self.bodies[li].frame;
            let mv = um.v.scale(&mut self.arena, cmass[li]);
            let wxs = um.w.cross(&mut self.arena, &cfirst[li]);
            let mut p = mv.add(&mut self.arena, &wxs);
            let jw = Fv::new(fr, mat_vec(&mut self.arena, &cinertia[li], &um.w.c));
            let sxv = cfirst[li].cross(&mut self.arena, &um.v);
            let mut h = jw.add(&mut self.arena, &sxv);
            let mut cur = lb;
            loop {
                for &k in &self.bodies[cur.index()].coordinates.clone() {
                    if cur == lb && k > l {
                        continue;
                    }
                    let a = motions[k].v.dot(&mut self.arena, &p);
                    let b = motions[k].w.dot(&mut self.arena, &h);
                    let mkl = self.arena.add(a, b);
                    mass[k][l] = mkl;
                    mass[l][k] = mkl;
                }
                let Some(parent) = self.bodies[cur.index()].parent else {
                    break;
                };
                if parent == BodyId::N {
                    break;
                }
                let pf = self.bodies[parent.index()].frame;
                let r = self.joint_vector(cur);
                p = p.reexpress(&mut self.arena, &mut self.frames, pf);
                let hp = h.reexpress(&mut self.arena, &mut self.frames, pf);
                let rxp = r.cross(&mut self.arena, &p);
                h = hp.add(&mut self.arena, &rxp);
                cur = parent;
            }
        }

        mass
    }
}
