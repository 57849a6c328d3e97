//! Checking a body before it is added: the one validation of body
//! specifications. Errors say which option is at fault ([`BodyField`]), so
//! the resolver can point at its text; the API returns them as they are.

use super::error::{BodyField, ModelError};
use super::system::{BodyId, BodySpec, System};
use crate::expr::ExprId;

impl System {
    /// The parent of a new body, after checking the body's name.
    pub(crate) fn body_parent(&self, spec: &BodySpec) -> Result<BodyId, ModelError> {
        let name = &spec.name;
        if name == "N" {
            return Err(ModelError::InertialFrame(
                "`N` is the inertial frame and cannot be declared as a body".to_string(),
            ));
        }
        self.check_new_name(name)?;
        if name == "t" {
            return Err(ModelError::DuplicateName(name.clone()));
        }
        self.body_named(&spec.parent)
            .ok_or_else(|| ModelError::UnknownBody(spec.parent.clone()))
    }

    /// The default coordinate and speed names of the next body: `q<k>` and
    /// `u<k>`, counting every degree of freedom declared so far (locked ones
    /// too), and `<Body>_e0` for a quaternion's scalar part.
    pub fn default_names(&self, spec: &BodySpec) -> (Vec<String>, Vec<String>) {
        spec.joint.default_names(&spec.name, self.declared_dofs)
    }

    /// Every mistake of a body specification, in itself and against the
    /// system (names taken, values that must be constant); empty if it can
    /// be added.
    pub fn body_errors(&self, spec: &BodySpec) -> Vec<ModelError> {
        let mut errors = Vec::new();
        spec.joint.check(&spec.name, &self.arena, &mut errors);
        self.check_lists(spec, &mut errors);
        self.check_constants(spec, &mut errors);
        self.check_mass_properties(spec, &mut errors);
        if errors.is_empty()
            && let Err(e) = self.check_names(spec)
        {
            errors.push(e);
        }
        errors
    }

    /// The per-degree-of-freedom lists: as long as they must be, constant
    /// initial values, no small quaternion.
    fn check_lists(&self, spec: &BodySpec, errors: &mut Vec<ModelError>) {
        let name = &spec.name;
        let dofs = spec.dofs();
        let ncoord = spec.coordinate_count();
        let has = |expected: usize| match expected == dofs {
            true => format!(
                "{dofs} degree{} of freedom",
                if dofs == 1 { "" } else { "s" }
            ),
            false => format!("{expected} coordinates (a quaternion has e0 to e3)"),
        };
        let lengths = [
            (
                BodyField::CoordinateNames,
                "coordinate names",
                spec.coordinate_names.as_ref().map(Vec::len),
                ncoord,
            ),
            (
                BodyField::SpeedNames,
                "speed names",
                spec.speed_names.as_ref().map(Vec::len),
                dofs,
            ),
            (
                BodyField::InitialCoordinates,
                "initial coordinates",
                spec.initial_coordinates.as_ref().map(Vec::len),
                ncoord,
            ),
            (
                BodyField::InitialSpeeds,
                "initial speeds",
                spec.initial_speeds.as_ref().map(Vec::len),
                dofs,
            ),
        ];
        for (field, what, len, expected) in lengths {
            if let Some(len) = len
                && len != expected
            {
                let message = format!(
                    "body `{name}` has {}, but {len} {what} were given",
                    has(expected)
                );
                errors.push(ModelError::body(name, field, message));
            }
        }
        for (field, values) in [
            (BodyField::InitialCoordinates, &spec.initial_coordinates),
            (BodyField::InitialSpeeds, &spec.initial_speeds),
        ] {
            if values.iter().flatten().any(|x| !self.arena.is_constant(*x)) {
                let what = if field == BodyField::InitialSpeeds {
                    "initial speed"
                } else {
                    "initial coordinate"
                };
                errors.push(ModelError::NotConstant {
                    what: format!("{what} values of body `{name}`"),
                });
            }
        }
        for (field, flags, what) in [
            (BodyField::Small, &spec.small, "small"),
            (BodyField::Lock, &spec.locked, "lock"),
        ] {
            if !flags.is_empty() && flags.len() != dofs {
                let message = format!(
                    "body `{name}`: {} {what} flags for {dofs} degrees of freedom",
                    flags.len()
                );
                errors.push(ModelError::body(name, field, message));
            }
        }
        if spec.joint.is_quaternion()
            && spec
                .small
                .iter()
                .skip(spec.joint.translations.len())
                .any(|s| *s)
        {
            let message = format!(
                "body `{name}`: quaternion coordinates cannot be small; use `rotate: [1, 2, 3]` with small angles"
            );
            errors.push(ModelError::body(name, BodyField::Small, message));
        }
    }

    /// Masses and moments of inertia are not negative, and the inertia
    /// matrix is symmetric.
    fn check_mass_properties(&self, spec: &BodySpec, errors: &mut Vec<ModelError>) {
        let negative = |x: ExprId| self.arena.as_number(x).is_some_and(|n| n.is_negative());
        let name = &spec.name;
        let fix = "masses and moments of inertia are zero or positive";
        if spec.mass.is_some_and(negative) {
            errors.push(
                ModelError::body(
                    name,
                    BodyField::Mass,
                    "a mass cannot be negative".to_string(),
                )
                .with_help(fix),
            );
        }
        let Some(m) = spec.inertia else { return };
        if (0..3).any(|k| negative(m[k][k])) {
            let message = "a moment of inertia cannot be negative".to_string();
            errors.push(ModelError::body(name, BodyField::Inertia, message).with_help(fix));
        }
        for i in 0..3 {
            for j in 0..i {
                if m[i][j] != m[j][i] {
                    let message = format!(
                        "the inertia matrix is not symmetric: entry ({}, {}) differs from ({}, {})",
                        i + 1,
                        j + 1,
                        j + 1,
                        i + 1
                    );
                    let help =
                        "entries are dyadic components about the mass center; I_jk must equal I_kj";
                    errors
                        .push(ModelError::body(name, BodyField::Inertia, message).with_help(help));
                    return;
                }
            }
        }
    }

    /// The names the body would declare (coordinates, speeds, rates, `e0`,
    /// default mass properties, locked coordinates' parameters) are free.
    fn check_names(&self, spec: &BodySpec) -> Result<(), ModelError> {
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
        let (default_q, default_u) = self.default_names(spec);
        let qn = spec.coordinate_names.clone().unwrap_or(default_q);
        let un = spec.speed_names.clone().unwrap_or(default_u);
        let mut new_names: Vec<String> = Vec::new();
        for k in 0..spec.dofs() {
            let q = &qn[spec.joint.coordinate_of_speed(k)];
            if spec.locked.get(k).copied().unwrap_or(false) {
                // A locked coordinate becomes (or reuses) a parameter.
                if taken(q) && !is_parameter(q) {
                    return Err(ModelError::DuplicateName(q.clone()));
                }
                continue;
            }
            new_names.extend([q.clone(), un[k].clone(), format!("{}_dot", un[k])]);
        }
        if let Some(e0) = spec.joint.e0_position() {
            new_names.push(qn[e0].clone());
        }
        for (i, n) in new_names.iter().enumerate() {
            if taken(n) || new_names[..i].contains(n) || *n == spec.name {
                return Err(ModelError::DuplicateName(n.clone()));
            }
        }
        let mut defaults = Vec::new();
        if spec.mass.is_none() {
            defaults.push(format!("M{}", spec.name));
        }
        if spec.inertia.is_none() {
            for j in 1..=3 {
                for k in j..=3 {
                    defaults.push(format!("I{}{j}{k}", spec.name));
                }
            }
        }
        match defaults.into_iter().find(|d| taken(d) && !is_parameter(d)) {
            Some(d) => Err(ModelError::DuplicateName(d)),
            None => Ok(()),
        }
    }

    /// The geometry and mass properties are constant (parameters and
    /// numbers only).
    fn check_constants(&self, spec: &BodySpec, errors: &mut Vec<ModelError>) {
        let name = &spec.name;
        let constant = |x: &ExprId| self.arena.is_constant(*x);
        for (what, c) in [
            ("joint coordinates", &spec.joint_point),
            ("mass center", &spec.cm),
        ] {
            if c.is_some_and(|c| !c.iter().all(constant)) {
                errors.push(ModelError::NotConstant {
                    what: format!("{what} of body `{name}`"),
                });
            }
        }
        let mass_ok = spec.mass.is_none_or(|m| constant(&m));
        let inertia_ok = spec
            .inertia
            .is_none_or(|i| i.iter().flatten().all(constant));
        if !mass_ok || !inertia_ok {
            errors.push(ModelError::NotConstant {
                what: format!("mass and inertia of body `{name}`"),
            });
        }
        if spec
            .fixed_rotations
            .iter()
            .any(|(_, angle)| !constant(angle))
        {
            errors.push(ModelError::NotConstant {
                what: format!("fixed rotation angle of body `{name}`"),
            });
        }
    }
}
