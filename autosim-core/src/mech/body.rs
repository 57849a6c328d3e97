//! Adding bodies: degrees of freedom, frames, kinematical equations and the
//! forward velocity recursion (the paper's Tables 7-11, Eqs. 8-10).

use super::error::ModelError;
use super::frames::FrameId;
use super::framevec::{Fv, Mat3};
use super::system::{Body, BodyId, BodySpec, Coordinate, Direction, DofKind, System};
use super::vector::Vector;
use crate::expr::{ExprId, SymbolKind};

impl System {
    /// Adds bodies given in any order: parents are resolved by name, and
    /// unknown parents and parent cycles are reported together.
    pub fn add_bodies(&mut self, specs: Vec<BodySpec>) -> Result<Vec<BodyId>, Vec<ModelError>> {
        let mut errors = Vec::new();
        let names: Vec<&str> = specs.iter().map(|s| s.name.as_str()).collect();
        for s in &specs {
            let known = s.parent == "N"
                || self.body_named(&s.parent).is_some()
                || names.contains(&s.parent.as_str());
            if !known {
                errors.push(ModelError::UnknownBody(s.parent.clone()));
            }
        }
        // Order parents first; whatever cannot be placed is on a cycle.
        let mut placed = vec![false; specs.len()];
        let mut order = Vec::with_capacity(specs.len());
        loop {
            let mut progress = false;
            for (i, s) in specs.iter().enumerate() {
                if placed[i] {
                    continue;
                }
                let parent_ready = s.parent == "N"
                    || self.body_named(&s.parent).is_some()
                    || specs
                        .iter()
                        .enumerate()
                        .any(|(j, p)| placed[j] && p.name == s.parent);
                if parent_ready {
                    placed[i] = true;
                    order.push(i);
                    progress = true;
                }
            }
            if !progress {
                break;
            }
        }
        let mut reported = vec![false; specs.len()];
        for start in 0..specs.len() {
            if placed[start] || reported[start] {
                continue;
            }
            // Follow parents from `start` until a body repeats.
            let mut path: Vec<usize> = Vec::new();
            let mut cur = Some(start);
            while let Some(i) = cur {
                if let Some(pos) = path.iter().position(|p| *p == i) {
                    let cycle: Vec<String> = path[pos..]
                        .iter()
                        .chain(std::iter::once(&i))
                        .map(|k| specs[*k].name.clone())
                        .collect();
                    if !path[pos..].iter().any(|k| reported[*k]) {
                        errors.push(ModelError::ParentCycle(cycle));
                    }
                    break;
                }
                path.push(i);
                cur = specs.iter().position(|p| p.name == specs[i].parent);
            }
            for k in path {
                reported[k] = true;
            }
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        let mut specs: Vec<Option<BodySpec>> = specs.into_iter().map(Some).collect();
        let mut ids = vec![BodyId::N; specs.len()];
        for i in order {
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

    /// Adds one body; its parent must already exist.
    pub fn add_body(&mut self, spec: BodySpec) -> Result<BodyId, ModelError> {
        let name = spec.name.clone();
        if name == "N" {
            return Err(ModelError::InertialFrame(
                "`N` is the inertial frame and cannot be declared as a body".to_string(),
            ));
        }
        self.check_new_name(&name)?;
        if name == "t" {
            return Err(ModelError::DuplicateName(name));
        }
        let parent = self
            .body_named(&spec.parent)
            .ok_or_else(|| ModelError::UnknownBody(spec.parent.clone()))?;
        self.validate(&spec)?;
        let mut spec = spec;
        let (q_names, u_names) = self.default_names(&spec);
        spec.coordinate_names.get_or_insert(q_names);
        spec.speed_names.get_or_insert(u_names);
        // Everything that can fail is checked before anything is created,
        // so a rejected body leaves the system as it was.
        self.precheck(&spec)?;
        let declared = spec.dofs();
        let (spec, locked) = self.apply_locks(spec)?;

        let parent_body = self.bodies[parent.index()].clone();
        let zero = self.arena.zero();
        let joint = spec.joint.unwrap_or([zero; 3]);
        let cm = spec.cm.unwrap_or([zero; 3]);
        for (what, c) in [("joint coordinates", &joint), ("mass center", &cm)] {
            if c.iter().any(|x| !self.arena.is_constant(*x)) {
                return Err(ModelError::NotConstant {
                    what: format!("{what} of body `{name}`"),
                });
            }
        }
        let id = BodyId(self.bodies.len() as u32);

        // Translation directions as unit components in the parent's axes.
        let mut directions: Vec<[ExprId; 3]> = Vec::with_capacity(spec.translations.len());
        for d in &spec.translations {
            directions.push(self.direction(&name, d)?);
        }

        // Coordinates and speeds.
        let dofs = spec.dofs();
        let nt = spec.translations.len();
        let first = self.coordinates.len();
        // For a quaternion the coordinate list has e0 before e1..e3.
        let name_index = |k: usize| if spec.quaternion && k >= nt { k + 1 } else { k };
        let mut syms = Vec::with_capacity(dofs);
        for k in 0..dofs {
            let global = first + k;
            let qn = spec
                .coordinate_names
                .as_ref()
                .map(|v| v[name_index(k)].clone())
                .unwrap_or_else(|| format!("q{}", global + 1));
            let un = spec
                .speed_names
                .as_ref()
                .map(|v| v[k].clone())
                .unwrap_or_else(|| format!("u{}", global + 1));
            let dn = format!("{un}_dot");
            for n in [&qn, &un, &dn] {
                if self.arena.symbol_named(n).is_some() || self.body_named(n).is_some() {
                    return Err(ModelError::DuplicateName(n.clone()));
                }
            }
            let q = self
                .arena
                .add_symbol(&qn, SymbolKind::Coordinate { index: global })?;
            let u = self
                .arena
                .add_symbol(&un, SymbolKind::Speed { index: global })?;
            let du = self
                .arena
                .add_symbol(&dn, SymbolKind::SpeedRate { index: global })?;
            let translation = k < spec.translations.len();
            let (qu, uu) = if translation {
                ("m", "m/s")
            } else {
                ("rad", "rad/s")
            };
            self.arena.set_unit(q, Some(qu.to_string()));
            self.arena.set_unit(u, Some(uu.to_string()));
            self.arena
                .set_unit(du, Some(format!("{uu}^2").replace("/s^2", "/s^2")));
            let small = spec.small.get(k).copied().unwrap_or(false);
            for s in [q, u, du] {
                self.arena.set_small(s, small);
            }
            let du_e = self.arena.sym(du);
            self.arena.set_dxdt(u, du_e);
            syms.push((q, u, du));
        }

        // Frames: one per rotation, sharing the rotation axis (Eqs. 8-10).
        let axes: Vec<usize> = spec.rotations.iter().map(|a| (*a - 1) as usize).collect();
        let prefix = name.to_lowercase();
        let mut frame = parent_body.frame;
        for (k, (axis, angle)) in spec.fixed_rotations.iter().enumerate() {
            if !self.arena.is_constant(*angle) {
                return Err(ModelError::NotConstant {
                    what: format!("fixed rotation angle of body `{name}`"),
                });
            }
            frame = self.frames.add_rotated(
                &mut self.arena,
                frame,
                (*axis - 1).clamp(0, 2) as usize,
                *angle,
                &format!("{name}#{k}"),
                &format!("{prefix}#{k}_"),
            );
            let w = self.frame_w[parent_body.frame.index()].clone();
            self.frame_w.push(w);
        }
        let mut rot_frames: Vec<FrameId> = Vec::with_capacity(axes.len());
        for (k, &axis) in axes.iter().enumerate() {
            let q = self.arena.sym(syms[nt + k].0);
            let primes = "'".repeat(axes.len() - 1 - k);
            frame = self.frames.add_rotated(
                &mut self.arena,
                frame,
                axis,
                q,
                &format!("{name}{primes}"),
                &format!("{prefix}{primes}"),
            );
            rot_frames.push(frame);
        }

        // Relative angular velocity in body axes, and each speed's axis.
        let mut w_rel = [zero; 3];
        let mut rot_kinds: Vec<usize> = Vec::with_capacity(axes.len());
        if axes.len() == 1 {
            w_rel[axes[0]] = self.arena.sym(syms[nt].1);
            rot_kinds.push(axes[0]);
        } else if axes.len() == 3 || spec.quaternion {
            for k in 0..3 {
                w_rel[k] = self.arena.sym(syms[nt + k].1);
                rot_kinds.push(k);
            }
        }
        let quaternion = if spec.quaternion {
            Some(self.quaternion_frame(&spec, &mut frame, &syms[nt..nt + 3], &w_rel)?)
        } else {
            None
        };

        // Kinematical equations dq/dt = f(q, u).
        let mut qdots: Vec<ExprId> = syms.iter().map(|s| self.arena.sym(s.1)).collect();
        if let Some(rates) = quaternion {
            qdots[nt..nt + 3].copy_from_slice(&rates);
        }
        if axes.len() == 3 {
            let rates =
                self.euler_rates(&name, &axes, &rot_frames, parent_body.frame, frame, &w_rel)?;
            qdots[nt..nt + 3].copy_from_slice(&rates);
        }

        // Angular velocities of the new frames (basis-free, for dxdt).
        // (Fixed rotations add no angular velocity.)
        let mut w_frame = self.frame_w[parent_body.frame.index()].clone();
        for (k, &axis) in axes.iter().enumerate() {
            let f = rot_frames[k];
            let parent_frame = self.frames.frame(f).parent.unwrap_or(FrameId::N);
            let e = self.frames.frame(parent_frame).triad[axis];
            let t = Vector::term(&mut self.arena, e, qdots[nt + k]);
            w_frame = w_frame.add(&mut self.arena, &t);
            if k + 1 < axes.len() {
                debug_assert_eq!(self.frame_w.len(), f.index());
                self.frame_w.push(w_frame.clone());
            }
        }

        // Forward velocity recursion, in body axes.
        let pf = parent_body.frame;
        let qs: Vec<crate::expr::SymId> = syms.iter().map(|s| s.0).collect();
        let r = self.joint_offset(pf, &joint, &directions, &qs);
        let mut v_rel = Fv::zero(&self.arena, pf);
        for (k, d) in directions.iter().enumerate() {
            let u = self.arena.sym(syms[k].1);
            let t = Fv::new(pf, *d).scale(&mut self.arena, u);
            v_rel = v_rel.add(&mut self.arena, &t);
        }
        let w_a = parent_body.w;
        let wxr = w_a.cross(&mut self.arena, &r);
        let v0_parent = parent_body
            .v0
            .add(&mut self.arena, &wxr)
            .add(&mut self.arena, &v_rel);
        let v0 = v0_parent.reexpress(&mut self.arena, &mut self.frames, frame);
        let w_in_b = w_a.reexpress(&mut self.arena, &mut self.frames, frame);
        let w = w_in_b.add(&mut self.arena, &Fv::new(frame, w_rel));
        if !axes.is_empty() || spec.quaternion {
            let wv = w.to_vector(&mut self.arena, &self.frames);
            debug_assert_eq!(self.frame_w.len(), frame.index());
            self.frame_w.push(wv);
        }

        // Mass properties (defaults named after the body, Table 13).
        let mass = match spec.mass {
            Some(m) => m,
            None => self.parameter_or_default(&format!("M{name}"), 1.0, "kg")?,
        };
        let inertia: Mat3 = match spec.inertia {
            Some(i) => i,
            None => {
                let mut m = [[zero; 3]; 3];
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
        if !self.arena.is_constant(mass)
            || inertia
                .iter()
                .flatten()
                .any(|x| !self.arena.is_constant(*x))
        {
            return Err(ModelError::NotConstant {
                what: format!("mass and inertia of body `{name}`"),
            });
        }

        // Points and coordinates.
        let origin = self.push_point(&format!("{name}.origin"), id, [zero; 3]);
        let cm_point = self.push_point(&format!("{name}.cm"), id, cm);
        let zero_init = zero;
        let mut coords = Vec::with_capacity(dofs);
        for (k, (q, u, du)) in syms.iter().enumerate() {
            let kind = if k < nt {
                DofKind::Translation {
                    direction: directions[k],
                }
            } else {
                DofKind::Rotation {
                    axis: rot_kinds[k - nt],
                }
            };
            let initial_q = spec
                .initial_coordinates
                .as_ref()
                .and_then(|v| v.get(name_index(k)).copied())
                .unwrap_or(zero_init);
            let initial_u = spec
                .initial_speeds
                .as_ref()
                .and_then(|v| v.get(k).copied())
                .unwrap_or(zero_init);
            self.arena.set_dxdt(*q, qdots[k]);
            coords.push(Coordinate {
                q: *q,
                u: *u,
                du: *du,
                body: id,
                kind,
                qdot: qdots[k],
                initial_q,
                initial_u,
            });
        }
        let indices: Vec<usize> = (first..first + dofs).collect();
        let mut body_dofs = Vec::with_capacity(declared);
        let mut free = syms.iter();
        for k in 0..declared {
            match locked.iter().find(|(i, _)| *i == k) {
                Some((_, p)) => body_dofs.push((*p, zero)),
                None => {
                    if let Some((q, u, _)) = free.next() {
                        body_dofs.push((self.arena.sym(*q), self.arena.sym(*u)));
                    }
                }
            }
        }
        self.coordinates.extend(coords);
        self.bodies[parent.index()].children.push(id);
        self.bodies.push(Body {
            name,
            description: spec.description,
            parent: Some(parent),
            children: Vec::new(),
            level: parent_body.level + 1,
            frame,
            joint,
            coordinates: indices,
            dofs: body_dofs,
            rotation_axes: axes,
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

    /// The checks of `add_body` that need names and expressions: free
    /// names, constant geometry and mass properties, valid directions.
    fn precheck(&self, spec: &BodySpec) -> Result<(), ModelError> {
        let name = &spec.name;
        let taken = |n: &str| {
            self.arena.symbol_named(n).is_some()
                || self.body_named(n).is_some()
                || self.point_named(n).is_some()
                || self.arena.user_fn_named(n).is_some()
        };
        let is_parameter = |n: &str| {
            self.arena
                .symbol_named(n)
                .is_some_and(|s| self.arena.symbol(s).is_constant())
        };
        let nt = spec.translations.len();
        let qn = spec.coordinate_names.clone().unwrap_or_default();
        let un = spec.speed_names.clone().unwrap_or_default();
        let mut new_names: Vec<String> = Vec::new();
        for k in 0..spec.dofs() {
            let q = &qn[if spec.quaternion && k >= nt { k + 1 } else { k }];
            if spec.locked.get(k).copied().unwrap_or(false) {
                // A locked coordinate becomes (or reuses) a parameter.
                if taken(q) && !is_parameter(q) {
                    return Err(ModelError::DuplicateName(q.clone()));
                }
                continue;
            }
            new_names.push(q.clone());
            new_names.push(un[k].clone());
            new_names.push(format!("{}_dot", un[k]));
        }
        if spec.quaternion {
            new_names.push(qn[nt].clone());
        }
        for (i, n) in new_names.iter().enumerate() {
            if taken(n) || new_names[..i].contains(n) || n == name {
                return Err(ModelError::DuplicateName(n.clone()));
            }
        }
        let zero = self.arena.zero();
        let joint = spec.joint.unwrap_or([zero; 3]);
        let cm = spec.cm.unwrap_or([zero; 3]);
        for (what, c) in [("joint coordinates", &joint), ("mass center", &cm)] {
            if c.iter().any(|x| !self.arena.is_constant(*x)) {
                return Err(ModelError::NotConstant {
                    what: format!("{what} of body `{name}`"),
                });
            }
        }
        let mass_ok = spec.mass.is_none_or(|m| self.arena.is_constant(m));
        let inertia_ok = spec
            .inertia
            .is_none_or(|i| i.iter().flatten().all(|x| self.arena.is_constant(*x)));
        if !mass_ok || !inertia_ok {
            return Err(ModelError::NotConstant {
                what: format!("mass and inertia of body `{name}`"),
            });
        }
        let mut defaults = Vec::new();
        if spec.mass.is_none() {
            defaults.push(format!("M{name}"));
        }
        if spec.inertia.is_none() {
            for j in 1..=3 {
                for k in j..=3 {
                    defaults.push(format!("I{name}{j}{k}"));
                }
            }
        }
        for d in defaults {
            if taken(&d) && !is_parameter(&d) {
                return Err(ModelError::DuplicateName(d));
            }
        }
        for d in &spec.translations {
            if let Direction::Vector(v) = d {
                if v.iter().any(|x| !self.arena.is_constant(*x)) {
                    return Err(ModelError::NotConstant {
                        what: format!("translation direction of body `{name}`"),
                    });
                }
                if v.iter().all(|x| self.arena.is_zero(*x)) {
                    return Err(ModelError::ZeroDirection { body: name.clone() });
                }
            }
        }
        for (axis, angle) in &spec.fixed_rotations {
            if !(1..=3).contains(axis) {
                return Err(ModelError::AxisOutOfRange {
                    body: name.clone(),
                    axis: *axis,
                });
            }
            if !self.arena.is_constant(*angle) {
                return Err(ModelError::NotConstant {
                    what: format!("fixed rotation angle of body `{name}`"),
                });
            }
        }
        Ok(())
    }

    /// The default coordinate and speed names of the next body: `q<k>` and
    /// `u<k>`, counting every degree of freedom declared so far (locked ones
    /// too), and `<Body>_e0` for a quaternion's scalar part.
    pub fn default_names(&self, spec: &BodySpec) -> (Vec<String>, Vec<String>) {
        let first = self.declared_dofs;
        let mut q: Vec<String> = (0..spec.dofs())
            .map(|k| format!("q{}", first + k + 1))
            .collect();
        if spec.quaternion {
            q.insert(spec.translations.len(), format!("{}_e0", spec.name));
        }
        let u = (0..spec.dofs())
            .map(|k| format!("u{}", first + k + 1))
            .collect();
        (q, u)
    }

    /// Turns locked degrees of freedom into parameters: a locked
    /// translation moves the joint point by a constant, a locked rotation
    /// becomes a constant rotation of the joint.
    #[allow(clippy::type_complexity)]
    fn apply_locks(
        &mut self,
        mut spec: BodySpec,
    ) -> Result<(BodySpec, Vec<(usize, ExprId)>), ModelError> {
        if !spec.locked.iter().any(|l| *l) {
            return Ok((spec, Vec::new()));
        }
        let mut locked_params = Vec::new();
        let name = spec.name.clone();
        let nt = spec.translations.len();
        let dofs = spec.dofs();
        if spec.locked.len() != dofs {
            return Err(ModelError::Invalid(format!(
                "body `{name}`: {} lock flags for {dofs} degrees of freedom",
                spec.locked.len()
            )));
        }
        let rot_locked: Vec<bool> = spec.locked[nt..].to_vec();
        if spec.quaternion && rot_locked.iter().any(|l| *l) {
            return Err(ModelError::Invalid(format!(
                "body `{name}`: a quaternion orientation cannot be locked; lock all three angles of `rotate: [1, 2, 3]` instead"
            )));
        }
        if rot_locked.len() == 3 && rot_locked.iter().any(|l| *l) && !rot_locked.iter().all(|l| *l)
        {
            return Err(ModelError::Invalid(format!(
                "body `{name}`: lock all three rotations of the body or none (its speeds are angular velocity components)"
            )));
        }
        let zero = self.arena.zero();
        let defaults = crate::expr::Bindings::with_defaults(&self.arena);
        let mut keep = Vec::new();
        let mut joint = spec.joint.unwrap_or([zero; 3]);
        let mut fixed = Vec::new();
        for k in 0..dofs {
            let global_hint = self.coordinates.len() + k + 1;
            let qn = spec
                .coordinate_names
                .as_ref()
                .map(|v| v[k].clone())
                .unwrap_or_else(|| format!("q{global_hint}"));
            if !spec.locked[k] {
                keep.push(k);
                continue;
            }
            let init = spec
                .initial_coordinates
                .as_ref()
                .and_then(|v| v.get(k).copied())
                .unwrap_or(zero);
            let value = self
                .arena
                .eval(init, &defaults, &mut crate::expr::NoUserFunctions);
            let unit = if k < nt { "m" } else { "rad" };
            let p =
                self.parameter_or_default(&qn, if value.is_finite() { value } else { 0.0 }, unit)?;
            locked_params.push((k, p));
            if k < nt {
                let d = self.direction(&name, &spec.translations[k])?;
                for i in 0..3 {
                    let t = self.arena.mul(d[i], p);
                    joint[i] = self.arena.add(joint[i], t);
                }
            } else {
                fixed.push((spec.rotations[k - nt], p));
            }
        }
        let pick = |v: &[_]| keep.iter().map(|k| v[*k]).collect::<Vec<_>>();
        spec.joint = Some(joint);
        spec.fixed_rotations.extend(fixed);
        let translations: Vec<Direction> = keep
            .iter()
            .filter(|k| **k < nt)
            .map(|k| spec.translations[*k].clone())
            .collect();
        // A quaternion has no rotation axes (and its rotation is never locked).
        let rotations: Vec<i64> = keep
            .iter()
            .filter(|k| **k >= nt && !spec.quaternion)
            .map(|k| spec.rotations[*k - nt])
            .collect();
        spec.translations = translations;
        spec.rotations = rotations;
        let quaternion = spec.quaternion;
        spec.coordinate_names = spec
            .coordinate_names
            .map(|v| kept_coordinates(&v, &keep, nt, quaternion));
        spec.speed_names = spec
            .speed_names
            .map(|v| keep.iter().map(|k| v[*k].clone()).collect());
        spec.initial_coordinates = spec
            .initial_coordinates
            .map(|v| kept_coordinates(&v, &keep, nt, quaternion));
        spec.initial_speeds = spec.initial_speeds.map(|v| pick(&v));
        if !spec.small.is_empty() {
            spec.small = keep.iter().map(|k| spec.small[*k]).collect();
        }
        spec.locked = Vec::new();
        Ok((spec, locked_params))
    }

    fn validate(&self, spec: &BodySpec) -> Result<(), ModelError> {
        let name = &spec.name;
        if spec.quaternion && !spec.rotations.is_empty() {
            return Err(ModelError::Invalid(format!(
                "body `{name}`: give either rotation axes or a quaternion, not both"
            )));
        }
        if spec.quaternion && spec.small.iter().skip(spec.translations.len()).any(|s| *s) {
            return Err(ModelError::Invalid(format!(
                "body `{name}`: quaternion coordinates cannot be small; use `rotate: [1, 2, 3]` with small angles"
            )));
        }
        if !matches!(spec.rotations.len(), 0 | 1 | 3) {
            return Err(ModelError::RotationCount {
                body: name.clone(),
                count: spec.rotations.len(),
            });
        }
        for &a in &spec.rotations {
            if !(1..=3).contains(&a) {
                return Err(ModelError::AxisOutOfRange {
                    body: name.clone(),
                    axis: a,
                });
            }
        }
        if spec.rotations.len() == 3
            && (spec.rotations[0] == spec.rotations[1] || spec.rotations[1] == spec.rotations[2])
        {
            return Err(ModelError::Invalid(format!(
                "body `{name}`: consecutive rotations about the same axis ({:?}) do not define an orientation; use a sequence such as [1, 2, 3] or [3, 1, 3]",
                spec.rotations
            )));
        }
        if spec.translations.len() > 3 {
            return Err(ModelError::TranslationCount {
                body: name.clone(),
                count: spec.translations.len(),
            });
        }
        for d in &spec.translations {
            if let Direction::Axis(a) = d
                && !(1..=3).contains(a)
            {
                return Err(ModelError::AxisOutOfRange {
                    body: name.clone(),
                    axis: *a,
                });
            }
        }
        let dofs = spec.dofs();
        let ncoord = spec.coordinate_count();
        for (what, names, expected) in [
            ("coordinate", &spec.coordinate_names, ncoord),
            ("speed", &spec.speed_names, dofs),
        ] {
            if let Some(v) = names
                && v.len() != expected
            {
                return Err(ModelError::NameCount {
                    body: name.clone(),
                    what,
                    expected,
                    got: v.len(),
                });
            }
        }
        for (what, vals, expected) in [
            ("initial coordinate", &spec.initial_coordinates, ncoord),
            ("initial speed", &spec.initial_speeds, dofs),
        ] {
            if let Some(v) = vals {
                if v.len() != expected {
                    return Err(ModelError::NameCount {
                        body: name.clone(),
                        what,
                        expected,
                        got: v.len(),
                    });
                }
                if v.iter().any(|x| !self.arena.is_constant(*x)) {
                    return Err(ModelError::NotConstant {
                        what: format!("{what} values of body `{name}`"),
                    });
                }
            }
        }
        if !spec.small.is_empty() && spec.small.len() != dofs {
            return Err(ModelError::Invalid(format!(
                "body `{name}`: {} small flags for {dofs} degrees of freedom",
                spec.small.len()
            )));
        }
        Ok(())
    }

    /// A unit direction in the parent's axes.
    fn direction(&mut self, body: &str, d: &Direction) -> Result<[ExprId; 3], ModelError> {
        let zero = self.arena.zero();
        let one = self.arena.one();
        match d {
            Direction::Axis(a) => {
                let mut c = [zero; 3];
                c[(*a - 1) as usize] = one;
                Ok(c)
            }
            Direction::Vector(v) => {
                if v.iter().any(|x| !self.arena.is_constant(*x)) {
                    return Err(ModelError::NotConstant {
                        what: format!("translation direction of body `{body}`"),
                    });
                }
                if v.iter().all(|x| self.arena.is_zero(*x)) {
                    return Err(ModelError::ZeroDirection {
                        body: body.to_string(),
                    });
                }
                let sq: Vec<ExprId> = v.iter().map(|x| self.arena.powi(*x, 2)).collect();
                let s = self.arena.sum(&sq);
                let len = self.arena.sqrt(s);
                Ok(v.map(|x| self.arena.div(x, len)))
            }
        }
    }

    /// The vector from the parent's origin to the joint, parent axes:
    /// joint point plus translations.
    pub(crate) fn joint_offset(
        &mut self,
        parent_frame: FrameId,
        joint: &[ExprId; 3],
        directions: &[[ExprId; 3]],
        qs: &[crate::expr::SymId],
    ) -> Fv {
        let mut c = *joint;
        for (k, d) in directions.iter().enumerate() {
            let q = self.arena.sym(qs[k]);
            for i in 0..3 {
                let t = self.arena.mul(d[i], q);
                c[i] = self.arena.add(c[i], t);
            }
        }
        Fv::new(parent_frame, c)
    }

    /// The frame of a body oriented by Euler parameters, and the rates of
    /// `e1, e2, e3` (`e0` becomes an added state with its own rate).
    ///
    /// `C_ij = b_i · a_j` in terms of `e0..e3`, and `de/dt = ½ e ⊗ (0, ω)`
    /// with `ω` the angular velocity relative to the parent in body axes.
    fn quaternion_frame(
        &mut self,
        spec: &BodySpec,
        frame: &mut FrameId,
        syms: &[(crate::expr::SymId, crate::expr::SymId, crate::expr::SymId)],
        w: &[ExprId; 3],
    ) -> Result<[ExprId; 3], ModelError> {
        let name = &spec.name;
        let nt = spec.translations.len();
        let e0_name = spec
            .coordinate_names
            .as_ref()
            .map(|v| v[nt].clone())
            .unwrap_or_else(|| format!("{name}_e0"));
        if self.arena.symbol_named(&e0_name).is_some() || self.body_named(&e0_name).is_some() {
            return Err(ModelError::DuplicateName(e0_name));
        }
        let one = self.arena.one();
        let e0_init = spec
            .initial_coordinates
            .as_ref()
            .and_then(|v| v.get(nt).copied())
            .unwrap_or(one);
        let e0s = self.add_state(&e0_name, Some("1"), e0_init)?;
        let e = [
            self.arena.sym(e0s),
            self.arena.sym(syms[0].0),
            self.arena.sym(syms[1].0),
            self.arena.sym(syms[2].0),
        ];
        let a = &mut self.arena;
        let sq = e.map(|x| a.powi(x, 2));
        let two = crate::expr::Number::int(2);
        let mut pr = |i: usize, j: usize| a.mul(e[i], e[j]);
        let (e01, e02, e03, e12, e13, e23) =
            (pr(0, 1), pr(0, 2), pr(0, 3), pr(1, 2), pr(1, 3), pr(2, 3));
        let lin = |a: &mut crate::expr::Arena, p: ExprId, m: ExprId| {
            let d = a.sub(p, m);
            a.scale(two, d)
        };
        let plus = |a: &mut crate::expr::Arena, p: ExprId, m: ExprId| {
            let d = a.add(p, m);
            a.scale(two, d)
        };
        let diag = |a: &mut crate::expr::Arena, k: usize| {
            let mut terms = vec![sq[0]];
            for (i, s) in sq.iter().enumerate().skip(1) {
                terms.push(if i == k { *s } else { a.neg(*s) });
            }
            a.sum(&terms)
        };
        let c = [
            [diag(a, 1), plus(a, e12, e03), lin(a, e13, e02)],
            [lin(a, e12, e03), diag(a, 2), plus(a, e23, e01)],
            [plus(a, e13, e02), lin(a, e23, e01), diag(a, 3)],
        ];
        let prefix = name.to_lowercase();
        *frame = self
            .frames
            .add_general(&mut self.arena, *frame, c, name, &prefix);
        // Rates: ė0 = -½ (e1 ω1 + e2 ω2 + e3 ω3), ė = ½ (e0 ω + e × ω).
        let a = &mut self.arena;
        let half = crate::expr::Number::rational(1, 2).unwrap_or(crate::expr::Number::ONE);
        let mut rate = |terms: [(ExprId, ExprId, i64); 3]| {
            let parts: Vec<ExprId> = terms
                .iter()
                .map(|(x, y, s)| {
                    let p = a.mul(*x, *y);
                    a.scale(crate::expr::Number::int(*s), p)
                })
                .collect();
            let sum = a.sum(&parts);
            a.scale(half, sum)
        };
        let e0dot = rate([(e[1], w[0], -1), (e[2], w[1], -1), (e[3], w[2], -1)]);
        let e1dot = rate([(e[0], w[0], 1), (e[2], w[2], 1), (e[3], w[1], -1)]);
        let e2dot = rate([(e[0], w[1], 1), (e[3], w[0], 1), (e[1], w[2], -1)]);
        let e3dot = rate([(e[0], w[2], 1), (e[1], w[1], 1), (e[2], w[0], -1)]);
        self.set_state_derivative(e0s, e0dot)?;
        Ok([e1dot, e2dot, e3dot])
    }

    /// dq/dt of three body-fixed rotations from the angular velocity
    /// components: q̇ = E⁻¹ ω with E's rows from cross products of the
    /// rotation axes (`det = e1 · (e2 × e3)`).
    fn euler_rates(
        &mut self,
        _name: &str,
        axes: &[usize],
        rot_frames: &[FrameId],
        parent_frame: FrameId,
        body_frame: FrameId,
        w_rel: &[ExprId; 3],
    ) -> Result<[ExprId; 3], ModelError> {
        let e1u = self.frames.frame(parent_frame).triad[axes[0]];
        let e2u = self.frames.frame(rot_frames[0]).triad[axes[1]];
        let e3u = self.frames.frame(rot_frames[1]).triad[axes[2]];
        let e = [e1u, e2u, e3u].map(|u| Vector::uv(&mut self.arena, u));
        let w = self.frames.vector_in(&mut self.arena, body_frame, *w_rel);
        let c23 = self.frames.cross_vec(&mut self.arena, &e[1], &e[2]);
        let c31 = self.frames.cross_vec(&mut self.arena, &e[2], &e[0]);
        let c12 = self.frames.cross_vec(&mut self.arena, &e[0], &e[1]);
        let det = self.frames.dot_vec(&mut self.arena, &e[0], &c23);
        let mut out = [self.arena.zero(); 3];
        for (k, c) in [c23, c31, c12].iter().enumerate() {
            let n = self.frames.dot_vec(&mut self.arena, c, &w);
            out[k] = self.arena.div(n, det);
        }
        Ok(out)
    }
}

/// The entries of a per-coordinate list (names, initial values) for the
/// kept degrees of freedom `keep`: a quaternion's four coordinates (after
/// the `nt` translations, one more than its speeds) stay whole, as its
/// rotation is never locked.
fn kept_coordinates<T: Clone>(v: &[T], keep: &[usize], nt: usize, quaternion: bool) -> Vec<T> {
    if quaternion {
        let translations = keep.iter().filter(|k| **k < nt).map(|k| v[*k].clone());
        translations.chain(v[nt..].iter().cloned()).collect()
    } else {
        keep.iter().map(|k| v[*k].clone()).collect()
    }
}
