//! Applied loads for Kane's equations: forces and moments gathered per
//! body about its origin, and the extra generalized forces of forces at
//! points that move in their body.

use crate::expr::{ExprId, SymId};
use crate::mech::error::{ItemRef, LocatedError};
use crate::mech::framevec::Fv;
use crate::mech::system::{PointId, System};
use crate::mech::vector::Vector;

/// The applied force and moment (about the origin) on each body.
pub(super) struct AppliedLoads {
    pub force: Vec<Vector>,
    pub moment: Vec<Vector>,
}

impl System {
    /// Forces and moments, per body, about the body's origin.
    pub(super) fn applied_loads(&mut self) -> AppliedLoads {
        let nb = self.bodies.len();
        let mut f_app: Vec<Vector> = vec![Vector::zero(); nb];
        let mut t_app: Vec<Vector> = vec![Vector::zero(); nb];
        for force in self.forces.clone() {
            self.add_point_force(&mut f_app, &mut t_app, force.at, &force.vector, false);
            if let Some(p) = force.reaction {
                self.add_point_force(&mut f_app, &mut t_app, p, &force.vector, true);
            }
        }
        for moment in self.moments.clone() {
            let b = moment.at.index();
            t_app[b] = t_app[b].add(&mut self.arena, &moment.vector);
            if let Some(c) = moment.reaction {
                let neg = moment.vector.neg(&mut self.arena);
                t_app[c.index()] = t_app[c.index()].add(&mut self.arena, &neg);
            }
        }

        AppliedLoads {
            force: f_app,
            moment: t_app,
        }
    }

    /// Adds the force `f` (`−f` when `negate`) at point `p` to its body's
    /// force and moment (about the body's origin).
    pub(super) fn add_point_force(
        &mut self,
        force: &mut [Vector],
        moment: &mut [Vector],
        p: PointId,
        f: &Vector,
        negate: bool,
    ) {
        let point = self.points[p.index()].clone();
        let b = point.body.index();
        let f = &if negate {
            f.neg(&mut self.arena)
        } else {
            f.clone()
        };
        let frame = self.bodies[b].frame;
        let r = self
            .frames
            .vector_in(&mut self.arena, frame, point.coordinates);
        let m = self.frames.cross_vec(&mut self.arena, &r, f);
        force[b] = force[b].add(&mut self.arena, f);
        moment[b] = moment[b].add(&mut self.arena, &m);
    }

    /// Adds to `forcing` what forces at points that move in their body
    /// (coordinates depending on the state) contribute besides the
    /// rigid-body part: the partial velocities of that motion,
    /// Σ_s (F · ∂r/∂s) ∂ṡ/∂u_k over the symbols s of the coordinates that
    /// have a derivative.
    pub(super) fn moving_point_forcing(
        &mut self,
        forcing: &mut [ExprId],
    ) -> Result<(), LocatedError> {
        let n = forcing.len();
        for (index, force) in self.forces.clone().into_iter().enumerate() {
            let at = |e| LocatedError::new(ItemRef::Force(index), e);
            for (p, negate) in [(Some(force.at), false), (force.reaction, true)] {
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

        Ok(())
    }
}
