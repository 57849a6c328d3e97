//! `modelDescription.xml` from the compiler's data: the variables with
//! their units, start values and doc comments, the unit definitions, the
//! Co-Simulation settings, and the `ModelStructure` from the program's
//! exact dependencies (`autosim_core::opt::dependencies`).

use crate::units::{Unit, unit_definitions};
use autosim_core::opt::dependencies::{Dependencies, Depends};
use autosim_core::opt::{Interpreter, Program, Quantity};
use autosim_fmi::log::CATEGORIES;
use autosim_fmi::{EventInterface, Layout, Method, Setting, Variable};
use std::fmt::Write as _;

/// The `DefaultExperiment` of an FMU.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Experiment {
    /// Start time (s).
    pub start: f64,
    /// Stop time (s).
    pub stop: f64,
    /// Communication step or output interval (s).
    pub step: f64,
    /// Relative tolerance for the importer's integrator.
    pub tolerance: f64,
}

impl Default for Experiment {
    /// 0 to 10 s, steps of 0.01 s, tolerance 1e-6.
    fn default() -> Self {
        Experiment {
            start: 0.0,
            stop: 10.0,
            step: 0.01,
            tolerance: 1e-6,
        }
    }
}

/// What the description says beyond the program.
#[derive(Clone, Debug)]
pub struct Options {
    /// `modelIdentifier`: the shared library's name.
    pub identifier: String,
    /// The GUID (see [`guid`]).
    pub guid: String,
    /// The default experiment.
    pub experiment: Experiment,
    /// Whether `fmi2GetDirectionalDerivative` is provided.
    pub directional: bool,
    /// The model's event indicators and discrete variables (from the
    /// built library, see [`EventInterface`]); empty for a model without
    /// events.
    pub events: EventInterface,
}

/// A GUID for a description text (without its GUID): name-based (UUID
/// version 5), so the same model built the same way gets the same GUID
/// and any change to the description gets another. The caller passes the
/// text with the default experiment: the experiment is advice to the
/// importer, not the model, and a user crate's build script
/// ([`generate`](crate::generate)) does not know it.
pub fn guid(text: &str) -> String {
    let id = uuid::Uuid::new_v5(&uuid::Uuid::NAMESPACE_OID, text.as_bytes());
    format!("{{{id}}}")
}

/// The value-reference numbering of a program's FMU with these events.
pub fn layout(program: &Program, deps: &Dependencies, events: &EventInterface) -> Layout {
    let i = &program.interface;
    Layout {
        parameters: i.model.parameters.len(),
        inputs: i.model.inputs.len(),
        states: i.states.len() - deps.dependent.len(),
        outputs: i.model.outputs.len(),
        dependent: deps.dependent.len(),
        discrete: events.discrete.len(),
    }
}

/// Escapes text for an XML attribute (line breaks become spaces).
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out += "&amp;",
            '<' => out += "&lt;",
            '>' => out += "&gt;",
            '"' => out += "&quot;",
            '\'' => out += "&apos;",
            '\n' | '\r' | '\t' => out.push(' '),
            c if c.is_control() => {}
            c => out.push(c),
        }
    }
    out
}

/// One `ScalarVariable`.
struct Scalar {
    name: String,
    causality: &'static str,
    variability: &'static str,
    initial: Option<&'static str>,
    description: String,
    /// The type element, e.g. `<Real unit="m" start="0.3"/>`.
    element: String,
}

/// `<Real .../>` with a unit and an optional start value.
fn real(unit: &str, start: Option<f64>, derivative: Option<u32>) -> String {
    let mut e = String::from("<Real");
    if !unit.is_empty() {
        let _ = write!(e, " unit=\"{}\"", escape(unit));
    }
    if let Some(d) = derivative {
        let _ = write!(e, " derivative=\"{d}\"");
    }
    if let Some(s) = start {
        let _ = write!(e, " start=\"{}\"", number(s));
    }
    e + "/>"
}

/// A number as XML writes it (shortest round-trip form).
fn number(v: f64) -> String {
    format!("{v:?}")
}

fn docs(q: &Quantity) -> String {
    join_docs(q.docs.as_deref().unwrap_or_default())
}

/// Doc comment lines as one line of text.
fn join_docs(lines: &[String]) -> String {
    let words: Vec<&str> = lines.iter().flat_map(|l| l.split_whitespace()).collect();
    words.join(" ")
}

/// The model's variables in value-reference order.
fn scalars(
    program: &Program,
    deps: &Dependencies,
    layout: &Layout,
    events: &EventInterface,
) -> Vec<Scalar> {
    let i = &program.interface;
    let defaults: Vec<f64> = i.model.parameters.iter().map(|p| p.default).collect();
    let x0 = Interpreter::new(program, &defaults).initial_state();
    let states: Vec<usize> = (0..i.states.len())
        .filter(|s| !deps.dependent.contains(s))
        .collect();
    let mut out = Vec::with_capacity(layout.len());
    for vr in 0..layout.len() as u32 {
        let v = layout
            .variable(vr)
            .unwrap_or_else(|| unreachable!("every reference below len names a variable"));
        out.push(match v {
            Variable::Time => Scalar {
                name: "time".into(),
                causality: "independent",
                variability: "continuous",
                initial: None,
                description: "Simulation time".into(),
                element: real("s", None, None),
            },
            Variable::Parameter(k) => {
                let p = &i.model.parameters[k];
                Scalar {
                    name: p.name.clone(),
                    causality: "parameter",
                    variability: "fixed",
                    initial: Some("exact"),
                    description: docs(p),
                    element: real(&p.unit, Some(p.default), None),
                }
            }
            Variable::Setting(s) => setting(s),
            Variable::Input(k) => {
                let w = &i.model.inputs[k];
                Scalar {
                    name: w.name.clone(),
                    causality: "input",
                    variability: "continuous",
                    initial: None,
                    description: docs(w),
                    element: real(&w.unit, Some(w.default), None),
                }
            }
            Variable::State(k) => {
                let s = i.states.state(states[k]);
                // An initial value computed from parameters is no start
                // value an importer could set and keep: it follows them.
                let (initial, start, how) = if deps.initial[states[k]].is_empty() {
                    ("exact", Some(x0[states[k]]), "")
                } else {
                    (
                        "calculated",
                        None,
                        ", its initial value computed from parameters",
                    )
                };
                Scalar {
                    name: s.name.clone(),
                    causality: "local",
                    variability: "continuous",
                    initial: Some(initial),
                    description: format!("State {} of the model{how}", s.name),
                    element: real(&s.unit, start, None),
                }
            }
            Variable::Derivative(k) => {
                let s = i.states.state(states[k]);
                let unit = Unit::parse(&s.unit).per_second().text();
                let state_index = layout.reference(Variable::State(k)) + 1;
                Scalar {
                    name: format!("der({})", s.name),
                    causality: "local",
                    variability: "continuous",
                    initial: Some("calculated"),
                    description: format!("Time derivative of {}", s.name),
                    element: real(&unit, None, Some(state_index)),
                }
            }
            Variable::Output(k) => {
                let y = &i.model.outputs[k];
                Scalar {
                    name: y.name.clone(),
                    causality: "output",
                    variability: "continuous",
                    initial: Some("calculated"),
                    description: docs(y),
                    element: real(&y.unit, None, None),
                }
            }
            Variable::Dependent(k) => {
                let s = i.states.state(deps.dependent[k]);
                Scalar {
                    name: s.name.clone(),
                    causality: "local",
                    variability: "continuous",
                    initial: Some("calculated"),
                    description: format!(
                        "Dependent coordinate {}, solved from the position constraints",
                        s.name
                    ),
                    element: real(&s.unit, None, None),
                }
            }
            Variable::Discrete(k) => {
                let (name, unit, start) = &events.discrete[k];
                Scalar {
                    name: name.clone(),
                    causality: "local",
                    variability: "discrete",
                    initial: Some("exact"),
                    description: format!("Discrete variable {name}, changed only by events"),
                    element: real(unit, Some(*start), None),
                }
            }
        });
    }
    out
}

/// The Co-Simulation settings' variables.
fn setting(s: Setting) -> Scalar {
    let (name, description, element) = match s {
        Setting::Method => (
            "cs.method",
            "Co-Simulation: the integrator",
            format!(
                "<Enumeration declaredType=\"IntegrationMethod\" start=\"{}\"/>",
                Method::DormandPrince as i32
            ),
        ),
        Setting::Tolerance => (
            "cs.tolerance",
            "Co-Simulation: relative and absolute tolerance of dormand_prince (the tolerance of fmi2SetupExperiment, when given, sets it)",
            real("", Some(autosim_fmi::layout::DEFAULT_TOLERANCE), None),
        ),
        Setting::Step => (
            "cs.step",
            "Co-Simulation: largest step of rk4 and abm4 (a communication step is split into equal steps no longer than this)",
            real("s", Some(autosim_fmi::layout::DEFAULT_STEP), None),
        ),
    };
    Scalar {
        name: name.into(),
        causality: "parameter",
        variability: "fixed",
        initial: Some("exact"),
        description: description.into(),
        element,
    }
}

/// The `modelDescription.xml` text of a compiled model.
pub fn model_description(program: &Program, deps: &Dependencies, options: &Options) -> String {
    let layout = layout(program, deps, &options.events);
    let vars = scalars(program, deps, &layout, &options.events);
    let i = &program.interface;
    let mut x = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        x,
        "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{}\" guid=\"{}\" description=\"{}\" generationTool=\"autosim {}\" variableNamingConvention=\"flat\" numberOfEventIndicators=\"{}\">",
        escape(&i.model.name),
        escape(&options.guid),
        escape(&join_docs(&i.model.docs)),
        env!("CARGO_PKG_VERSION"),
        options.events.indicators.len(),
    );
    let dd = options.directional;
    let common = format!(
        "modelIdentifier=\"{}\" canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\" providesDirectionalDerivative=\"{dd}\" canNotUseMemoryManagementFunctions=\"true\"",
        escape(&options.identifier)
    );
    let _ = writeln!(
        x,
        "  <ModelExchange {common} completedIntegratorStepNotNeeded=\"true\"/>"
    );
    let _ = writeln!(
        x,
        "  <CoSimulation {common} canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"false\" maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\"/>"
    );
    let units = vars.iter().filter_map(|v| unit_of(&v.element));
    x += &unit_definitions(units.collect::<Vec<_>>().iter().map(String::as_str));
    x += &type_definitions();
    x += "  <LogCategories>\n";
    for (name, description) in CATEGORIES {
        let _ = writeln!(
            x,
            "    <Category name=\"{name}\" description=\"{description}\"/>"
        );
    }
    x += "  </LogCategories>\n";
    let e = options.experiment;
    let _ = writeln!(
        x,
        "  <DefaultExperiment startTime=\"{}\" stopTime=\"{}\" tolerance=\"{}\" stepSize=\"{}\"/>",
        number(e.start),
        number(e.stop),
        number(e.tolerance),
        number(e.step)
    );
    x += "  <ModelVariables>\n";
    for (vr, v) in vars.iter().enumerate() {
        let _ = write!(
            x,
            "    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" causality=\"{}\" variability=\"{}\"",
            escape(&v.name),
            v.causality,
            v.variability
        );
        if let Some(initial) = v.initial {
            let _ = write!(x, " initial=\"{initial}\"");
        }
        if !v.description.is_empty() {
            let _ = write!(x, " description=\"{}\"", escape(&v.description));
        }
        let _ = writeln!(x, ">\n      {}\n    </ScalarVariable>", v.element);
    }
    x += "  </ModelVariables>\n";
    let ny = i.model.outputs.len();
    let first_residual = ny - i.model.motions.len() - i.closures.len();
    x += &model_structure(deps, &layout, first_residual..ny - i.model.motions.len());
    x + "</fmiModelDescription>\n"
}

/// The unit attribute of a type element.
fn unit_of(element: &str) -> Option<String> {
    let rest = element.split_once("unit=\"")?.1;
    Some(rest.split_once('"')?.0.replace("&amp;", "&"))
}

/// The enumeration of `cs.method`.
fn type_definitions() -> String {
    let mut x = String::from(
        "  <TypeDefinitions>\n    <SimpleType name=\"IntegrationMethod\" description=\"Co-Simulation integrators\">\n      <Enumeration>\n",
    );
    for m in Method::ALL {
        let _ = writeln!(
            x,
            "        <Item name=\"{}\" value=\"{}\" description=\"{}\"/>",
            m.name(),
            m as i32,
            m.description()
        );
    }
    x + "      </Enumeration>\n    </SimpleType>\n  </TypeDefinitions>\n"
}

/// `ModelStructure`: outputs and derivatives on states and inputs; the
/// initial unknowns (outputs, derivatives and the states whose initial
/// values are computed from parameters, in index order) on the states
/// with exact start values, the inputs and the parameters they read
/// (through such a computed state, the parameters it is computed from).
/// The outputs in `residuals`, the residuals of position
/// constraints, depend on nothing: the FMU solves the constraints before
/// it evaluates, so they are zero (to the solution's rounding) whatever
/// the states.
fn model_structure(
    deps: &Dependencies,
    layout: &Layout,
    residuals: std::ops::Range<usize>,
) -> String {
    let states: Vec<usize> = (0..deps.derivatives.len())
        .filter(|s| !deps.dependent.contains(s))
        .collect();
    let index = |v: Variable| layout.reference(v) + 1;
    let fmu_state = |s: &usize| {
        let k = states.iter().position(|x| x == s);
        index(Variable::State(k.unwrap_or_else(|| {
            unreachable!("dependencies name independent states")
        })))
    };
    let computed = |s: &usize| !deps.initial[*s].is_empty();
    let list = |d: &Depends, initial: bool| -> String {
        let mut ids: Vec<u32> = d
            .states
            .iter()
            .filter(|s| !(initial && computed(s)))
            .map(fmu_state)
            .collect();
        ids.extend(d.inputs.iter().map(|&w| index(Variable::Input(w))));
        if initial {
            let through = d.states.iter().filter(|s| computed(s));
            let mut parameters: Vec<usize> = d.parameters.clone();
            parameters.extend(through.flat_map(|s| deps.initial[*s].iter().copied()));
            parameters.sort_unstable();
            parameters.dedup();
            ids.extend(parameters.iter().map(|&p| index(Variable::Parameter(p))));
        }
        ids.sort_unstable();
        ids.iter().map(u32::to_string).collect::<Vec<_>>().join(" ")
    };
    let unknown =
        |i: u32, deps: String| format!("      <Unknown index=\"{i}\" dependencies=\"{deps}\"/>\n");
    let nothing = Depends::default();
    let outputs: Vec<(u32, &Depends)> = deps
        .outputs
        .iter()
        .enumerate()
        .map(|(k, d)| {
            let d = if residuals.contains(&k) { &nothing } else { d };
            (index(Variable::Output(k)), d)
        })
        .collect();
    let derivatives: Vec<(u32, &Depends)> = states
        .iter()
        .enumerate()
        .map(|(k, &s)| (index(Variable::Derivative(k)), &deps.derivatives[s]))
        .collect();
    let mut x = String::from("  <ModelStructure>\n");
    let mut section = |name: &str, items: &[(u32, &Depends)], parameters: bool| {
        if items.is_empty() {
            return;
        }
        x += &format!("    <{name}>\n");
        for (i, d) in items {
            x += &unknown(*i, list(d, parameters));
        }
        x += &format!("    </{name}>\n");
    };
    section("Outputs", &outputs, false);
    section("Derivatives", &derivatives, false);
    let computed_states: Vec<(u32, Depends)> = states
        .iter()
        .enumerate()
        .filter(|(_, s)| computed(s))
        .map(|(k, &s)| {
            let from = Depends {
                parameters: deps.initial[s].clone(),
                ..Depends::default()
            };
            (index(Variable::State(k)), from)
        })
        .collect();
    let mut initial: Vec<(u32, &Depends)> = outputs.iter().chain(&derivatives).copied().collect();
    initial.extend(computed_states.iter().map(|(i, d)| (*i, d)));
    initial.sort_by_key(|(i, _)| *i);
    section("InitialUnknowns", &initial, true);
    x + "  </ModelStructure>\n"
}
