//! What a generated model exposes, as data: the names, units, defaults,
//! docs and source spans of its parameters, inputs, states, outputs and
//! user code, and the layout of its state vector. The emitter and the
//! documentation read this and the program, nothing else.

use super::split::Split;
use crate::diag::Span;
use crate::expr::{SymId, SymbolKind};
use crate::mech::{ConstraintKind, Equations};
use crate::model::{FloatType, ResolvedModel};

/// One state variable.
#[derive(Clone, Debug, PartialEq)]
pub struct StateVar {
    /// Name in generated code.
    pub name: String,
    /// Unit text (empty when unknown).
    pub unit: String,
    /// The unit the unit check inferred, when none is declared (empty
    /// otherwise): shown in the documentation only.
    pub inferred_unit: String,
}

/// The state vector: generalized coordinates, then the independent
/// generalized speeds, then extra states (the model's `state` items and the
/// scalar part `e0` of quaternion bodies), in that order. A tree has one
/// speed per coordinate; a constrained model has fewer (the dependent
/// speeds are solved from the constraints), and a prescribed coordinate is
/// no state at all.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StateLayout {
    /// Generalized coordinates.
    pub coordinates: Vec<StateVar>,
    /// Independent generalized speeds.
    pub speeds: Vec<StateVar>,
    /// States with their own differential equations.
    pub extra: Vec<StateVar>,
}

impl StateLayout {
    /// Number of independent generalized speeds (= coordinates in a tree).
    pub fn n_speeds(&self) -> usize {
        self.speeds.len()
    }

    /// Length of the state vector.
    pub fn len(&self) -> usize {
        self.coordinates.len() + self.speeds.len() + self.extra.len()
    }

    /// `true` for a model without states.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every state in vector order.
    pub fn states(&self) -> impl Iterator<Item = &StateVar> {
        self.coordinates
            .iter()
            .chain(&self.speeds)
            .chain(&self.extra)
    }

    /// The state at position `i` of the vector.
    pub fn state(&self, i: usize) -> &StateVar {
        let (nq, nu) = (self.coordinates.len(), self.speeds.len());
        if i < nq {
            &self.coordinates[i]
        } else if i < nq + nu {
            &self.speeds[i - nq]
        } else {
            &self.extra[i - nq - nu]
        }
    }

    /// Position of speed `k` in the state vector.
    pub fn speed_slot(&self, k: usize) -> usize {
        self.coordinates.len() + k
    }

    /// The name of du/dt of speed `k` in generated code (`<speed>_dot`).
    pub fn speed_rate_name(&self, k: usize) -> String {
        format!("{}_dot", self.speeds[k].name)
    }
}

/// A named value of the interface: a parameter (a field of `Parameters`),
/// an input (of `Inputs`) or an output.
#[derive(Clone, Debug)]
pub struct Quantity {
    /// Name.
    pub name: String,
    /// Unit text (empty when none).
    pub unit: String,
    /// The unit the unit check inferred, when none is declared (empty
    /// otherwise): shown in the documentation only.
    pub inferred_unit: String,
    /// Default value (0 for outputs).
    pub default: f64,
    /// The model's doc comments; `None` for a parameter the compiler
    /// declared (a body's default mass or inertia).
    pub docs: Option<Vec<String>>,
    /// Where it is declared (the body, for a default mass property).
    pub span: Span,
}

/// User code the model calls: an `extern fn` (one value) or an `extern
/// sub` (an array of values), a method of the `Externs` trait.
#[derive(Clone, Debug)]
pub struct UserCode {
    /// Name.
    pub name: String,
    /// Formal argument names.
    pub params: Vec<String>,
    /// Names of the values a subroutine returns (empty for a function).
    pub outputs: Vec<String>,
    /// The declared unit of each argument (empty where none, and for a
    /// subroutine, whose arguments are expressions).
    pub param_units: Vec<String>,
    /// The declared unit of a function's result, or of each output of a
    /// subroutine (empty where none).
    pub result_units: Vec<String>,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
}

/// A constraint, as generated code and its documentation name it.
#[derive(Clone, Debug)]
pub struct ConstraintInfo {
    /// Name.
    pub name: String,
    /// Position or speed.
    pub kind: ConstraintKind,
    /// The speed it determines.
    pub dependent_speed: String,
    /// The coordinate it determines (position constraints).
    pub dependent_coordinate: Option<String>,
    /// Unit of its expression (empty when not given).
    pub unit: String,
    /// The unit the unit check inferred, when none is declared (empty
    /// otherwise): shown in the documentation only.
    pub inferred_unit: String,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
}

/// A prescribed motion.
#[derive(Clone, Debug)]
pub struct MotionInfo {
    /// Name (also the output of the generalized force that enforces it).
    pub name: String,
    /// The coordinate it drives.
    pub coordinate: String,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
}

/// What assembly solves: each position constraint (an index into
/// [`Interface::constraints`]) for its dependent coordinate (a position in
/// the state vector), in the order of the assembly block's slots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Closure {
    /// The position constraint.
    pub constraint: usize,
    /// Its dependent coordinate's position in the state vector.
    pub slot: usize,
}

/// Everything about a model's interface that generated code and its
/// documentation name.
#[derive(Clone, Debug)]
pub struct Interface {
    /// The model's name (the generated type).
    pub name: String,
    /// The model's doc comments.
    pub docs: Vec<String>,
    /// Float type of generated code.
    pub float: FloatType,
    /// Parameters in declaration order (`Leaf::Param` indices).
    pub parameters: Vec<Quantity>,
    /// Inputs in declaration order (`Leaf::Input` indices).
    pub inputs: Vec<Quantity>,
    /// The state vector (`Leaf::State` indices).
    pub states: StateLayout,
    /// Outputs in order (slots of the outputs block).
    pub outputs: Vec<Quantity>,
    /// User functions, by `UserFnId` index.
    pub extern_fns: Vec<UserCode>,
    /// User subroutines in declaration order.
    pub subroutines: Vec<UserCode>,
    /// Constraints in declaration order (`Guard::Regular` indices).
    pub constraints: Vec<ConstraintInfo>,
    /// Prescribed motions in declaration order.
    pub motions: Vec<MotionInfo>,
    /// The position constraints and their dependent coordinates, in the
    /// order of the assembly block's slots (empty without position
    /// constraints).
    pub closures: Vec<Closure>,
    /// The states of the linear model (state-vector positions; all but the
    /// dependent coordinates), when the linearization is generated.
    pub linear_states: Option<Vec<usize>>,
    /// Cautions for the user, printed in the model's documentation (e.g. a
    /// body whose initial angles sit on its rotation sequence's
    /// singularity).
    pub cautions: Vec<String>,
}

impl Interface {
    /// The interface of a resolved model with these equations, its speeds
    /// split as `split` says.
    pub fn new(model: &ResolvedModel, eqs: &Equations, split: &Split) -> Interface {
        let sys = &model.system;
        let a = &sys.arena;
        let state = |s: &SymId| StateVar {
            name: a.symbol(*s).name.clone(),
            unit: a.symbol(*s).unit.clone().unwrap_or_default(),
            inferred_unit: model.inferred_unit(&a.symbol(*s).name, a.symbol(*s).unit.as_deref()),
        };
        let symbol = |s: &SymId| {
            let sym = a.symbol(*s);
            let default = match sym.kind {
                SymbolKind::Parameter { default } | SymbolKind::Input { default } => default,
                _ => 0.0,
            };
            model.quantity(&sym.name, sym.unit.as_deref(), default)
        };
        let mut outputs: Vec<Quantity> = sys
            .outputs()
            .iter()
            .map(|o| model.quantity(&o.name, o.unit.as_deref(), 0.0))
            .collect();
        outputs.extend(model.constraint_outputs(eqs));
        let subroutines = sys
            .subroutines()
            .iter()
            .map(|s| {
                model.user_code(
                    &s.name,
                    s.outputs
                        .iter()
                        .map(|o| a.symbol(*o).name.clone())
                        .collect(),
                )
            })
            .collect();
        let extern_fns = a
            .user_fns()
            .map(|(_, f)| model.user_code(&f.name, Vec::new()))
            .collect();
        Interface {
            name: sys.name().to_string(),
            docs: model.docs.clone(),
            float: model.float,
            parameters: sys.parameters().iter().map(symbol).collect(),
            inputs: sys.inputs().iter().map(symbol).collect(),
            states: StateLayout {
                coordinates: split
                    .coordinates
                    .iter()
                    .map(|&k| state(&eqs.coordinates[k]))
                    .collect(),
                speeds: split.free.iter().map(|&k| state(&eqs.speeds[k])).collect(),
                extra: eqs.states.iter().map(state).collect(),
            },
            outputs,
            extern_fns,
            subroutines,
            constraints: model.constraint_infos(eqs),
            motions: model.motion_infos(),
            closures: closures(eqs, split),
            linear_states: None,
            cautions: model.singular_starts(),
        }
    }

    /// Whether generated code calls user code (and so has an `Externs`
    /// type parameter).
    pub fn has_externs(&self) -> bool {
        !self.extern_fns.is_empty() || !self.subroutines.is_empty()
    }
}

/// Each position constraint with the state slot of its dependent
/// coordinate, in assembly order.
fn closures(eqs: &Equations, split: &Split) -> Vec<Closure> {
    let c = &eqs.constraints;
    c.positions
        .iter()
        .zip(&c.dependent_coordinates)
        .map(|(&constraint, q)| Closure {
            constraint,
            slot: split.coordinates.iter().position(|k| k == q).unwrap_or(0),
        })
        .collect()
}

impl ResolvedModel {
    /// A note for every body whose three-angle rotation starts where its
    /// kinematical equations divide by zero: the middle angle at 0 (or π)
    /// for a repeated axis (3-1-3), at ±π/2 for three distinct axes
    /// (1-2-3). The first `derivatives` call would fail there.
    fn singular_starts(&self) -> Vec<String> {
        use crate::expr::{Bindings, NoUserFunctions};
        use crate::mech::Rotation;
        let sys = &self.system;
        let b = Bindings::with_defaults(&sys.arena);
        let mut notes = Vec::new();
        for body in sys.bodies() {
            let Rotation::Sequence([a, _, c]) = body.joint.rotation else {
                continue;
            };
            let n = body.coordinates.len();
            if n < 3 {
                continue;
            }
            let middle = &sys.coordinates()[body.coordinates[n - 2]];
            let angle = sys.arena.eval(middle.initial_q, &b, &mut NoUserFunctions);
            let (s, co) = angle.sin_cos();
            let singular = if a == c {
                s.abs() < 1e-9
            } else {
                co.abs() < 1e-9
            };
            if singular {
                let q = &sys.arena.symbol(middle.q).name;
                notes.push(format!(
                    "Body `{}` starts at a singularity of its rotation sequence ({q} = {angle}): its kinematical equations divide by zero there (the angle rates are not finite). Start it elsewhere (`initial: [...]`) or use `rotate: quaternion`.",
                    body.name
                ));
            }
        }
        notes
    }

    /// The constraints with their dependents.
    fn constraint_infos(&self, eqs: &Equations) -> Vec<ConstraintInfo> {
        let sys = &self.system;
        let name = |s: SymId| sys.arena.symbol(s).name.clone();
        let c = &eqs.constraints;
        sys.constraints()
            .iter()
            .enumerate()
            .map(|(k, con)| ConstraintInfo {
                name: con.name.clone(),
                kind: con.kind,
                dependent_speed: name(eqs.speeds[c.dependent_speeds[k]]),
                dependent_coordinate: c
                    .positions
                    .iter()
                    .position(|&p| p == k)
                    .map(|i| name(eqs.coordinates[c.dependent_coordinates[i]])),
                unit: con.unit.clone().unwrap_or_default(),
                inferred_unit: self.inferred_unit(&con.name, con.unit.as_deref()),
                docs: self.item_docs.get(&con.name).cloned().unwrap_or_default(),
                span: self.spans.named(&con.name),
            })
            .collect()
    }

    /// The prescribed motions.
    fn motion_infos(&self) -> Vec<MotionInfo> {
        let sys = &self.system;
        sys.motions()
            .iter()
            .map(|m| MotionInfo {
                name: m.name.clone(),
                coordinate: sys
                    .arena
                    .symbol(sys.coordinates()[m.coordinate].q)
                    .name
                    .clone(),
                docs: self.item_docs.get(&m.name).cloned().unwrap_or_default(),
                span: self.spans.named(&m.name),
            })
            .collect()
    }

    /// The outputs every constrained model adds after the model's own: the
    /// residual of each position constraint, then the generalized force
    /// that enforces each motion (N for a translation, N m for a
    /// rotation).
    fn constraint_outputs(&self, eqs: &Equations) -> Vec<Quantity> {
        let sys = &self.system;
        let mut out = Vec::new();
        for &k in &eqs.constraints.positions {
            let c = &sys.constraints()[k];
            out.push(Quantity {
                name: c.name.clone(),
                unit: c.unit.clone().unwrap_or_default(),
                inferred_unit: self.inferred_unit(&c.name, c.unit.as_deref()),
                default: 0.0,
                docs: Some(vec![format!(
                    "Residual of the position constraint `{}` (zero when the configuration satisfies it).",
                    c.name
                )]),
                span: self.spans.named(&c.name),
            });
        }
        for m in sys.motions() {
            let coordinate = &sys.coordinates()[m.coordinate];
            let unit = match sys.arena.symbol(coordinate.q).unit.as_deref() {
                Some("m") => "N",
                Some("rad") => "N m",
                _ => "",
            };
            let q = &sys.arena.symbol(coordinate.q).name;
            out.push(Quantity {
                name: m.name.clone(),
                unit: unit.to_string(),
                inferred_unit: String::new(),
                default: 0.0,
                docs: Some(vec![format!(
                    "Generalized force along `{q}` that enforces the motion `{}`.",
                    m.name
                )]),
                span: self.spans.named(&m.name),
            });
        }
        out
    }

    /// The unit inferred for `name` when `declared` is none (empty
    /// otherwise, and when its uses do not determine it).
    fn inferred_unit(&self, name: &str, declared: Option<&str>) -> String {
        match declared {
            Some(_) => String::new(),
            None => self.inferred_units.get(name).cloned().unwrap_or_default(),
        }
    }

    /// The interface entry of a named value declared by the model.
    fn quantity(&self, name: &str, unit: Option<&str>, default: f64) -> Quantity {
        Quantity {
            name: name.to_string(),
            unit: unit.unwrap_or_default().to_string(),
            inferred_unit: self.inferred_unit(name, unit),
            default,
            docs: self.item_docs.get(name).cloned(),
            span: self.spans.named(name),
        }
    }

    /// The interface entry of user code.
    fn user_code(&self, name: &str, outputs: Vec<String>) -> UserCode {
        let (param_units, result_units) =
            self.user_code_units.get(name).cloned().unwrap_or_default();
        UserCode {
            name: name.to_string(),
            params: self.formal_params.get(name).cloned().unwrap_or_default(),
            outputs,
            param_units,
            result_units,
            docs: self.item_docs.get(name).cloned().unwrap_or_default(),
            span: self.spans.named(name),
        }
    }
}
