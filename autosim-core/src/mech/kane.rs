//! Kane's equations for tree systems in composite-body form.
//!
//! For a speed `u_k` of body `K`, every point of `K`'s subtree has partial
//! velocity `d_k` (translation along `d_k`) or `e_k × r` (rotation about
//! `e_k` through `K`'s origin), and every body of the subtree has partial
//! angular velocity `0` or `e_k`; bodies outside the subtree have none. So
//! the generalized active plus inertia force of `u_k` is `d_k · R_K` or
//! `e_k · H_K`, where `R_K` and `H_K` are the resultant force and the moment
//! about `K`'s origin of all applied and (velocity-dependent) inertia forces
//! on the subtree. Those are accumulated from the leaves inward, each body's
//! in its own axes, which keeps the expressions of size O(1) per body.
//! Likewise the mass matrix `M_kl` is `d_k · P_l + e_k · H_l` with the
//! momentum of the subtree of `l` moving at unit rate `u_l` (composite
//! mass, first moment and inertia), carried inward body by body. Gravity is
//! an acceleration `-g` of N. The mass matrix is never inverted: the
//! accelerations are solved numerically by the caller.

use super::error::{ItemRef, LocatedError, ModelError};
use super::frames::FrameId;
use super::framevec::{
    Fv, Mat3, mat_add, mat_rotate_symmetric, mat_vec, point_inertia, shift_cross_term,
};
use super::joint::UnitMotion;
use super::system::{BodyId, System};
use super::vector::Vector;
use crate::expr::{ExprId, SymId};

/// The equations of motion `dq/dt = f(q, u)`, `M(q) du/dt = f(q, u, t)`.
#[derive(Clone, Debug)]
pub struct Equations {
    /// Generalized coordinates.
    pub coordinates: Vec<SymId>,
    /// Generalized speeds.
    pub speeds: Vec<SymId>,
    /// Symbols for du/dt.
    pub speed_rates: Vec<SymId>,
    /// dq/dt for each coordinate.
    pub kinematics: Vec<ExprId>,
    /// The mass matrix, symmetric, `n × n`.
    pub mass_matrix: Vec<Vec<ExprId>>,
    /// The forcing vector: generalized active forces plus the
    /// velocity-dependent generalized inertia forces.
    pub forcing: Vec<ExprId>,
    /// Added state variables.
    pub states: Vec<SymId>,
    /// Their derivatives.
    pub state_derivatives: Vec<ExprId>,
}

impl Equations {
    /// All expressions (kinematics, mass matrix, forcing, state derivatives).
    pub fn all_expressions(&self) -> Vec<ExprId> {
        let mut v = self.kinematics.clone();
        for row in &self.mass_matrix {
            v.extend(row);
        }
        v.extend(&self.forcing);
        v.extend(&self.state_derivatives);
        v
    }
}

impl System {
    /// Derives the equations of motion (Kane's method, composite-body form).
    pub fn equations(&mut self) -> Result<Equations, LocatedError> {
        let n = self.coordinates.len();
        let nb = self.bodies.len();
        let zero = self.arena.zero();

        // 1. Applied forces and moments, per body, about the body's origin.
        let mut f_app: Vec<Vector> = vec![Vector::zero(); nb];
        let mut t_app: Vec<Vector> = vec![Vector::zero(); nb];
        for force in self.forces.clone() {
            for (p, sign) in [(Some(force.point), 1), (force.reaction, -1)] {
                let Some(p) = p else { continue };
                let point = self.points[p.index()].clone();
                let b = point.body.index();
                let f = if sign > 0 {
                    force.vector.clone()
                } else {
                    force.vector.neg(&mut self.arena)
                };
                let frame = self.bodies[b].frame;
                let r = self
                    .frames
                    .vector_in(&mut self.arena, frame, point.coordinates);
                let m = self.frames.cross_vec(&mut self.arena, &r, &f);
                f_app[b] = f_app[b].add(&mut self.arena, &f);
                t_app[b] = t_app[b].add(&mut self.arena, &m);
            }
        }
        for moment in self.moments.clone() {
            let b = moment.body.index();
            t_app[b] = t_app[b].add(&mut self.arena, &moment.vector);
            if let Some(c) = moment.reaction {
                let neg = moment.vector.neg(&mut self.arena);
                t_app[c.index()] = t_app[c.index()].add(&mut self.arena, &neg);
            }
        }

        // 2. Accelerations with du/dt = 0, body axes; N accelerates at -g.
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

        // 3. Applied plus inertia forces per body (body axes, about origin).
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

        // 4. Inward accumulation: subtree resultants and composite bodies.
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
                let r = self.joint_vector(ch);
                let rc = res[ci].reexpress(&mut self.arena, &mut self.frames, fr);
                let hc = mom[ci].reexpress(&mut self.arena, &mut self.frames, fr);
                let rxr = r.cross(&mut self.arena, &rc);
                res[b] = res[b].add(&mut self.arena, &rc);
                let h = hc.add(&mut self.arena, &rxr);
                mom[b] = mom[b].add(&mut self.arena, &h);
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

        // 5. Forcing: project each subtree's resultants on its joint's speeds.
        let motions: Vec<UnitMotion> = (0..n).map(|k| self.unit_motion(k)).collect();
        let mut forcing = vec![zero; n];
        for (k, um) in motions.iter().enumerate() {
            let b = self.coordinates[k].body.index();
            let a = um.v.dot(&mut self.arena, &res[b]);
            let c = um.w.dot(&mut self.arena, &mom[b]);
            forcing[k] = self.arena.add(a, c);
        }
        // A force at a point that moves in its body (coordinates depending
        // on the state) has, besides the rigid-body part projected above,
        // the partial velocities of that motion: Σ_s (F · ∂r/∂s) ∂ṡ/∂u_k
        // over the symbols s of the coordinates that have a derivative.
        for (index, force) in self.forces.clone().into_iter().enumerate() {
            let at = |e| LocatedError::new(ItemRef::Force(index), e);
            for (p, negate) in [(Some(force.point), false), (force.reaction, true)] {
                let Some(p) = p else { continue };
                let point = self.points[p.index()].clone();
                let mut syms: Vec<SymId> = Vec::new();
                for c in point.coordinates {
                    if !self.arena.is_constant(c) {
                        syms.extend(self.arena.free_symbols(c));
                    }
                }
                syms.sort();
                syms.dedup();
                let rates: Vec<(SymId, ExprId)> = syms
                    .iter()
                    .filter_map(|s| self.arena.dxdt_of_symbol(*s).map(|d| (*s, d)))
                    .filter(|(_, d)| !self.arena.is_constant(*d))
                    .collect();
                if rates.is_empty() {
                    continue;
                }
                let frame = self.bodies[point.body.index()].frame;
                let f = Fv::from_vector(&mut self.arena, &mut self.frames, &force.vector, frame);
                let mut f_dr = Vec::with_capacity(rates.len());
                for (s, d) in &rates {
                    let mut t = Vec::with_capacity(3);
                    for i in 0..3 {
                        let dr = self.arena.partial(point.coordinates[i], *s).map_err(at)?;
                        t.push(self.arena.mul(dr, f.c[i]));
                    }
                    f_dr.push((self.arena.sum(&t), *d));
                }
                for k in 0..n {
                    let u = self.coordinates[k].u;
                    let mut terms = Vec::new();
                    for (fd, d) in &f_dr {
                        let du = self.arena.partial(*d, u).map_err(at)?;
                        if !self.arena.is_zero(du) {
                            terms.push(self.arena.mul(*fd, du));
                        }
                    }
                    if terms.is_empty() {
                        continue;
                    }
                    let mut s = self.arena.sum(&terms);
                    if negate {
                        s = self.arena.neg(s);
                    }
                    forcing[k] = self.arena.add(forcing[k], s);
                }
            }
        }

        // 6. Mass matrix: unit-rate momentum of each subtree, carried inward.
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

        let mut state_derivatives = Vec::with_capacity(self.states.len());
        for st in &self.states {
            match st.derivative {
                Some(d) => state_derivatives.push(d),
                None => {
                    return Err(LocatedError::new(
                        ItemRef::State(st.sym),
                        ModelError::Invalid(format!(
                            "the added state `{}` has no derivative",
                            self.arena.symbol(st.sym).name
                        )),
                    ));
                }
            }
        }

        Ok(Equations {
            coordinates: self.coordinates.iter().map(|c| c.q).collect(),
            speeds: self.coordinates.iter().map(|c| c.u).collect(),
            speed_rates: self.coordinates.iter().map(|c| c.du).collect(),
            kinematics: self.coordinates.iter().map(|c| c.qdot).collect(),
            mass_matrix: mass,
            forcing,
            states: self.states.iter().map(|s| s.sym).collect(),
            state_derivatives,
        })
    }
}
