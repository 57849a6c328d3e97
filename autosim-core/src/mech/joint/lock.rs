//! Locking degrees of freedom at compile time: each locked coordinate
//! becomes a parameter (its initial value the default); a locked
//! translation moves the joint point by a constant, a locked rotation
//! becomes a constant rotation of the joint.

use super::translation::unit_direction;
use super::{Joint, Rotation};
use crate::expr::{Bindings, ExprId, NoUserFunctions};
use crate::mech::error::{BodyField, ModelError};
use crate::mech::system::{BodySpec, System};

/// A locked degree of freedom: its index among the body's declared ones
/// and the parameter it became.
pub(crate) type Locked = Vec<(usize, ExprId)>;

impl System {
    /// The body without its locked degrees of freedom, and the parameters
    /// they became.
    pub(crate) fn apply_locks(
        &mut self,
        mut spec: BodySpec,
    ) -> Result<(BodySpec, Locked), ModelError> {
        if !spec.locked.iter().any(|l| *l) {
            return Ok((spec, Vec::new()));
        }
        check_locks(&spec)?;
        let nt = spec.joint.translations.len();
        let turns = spec.joint.rotation.locked_turns();
        let zero = self.arena.zero();
        let defaults = Bindings::with_defaults(&self.arena);
        let mut locked = Vec::new();
        let mut keep = Vec::new();
        let mut joint_point = spec.joint_point.unwrap_or([zero; 3]);
        for k in 0..spec.joint.dofs() {
            if !spec.locked[k] {
                keep.push(k);
                continue;
            }
            let qn = spec
                .coordinate_names
                .as_ref()
                .map(|v| v[k].clone())
                .unwrap_or_else(|| format!("q{}", self.coordinates.len() + k + 1));
            let init = spec
                .initial_coordinates
                .as_ref()
                .and_then(|v| v.get(k).copied())
                .unwrap_or(zero);
            let value = self.arena.eval(init, &defaults, &mut NoUserFunctions);
            let unit = if k < nt { "m" } else { "rad" };
            let value = if value.is_finite() { value } else { 0.0 };
            let p = self.parameter_or_default(&qn, value, unit)?;
            locked.push((k, p));
            if k < nt {
                let d = unit_direction(&mut self.arena, &spec.joint.translations[k]);
                for i in 0..3 {
                    let t = self.arena.mul(d[i], p);
                    joint_point[i] = self.arena.add(joint_point[i], t);
                }
            } else {
                spec.fixed_rotations.push((turns[k - nt].clone(), p));
            }
        }
        spec.joint_point = Some(joint_point);
        spec.joint = kept_joint(&spec.joint, &keep);
        keep_entries(&mut spec, &keep, nt);
        Ok((spec, locked))
    }
}

/// Locks must be possible: one flag per degree of freedom, no quaternion,
/// and a rotation sequence locked whole or not at all.
fn check_locks(spec: &BodySpec) -> Result<(), ModelError> {
    let name = &spec.name;
    let (nt, dofs) = (spec.joint.translations.len(), spec.joint.dofs());
    if spec.locked.len() != dofs {
        return Err(ModelError::Invalid(format!(
            "body `{name}`: {} lock flags for {dofs} degrees of freedom",
            spec.locked.len()
        )));
    }
    let rot_locked = &spec.locked[nt..];
    if spec.joint.is_quaternion() && rot_locked.iter().any(|l| *l) {
        return Err(ModelError::body(
            name,
            BodyField::Lock,
            format!(
                "body `{name}`: a quaternion orientation cannot be locked; lock all three angles of `rotate: [1, 2, 3]` instead"
            ),
        ));
    }
    if rot_locked.len() == 3 && rot_locked.iter().any(|l| *l) && !rot_locked.iter().all(|l| *l) {
        return Err(ModelError::body(
            name,
            BodyField::Lock,
            format!(
                "body `{name}`: lock all three rotations of the body or none (its speeds are angular velocity components)"
            ),
        ));
    }
    Ok(())
}

/// The joint with only the degrees of freedom `keep` (a rotation is kept
/// whole or dropped whole).
fn kept_joint(joint: &Joint, keep: &[usize]) -> Joint {
    let nt = joint.translations.len();
    let translations = keep
        .iter()
        .filter(|k| **k < nt)
        .map(|k| joint.translations[*k].clone())
        .collect();
    let rotation = match keep.iter().any(|k| *k >= nt) {
        true => joint.rotation.clone(),
        false => Rotation::None,
    };
    Joint {
        translations,
        rotation,
    }
}

/// The per-degree-of-freedom lists of `spec` (names, initial values,
/// smallness) for the kept degrees of freedom.
fn keep_entries(spec: &mut BodySpec, keep: &[usize], nt: usize) {
    let quaternion = spec.joint.is_quaternion();
    let pick = |v: &[_]| keep.iter().map(|k| v[*k]).collect::<Vec<_>>();
    spec.coordinate_names = spec
        .coordinate_names
        .take()
        .map(|v| kept_coordinates(&v, keep, nt, quaternion));
    spec.speed_names = spec
        .speed_names
        .take()
        .map(|v| keep.iter().map(|k| v[*k].clone()).collect());
    spec.initial_coordinates = spec
        .initial_coordinates
        .take()
        .map(|v| kept_coordinates(&v, keep, nt, quaternion));
    spec.initial_speeds = spec.initial_speeds.take().map(|v| pick(&v));
    if !spec.small.is_empty() {
        spec.small = keep.iter().map(|k| spec.small[*k]).collect();
    }
    spec.locked = Vec::new();
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
