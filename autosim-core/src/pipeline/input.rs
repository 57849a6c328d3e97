//! The hand-off to `opt`: one owned [`Input`] built from the resolved
//! model and its equations (the arena, the symbols and expressions the
//! model declares beside its equations, what generated code exposes of it,
//! the options). Everything `opt` knows of the model passes here.

use crate::expr::{SymId, SymbolKind};
use crate::mech::{Equations, ItemRef};
use crate::model::ResolvedModel;
use crate::opt::{
    ConstraintInfo, Declared, Described, EventCode, EventInfo, Input, MotionInfo, Options,
    Quantity, SubroutineCall, UserCode,
};

/// The input of `opt::build` for `model` with these equations.
pub fn opt_input(model: &ResolvedModel, equations: &Equations) -> Input {
    let sys = &model.system;
    let coordinates = sys.coordinates();
    Input {
        arena: sys.arena.clone(),
        equations: equations.clone(),
        declared: Declared {
            parameters: sys.parameters().to_vec(),
            inputs: sys.inputs().to_vec(),
            time: sys.time(),
            subroutines: sys
                .subroutines()
                .iter()
                .map(|s| SubroutineCall {
                    args: s.args.clone(),
                    outputs: s.outputs.clone(),
                })
                .collect(),
            outputs: sys.outputs().iter().map(|o| o.expr).collect(),
            coordinate_items: coordinates.iter().map(|c| ItemRef::Body(c.body)).collect(),
            initial_q: coordinates.iter().map(|c| c.initial_q).collect(),
            initial_u: coordinates.iter().map(|c| c.initial_u).collect(),
            initial_states: sys.states().iter().map(|s| s.initial).collect(),
            discrete: sys.discrete().to_vec(),
            events: sys
                .events()
                .iter()
                .map(|e| EventCode {
                    indicator: e.indicator,
                    sets: e
                        .sets
                        .iter()
                        .filter_map(|(s, v)| {
                            let k = sys.discrete().iter().position(|d| d == s)?;
                            Some((k, *v))
                        })
                        .collect(),
                    resets: e.resets.clone(),
                })
                .collect(),
        },
        described: model.described(equations),
        options: Options {
            formulation: model.formulation,
            linearize: model.linearize,
            lanes: model.lanes,
            float: model.float,
        },
    }
}

impl ResolvedModel {
    /// What generated code exposes of the model as declared.
    fn described(&self, eqs: &Equations) -> Described {
        let sys = &self.system;
        let a = &sys.arena;
        let symbol = |s: &SymId| {
            let sym = a.symbol(*s);
            let default = match sym.kind {
                SymbolKind::Parameter { default }
                | SymbolKind::Input { default }
                | SymbolKind::Discrete { default } => default,
                _ => 0.0,
            };
            self.quantity(&sym.name, sym.unit.as_deref(), default)
        };
        let mut outputs: Vec<Quantity> = sys
            .outputs()
            .iter()
            .map(|o| self.quantity(&o.name, o.unit.as_deref(), 0.0))
            .collect();
        outputs.extend(self.constraint_outputs(eqs));
        let subroutines = sys
            .subroutines()
            .iter()
            .map(|s| {
                let outputs = s.outputs.iter().map(|o| a.symbol(*o).name.clone());
                self.user_code(&s.name, outputs.collect())
            })
            .collect();
        Described {
            name: sys.name().to_string(),
            docs: self.docs.clone(),
            parameters: sys.parameters().iter().map(symbol).collect(),
            inputs: sys.inputs().iter().map(symbol).collect(),
            outputs,
            extern_fns: a
                .user_fns()
                .map(|(_, f)| self.user_code(&f.name, Vec::new()))
                .collect(),
            subroutines,
            constraints: self.constraint_infos(eqs),
            discrete: sys.discrete().iter().map(symbol).collect(),
            events: sys
                .events()
                .iter()
                .map(|e| EventInfo {
                    name: e.name.clone(),
                    direction: e.direction,
                    stop: e.stop,
                    unit: e.unit.clone().unwrap_or_default(),
                    docs: self.item_docs.get(&e.name).cloned().unwrap_or_default(),
                    span: self.spans.named(&e.name),
                })
                .collect(),
            motions: self.motion_infos(),
            cautions: [self.singular_starts(), self.moved_initials(eqs)].concat(),
            inferred_state_units: self
                .inferred_units
                .iter()
                .map(|(name, unit)| (name.clone(), unit.clone()))
                .collect(),
        }
    }

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

    /// A note for every dependent coordinate whose `initial:` the model
    /// declared and the compiler chose (no `dependent:`): assembly moves
    /// it. Only where no other choice closes the constraints.
    fn moved_initials(&self, eqs: &Equations) -> Vec<String> {
        let sys = &self.system;
        let c = &eqs.constraints;
        c.positions
            .iter()
            .zip(&c.dependent_coordinates)
            .filter(|&(&row, &k)| {
                sys.coordinates()[k].initial_declared && sys.constraints()[row].dependent.is_none()
            })
            .map(|(&row, &k)| {
                format!(
                    "Assembly solves `{}` from the other coordinates (it is the dependent coordinate of constraint `{}`, and no other choice closes the constraints at the initial state): its declared `initial:` value is only a guess, moved unless it already closes them. Name another with `dependent:` to keep it.",
                    sys.arena.symbol(sys.coordinates()[k].q).name,
                    sys.constraints()[row].name
                )
            })
            .collect()
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
