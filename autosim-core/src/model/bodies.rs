//! `body` items: parents ordered and checked (unknown parents, cycles),
//! each body's options turned into a [`BodySpec`], and the body added
//! through the `mech` API, whose errors are mapped to the options' spans.

use super::body_options::items;
use super::scope::{Named, Resolver};
use crate::diag::{Diagnostic, Span};
use crate::mech::{BodyField, BodySpec, Joint, ModelError, Rotation, order_parents_first};
use crate::syntax::ast::{self, BodyKey, Expr};

impl<'a> Resolver<'a> {
    /// Adds all bodies, parents first.
    pub fn add_bodies(&mut self, bodies: &[&'a ast::Body]) {
        // A body whose name is refused (reported) is not added.
        let declared: Vec<bool> = bodies
            .iter()
            .map(|b| self.declare(&b.name, Named::Body(None)))
            .collect();
        let (parents, parent_ok) = self.parents(bodies, declared);
        let ordered = order_parents_first(&parents);
        for cycle in &ordered.cycles {
            self.report_cycle(bodies, cycle);
        }
        for i in ordered.order {
            let b = bodies[i];
            let parent = parents[i].map_or("N".to_string(), |j| bodies[j].name.text.clone());
            // A bad parent, a failed parent (already reported), or options
            // that fail: the body is not added.
            if parent_ok[i]
                && self.sys.body_named(&parent).is_some()
                && let Some(spec) = self.body_spec(b, parent)
            {
                self.add_body(b, spec);
            }
            if self.sys.body_named(&b.name.text).is_none() {
                self.names_of_failed_bodies.extend(declared_names(b));
                let named = |key| b.options.get(key).is_some();
                if !named(BodyKey::Q) || !named(BodyKey::U) {
                    self.failed_body_with_default_names = true;
                }
            }
        }
        // Unit-vector shorthands: `b1` for body `B`, `n1` for N.
        for (id, body) in self.sys.bodies().iter().enumerate() {
            for axis in crate::mech::Axis::ALL {
                let short = format!("{}{}", body.name.to_lowercase(), axis.to_number());
                if !self.names.contains_key(&short) {
                    self.uv_short
                        .insert(short, (crate::mech::BodyId(id as u32), axis));
                }
            }
        }
    }

    /// The names of a body's locked degrees of freedom: the coordinate is
    /// the parameter it became, the speed is zero (named as the mech
    /// layer named them: the given names, else `q<k>`/`u<k>` counted as
    /// the coordinate was).
    fn declare_locked(
        &mut self,
        b: &ast::Body,
        spec: &BodySpec,
        id: crate::mech::BodyId,
        before: usize,
    ) {
        let dofs = self.sys.body(id).dofs.clone();
        for (k, locked) in spec.locked.iter().enumerate() {
            let Some((q, _)) = dofs.get(k).copied().filter(|_| *locked) else {
                continue;
            };
            let given =
                |names: &Option<Vec<String>>| names.as_ref().and_then(|v| v.get(k).cloned());
            let un = given(&spec.speed_names).unwrap_or_else(|| format!("u{}", before + k + 1));
            if let Some(p) = self.sys.arena.as_symbol(q) {
                let qn = self.sys.arena.symbol(p).name.clone();
                self.names
                    .entry(qn)
                    .or_insert((Named::Symbol(p), b.name.span));
            }
            let zero = self.sys.arena.zero();
            self.names
                .entry(un)
                .or_insert((Named::Constant(zero), b.name.span));
        }
    }

    /// The parent of each body (index among `bodies`, `None` for `N` or an
    /// unknown parent), and whether it is usable.
    fn parents(
        &mut self,
        bodies: &[&ast::Body],
        declared: Vec<bool>,
    ) -> (Vec<Option<usize>>, Vec<bool>) {
        let mut parents: Vec<Option<usize>> = vec![None; bodies.len()];
        let mut ok = declared;
        for (i, b) in bodies.iter().enumerate() {
            let Some(opt) = b.options.get(BodyKey::Parent) else {
                continue;
            };
            let Expr::Name(p) = &opt.value else {
                self.error(
                    opt.value.span(),
                    "`parent` must be the name of a body (or `N`)",
                );
                ok[i] = false;
                continue;
            };
            if p.text == "N" {
                continue;
            }
            match bodies.iter().position(|x| x.name.text == p.text) {
                Some(j) => parents[i] = Some(j),
                None => {
                    self.body_by_name(p);
                    ok[i] = false;
                }
            }
        }
        (parents, ok)
    }

    fn report_cycle(&mut self, bodies: &[&ast::Body], cycle: &[usize]) {
        let names: Vec<String> = cycle
            .iter()
            .chain(cycle.first())
            .map(|k| format!("`{}`", bodies[*k].name.text))
            .collect();
        let first = bodies[cycle[0]];
        let span = first
            .options
            .get(BodyKey::Parent)
            .map(|o| o.value.span())
            .unwrap_or(first.name.span);
        self.push(
            Diagnostic::error(
                span,
                format!("the parents of bodies form a cycle: {}", names.join(" -> ")),
            )
            .help("every chain of parents must end at `N`"),
        );
    }

    /// Adds the body, declaring its coordinates and speeds, or reports
    /// every mistake `mech` finds in it.
    fn add_body(&mut self, b: &ast::Body, spec: BodySpec) {
        let parameters_before = self.sys.parameters().len();
        let coordinates_before = self.sys.coordinates().len();
        let states_before = self.sys.states().len();
        match self.sys.add_body(spec.clone()) {
            Ok(id) => {
                for &p in &self.sys.parameters()[parameters_before..] {
                    let name = self.sys.arena.symbol(p).name.clone();
                    self.implicit_parameters.push((name, b.name.span));
                }
                for c in self.sys.body(id).coordinates.clone() {
                    let coord = self.sys.coordinates()[c].clone();
                    for s in [coord.q, coord.u] {
                        let name = self.sys.arena.symbol(s).name.clone();
                        self.names.insert(name, (Named::Symbol(s), b.name.span));
                    }
                }
                // A quaternion's scalar part `e0`, a state the body adds.
                for state in &self.sys.states()[states_before..] {
                    let name = self.sys.arena.symbol(state.sym).name.clone();
                    self.names
                        .insert(name, (Named::Symbol(state.sym), b.name.span));
                }
                self.declare_locked(b, &spec, id, coordinates_before);
                self.names
                    .insert(b.name.text.clone(), (Named::Body(Some(id)), b.name.span));
            }
            Err(first) => {
                let mut errors = self.sys.body_errors(&spec);
                if errors.is_empty() {
                    errors.push(first);
                }
                for e in errors {
                    let span = field_span(b, &e);
                    let help = e.help().map(str::to_string);
                    let mut d = Diagnostic::error(span, e.local_message());
                    if let Some(h) = help {
                        d = d.help(h);
                    }
                    self.push(d);
                }
            }
        }
    }

    fn body_spec(&mut self, b: &ast::Body, parent: String) -> Option<BodySpec> {
        let name = b.name.text.clone();
        let mut spec = BodySpec::new(&name, &parent);
        spec.description = b.label.as_ref().map(|l| l.text.clone());
        let mut ok = true;
        for opt in &b.options.entries {
            let v = &opt.value;
            let good = match opt.key {
                BodyKey::Parent | BodyKey::Small | BodyKey::Lock | BodyKey::Reference => true,
                BodyKey::Joint => store(
                    &mut spec.joint_point,
                    self.list3(v, "the joint point", true),
                ),
                BodyKey::Cm => store(&mut spec.cm, self.list3(v, "the mass center", true)),
                BodyKey::Mass => store(&mut spec.mass, self.constant(v, "the mass")),
                BodyKey::Inertia => store(&mut spec.inertia, self.inertia(v)),
                BodyKey::Rotate => self
                    .rotation(b, v)
                    .map(|r| spec.joint.rotation = r)
                    .is_some(),
                BodyKey::Translate => self
                    .translations(v)
                    .map(|t| spec.joint.translations = t)
                    .is_some(),
                BodyKey::Q => store(
                    &mut spec.coordinate_names,
                    self.names_list(v, "coordinate names"),
                ),
                BodyKey::U => store(&mut spec.speed_names, self.names_list(v, "speed names")),
                BodyKey::Initial => store(
                    &mut spec.initial_coordinates,
                    self.constants_list(v, "initial coordinates"),
                ),
                BodyKey::InitialSpeeds => store(
                    &mut spec.initial_speeds,
                    self.constants_list(v, "initial speeds"),
                ),
            };
            ok &= good;
        }
        if let Some(opt) = b.options.get(BodyKey::Reference)
            && !matches!(
                spec.joint.rotation,
                Rotation::About {
                    reference: Some(_),
                    ..
                }
            )
            && ok
        {
            self.push(
                Diagnostic::error(
                    opt.value.span(),
                    "`reference` only applies to a rotation about a direction",
                )
                .help("write the rotation as `rotate: [[x, y, z]]`, or remove `reference`"),
            );
            ok = false;
        }
        ok &= self.flags(b, &mut spec);
        ok.then_some(spec)
    }

    /// `rotate: quaternion`, `rotate: [[x, y, z]]` (with the body's
    /// `reference`), or 0, 1 or 3 axes.
    fn rotation(&mut self, b: &ast::Body, v: &Expr) -> Option<Rotation> {
        let body = &b.name.text;
        if let Expr::Name(n) = v
            && n.text == "quaternion"
        {
            return Some(Rotation::Quaternion);
        }
        if let Expr::List { items, .. } = v
            && let [direction @ Expr::List { .. }] = items.as_slice()
        {
            let d = self.list3(direction, "a rotation axis", true);
            let r = match b.options.get(BodyKey::Reference) {
                Some(opt) => Some(self.list3(&opt.value, "a reference direction", true)?),
                None => None,
            };
            return Some(Rotation::about(d?, r, &self.sys.arena));
        }
        let axes = self.axes(v, "a rotation axis")?;
        let rotation = Rotation::from_axes(&axes);
        if rotation.is_none() {
            self.push(
                Diagnostic::error(
                    v.span(),
                    format!("body `{body}` has {} rotations", axes.len()),
                )
                .help("a body rotates 0, 1 or 3 times: `rotate: 3` or `rotate: [1, 2, 3]`"),
            );
        }
        rotation
    }

    /// The body's `small` and `lock` flags, with the scene's added; `false`
    /// if one was reported.
    fn flags(&mut self, b: &ast::Body, spec: &mut BodySpec) -> bool {
        let mut ok = true;
        // `small` and `lock` may name default coordinates (`q9`); the
        // counts are checked by `mech`, so mismatched names are left to it.
        let coordinates = spec
            .coordinate_names
            .clone()
            .unwrap_or_else(|| self.sys.default_names(spec).0);
        let joint: Joint = spec.joint.clone();
        if let Some(opt) = b.options.get(BodyKey::Small) {
            match self.dof_flags(&opt.value, &spec.name, &joint, &coordinates) {
                Some(flags) => spec.small = flags,
                None => ok = false,
            }
        }
        if let Some(opt) = b.options.get(BodyKey::Lock) {
            match self.dof_flags(&opt.value, &spec.name, &joint, &coordinates) {
                Some(flags) => spec.locked = flags,
                None => ok = false,
            }
        }
        // The scene's `small` and `lock` add to the body's own.
        for (names, is_lock) in [
            (self.scene.small.clone(), false),
            (self.scene.lock.clone(), true),
        ] {
            let (flags, matched) =
                crate::model::Scene::flags(&names, &spec.name, &coordinates, &joint);
            if matched.is_empty() {
                continue;
            }
            self.scene_matched.extend(matched);
            let target = if is_lock {
                &mut spec.locked
            } else {
                &mut spec.small
            };
            if target.is_empty() {
                *target = vec![false; joint.dofs()];
            }
            for (t, f) in target.iter_mut().zip(flags) {
                *t |= f;
            }
        }
        ok
    }
}

/// Where a body's mistake is written: the option it is about (the item of
/// a list, where it is about one), else the body's name.
fn field_span(b: &ast::Body, e: &ModelError) -> Span {
    let ModelError::Body { field, .. } = e else {
        return b.name.span;
    };
    let key = match field {
        BodyField::Translations | BodyField::Translation(_) => BodyKey::Translate,
        BodyField::Rotation => BodyKey::Rotate,
        BodyField::Reference => BodyKey::Reference,
        BodyField::FixedRotation(_) => return b.name.span,
        BodyField::JointPoint => BodyKey::Joint,
        BodyField::Cm => BodyKey::Cm,
        BodyField::Mass => BodyKey::Mass,
        BodyField::Inertia => BodyKey::Inertia,
        BodyField::Small => BodyKey::Small,
        BodyField::Lock => BodyKey::Lock,
        BodyField::CoordinateNames => BodyKey::Q,
        BodyField::SpeedNames => BodyKey::U,
        BodyField::InitialCoordinates => BodyKey::Initial,
        BodyField::InitialSpeeds => BodyKey::InitialSpeeds,
    };
    let Some(opt) = b.options.get(key) else {
        return b.name.span;
    };
    match field {
        BodyField::Translation(k) => items(&opt.value)
            .get(*k)
            .map_or(opt.value.span(), |it| it.span()),
        _ => opt.value.span(),
    }
}

/// Puts `value` in `slot` if there is one; whether there was.
fn store<T>(slot: &mut Option<T>, value: Option<T>) -> bool {
    let given = value.is_some();
    if given {
        *slot = value;
    }
    given
}

/// The coordinate and speed names a body declares (`q: [...]`,
/// `u: [...]`), read without checking them, and its unit vectors'
/// shorthands (`b1` to `b3`).
fn declared_names(b: &ast::Body) -> Vec<String> {
    let axes = (1..=3).map(|k| format!("{}{k}", b.name.text.to_lowercase()));
    b.options
        .entries
        .iter()
        .filter(|o| matches!(o.key, BodyKey::Q | BodyKey::U))
        .flat_map(|o| items(&o.value))
        .filter_map(|e| match e {
            Expr::Name(n) => Some(n.text.clone()),
            _ => None,
        })
        .chain(axes)
        .collect()
}
