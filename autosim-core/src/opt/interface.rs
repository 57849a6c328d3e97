//! What a generated model exposes, as data: the names, units, defaults,
//! docs and source spans of its parameters, inputs, states, outputs and
//! user code, and the layout of its state vector. The emitter and the
//! documentation read this and the program, nothing else.

use crate::diag::Span;
use crate::expr::{SymId, SymbolKind};
use crate::mech::Equations;
use crate::model::{FloatType, ResolvedModel};

/// One state variable.
#[derive(Clone, Debug, PartialEq)]
pub struct StateVar {
    /// Name in generated code.
    pub name: String,
    /// Unit text (empty when unknown).
    pub unit: String,
}

/// The state vector: generalized coordinates, then one generalized speed
/// per coordinate, then extra states (the model's `state` items and the
/// scalar part `e0` of quaternion bodies), in that order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StateLayout {
    /// Generalized coordinates.
    pub coordinates: Vec<StateVar>,
    /// Generalized speeds, one per coordinate.
    pub speeds: Vec<StateVar>,
    /// States with their own differential equations.
    pub extra: Vec<StateVar>,
}

impl StateLayout {
    /// Number of generalized speeds (= coordinates).
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
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
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
}

impl Interface {
    /// The interface of a resolved model with these equations.
    pub fn new(model: &ResolvedModel, eqs: &Equations) -> Interface {
        let sys = &model.system;
        let a = &sys.arena;
        let state = |s: &SymId| StateVar {
            name: a.symbol(*s).name.clone(),
            unit: a.symbol(*s).unit.clone().unwrap_or_default(),
        };
        let symbol = |s: &SymId| {
            let sym = a.symbol(*s);
            let default = match sym.kind {
                SymbolKind::Parameter { default } | SymbolKind::Input { default } => default,
                _ => 0.0,
            };
            model.quantity(&sym.name, sym.unit.as_deref(), default)
        };
        let outputs = sys
            .outputs()
            .iter()
            .map(|o| model.quantity(&o.name, o.unit.as_deref(), 0.0))
            .collect();
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
                coordinates: eqs.coordinates.iter().map(state).collect(),
                speeds: eqs.speeds.iter().map(state).collect(),
                extra: eqs.states.iter().map(state).collect(),
            },
            outputs,
            extern_fns,
            subroutines,
        }
    }

    /// Whether generated code calls user code (and so has an `Externs`
    /// type parameter).
    pub fn has_externs(&self) -> bool {
        !self.extern_fns.is_empty() || !self.subroutines.is_empty()
    }
}

impl ResolvedModel {
    /// The interface entry of a named value declared by the model.
    fn quantity(&self, name: &str, unit: Option<&str>, default: f64) -> Quantity {
        Quantity {
            name: name.to_string(),
            unit: unit.unwrap_or_default().to_string(),
            default,
            docs: self.item_docs.get(name).cloned(),
            span: self.spans.named(name),
        }
    }

    /// The interface entry of user code.
    fn user_code(&self, name: &str, outputs: Vec<String>) -> UserCode {
        UserCode {
            name: name.to_string(),
            params: self.formal_params.get(name).cloned().unwrap_or_default(),
            outputs,
            docs: self.item_docs.get(name).cloned().unwrap_or_default(),
            span: self.spans.named(name),
        }
    }
}
