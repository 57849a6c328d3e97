//! Joints: how a body moves relative to its parent (the paper's Tables 7-10).
//!
//! A [`Joint`] is up to three translations along directions fixed in the
//! parent, followed by a [`Rotation`]: none, one about an axis, a sequence
//! of three body-fixed rotations, Euler parameters, or one about a constant
//! direction of the parent. It owns the body's degrees of freedom: how many
//! there are and how they are named, their symbols, the frames they create
//! and the kinematical equations `dq/dt = f(q, u)` (`symbols.rs`), the
//! unit motion of each speed ([`DofKind`], `motion.rs`), the translations
//! (`translation.rs`) and what locking does (`lock.rs`). Each rotation kind
//! lives in a file of its own (`simple.rs`, `euler.rs`, `quaternion.rs`,
//! `about.rs`); adding a kind is a variant of [`Rotation`], its file, and
//! its arms in this one and in `symbols.rs`.

mod about;
mod euler;
mod lock;
mod motion;
mod quaternion;
mod simple;
mod symbols;
pub(crate) mod translation;

pub use motion::UnitMotion;
pub(crate) use symbols::{BuiltJoint, DofSymbols};

use super::error::{BodyField, ModelError};
use crate::expr::{Arena, ExprId};

/// An axis of a frame: `1`, `2` or `3` in the language and the paper,
/// stored 0-based.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Axis(u8);

impl Axis {
    /// Axis 1.
    pub const A1: Axis = Axis(0);
    /// Axis 2.
    pub const A2: Axis = Axis(1);
    /// Axis 3.
    pub const A3: Axis = Axis(2);
    /// The three axes in order.
    pub const ALL: [Axis; 3] = [Axis::A1, Axis::A2, Axis::A3];

    /// The axis numbered `k` (1, 2 or 3), if there is one.
    pub fn number(k: i64) -> Option<Axis> {
        match k {
            1..=3 => Some(Axis(k as u8 - 1)),
            _ => None,
        }
    }

    /// The axis at 0-based position `i` (taken modulo 3).
    pub fn from_index(i: usize) -> Axis {
        Axis((i % 3) as u8)
    }

    /// The 0-based index.
    pub fn index(self) -> usize {
        usize::from(self.0)
    }

    /// The 1-based number, as the language and messages write it.
    pub fn to_number(self) -> usize {
        self.index() + 1
    }

    /// The next two axes in cyclic order (`2, 3` for axis 1).
    pub fn others(self) -> (Axis, Axis) {
        (
            Axis::from_index(self.index() + 1),
            Axis::from_index(self.index() + 2),
        )
    }
}

/// A direction of translation, fixed in the parent.
#[derive(Clone, Debug, PartialEq)]
pub enum Direction {
    /// Along one of the parent's axes.
    Axis(Axis),
    /// Along a constant vector given by its components in the parent's axes
    /// (normalized).
    Vector([ExprId; 3]),
}

/// How a body turns relative to its parent, after its translations.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Rotation {
    /// It does not.
    #[default]
    None,
    /// About one of the parent's axes (shared with the body): one speed,
    /// `u = dq/dt`.
    Simple(Axis),
    /// Three body-fixed rotations in sequence (consecutive axes differ):
    /// three speeds, the angular velocity relative to the parent in the
    /// body's axes.
    Sequence([Axis; 3]),
    /// Euler parameters `e0..e3` (no singularity): three speeds as for a
    /// sequence, four coordinates of which `e0` is an extra state.
    Quaternion,
    /// About a constant direction fixed in the parent (components in the
    /// parent's axes, normalized): one speed, `u = dq/dt`. Without a
    /// `reference` the body's axes are the parent's at zero angle; with one,
    /// the body's nominal axes are the paper's Eq. 8 (axis 3 along the
    /// direction, axis 2 along `direction × reference`).
    About {
        /// The rotation axis, parent axes.
        direction: [ExprId; 3],
        /// The reference direction fixing the nominal orientation.
        reference: Option<[ExprId; 3]>,
    },
}

impl Rotation {
    /// The rotation about the axes `axes` (0, 1 or 3 of them); `None` for
    /// another count.
    pub fn from_axes(axes: &[Axis]) -> Option<Rotation> {
        match *axes {
            [] => Some(Rotation::None),
            [a] => Some(Rotation::Simple(a)),
            [a, b, c] => Some(Rotation::Sequence([a, b, c])),
            _ => None,
        }
    }

    /// Number of rotational degrees of freedom.
    pub fn dofs(&self) -> usize {
        match self {
            Rotation::None => 0,
            Rotation::Simple(_) | Rotation::About { .. } => 1,
            Rotation::Sequence(_) | Rotation::Quaternion => 3,
        }
    }

    /// The axes rotated about in sequence (none for Euler parameters).
    pub fn axes(&self) -> Vec<Axis> {
        match self {
            Rotation::None | Rotation::Quaternion | Rotation::About { .. } => Vec::new(),
            Rotation::Simple(a) => vec![*a],
            Rotation::Sequence(s) => s.to_vec(),
        }
    }
}

/// The motion a joint allows: translations, then a rotation.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Joint {
    /// Translations along directions fixed in the parent (0 to 3).
    pub translations: Vec<Direction>,
    /// The rotation after them.
    pub rotation: Rotation,
}

impl Joint {
    /// A joint without degrees of freedom (the body is fixed in its parent).
    pub fn fixed() -> Joint {
        Joint::default()
    }

    /// Number of degrees of freedom (= generalized speeds).
    pub fn dofs(&self) -> usize {
        self.translations.len() + self.rotation.dofs()
    }

    /// Number of coordinates (one more than the speeds for Euler
    /// parameters).
    pub fn coordinate_count(&self) -> usize {
        self.dofs() + usize::from(self.is_quaternion())
    }

    /// Whether the rotation is by Euler parameters.
    pub fn is_quaternion(&self) -> bool {
        self.rotation == Rotation::Quaternion
    }

    /// Where `e0` stands in the list of coordinate names of a quaternion
    /// joint (after the translations).
    pub fn e0_position(&self) -> Option<usize> {
        self.is_quaternion().then_some(self.translations.len())
    }

    /// The position in the coordinate list of the coordinate paired with
    /// speed `k` (a quaternion's `e1..e3` come after its `e0`).
    pub fn coordinate_of_speed(&self, k: usize) -> usize {
        match self.e0_position() {
            Some(e0) if k >= e0 => k + 1,
            _ => k,
        }
    }

    /// The speed paired with the coordinate at position `k` of the
    /// coordinate list (`None` for a quaternion's `e0`).
    pub fn speed_of_coordinate(&self, k: usize) -> Option<usize> {
        match self.e0_position() {
            Some(e0) if k == e0 => None,
            Some(e0) if k > e0 => (k - 1 < self.dofs()).then_some(k - 1),
            _ => (k < self.dofs()).then_some(k),
        }
    }

    /// Default coordinate and speed names: `q<k>` and `u<k>` numbered from
    /// `first + 1`, and `<Body>_e0` for a quaternion's scalar part.
    pub fn default_names(&self, body: &str, first: usize) -> (Vec<String>, Vec<String>) {
        let mut q: Vec<String> = (0..self.dofs())
            .map(|k| format!("q{}", first + k + 1))
            .collect();
        if let Some(e0) = self.e0_position() {
            q.insert(e0, format!("{body}_e0"));
        }
        let u = (0..self.dofs())
            .map(|k| format!("u{}", first + k + 1))
            .collect();
        (q, u)
    }

    /// Checks the joint's own structure (every mistake into `errors`): at
    /// most three translations, each along a constant, nonzero direction of
    /// its own; consecutive axes of a rotation sequence differ.
    pub fn check(&self, body: &str, arena: &Arena, errors: &mut Vec<ModelError>) {
        let n = self.translations.len();
        if n > 3 {
            errors.push(ModelError::body(
                body,
                BodyField::Translations,
                format!("{n} translations: a body translates at most 3 times"),
            ));
        }
        for (k, d) in self.translations.iter().enumerate() {
            if let Err(e) = translation::check(body, k, d, &self.translations[..k], arena) {
                errors.push(e);
            }
        }
        if let Rotation::About {
            direction,
            reference,
        } = &self.rotation
        {
            about_check(body, direction, reference.as_ref(), arena, errors);
        }
        if let Rotation::Sequence([a, b, c]) = self.rotation
            && (a == b || b == c)
        {
            errors.push(
                ModelError::body(
                    body,
                    BodyField::Rotation,
                    format!(
                        "body `{body}`: consecutive rotations about the same axis ([{}, {}, {}]) do not define an orientation",
                        a.to_number(),
                        b.to_number(),
                        c.to_number()
                    ),
                )
                .with_help("use a sequence such as [1, 2, 3] or [3, 1, 3]"),
            );
        }
    }
}

/// A constant turn of a joint, before its free rotation: what a locked
/// rotation becomes.
#[derive(Clone, Debug, PartialEq)]
pub enum FixedTurn {
    /// About one of the axes.
    Axis(Axis),
    /// About a constant direction (see [`Rotation::About`]).
    About {
        /// The direction, parent axes.
        direction: [ExprId; 3],
        /// The reference direction, if any.
        reference: Option<[ExprId; 3]>,
    },
}

/// A rotation about a direction needs a constant, nonzero direction, and a
/// constant reference direction that is not along it.
fn about_check(
    body: &str,
    direction: &[ExprId; 3],
    reference: Option<&[ExprId; 3]>,
    arena: &Arena,
    errors: &mut Vec<ModelError>,
) {
    let constant = |v: &[ExprId; 3]| v.iter().all(|x| arena.is_constant(*x));
    let zero = |v: &[ExprId; 3]| v.iter().all(|x| arena.is_zero(*x));
    if !constant(direction) || reference.is_some_and(|r| !constant(r)) {
        errors.push(ModelError::NotConstant {
            what: format!("rotation direction of body `{body}`"),
        });
        return;
    }
    if zero(direction) {
        errors.push(ModelError::body(
            body,
            BodyField::Rotation,
            "the rotation axis cannot be the zero vector".to_string(),
        ));
    }
    let Some(r) = reference else { return };
    // |d × r| at the parameters' default values.
    let defaults = crate::expr::Bindings::with_defaults(arena);
    let value = |x: ExprId| arena.eval(x, &defaults, &mut crate::expr::NoUserFunctions);
    let (d, r) = (direction.map(value), r.map(value));
    let cross: f64 = (0..3)
        .map(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            (d[j] * r[k] - d[k] * r[j]).powi(2)
        })
        .sum();
    let norms = d.iter().map(|x| x * x).sum::<f64>() * r.iter().map(|x| x * x).sum::<f64>();
    let parallel = cross.partial_cmp(&(1e-24 * norms)) != Some(std::cmp::Ordering::Greater);
    if parallel {
        errors.push(
            ModelError::body(
                body,
                BodyField::Reference,
                "the reference direction must not be zero or along the rotation axis".to_string(),
            )
            .with_help(
                "give a direction across the axis: the body's axis 2 is along `axis × reference`",
            ),
        );
    }
}

impl Rotation {
    /// A rotation about `direction` (parent axes): a simple rotation when it
    /// is one of the axes (sharing the axis makes products cheaper), else
    /// [`Rotation::About`].
    pub fn about(
        direction: [ExprId; 3],
        reference: Option<[ExprId; 3]>,
        arena: &Arena,
    ) -> Rotation {
        let positive_axis = direction
            .iter()
            .enumerate()
            .filter(|(_, x)| !arena.is_zero(**x))
            .map(|(i, x)| (i, arena.as_number(*x).is_some_and(|n| !n.is_negative())))
            .collect::<Vec<_>>();
        match (positive_axis.as_slice(), reference) {
            ([(i, true)], None) => Rotation::Simple(Axis::from_index(*i)),
            _ => Rotation::About {
                direction,
                reference,
            },
        }
    }

    /// The constant turns that lock this rotation, one per coordinate.
    pub(crate) fn locked_turns(&self) -> Vec<FixedTurn> {
        match self {
            Rotation::About {
                direction,
                reference,
            } => vec![FixedTurn::About {
                direction: *direction,
                reference: *reference,
            }],
            other => other.axes().into_iter().map(FixedTurn::Axis).collect(),
        }
    }
}

/// How a generalized speed moves its body.
#[derive(Clone, Debug, PartialEq)]
pub enum DofKind {
    /// Translation along a unit direction, components in the parent's axes.
    Translation {
        /// Unit direction in the parent's axes.
        direction: [ExprId; 3],
    },
    /// Rotation; the speed is the component of the body's angular velocity
    /// relative to its parent along the body's axis `axis`.
    Rotation {
        /// The body axis of the angular-velocity component.
        axis: Axis,
    },
    /// Rotation about a unit direction (components in the body's axes,
    /// which are also its components in the parent's): the speed is the
    /// angular velocity relative to the parent along it.
    RotationAbout {
        /// The unit direction.
        direction: [ExprId; 3],
    },
}
