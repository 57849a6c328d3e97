//! Translations: unit directions fixed in the parent, and the vector from
//! the parent's origin to the body's (joint point plus translations).

use super::Direction;
use crate::expr::{Arena, ExprId, SymId};
use crate::mech::error::{BodyField, ModelError};
use crate::mech::frames::FrameId;
use crate::mech::framevec::Fv;

/// Checks translation `k` against the ones before it: constant, not zero,
/// not along an axis already used.
pub(super) fn check(
    body: &str,
    k: usize,
    d: &Direction,
    before: &[Direction],
    arena: &Arena,
) -> Result<(), ModelError> {
    match d {
        Direction::Axis(a) if before.contains(d) => Err(ModelError::body(
            body,
            BodyField::Translation(k),
            format!("the body already translates along axis {}", a.to_number()),
        )
        .with_help("each translation needs a direction of its own")),
        Direction::Axis(_) => Ok(()),
        Direction::Vector(v) if v.iter().any(|x| !arena.is_constant(*x)) => {
            Err(ModelError::NotConstant {
                what: format!("translation direction of body `{body}`"),
            })
        }
        Direction::Vector(v) if v.iter().all(|x| arena.is_zero(*x)) => Err(ModelError::body(
            body,
            BodyField::Translation(k),
            "a translation direction cannot be the zero vector".to_string(),
        )),
        Direction::Vector(_) => Ok(()),
    }
}

/// The unit direction's components in the parent's axes (a vector is
/// normalized; it was checked to be constant and nonzero).
pub(crate) fn unit_direction(arena: &mut Arena, d: &Direction) -> [ExprId; 3] {
    match d {
        Direction::Axis(a) => {
            let mut c = [arena.zero(); 3];
            c[a.index()] = arena.one();
            c
        }
        Direction::Vector(v) => {
            let sq: Vec<ExprId> = v.iter().map(|x| arena.powi(*x, 2)).collect();
            let s = arena.sum(&sq);
            let len = arena.sqrt(s);
            v.map(|x| arena.div(x, len))
        }
    }
}

/// The vector from the parent's origin to the body's origin, in the
/// parent's axes: the joint point plus each translation's direction times
/// its coordinate.
pub(crate) fn joint_offset(
    arena: &mut Arena,
    parent_frame: FrameId,
    joint_point: &[ExprId; 3],
    directions: &[[ExprId; 3]],
    qs: &[SymId],
) -> Fv {
    let mut c = *joint_point;
    for (k, d) in directions.iter().enumerate() {
        let q = arena.sym(qs[k]);
        for i in 0..3 {
            let t = arena.mul(d[i], q);
            c[i] = arena.add(c[i], t);
        }
    }
    Fv::new(parent_frame, c)
}
