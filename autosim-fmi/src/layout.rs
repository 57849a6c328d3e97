//! The value references of an autosim FMU: one numbering for every
//! variable, in the order `modelDescription.xml` lists them (so a
//! variable's `index` in `ModelStructure` is its value reference + 1).
//!
//! | value references | variables | causality |
//! | --- | --- | --- |
//! | 0 | `time` | independent |
//! | 1 .. | the model's parameters, declaration order | parameter (fixed) |
//! | then 3 | `cs.method` (Integer, enumeration), `cs.tolerance`, `cs.step` | parameter (fixed) |
//! | then | the inputs | input |
//! | then | the FMU's continuous states (all but the dependent coordinates) | local |
//! | then | their derivatives `der(<state>)`, same order | local |
//! | then | the outputs | output |
//! | then | the dependent coordinates of position constraints | local (calculated) |
//! | then | the model's discrete variables (changed by events) | local (discrete) |

/// Which kind of variable a value reference names, with its position
/// among the variables of that kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variable {
    /// The independent variable, time.
    Time,
    /// Parameter `k` (the model's declaration order).
    Parameter(usize),
    /// A Co-Simulation setting.
    Setting(Setting),
    /// Input `k`.
    Input(usize),
    /// FMU state `k` (the `k`-th independent state).
    State(usize),
    /// The derivative of FMU state `k`.
    Derivative(usize),
    /// Output `k`.
    Output(usize),
    /// Dependent coordinate `k` (a local solved from the constraints).
    Dependent(usize),
    /// Discrete variable `k` (`Model::DISCRETE_NAMES` order).
    Discrete(usize),
}

/// The Co-Simulation settings, parameters of every autosim FMU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Setting {
    /// `cs.method`: the integrator (an enumeration, see [`Method`]).
    Method,
    /// `cs.tolerance`: Dormand–Prince's relative and absolute tolerance.
    Tolerance,
    /// `cs.step` (s): the largest step of the fixed-step methods.
    Step,
}

/// The integrators Co-Simulation offers, with their `cs.method` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// 1: adaptive Dormand–Prince 5(4) at `cs.tolerance` (the default).
    DormandPrince = 1,
    /// 2: classic fourth-order Runge–Kutta, steps of at most `cs.step`.
    Rk4 = 2,
    /// 3: Adams–Bashforth–Moulton of order 4, steps of at most `cs.step`.
    Abm4 = 3,
}

impl Method {
    /// Every method, in `cs.method` order.
    pub const ALL: [Method; 3] = [Method::DormandPrince, Method::Rk4, Method::Abm4];

    /// The method of a `cs.method` value.
    pub fn from_value(value: i32) -> Option<Method> {
        Method::ALL.into_iter().find(|m| *m as i32 == value)
    }

    /// The enumeration item's name in `modelDescription.xml`.
    pub fn name(self) -> &'static str {
        match self {
            Method::DormandPrince => "dormand_prince",
            Method::Rk4 => "rk4",
            Method::Abm4 => "abm4",
        }
    }

    /// One line for the enumeration item's description.
    pub fn description(self) -> &'static str {
        match self {
            Method::DormandPrince => "adaptive Dormand-Prince 5(4) at cs.tolerance",
            Method::Rk4 => "classic Runge-Kutta of order 4, equal steps of at most cs.step",
            Method::Abm4 => "Adams-Bashforth-Moulton of order 4, equal steps of at most cs.step",
        }
    }
}

/// Default of `cs.tolerance`.
pub const DEFAULT_TOLERANCE: f64 = 1e-8;
/// Default of `cs.step` (s).
pub const DEFAULT_STEP: f64 = 1e-3;

/// The counts that fix an FMU's numbering.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    /// Parameters.
    pub parameters: usize,
    /// Inputs.
    pub inputs: usize,
    /// FMU states (the model's states less the dependent coordinates).
    pub states: usize,
    /// Outputs.
    pub outputs: usize,
    /// Dependent coordinates.
    pub dependent: usize,
    /// Discrete variables.
    pub discrete: usize,
}

/// Number of Co-Simulation settings.
const SETTINGS: usize = 3;

impl Layout {
    fn first_setting(&self) -> usize {
        1 + self.parameters
    }
    fn first_input(&self) -> usize {
        self.first_setting() + SETTINGS
    }
    fn first_state(&self) -> usize {
        self.first_input() + self.inputs
    }
    fn first_derivative(&self) -> usize {
        self.first_state() + self.states
    }
    fn first_output(&self) -> usize {
        self.first_derivative() + self.states
    }
    fn first_dependent(&self) -> usize {
        self.first_output() + self.outputs
    }
    fn first_discrete(&self) -> usize {
        self.first_dependent() + self.dependent
    }

    /// Number of variables (and value references).
    pub fn len(&self) -> usize {
        self.first_discrete() + self.discrete
    }

    /// `false`: every FMU has at least `time` and the settings.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The variable a value reference names, if any.
    pub fn variable(&self, vr: u32) -> Option<Variable> {
        let v = vr as usize;
        let within = |first: usize, n: usize| (v >= first && v < first + n).then(|| v - first);
        if v == 0 {
            return Some(Variable::Time);
        }
        if let Some(k) = within(1, self.parameters) {
            return Some(Variable::Parameter(k));
        }
        if let Some(k) = within(self.first_setting(), SETTINGS) {
            let setting = [Setting::Method, Setting::Tolerance, Setting::Step][k];
            return Some(Variable::Setting(setting));
        }
        type Kind = (usize, usize, fn(usize) -> Variable);
        let kinds: [Kind; 6] = [
            (self.first_input(), self.inputs, Variable::Input),
            (self.first_state(), self.states, Variable::State),
            (self.first_derivative(), self.states, Variable::Derivative),
            (self.first_output(), self.outputs, Variable::Output),
            (self.first_dependent(), self.dependent, Variable::Dependent),
            (self.first_discrete(), self.discrete, Variable::Discrete),
        ];
        kinds
            .into_iter()
            .find_map(|(first, n, kind)| within(first, n).map(kind))
    }

    /// The value reference of a variable.
    pub fn reference(&self, variable: Variable) -> u32 {
        let v = match variable {
            Variable::Time => 0,
            Variable::Parameter(k) => 1 + k,
            Variable::Setting(s) => {
                self.first_setting()
                    + match s {
                        Setting::Method => 0,
                        Setting::Tolerance => 1,
                        Setting::Step => 2,
                    }
            }
            Variable::Input(k) => self.first_input() + k,
            Variable::State(k) => self.first_state() + k,
            Variable::Derivative(k) => self.first_derivative() + k,
            Variable::Output(k) => self.first_output() + k,
            Variable::Dependent(k) => self.first_dependent() + k,
            Variable::Discrete(k) => self.first_discrete() + k,
        };
        v as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_reference_names_one_variable_and_back() {
        let layout = Layout {
            parameters: 3,
            inputs: 2,
            states: 4,
            outputs: 2,
            dependent: 2,
            discrete: 1,
        };
        assert_eq!(layout.len(), 1 + 3 + 3 + 2 + 4 + 4 + 2 + 2 + 1);
        for vr in 0..layout.len() as u32 {
            let v = layout.variable(vr).expect("a variable");
            assert_eq!(layout.reference(v), vr);
        }
        assert_eq!(layout.variable(layout.len() as u32), None);
        assert_eq!(layout.variable(4), Some(Variable::Setting(Setting::Method)));
    }
}
