//! Which model value each column of the case table sets, and setting them
//! for a case.

use std::string::{String, ToString};
use std::vec::Vec;

use super::StudyError;
use crate::batch::LANES;
use crate::{Float, Lanes, Model};

/// What a column of the case table sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Target {
    Parameter(usize),
    Input(usize),
    State(usize),
    /// A discrete variable's value at the start.
    Discrete(usize),
    /// The k-th value passed to the study's setup function.
    Setup(usize),
}

/// Resolves every column: `parameter:NAME`, `input:NAME`, `state:NAME` or
/// `discrete:NAME` name one kind; a bare name must be exactly one
/// parameter, input, state, discrete variable or setup column.
pub(super) fn resolve<M: Model>(
    columns: &[String],
    setup: &[String],
) -> Result<Vec<Target>, StudyError> {
    for name in setup {
        if !columns.contains(name) {
            return Err(StudyError::UnknownColumn {
                name: name.clone(),
                model: M::NAME,
                why: "the setup function reads it, but the case table has no such column"
                    .to_string(),
            });
        }
    }
    columns.iter().map(|c| resolve_one::<M>(c, setup)).collect()
}

/// A kind of model value: its name, the model's names of that kind, and
/// the target for an index.
type Kind = (&'static str, &'static [&'static str], fn(usize) -> Target);

fn resolve_one<M: Model>(column: &str, setup: &[String]) -> Result<Target, StudyError> {
    let find = |names: &[&str], name: &str| names.iter().position(|n| *n == name);
    let kinds: [Kind; 4] = [
        ("parameter", M::PARAMETER_NAMES, Target::Parameter),
        ("input", M::INPUT_NAMES, Target::Input),
        ("state", M::STATE_NAMES, Target::State),
        ("discrete", M::DISCRETE_NAMES, Target::Discrete),
    ];
    if let Some((kind, name)) = column.split_once(':') {
        let Some((_, names, target)) = kinds.iter().find(|k| k.0 == kind) else {
            return Err(unknown::<M>(
                column,
                "the prefix must be `parameter:`, `input:`, `state:` or `discrete:`",
            ));
        };
        return find(names, name).map(target).ok_or_else(|| {
            unknown::<M>(column, &std::format!("the model has no {kind} `{name}`"))
        });
    }
    let mut found: Vec<(&str, Target)> = kinds
        .iter()
        .filter_map(|(kind, names, target)| find(names, column).map(|k| (*kind, target(k))))
        .collect();
    if let Some(k) = setup.iter().position(|s| s == column) {
        found.push(("setup", Target::Setup(k)));
    }
    let every = kinds
        .iter()
        .flat_map(|k| k.1.iter().copied())
        .chain(setup.iter().map(String::as_str));
    let hint = match alike(column, every) {
        Some(name) => std::format!("; did you mean `{name}`?"),
        None => String::new(),
    };
    match found.as_slice() {
        [(_, target)] => Ok(*target),
        [] if setup.is_empty() => Err(unknown::<M>(
            column,
            &std::format!(
                "it is not a parameter, input, state or discrete variable of the model{hint}"
            ),
        )),
        [] => Err(unknown::<M>(
            column,
            &std::format!(
                "it is not a parameter, input, state or discrete variable of the model, nor a column the setup function reads{hint}"
            ),
        )),
        many => Err(StudyError::AmbiguousColumn {
            name: column.to_string(),
            kinds: many.iter().map(|f| f.0).collect(),
        }),
    }
}

/// The first of `names` spelled as `column` whatever the case and the
/// underscores, else the first that one of the two starts (at least two
/// letters shared).
fn alike<'a>(column: &str, names: impl Iterator<Item = &'a str> + Clone) -> Option<&'a str> {
    let bare = |s: &str| s.to_lowercase().replace('_', "");
    let lower = column.to_lowercase();
    let same = names.clone().find(|n| bare(n) == bare(column));
    same.or_else(|| {
        names.into_iter().find(|n| {
            let n = n.to_lowercase();
            n.len().min(lower.len()) >= 2 && (n.starts_with(&lower) || lower.starts_with(&n))
        })
    })
}

fn unknown<M: Model>(name: &str, why: &str) -> StudyError {
    StudyError::UnknownColumn {
        name: name.to_string(),
        model: M::NAME,
        why: why.to_string(),
    }
}

/// Scratch space for setting a case: the model's parameter, input and
/// discrete vectors and the setup function's values; and for a group of
/// cases in lockstep, their models' lane values ([`Model::lane_values`]).
pub(super) struct Setter<F> {
    parameters: Vec<F>,
    inputs: Vec<F>,
    discrete: Vec<F>,
    pub(super) setup: Vec<f64>,
    pub(super) lane_values: Vec<Lanes<LANES>>,
}

impl<F: Float> Setter<F> {
    pub(super) fn new<M: Model<Float = F>>(setup_len: usize) -> Setter<F> {
        Setter {
            parameters: std::vec![F::ZERO; M::PARAMETER_NAMES.len()],
            inputs: std::vec![F::ZERO; M::INPUT_NAMES.len()],
            discrete: std::vec![F::ZERO; M::DISCRETE_NAMES.len()],
            setup: std::vec![0.0; setup_len],
            lane_values: std::vec![Lanes::ZERO; M::LANE_VALUES],
        }
    }

    /// Sets the case's parameters, inputs and discrete variables on
    /// `model`, and returns the
    /// model's initial state (with those parameters) with the case's
    /// initial states set; collects the setup values.
    pub(super) fn apply<M: Model<Float = F>>(
        &mut self,
        targets: &[Target],
        values: &[f64],
        model: &mut M,
    ) -> M::State {
        let has = |f: fn(&Target) -> bool| targets.iter().any(f);
        let parameters = has(|t| matches!(t, Target::Parameter(_)));
        let inputs = has(|t| matches!(t, Target::Input(_)));
        let discrete = has(|t| matches!(t, Target::Discrete(_)));
        if parameters {
            model.parameter_values(&mut self.parameters);
        }
        if inputs {
            model.input_values(&mut self.inputs);
        }
        if discrete {
            model.discrete_values(&mut self.discrete);
        }
        for (t, v) in targets.iter().zip(values) {
            match *t {
                Target::Parameter(k) => self.parameters[k] = F::from_f64(*v),
                Target::Input(k) => self.inputs[k] = F::from_f64(*v),
                Target::Discrete(k) => self.discrete[k] = F::from_f64(*v),
                Target::Setup(k) => self.setup[k] = *v,
                Target::State(_) => {}
            }
        }
        if parameters {
            model.set_parameter_values(&self.parameters);
        }
        if inputs {
            model.set_input_values(&self.inputs);
        }
        if discrete {
            model.set_discrete_values(&self.discrete);
        }
        initial_state(targets, values, model)
    }
}

/// The model's initial state with the case's initial states (`values` of
/// the state columns) set.
fn initial_state<M: Model>(targets: &[Target], values: &[f64], model: &M) -> M::State {
    let mut x = model.initial_state();
    for (t, v) in targets.iter().zip(values) {
        if let Target::State(k) = *t {
            x.as_mut()[k] = M::Float::from_f64(*v);
        }
    }
    x
}
