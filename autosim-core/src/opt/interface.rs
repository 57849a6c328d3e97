//! What a generated model exposes, as data: the names, units, defaults,
//! docs and source spans of its parameters, inputs, states, outputs and
//! user code, and the layout of its state vector. The emitter and the
//! documentation read this and the program, nothing else.

use crate::diag::Span;
use crate::expr::{Arena, SymId, SymbolKind};
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

/// A parameter of the generated `Parameters` struct.
#[derive(Clone, Debug)]
pub struct ParameterInfo {
    /// Name (a field of `Parameters`).
    pub name: String,
    /// Unit text (empty when none).
    pub unit: String,
    /// Default value.
    pub default: f64,
    /// The model's doc comments; `None` for a parameter the compiler
    /// declared (a body's default mass or inertia).
    pub docs: Option<Vec<String>>,
    /// Where it is declared (the body, for a default mass property).
    pub span: Span,
}

/// An input of the generated `Inputs` struct.
#[derive(Clone, Debug)]
pub struct InputInfo {
    /// Name.
    pub name: String,
    /// Unit text.
    pub unit: String,
    /// Default value.
    pub default: f64,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
}

/// An output variable.
#[derive(Clone, Debug)]
pub struct OutputInfo {
    /// Name.
    pub name: String,
    /// Unit text.
    pub unit: String,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
}

/// A user function (`extern fn`): a method of the `Externs` trait.
#[derive(Clone, Debug)]
pub struct ExternFnInfo {
    /// Name.
    pub name: String,
    /// Formal argument names.
    pub params: Vec<String>,
    /// Doc comments.
    pub docs: Vec<String>,
    /// Where it is declared.
    pub span: Span,
}

/// A user subroutine (`extern sub`): a method of the `Externs` trait
/// returning an array.
#[derive(Clone, Debug)]
pub struct SubroutineInfo {
    /// Name.
    pub name: String,
    /// Formal argument names (a plain-name argument gives its name, others
    /// are `arg1`, `arg2`, ...).
    pub params: Vec<String>,
    /// Names of the values it returns.
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
    pub parameters: Vec<ParameterInfo>,
    /// Inputs in declaration order (`Leaf::Input` indices).
    pub inputs: Vec<InputInfo>,
    /// The state vector (`Leaf::State` indices).
    pub states: StateLayout,
    /// Outputs in order (slots of the outputs block).
    pub outputs: Vec<OutputInfo>,
    /// User functions, by `UserFnId` index.
    pub extern_fns: Vec<ExternFnInfo>,
    /// User subroutines in declaration order.
    pub subroutines: Vec<SubroutineInfo>,
}

impl Interface {
    /// The interface of a resolved model with these equations.
    pub fn new(model: &ResolvedModel, eqs: &Equations) -> Interface {
        let sys = &model.system;
        let a = &sys.arena;
        let spans = &model.spans;
        let state = |s: &SymId| StateVar {
            name: a.symbol(*s).name.clone(),
            unit: a.symbol(*s).unit.clone().unwrap_or_default(),
        };
        let parameters = sys
            .parameters()
            .iter()
            .map(|s| {
                let sym = a.symbol(*s);
                let declared = model.parameter_docs.iter().find(|d| d.name == sym.name);
                ParameterInfo {
                    name: sym.name.clone(),
                    unit: sym.unit.clone().unwrap_or_default(),
                    default: symbol_default(a, *s),
                    docs: declared.map(|d| d.docs.clone()),
                    span: spans.named(&sym.name),
                }
            })
            .collect();
        let inputs = sys
            .inputs()
            .iter()
            .map(|s| {
                let sym = a.symbol(*s);
                InputInfo {
                    name: sym.name.clone(),
                    unit: sym.unit.clone().unwrap_or_default(),
                    default: symbol_default(a, *s),
                    docs: model
                        .input_docs
                        .iter()
                        .find(|d| d.name == sym.name)
                        .map(|d| d.docs.clone())
                        .unwrap_or_default(),
                    span: spans.named(&sym.name),
                }
            })
            .collect();
        let outputs = sys
            .outputs()
            .iter()
            .map(|o| {
                let declared = model.output_docs.iter().find(|d| d.name == o.name);
                OutputInfo {
                    name: o.name.clone(),
                    unit: declared.and_then(|d| d.unit.clone()).unwrap_or_default(),
                    docs: declared.map(|d| d.docs.clone()).unwrap_or_default(),
                    span: spans.named(&o.name),
                }
            })
            .collect();
        let subroutines = sys
            .subroutines()
            .iter()
            .enumerate()
            .map(|(k, s)| SubroutineInfo {
                name: s.name.clone(),
                params: model.subroutine_params.get(k).cloned().unwrap_or_default(),
                outputs: s
                    .outputs
                    .iter()
                    .map(|o| a.symbol(*o).name.clone())
                    .collect(),
                docs: model.subroutine_docs.get(k).cloned().unwrap_or_default(),
                span: spans.named(&s.name),
            })
            .collect();
        let extern_fns = a
            .user_fns()
            .map(|(_, f)| {
                let declared = model.extern_fns.iter().find(|d| d.name == f.name);
                ExternFnInfo {
                    name: f.name.clone(),
                    params: declared.map(|d| d.params.clone()).unwrap_or_default(),
                    docs: declared.map(|d| d.docs.clone()).unwrap_or_default(),
                    span: spans.named(&f.name),
                }
            })
            .collect();
        Interface {
            name: sys.name().to_string(),
            docs: model.docs.clone(),
            float: model.float,
            parameters,
            inputs,
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

/// The default value of a parameter or input symbol.
fn symbol_default(a: &Arena, s: SymId) -> f64 {
    match a.symbol(s).kind {
        SymbolKind::Parameter { default } | SymbolKind::Input { default } => default,
        _ => 0.0,
    }
}
