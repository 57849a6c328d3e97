//! Constraints and prescribed motion (the paper's closed loops and
//! nonholonomic constraints, its reference 20): declared through the API
//! and checked here; their equations are formed with Kane's equations
//! (`kane/constraints.rs`).
//!
//! - A **position** constraint `g(q, t) = 0` restricts the configuration
//!   (a closed loop, a wheel touching the ground); its time derivative
//!   restricts the speeds.
//! - A **speed** constraint `c(q, u, t) = A u + b = 0`, linear in the
//!   speeds, restricts the motion only (a rolling wheel).
//! - A **motion** gives a coordinate as a function of time (a driven joint):
//!   the coordinate, its speed and its acceleration are known.
//!
//! Each constraint makes one speed dependent (and a position constraint
//! one coordinate), named by the user or chosen when the equations are
//! formed.

use super::error::ModelError;
use super::system::{BodyId, PointId, System};
use super::vector::Vector;
use crate::expr::{ExprId, SymId, SymbolKind};

/// What a constraint restricts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConstraintKind {
    /// The configuration: `g(q, t) = 0`.
    Position,
    /// The speeds: `A(q, t) u + b(q, t) = 0`.
    Speed,
}

/// A constraint of the system.
#[derive(Clone, Debug)]
pub struct Constraint {
    /// Name (unique among the model's items).
    pub name: String,
    /// Position or speed.
    pub kind: ConstraintKind,
    /// The expression that must vanish.
    pub value: ExprId,
    /// The coordinate (position constraint) or speed (speed constraint) the
    /// user chose to depend on it.
    pub dependent: Option<SymId>,
    /// The unit of the expression (a position constraint's residual is an
    /// output in this unit).
    pub unit: Option<String>,
}

/// Where a constraint's load acts, per unit of its multiplier `λ`: forces
/// at points and moments on bodies whose generalized force is the
/// constraint's row `A` (so `λ` times them does what `Aᵀ λ` does in
/// Kane's equations). The language reads it from the constraint's
/// expression when joint reactions need it.
#[derive(Clone, Debug, Default)]
pub struct ConstraintLoad {
    /// Forces per unit `λ`, each on the body of its point, at the point.
    pub forces: Vec<(PointId, Vector)>,
    /// Moments per unit `λ` on bodies.
    pub moments: Vec<(BodyId, Vector)>,
}

/// A coordinate given as a function of time.
#[derive(Clone, Debug)]
pub struct Motion {
    /// Name (an output of the generated model: the generalized force that
    /// enforces the motion).
    pub name: String,
    /// The coordinate's index.
    pub coordinate: usize,
    /// Its value, a function of time and parameters.
    pub value: ExprId,
}

impl System {
    /// Adds a constraint that `c.value` vanishes; `c.dependent` (optional)
    /// names the coordinate or speed it determines.
    pub fn add_constraint(&mut self, c: Constraint) -> Result<(), ModelError> {
        self.check_new_item_name(&c.name)?;
        self.check_constraint(&c.name, c.kind, c.value, c.dependent)?;
        self.constraints.push(c);
        Ok(())
    }

    /// Prescribes coordinate `q` as `value(t)`: it is known, with its speed
    /// and acceleration, and the generalized force that enforces it is an
    /// output named `name`.
    pub fn add_motion(&mut self, name: &str, q: SymId, value: ExprId) -> Result<(), ModelError> {
        self.check_new_item_name(name)?;
        let err = |key, (message, help): (String, &str)| ModelError::Option {
            item: name.to_string(),
            key,
            message,
            help: help.to_string(),
        };
        let q_name = self.arena.symbol(q).name.clone();
        let Some(k) = self.coordinates.iter().position(|c| c.q == q) else {
            let m = format!("`{q_name}` is not a generalized coordinate");
            return Err(err(
                "coordinate",
                (m, "name a coordinate of a body (as in its `q: [...]`)"),
            ));
        };
        let c = &self.coordinates[k];
        if c.qdot != self.arena.sym(c.u) {
            let m = format!(
                "`{q_name}` is not the integral of its speed (it is one of three rotations, or a quaternion)"
            );
            return Err(err(
                "coordinate",
                (
                    m,
                    "prescribe a single rotation or a translation: split the body's rotations into bodies of one rotation each",
                ),
            ));
        }
        if self.motions.iter().any(|m| m.coordinate == k) {
            let m = format!("`{q_name}` already has a motion");
            return Err(err("coordinate", (m, "remove one of the two motions")));
        }
        let state = self.arena.free_symbols(value).into_iter().find(|s| {
            !matches!(
                self.arena.symbol(*s).kind,
                SymbolKind::Time | SymbolKind::Parameter { .. }
            )
        });
        if let Some(s) = state {
            let m = format!(
                "a motion is a function of time and parameters, but this uses `{}`",
                self.arena.symbol(s).name
            );
            return Err(err(
                "value",
                (
                    m,
                    "write the value with `t` and parameters only; for a coupling between coordinates use a `constraint`",
                ),
            ));
        }
        self.motions.push(Motion {
            name: name.to_string(),
            coordinate: k,
            value,
        });
        Ok(())
    }

    /// The constraints, in declaration order.
    pub fn constraints(&self) -> &[Constraint] {
        &self.constraints
    }

    /// The prescribed motions, in declaration order.
    pub fn motions(&self) -> &[Motion] {
        &self.motions
    }

    /// Constraints, motions, loads and outputs are items with names of
    /// their own.
    fn check_new_item_name(&self, name: &str) -> Result<(), ModelError> {
        let taken = self.constraints.iter().any(|c| c.name == name)
            || self.motions.iter().any(|m| m.name == name)
            || self.outputs.iter().any(|o| o.name == name);
        match taken {
            true => Err(ModelError::DuplicateName(name.to_string())),
            false => self.check_new_name(name),
        }
    }

    /// A position constraint uses coordinates (or time) and no speeds; a
    /// speed constraint is linear in the speeds and uses one; a dependent
    /// is a coordinate or speed the constraint uses.
    fn check_constraint(
        &mut self,
        name: &str,
        kind: ConstraintKind,
        value: ExprId,
        dependent: Option<SymId>,
    ) -> Result<(), ModelError> {
        let key = match kind {
            ConstraintKind::Position => "position",
            ConstraintKind::Speed => "speed",
        };
        let at = |key, message, help: &str| ModelError::Option {
            item: name.to_string(),
            key,
            message,
            help: help.to_string(),
        };
        let err = |m: String, help: &str| at(key, m, help);
        if self.arena.is_constant(value) {
            return Err(err(
                "the constraint is constant (or identically zero): it restricts nothing"
                    .to_string(),
                "write an expression of the coordinates (position) or speeds (speed) that must vanish, or remove the constraint",
            ));
        }
        let symbols = self.arena.free_symbols(value);
        let kinds: Vec<SymbolKind> = self.arena.symbols().map(|(_, s)| s.kind.clone()).collect();
        let kind_of = |s: &SymId| kinds[s.index()].clone();
        if let Some(s) = symbols
            .iter()
            .find(|s| matches!(kind_of(s), SymbolKind::SpeedRate { .. }))
        {
            let n = &self.arena.symbol(*s).name;
            return Err(err(
                format!("a constraint cannot use the acceleration `{n}`"),
                "constrain positions or speeds; their accelerations follow",
            ));
        }
        if let Some(s) = symbols.iter().find(|s| {
            matches!(
                kind_of(s),
                SymbolKind::State { .. } | SymbolKind::ExternOutput { .. }
            )
        }) {
            let n = &self.arena.symbol(*s).name;
            return Err(err(
                format!("a constraint cannot use `{n}` (an added state or a subroutine's output)"),
                "constraints are on coordinates, speeds, time, parameters and inputs; the dependent speeds are solved before user subroutines are called",
            ));
        }
        let speeds: Vec<SymId> = symbols
            .iter()
            .copied()
            .filter(|s| matches!(kind_of(s), SymbolKind::Speed { .. }))
            .collect();
        match kind {
            ConstraintKind::Position => {
                if !symbols
                    .iter()
                    .any(|s| matches!(kind_of(s), SymbolKind::Coordinate { .. }))
                {
                    return Err(err(
                        "a position constraint must use a coordinate (it restricts the configuration)".to_string(),
                        "use `speed:` for a constraint on speeds",
                    ));
                }
                if let Some(s) = speeds.first() {
                    let n = &self.arena.symbol(*s).name;
                    return Err(err(
                        format!("a position constraint cannot use the speed `{n}`"),
                        "write it as a `speed:` constraint (linear in the speeds)",
                    ));
                }
            }
            ConstraintKind::Speed => {
                if speeds.is_empty() {
                    return Err(err(
                        "a speed constraint must use a speed".to_string(),
                        "write a constraint on coordinates as a `position:` constraint",
                    ));
                }
                for u in &speeds {
                    let d = self.arena.partial(value, *u)?;
                    if let Some(v) = self
                        .arena
                        .free_symbols(d)
                        .into_iter()
                        .find(|s| matches!(kind_of(s), SymbolKind::Speed { .. }))
                    {
                        let (a, b) = (&self.arena.symbol(*u).name, &self.arena.symbol(v).name);
                        return Err(err(
                            format!(
                                "the speed constraint is not linear in the speeds: its derivative by `{a}` uses `{b}`"
                            ),
                            "a speed constraint is `A(q, t) u + b(q, t)`: write a nonlinear condition on the configuration as a `position:` constraint",
                        ));
                    }
                }
            }
        }
        match dependent {
            Some(d) => self.check_dependent(name, kind, &symbols, d),
            None => Ok(()),
        }
    }

    /// The dependent a constraint names is a coordinate (position) or a
    /// speed (speed constraint) that the constraint uses.
    fn check_dependent(
        &self,
        name: &str,
        kind: ConstraintKind,
        symbols: &[SymId],
        d: SymId,
    ) -> Result<(), ModelError> {
        let at = |message, help: &str| ModelError::Option {
            item: name.to_string(),
            key: "dependent",
            message,
            help: help.to_string(),
        };
        let wanted = match kind {
            ConstraintKind::Position => "coordinate",
            ConstraintKind::Speed => "speed",
        };
        let right_kind = matches!(
            (kind, &self.arena.symbol(d).kind),
            (ConstraintKind::Position, SymbolKind::Coordinate { .. })
                | (ConstraintKind::Speed, SymbolKind::Speed { .. })
        );
        let n = &self.arena.symbol(d).name;
        if !right_kind {
            let help = match kind {
                ConstraintKind::Position => "a position constraint determines a coordinate",
                ConstraintKind::Speed => "a speed constraint determines a speed",
            };
            return Err(at(format!("the dependent `{n}` is not a {wanted}"), help));
        }
        if !symbols.contains(&d) {
            return Err(at(
                format!("the dependent {wanted} `{n}` does not appear in the constraint"),
                "name one the constraint uses, or leave `dependent` out to let the compiler choose",
            ));
        }
        Ok(())
    }
}
