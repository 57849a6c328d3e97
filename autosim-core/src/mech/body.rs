//! Adding bodies: each is built from its joint (degrees of freedom, frames,
//! kinematical equations), then gets its velocity by the forward recursion
//! (the paper's Eq. 11), its mass properties and its points.

use super::body_order::order_parents_first;
use super::error::ModelError;
use super::framevec::{Fv, Mat3};
use super::joint::{BuiltJoint, DofKind, DofSymbols, translation};
use super::system::{Body, BodyId, BodySpec, Coordinate, System};
use super::vector::Vector;
use crate::expr::ExprId;

impl System {
    /// Adds bodies given in any order: parents are resolved by name, and
    /// unknown parents and parent cycles are reported together.
    pub fn add_bodies(&mut self, specs: Vec<BodySpec>) -> Result<Vec<BodyId>, Vec<ModelError>> {
        let mut errors = Vec::new();
        let mut parents = Vec::with_capacity(specs.len());
        for s in &specs {
            let among = (s.parent != "N")
                .then(|| specs.iter().position(|p| p.name == s.parent))
                .flatten();
            if among.is_none() && s.parent != "N" && self.body_named(&s.parent).is_none() {
                errors.push(ModelError::UnknownBody(s.parent.clone()));
            }
            parents.push(among);
        }
        let ordered = order_parents_first(&parents);
        for cycle in &ordered.cycles {
            let names = cycle
                .iter()
                .chain(cycle.first())
                .map(|k| specs[*k].name.clone())
                .collect();
            errors.push(ModelError::ParentCycle(names));
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        let mut specs: Vec<Option<BodySpec>> = specs.into_iter().map(Some).collect();
        let mut ids = vec![BodyId::N; specs.len()];
        for i in ordered.order {
            if let Some(spec) = specs[i].take() {
                match self.add_body(spec) {
                    Ok(id) => ids[i] = id,
                    Err(e) => errors.push(e),
                }
            }
        }
        if errors.is_empty() {
            Ok(ids)
        } else {
            Err(errors)
        }
    }

    /// Adds one body; its parent must already exist. A body that is
    /// refused leaves the system as it was (see [`System::body_errors`]
    /// for all of its mistakes at once).
    pub fn add_body(&mut self, spec: BodySpec) -> Result<BodyId, ModelError> {
        let parent = self.body_parent(&spec)?;
        let mut spec = spec;
        let (q_names, u_names) = self.default_names(&spec);
        spec.coordinate_names.get_or_insert(q_names);
        spec.speed_names.get_or_insert(u_names);
        // Everything that can fail is checked before anything is created.
        if let Some(e) = self.body_errors(&spec).into_iter().next() {
            return Err(e);
        }
        let declared = spec.dofs();
        let (spec, locked) = self.apply_locks(spec)?;
        let parent_body = self.bodies[parent.index()].clone();
        let id = BodyId(self.bodies.len() as u32);

        let directions: Vec<[ExprId; 3]> = spec
            .joint
            .translations
            .iter()
            .map(|d| translation::unit_direction(&mut self.arena, d))
            .collect();
        let syms = self.dof_symbols(&spec)?;
        let built = self.build_joint(&spec, parent_body.frame, &syms)?;
        let (w, v0) = self.body_velocity(&spec, &parent_body, &built, &directions, &syms);
        let (mass, inertia) = self.mass_properties(&spec)?;

        let zero = self.arena.zero();
        let joint_point = spec.joint_point.unwrap_or([zero; 3]);
        let cm = spec.cm.unwrap_or([zero; 3]);
        let origin = self.push_point(&format!("{}.origin", spec.name), id, [zero; 3]);
        let cm_point = self.push_point(&format!("{}.cm", spec.name), id, cm);
        let first = self.coordinates.len();
        let coordinates = self.coordinates_of(&spec, id, &built, &directions, &syms);
        let dofs = body_dofs(&mut self.arena, declared, &locked, &syms);
        self.coordinates.extend(coordinates);
        self.bodies[parent.index()].children.push(id);
        self.bodies.push(Body {
            name: spec.name,
            description: spec.description,
            parent: Some(parent),
            children: Vec::new(),
            level: parent_body.level + 1,
            frame: built.frame,
            joint_point,
            joint: spec.joint,
            coordinates: (first..first + syms.len()).collect(),
            dofs,
            mass,
            inertia,
            cm,
            origin,
            cm_point,
            w,
            v0,
        });
        self.declared_dofs += declared;
        Ok(id)
    }

    /// The forward velocity recursion, in body axes: the angular velocity
    /// and the velocity of the origin, from the parent's.
    fn body_velocity(
        &mut self,
        spec: &BodySpec,
        parent: &Body,
        built: &BuiltJoint,
        directions: &[[ExprId; 3]],
        syms: &DofSymbols,
    ) -> (Fv, Vector) {
        let zero = self.arena.zero();
        let joint_point = spec.joint_point.unwrap_or([zero; 3]);
        let pf = parent.frame;
        let frame = built.frame;
        let qs: Vec<crate::expr::SymId> = syms.iter().map(|s| s.0).collect();
        let r = translation::joint_offset(&mut self.arena, pf, &joint_point, directions, &qs);
        let mut v_rel = Fv::zero(&self.arena, pf);
        for (k, d) in directions.iter().enumerate() {
            let u = self.arena.sym(syms[k].1);
            let t = Fv::new(pf, *d).scale(&mut self.arena, u);
            v_rel = v_rel.add(&mut self.arena, &t);
        }
        let w_a = parent.w;
        let wxr = w_a.cross(&mut self.arena, &r);
        let across = wxr
            .add(&mut self.arena, &v_rel)
            .to_vector(&mut self.arena, &self.frames);
        let v0 = parent.v0.add(&mut self.arena, &across);
        let w_in_b = w_a.reexpress(&mut self.arena, &mut self.frames, frame);
        let w = w_in_b.add(&mut self.arena, &Fv::new(frame, built.w_rel));
        if spec.joint.rotation.dofs() > 0 {
            let wv = w.to_vector(&mut self.arena, &self.frames);
            debug_assert_eq!(self.frame_w.len(), frame.index());
            self.frame_w.push(wv);
        }
        (w, v0)
    }

    /// Mass and inertia (defaults named after the body, the paper's Table
    /// 13: `M<Body>` and `I<Body>11`, `I<Body>12`, ...).
    fn mass_properties(&mut self, spec: &BodySpec) -> Result<(ExprId, Mat3), ModelError> {
        let name = &spec.name;
        let mass = match spec.mass {
            Some(m) => m,
            None => self.parameter_or_default(&format!("M{name}"), 1.0, "kg")?,
        };
        let inertia = match spec.inertia {
            Some(i) => i,
            None => {
                let mut m = [[self.arena.zero(); 3]; 3];
                for j in 0..3 {
                    for k in j..3 {
                        let default = if j == k { 1.0 } else { 0.0 };
                        let p = self.parameter_or_default(
                            &format!("I{name}{}{}", j + 1, k + 1),
                            default,
                            "kg m^2",
                        )?;
                        m[j][k] = p;
                        m[k][j] = p;
                    }
                }
                m
            }
        };
        Ok((mass, inertia))
    }

    /// The generalized coordinates of a body, with their kinematical
    /// equations and initial values.
    fn coordinates_of(
        &mut self,
        spec: &BodySpec,
        id: BodyId,
        built: &BuiltJoint,
        directions: &[[ExprId; 3]],
        syms: &DofSymbols,
    ) -> Vec<Coordinate> {
        let zero = self.arena.zero();
        let nt = directions.len();
        let mut coords = Vec::with_capacity(syms.len());
        for (k, &(q, u, du)) in syms.iter().enumerate() {
            let kind = match k < nt {
                true => DofKind::Translation {
                    direction: directions[k],
                },
                false => built.rotation_kinds[k - nt].clone(),
            };
            let initial_q = spec
                .initial_coordinates
                .as_ref()
                .and_then(|v| v.get(spec.joint.coordinate_of_speed(k)).copied())
                .unwrap_or(zero);
            let initial_u = spec
                .initial_speeds
                .as_ref()
                .and_then(|v| v.get(k).copied())
                .unwrap_or(zero);
            self.arena.set_dxdt(q, built.qdots[k]);
            coords.push(Coordinate {
                q,
                u,
                du,
                body: id,
                kind,
                qdot: built.qdots[k],
                initial_q,
                initial_u,
                initial_declared: spec.initial_coordinates.is_some(),
            });
        }
        coords
    }
}

/// Every declared degree of freedom in order, as (coordinate, speed)
/// expressions: the symbols of a free one, the parameter and 0 of a locked
/// one.
fn body_dofs(
    arena: &mut crate::expr::Arena,
    declared: usize,
    locked: &[(usize, ExprId)],
    syms: &DofSymbols,
) -> Vec<(ExprId, ExprId)> {
    let zero = arena.zero();
    let mut free = syms.iter();
    let mut out = Vec::with_capacity(declared);
    for k in 0..declared {
        match locked.iter().find(|(i, _)| *i == k) {
            Some((_, p)) => out.push((*p, zero)),
            None => {
                if let Some((q, u, _)) = free.next() {
                    out.push((arena.sym(*q), arena.sym(*u)));
                }
            }
        }
    }
    out
}
