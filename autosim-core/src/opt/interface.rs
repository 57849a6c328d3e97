//! What a generated model exposes, as data: the names, units, defaults,
//! docs and source spans of its parameters, inputs, states, outputs and
//! user code, and the layout of its state vector. The emitter and the
//! documentation read this and the program, nothing else.

use crate::expr::SymId;
use crate::mech::Equations;
use crate::opt::input::{Described, FloatType, Input};
use crate::opt::split::Split;

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

/// What assembly solves: each position constraint (an index into
/// [`Described::constraints`]) for its dependent coordinate (a position in
/// the state vector), in the order of the assembly block's slots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Closure {
    /// The position constraint.
    pub constraint: usize,
    /// Its dependent coordinate's position in the state vector.
    pub slot: usize,
}

/// Everything about a model's interface that generated code and its
/// documentation name: the model as it declares itself, and what opt adds
/// (the float type, the state vector, what assembly and the linearization
/// solve for).
#[derive(Clone, Debug)]
pub struct Interface {
    /// The model as it declares itself: names, units, defaults, docs and
    /// spans of its parameters (`Leaf::Param` indices), inputs
    /// (`Leaf::Input`), outputs (slots of the outputs block), user code,
    /// constraints (`Guard::Regular` indices), motions, discrete variables
    /// (`Leaf::Discrete`) and events (slots of the event indicators block).
    pub model: Described,
    /// Float type of generated code.
    pub float: FloatType,
    /// Whether generated code has `derivatives_lanes` (the `lanes` option).
    pub lanes: bool,
    /// The state vector (`Leaf::State` indices).
    pub states: StateLayout,
    /// The position constraints and their dependent coordinates, in the
    /// order of the assembly block's slots (empty without position
    /// constraints).
    pub closures: Vec<Closure>,
    /// The states of the linear model (state-vector positions; all but the
    /// dependent coordinates), when the linearization is generated.
    pub linear_states: Option<Vec<usize>>,
}

impl Interface {
    /// The interface of a model as its input describes it, its speeds
    /// split as `split` says.
    pub fn new(input: &Input, split: &Split) -> Interface {
        let (a, eqs, d) = (&input.arena, &input.equations, &input.described);
        let state = |s: &SymId| {
            let symbol = a.symbol(*s);
            let inferred = match symbol.unit {
                Some(_) => None,
                None => d.inferred_state_units.get(&symbol.name).cloned(),
            };
            StateVar {
                name: symbol.name.clone(),
                unit: symbol.unit.clone().unwrap_or_default(),
                inferred_unit: inferred.unwrap_or_default(),
            }
        };
        Interface {
            model: d.clone(),
            float: input.options.float,
            lanes: input.options.lanes,
            states: StateLayout {
                coordinates: split
                    .coordinates
                    .iter()
                    .map(|&k| state(&eqs.coordinates[k]))
                    .collect(),
                speeds: split.free.iter().map(|&k| state(&eqs.speeds[k])).collect(),
                extra: eqs.states.iter().map(state).collect(),
            },
            closures: closures(eqs, split),
            linear_states: None,
        }
    }

    /// Whether generated code calls user code (and so has an `Externs`
    /// type parameter).
    pub fn has_externs(&self) -> bool {
        !self.model.extern_fns.is_empty() || !self.model.subroutines.is_empty()
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
