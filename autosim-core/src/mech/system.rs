//! The multibody system and the API that builds it: parameters, inputs,
//! user functions and subroutines, bodies, points, forces, moments, gravity,
//! added state variables and outputs.

use super::constraint::{Constraint, Motion};
use super::error::ModelError;
use super::frames::{FrameId, Frames};
use super::framevec::{Fv, Mat3};
use super::joint::{DofKind, FixedTurn, Joint};
use super::vector::Vector;
use crate::expr::{Arena, ExprId, SymId, SymbolKind};

crate::ids::id_type!(
    /// A body; `BodyId::N` is the inertial frame.
    BodyId,
    "body table (N is 0)"
);

impl BodyId {
    /// The inertial frame N.
    pub const N: BodyId = BodyId(0);
}

crate::ids::id_type!(
    /// A point fixed in (or moving relative to) a body.
    PointId,
    "point table"
);

/// What a body is made of and how it moves relative to its parent.
#[derive(Clone, Debug)]
pub struct BodySpec {
    /// Name, unique in the model.
    pub name: String,
    /// Descriptive name.
    pub description: Option<String>,
    /// Parent body name (`"N"` for the inertial frame).
    pub parent: String,
    /// Joint point: coordinates in the parent's axes from the parent's origin
    /// (default: the parent's origin).
    pub joint_point: Option<[ExprId; 3]>,
    /// How the body moves relative to its parent.
    pub joint: Joint,
    /// Constant rotations (axis, angle) applied at the joint before the
    /// free rotation (what locked rotations become).
    pub fixed_rotations: Vec<(FixedTurn, ExprId)>,
    /// Degrees of freedom locked at compile time (translations first, then
    /// rotations; empty means none): each becomes a parameter named after
    /// its coordinate, with its initial value as default, and has no speed.
    pub locked: Vec<bool>,
    /// Mass (default: parameter `M<name>`).
    pub mass: Option<ExprId>,
    /// Inertia matrix about the mass center in the body's axes (default:
    /// parameters `I<name>11`, `I<name>12`, ... `I<name>33`).
    pub inertia: Option<Mat3>,
    /// Mass center in the body's axes (default: the origin).
    pub cm: Option<[ExprId; 3]>,
    /// Which degrees of freedom are small (translations first, then
    /// rotations); empty means none.
    pub small: Vec<bool>,
    /// Names of the coordinates (default `q<k>` by global index); for a
    /// quaternion body the rotational names are `e0, e1, e2, e3`.
    pub coordinate_names: Option<Vec<String>>,
    /// Names of the speeds (default `u<k>`).
    pub speed_names: Option<Vec<String>>,
    /// Initial coordinate values (default 0; `e0 = 1` for a quaternion).
    pub initial_coordinates: Option<Vec<ExprId>>,
    /// Initial speed values (default 0).
    pub initial_speeds: Option<Vec<ExprId>>,
}

impl BodySpec {
    /// A body with no degrees of freedom and default mass properties.
    pub fn new(name: &str, parent: &str) -> BodySpec {
        BodySpec {
            name: name.to_string(),
            description: None,
            parent: parent.to_string(),
            joint_point: None,
            joint: Joint::fixed(),
            fixed_rotations: Vec::new(),
            locked: Vec::new(),
            mass: None,
            inertia: None,
            cm: None,
            small: Vec::new(),
            coordinate_names: None,
            speed_names: None,
            initial_coordinates: None,
            initial_speeds: None,
        }
    }

    /// Number of degrees of freedom (= speeds).
    pub fn dofs(&self) -> usize {
        self.joint.dofs()
    }

    /// Number of coordinates (one more than the speeds for a quaternion).
    pub fn coordinate_count(&self) -> usize {
        self.joint.coordinate_count()
    }
}

/// A generalized coordinate with its speed.
#[derive(Clone, Debug)]
pub struct Coordinate {
    /// The coordinate symbol.
    pub q: SymId,
    /// The generalized speed symbol.
    pub u: SymId,
    /// The symbol for du/dt.
    pub du: SymId,
    /// The body it moves.
    pub body: BodyId,
    /// Translation or rotation.
    pub kind: DofKind,
    /// dq/dt in terms of coordinates and speeds.
    pub qdot: ExprId,
    /// Initial value of q.
    pub initial_q: ExprId,
    /// Initial value of u.
    pub initial_u: ExprId,
    /// Whether the model declared the initial value (its body's
    /// `initial:`): the automatic choice of dependent coordinates avoids
    /// moving it.
    pub initial_declared: bool,
}

/// A body of the system.
#[derive(Clone, Debug)]
pub struct Body {
    /// Name.
    pub name: String,
    /// Descriptive name.
    pub description: Option<String>,
    /// Parent (`None` only for N).
    pub parent: Option<BodyId>,
    /// Children in order of creation.
    pub children: Vec<BodyId>,
    /// Depth in the tree (N is 0).
    pub level: u32,
    /// The body's frame (shared with the parent for non-rotating bodies).
    pub frame: FrameId,
    /// Joint point in the parent's axes.
    pub joint_point: [ExprId; 3],
    /// How the body moves relative to its parent (locked degrees of
    /// freedom removed).
    pub joint: Joint,
    /// Indices of the body's coordinates (translations, then rotations).
    pub coordinates: Vec<usize>,
    /// Every declared degree of freedom in order, as (coordinate, speed)
    /// expressions: the symbols of a free one, the parameter and 0 of a
    /// locked one.
    pub dofs: Vec<(ExprId, ExprId)>,
    /// Mass.
    pub mass: ExprId,
    /// Inertia matrix about the mass center, body axes.
    pub inertia: Mat3,
    /// Mass center, body axes.
    pub cm: [ExprId; 3],
    /// The origin (joint point) as a point of this body.
    pub origin: PointId,
    /// The mass center as a point of this body.
    pub cm_point: PointId,
    /// Absolute angular velocity, body axes.
    pub w: Fv,
    /// Absolute velocity of the origin, basis-free: each joint's part in
    /// the axes it arises in (a translation along its parent's axes, the
    /// parent's turning in the parent's axes), never rotated into this
    /// body's axes. A translating body's `vel` then reads `u_x n1 + ...`,
    /// not `u_x` spread over the rotated axes, whose projections back on N
    /// would be sums of squared direction cosines.
    pub v0: Vector,
}

/// A point.
#[derive(Clone, Debug)]
pub struct Point {
    /// Name.
    pub name: String,
    /// Descriptive name.
    pub description: Option<String>,
    /// The body it belongs to.
    pub body: BodyId,
    /// Coordinates in the body's axes from the body's origin (may vary).
    pub coordinates: [ExprId; 3],
}

/// A force or a moment: `vector` acting at `at` (a point for a force, a
/// body for a moment), with an optional equal and opposite reaction.
#[derive(Clone, Debug)]
pub struct Load<At> {
    /// Name.
    pub name: String,
    /// Where it acts (with +vector).
    pub at: At,
    /// Where the reaction acts (with -vector).
    pub reaction: Option<At>,
    /// The force or moment vector.
    pub vector: Vector,
}

/// A force on a point of a body, with an optional equal and opposite
/// reaction on a point of another body.
pub type Force = Load<PointId>;

/// A moment on a body, with an optional reaction on another body.
pub type Moment = Load<BodyId>;

/// An added state variable with its own differential equation.
#[derive(Clone, Debug)]
pub struct ExtraState {
    /// The state symbol.
    pub sym: SymId,
    /// d/dt of the state (set with [`System::set_state_derivative`]).
    pub derivative: Option<ExprId>,
    /// Initial value.
    pub initial: ExprId,
}

/// An output variable.
#[derive(Clone, Debug)]
pub struct Output {
    /// Name.
    pub name: String,
    /// Unit text.
    pub unit: Option<String>,
    /// Descriptive text.
    pub description: Option<String>,
    /// The value.
    pub expr: ExprId,
}

/// A user subroutine: called with argument expressions, it sets several
/// output symbols (the paper's `add-subroutine`).
#[derive(Clone, Debug)]
pub struct Subroutine {
    /// Name.
    pub name: String,
    /// Argument expressions.
    pub args: Vec<ExprId>,
    /// The symbols it sets.
    pub outputs: Vec<SymId>,
}

/// A multibody system under construction, and the analyses on it.
#[derive(Clone, Debug)]
pub struct System {
    /// All expressions of the model.
    pub arena: Arena,
    /// All frames and unit vectors.
    pub frames: Frames,
    pub(crate) name: String,
    pub(crate) bodies: Vec<Body>,
    pub(crate) points: Vec<Point>,
    pub(crate) coordinates: Vec<Coordinate>,
    pub(crate) frame_w: Vec<Vector>,
    pub(crate) forces: Vec<Force>,
    pub(crate) moments: Vec<Moment>,
    pub(crate) gravity: Option<Vector>,
    pub(crate) states: Vec<ExtraState>,
    pub(crate) outputs: Vec<Output>,
    pub(crate) subroutines: Vec<Subroutine>,
    pub(crate) constraints: Vec<Constraint>,
    /// The symbols outputs read for the load a constraint carries (its
    /// multiplier, `constraint_force`): (constraint index, symbol), given
    /// their values by the constrained lowering.
    pub(crate) constraint_forces: Vec<(usize, SymId)>,
    pub(crate) motions: Vec<Motion>,
    pub(crate) inputs: Vec<SymId>,
    pub(crate) parameters: Vec<SymId>,
    pub(crate) discrete: Vec<SymId>,
    pub(crate) events: Vec<super::event::Event>,
    pub(crate) time: SymId,
    /// Degrees of freedom declared so far, locked ones included: default
    /// names `q<k>`, `u<k>` count them, so locking one does not rename the
    /// others.
    pub(crate) declared_dofs: usize,
}

impl Default for System {
    fn default() -> Self {
        System::new("Model")
    }
}

impl System {
    /// An empty system with the inertial frame `N` and time `t`.
    pub fn new(name: &str) -> System {
        let mut arena = Arena::new();
        let mut frames = Frames::new();
        // `t` is the first symbol, so the name can never be taken.
        let time = arena.add_symbol("t", SymbolKind::Time).unwrap_or(SymId(0));
        arena.set_unit(time, Some("s".to_string()));
        let zero = arena.zero();
        let n_origin = PointId(0);
        let w = Fv::zero(&arena, FrameId::N);
        let n = Body {
            name: "N".to_string(),
            description: Some("inertial frame".to_string()),
            parent: None,
            children: Vec::new(),
            level: 0,
            frame: FrameId::N,
            joint_point: [zero; 3],
            joint: Joint::fixed(),
            coordinates: Vec::new(),
            dofs: Vec::new(),
            mass: zero,
            inertia: [[zero; 3]; 3],
            cm: [zero; 3],
            origin: n_origin,
            cm_point: n_origin,
            w,
            v0: Vector::zero(),
        };
        let _ = &mut frames;
        System {
            arena,
            frames,
            name: name.to_string(),
            bodies: vec![n],
            points: vec![Point {
                name: "N.origin".to_string(),
                description: None,
                body: BodyId::N,
                coordinates: [zero; 3],
            }],
            coordinates: Vec::new(),
            frame_w: vec![Vector::zero()],
            forces: Vec::new(),
            moments: Vec::new(),
            gravity: None,
            states: Vec::new(),
            outputs: Vec::new(),
            subroutines: Vec::new(),
            constraints: Vec::new(),
            constraint_forces: Vec::new(),
            motions: Vec::new(),
            inputs: Vec::new(),
            parameters: Vec::new(),
            discrete: Vec::new(),
            events: Vec::new(),
            time,
            declared_dofs: 0,
        }
    }

    /// The model's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The time symbol `t`.
    pub fn time(&self) -> SymId {
        self.time
    }

    /// Sets the small-term threshold (default 2); call before adding bodies.
    pub fn set_threshold(&mut self, threshold: i16) {
        self.arena.set_threshold(threshold);
    }

    pub(crate) fn check_new_name(&self, name: &str) -> Result<(), ModelError> {
        if self.arena.symbol_named(name).is_some()
            || self.body_named(name).is_some()
            || self.point_named(name).is_some()
            || self.arena.user_fn_named(name).is_some()
        {
            return Err(ModelError::DuplicateName(name.to_string()));
        }
        Ok(())
    }

    /// The body named `name` (`"N"` is the inertial frame).
    pub fn body_named(&self, name: &str) -> Option<BodyId> {
        self.bodies
            .iter()
            .position(|b| b.name == name)
            .map(|i| BodyId(i as u32))
    }

    /// The point named `name`.
    pub fn point_named(&self, name: &str) -> Option<PointId> {
        self.points
            .iter()
            .position(|p| p.name == name)
            .map(|i| PointId(i as u32))
    }

    /// A body.
    pub fn body(&self, b: BodyId) -> &Body {
        &self.bodies[b.index()]
    }

    /// All bodies (index 0 is N), parents before children.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// A point.
    pub fn point(&self, p: PointId) -> &Point {
        &self.points[p.index()]
    }

    /// All points.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// All generalized coordinates in order.
    pub fn coordinates(&self) -> &[Coordinate] {
        &self.coordinates
    }

    /// All forces.
    pub fn forces(&self) -> &[Force] {
        &self.forces
    }

    /// All moments.
    pub fn moments(&self) -> &[Moment] {
        &self.moments
    }

    /// Gravity, if set.
    pub fn gravity(&self) -> Option<&Vector> {
        self.gravity.as_ref()
    }

    /// Added state variables.
    pub fn states(&self) -> &[ExtraState] {
        &self.states
    }

    /// Output variables.
    pub fn outputs(&self) -> &[Output] {
        &self.outputs
    }

    /// User subroutines in declaration order.
    pub fn subroutines(&self) -> &[Subroutine] {
        &self.subroutines
    }

    /// Inputs in declaration order.
    pub fn inputs(&self) -> &[SymId] {
        &self.inputs
    }

    /// Parameters in declaration order (including default masses and
    /// inertias created for bodies).
    pub fn parameters(&self) -> &[SymId] {
        &self.parameters
    }
}
