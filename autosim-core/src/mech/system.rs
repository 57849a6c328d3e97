//! The multibody system and the API that builds it: parameters, inputs,
//! user functions and subroutines, bodies, points, forces, moments, gravity,
//! added state variables and outputs.

use super::error::ModelError;
use super::frames::{FrameId, Frames};
use super::framevec::{Fv, Mat3};
use super::joint::{Axis, DofKind, Joint};
use super::vector::Vector;
use crate::expr::{Arena, ExprId, SymId, SymbolKind, UserFnId};

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
    pub fixed_rotations: Vec<(Axis, ExprId)>,
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
    /// Absolute velocity of the origin, body axes.
    pub v0: Fv,
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

/// A force on a point of a body, with an optional equal and opposite
/// reaction on a point of another body.
#[derive(Clone, Debug)]
pub struct Force {
    /// Name.
    pub name: String,
    /// Where it acts (with +vector).
    pub point: PointId,
    /// Where the reaction acts (with -vector).
    pub reaction: Option<PointId>,
    /// The force vector.
    pub vector: Vector,
}

/// A moment on a body, with an optional reaction on another body.
#[derive(Clone, Debug)]
pub struct Moment {
    /// Name.
    pub name: String,
    /// The body it acts on (with +vector).
    pub body: BodyId,
    /// The body that takes the reaction (with -vector).
    pub reaction: Option<BodyId>,
    /// The moment vector.
    pub vector: Vector,
}

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
    pub(crate) inputs: Vec<SymId>,
    pub(crate) parameters: Vec<SymId>,
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
            v0: w,
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
            inputs: Vec::new(),
            parameters: Vec::new(),
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

    /// Declares a parameter with its default value and unit.
    pub fn add_parameter(
        &mut self,
        name: &str,
        default: f64,
        unit: Option<&str>,
    ) -> Result<SymId, ModelError> {
        self.check_new_name(name)?;
        let s = self
            .arena
            .add_symbol(name, SymbolKind::Parameter { default })?;
        self.arena.set_unit(s, unit.map(str::to_string));
        self.parameters.push(s);
        Ok(s)
    }

    /// The parameter named `name`, declaring it with `default` if it does not
    /// exist (used for default masses and inertias).
    pub(crate) fn parameter_or_default(
        &mut self,
        name: &str,
        default: f64,
        unit: &str,
    ) -> Result<ExprId, ModelError> {
        if let Some(s) = self.arena.symbol_named(name) {
            if self.arena.symbol(s).is_constant() {
                return Ok(self.arena.sym(s));
            }
            return Err(ModelError::DuplicateName(name.to_string()));
        }
        let s = self.add_parameter(name, default, Some(unit))?;
        Ok(self.arena.sym(s))
    }

    /// Declares an input, supplied at run time.
    pub fn add_input(
        &mut self,
        name: &str,
        default: f64,
        unit: Option<&str>,
    ) -> Result<SymId, ModelError> {
        self.check_new_name(name)?;
        let s = self.arena.add_symbol(name, SymbolKind::Input { default })?;
        self.arena.set_unit(s, unit.map(str::to_string));
        self.inputs.push(s);
        Ok(s)
    }

    /// Declares a user function (one value, may keep state).
    pub fn add_user_function(&mut self, name: &str, arity: usize) -> Result<UserFnId, ModelError> {
        self.check_new_name(name)?;
        Ok(self.arena.add_user_fn(name, arity)?)
    }

    /// Declares a user subroutine called with `args` that sets the named
    /// outputs; returns the output symbols.
    pub fn add_subroutine(
        &mut self,
        name: &str,
        args: Vec<ExprId>,
        outputs: &[(&str, Option<&str>)],
    ) -> Result<Vec<SymId>, ModelError> {
        self.check_new_name(name)?;
        if self.subroutines.iter().any(|s| s.name == name) {
            return Err(ModelError::DuplicateName(name.to_string()));
        }
        let sub = self.subroutines.len();
        let mut syms = Vec::with_capacity(outputs.len());
        for (index, (out, unit)) in outputs.iter().enumerate() {
            self.check_new_name(out)?;
            let s = self
                .arena
                .add_symbol(out, SymbolKind::ExternOutput { sub, index })?;
            self.arena.set_unit(s, unit.map(str::to_string));
            syms.push(s);
        }
        self.subroutines.push(Subroutine {
            name: name.to_string(),
            args,
            outputs: syms.clone(),
        });
        Ok(syms)
    }

    /// Sets the argument expressions of subroutine `index` (declaration order).
    pub fn set_subroutine_args(
        &mut self,
        index: usize,
        args: Vec<ExprId>,
    ) -> Result<(), ModelError> {
        let sub = self
            .subroutines
            .get_mut(index)
            .ok_or_else(|| ModelError::Invalid("unknown subroutine".to_string()))?;
        sub.args = args;
        Ok(())
    }

    /// Sets the initial value of an added state variable.
    pub fn set_state_initial(&mut self, s: SymId, initial: ExprId) -> Result<(), ModelError> {
        let st = self
            .states
            .iter_mut()
            .find(|x| x.sym == s)
            .ok_or_else(|| ModelError::Invalid("not an added state variable".to_string()))?;
        st.initial = initial;
        Ok(())
    }

    /// Uniform gravity: the acceleration vector of free fall (e.g. `-g n3`).
    pub fn set_gravity(&mut self, g: Vector) {
        self.gravity = if g.is_zero() { None } else { Some(g) };
    }

    /// Declares an added state variable with its initial value; give its
    /// derivative with [`System::set_state_derivative`].
    pub fn add_state(
        &mut self,
        name: &str,
        unit: Option<&str>,
        initial: ExprId,
    ) -> Result<SymId, ModelError> {
        self.check_new_name(name)?;
        let index = self.states.len();
        let s = self.arena.add_symbol(name, SymbolKind::State { index })?;
        self.arena.set_unit(s, unit.map(str::to_string));
        self.states.push(ExtraState {
            sym: s,
            derivative: None,
            initial,
        });
        Ok(s)
    }

    /// Sets d/dt of an added state variable.
    pub fn set_state_derivative(&mut self, s: SymId, derivative: ExprId) -> Result<(), ModelError> {
        let st = self
            .states
            .iter_mut()
            .find(|x| x.sym == s)
            .ok_or_else(|| ModelError::Invalid("not an added state variable".to_string()))?;
        st.derivative = Some(derivative);
        self.arena.set_dxdt(s, derivative);
        Ok(())
    }

    /// Adds an output variable.
    pub fn add_output(
        &mut self,
        name: &str,
        unit: Option<&str>,
        expr: ExprId,
    ) -> Result<(), ModelError> {
        if self.outputs.iter().any(|o| o.name == name) {
            return Err(ModelError::DuplicateName(name.to_string()));
        }
        self.outputs.push(Output {
            name: name.to_string(),
            unit: unit.map(str::to_string),
            description: None,
            expr,
        });
        Ok(())
    }

    /// Sets the description of the most recent output.
    pub fn describe_last_output(&mut self, description: &str) {
        if let Some(o) = self.outputs.last_mut() {
            o.description = Some(description.to_string());
        }
    }

    /// Adds a point of `body` at `coordinates` (body axes, from its origin).
    pub fn add_point(
        &mut self,
        name: &str,
        body: BodyId,
        coordinates: [ExprId; 3],
    ) -> Result<PointId, ModelError> {
        self.check_new_name(name)?;
        if body.index() >= self.bodies.len() {
            return Err(ModelError::Invalid("unknown body id".to_string()));
        }
        Ok(self.push_point(name, body, coordinates))
    }

    pub(crate) fn push_point(
        &mut self,
        name: &str,
        body: BodyId,
        coordinates: [ExprId; 3],
    ) -> PointId {
        self.points.push(Point {
            name: name.to_string(),
            description: None,
            body,
            coordinates,
        });
        PointId(self.points.len() as u32 - 1)
    }

    /// Sets a point's description.
    pub fn describe_point(&mut self, p: PointId, description: &str) {
        if let Some(pt) = self.points.get_mut(p.index()) {
            pt.description = Some(description.to_string());
        }
    }

    /// A new load named `name` on the items `ids` (of `count`, called
    /// `what`): forces and moments share one namespace.
    fn check_load(
        &self,
        name: &str,
        ids: impl IntoIterator<Item = usize>,
        count: usize,
        what: &str,
    ) -> Result<(), ModelError> {
        if self.forces.iter().any(|f| f.name == name) || self.moments.iter().any(|m| m.name == name)
        {
            return Err(ModelError::DuplicateName(name.to_string()));
        }
        match ids.into_iter().all(|i| i < count) {
            true => Ok(()),
            false => Err(ModelError::Invalid(format!("unknown {what} id"))),
        }
    }

    /// Adds a force `vector` at `point`, with `-vector` at `reaction`.
    pub fn add_force(
        &mut self,
        name: &str,
        point: PointId,
        reaction: Option<PointId>,
        vector: Vector,
    ) -> Result<(), ModelError> {
        let ids = std::iter::once(point).chain(reaction).map(PointId::index);
        self.check_load(name, ids, self.points.len(), "point")?;
        let name = name.to_string();
        self.forces.push(Force {
            name,
            point,
            reaction,
            vector,
        });
        Ok(())
    }

    /// Adds a moment `vector` on `body`, with `-vector` on `reaction`.
    pub fn add_moment(
        &mut self,
        name: &str,
        body: BodyId,
        reaction: Option<BodyId>,
        vector: Vector,
    ) -> Result<(), ModelError> {
        let ids = std::iter::once(body).chain(reaction).map(BodyId::index);
        self.check_load(name, ids, self.bodies.len(), "body")?;
        let name = name.to_string();
        self.moments.push(Moment {
            name,
            body,
            reaction,
            vector,
        });
        Ok(())
    }

    // ----- lookups -----

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

    /// The absolute angular velocity of a frame (basis-free).
    pub fn frame_angular_velocity(&self, f: FrameId) -> &Vector {
        &self.frame_w[f.index()]
    }
}
