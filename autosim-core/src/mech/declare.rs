//! Declaring the items of a system through its API: parameters, inputs,
//! user functions and subroutines, added states, outputs, points, forces
//! and moments, gravity. Bodies are added in `body.rs`.

use super::error::ModelError;
use super::system::{BodyId, ExtraState, Load, Output, Point, PointId, Subroutine, System};
use super::vector::Vector;
use crate::expr::{ExprId, SymId, SymbolKind, UserFnId};

impl System {
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
        let s = self.add_run_time_value(name, SymbolKind::Input { default }, unit)?;
        self.inputs.push(s);
        Ok(s)
    }

    /// A new symbol of `kind` (an input or a discrete variable: a value
    /// set at run time) with its unit.
    pub(crate) fn add_run_time_value(
        &mut self,
        name: &str,
        kind: SymbolKind,
        unit: Option<&str>,
    ) -> Result<SymId, ModelError> {
        self.check_new_name(name)?;
        let s = self.arena.add_symbol(name, kind)?;
        self.arena.set_unit(s, unit.map(str::to_string));
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

    /// Replaces symbols in every output's value (the resolver's
    /// placeholders for values known only once every load is declared).
    pub fn substitute_in_outputs(&mut self, map: &rustc_hash::FxHashMap<SymId, ExprId>) {
        for o in &mut self.outputs {
            o.expr = self.arena.substitute(o.expr, map);
        }
    }

    /// Whether the model has constraints (not counting motions).
    pub fn has_constraints(&self) -> bool {
        !self.constraints.is_empty()
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

    /// A new load named `name` at `at` with its reaction, on items of a
    /// list of `count` (`index` gives their place, `what` their kind):
    /// forces and moments share one namespace.
    fn new_load<At: Copy>(
        &self,
        name: &str,
        (at, reaction): (At, Option<At>),
        vector: Vector,
        (index, count, what): (fn(At) -> usize, usize, &str),
    ) -> Result<Load<At>, ModelError> {
        if self.forces.iter().any(|f| f.name == name) || self.moments.iter().any(|m| m.name == name)
        {
            return Err(ModelError::DuplicateName(name.to_string()));
        }
        if std::iter::once(at)
            .chain(reaction)
            .any(|i| index(i) >= count)
        {
            return Err(ModelError::Invalid(format!("unknown {what} id")));
        }
        Ok(Load {
            name: name.to_string(),
            at,
            reaction,
            vector,
        })
    }

    /// Adds a force `vector` at `point`, with `-vector` at `reaction`.
    pub fn add_force(
        &mut self,
        name: &str,
        point: PointId,
        reaction: Option<PointId>,
        vector: Vector,
    ) -> Result<(), ModelError> {
        let points = (PointId::index as fn(_) -> _, self.points.len(), "point");
        let force = self.new_load(name, (point, reaction), vector, points)?;
        self.forces.push(force);
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
        let bodies = (BodyId::index as fn(_) -> _, self.bodies.len(), "body");
        let moment = self.new_load(name, (body, reaction), vector, bodies)?;
        self.moments.push(moment);
        Ok(())
    }
}
