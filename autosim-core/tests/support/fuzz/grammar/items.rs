//! Items: settings, parameters, inputs, externs, points, `let`s, states and
//! outputs, in the order of the model (bodies are in `bodies`, forces,
//! moments and gravity in `loads`, discrete variables and events in
//! `events`).

use std::fmt::Write;

use super::super::vocab::*;
use super::{Grammar, LetKind, Names};

impl Grammar<'_> {
    /// Every item of the model, in order.
    pub(super) fn items(&mut self, names: &Names) -> Vec<String> {
        let mut items: Vec<String> = Vec::new();
        let settings = if self.wrong() {
            2
        } else {
            self.rng.range(0, 1)
        };
        for _ in 0..settings {
            items.push(self.settings());
        }
        self.parameter_items(&mut items);
        for input in &names.inputs {
            let default = if self.rng.chance(50) {
                format!(" = {}", self.value())
            } else {
                String::new()
            };
            items.push(format!("input {input}{}{default};", self.unit()));
        }
        self.extern_items(names, &mut items);
        for i in 0..self.bodies.len() {
            items.push(self.body(i));
        }
        self.point_and_let_items(&mut items);
        self.load_items(&mut items);
        self.constraint_items(&mut items);
        self.accelerations = true;
        for s in &names.states {
            items.push(self.state(s));
        }
        for name in self.outputs.clone() {
            let value = if self.wrong() {
                self.any(3)
            } else {
                self.scalar(3)
            };
            let unit = self.unit();
            let value = self.in_unit(value, unit_text(&unit));
            items.push(format!("output {name}{unit} = {value};"));
        }
        self.event_items(&mut items);
        items
    }

    fn settings(&mut self) -> String {
        let mut entries = Vec::new();
        if self.rng.chance(70) {
            let v = if self.wrong() {
                *self.rng.pick(&[
                    "0",
                    "-1",
                    "100",
                    "1e40",
                    "99999999999999999999",
                    "x",
                    "1.5",
                    "[1]",
                ])
            } else {
                *self.rng.pick(&["1", "2", "3"])
            };
            entries.push(format!("threshold: {v}"));
        }
        if self.rng.chance(70) {
            let v = if self.wrong() {
                *self.rng.pick(&["f16", "i32", "1", "\"f64\""])
            } else {
                *self.rng.pick(&["f64", "f32"])
            };
            entries.push(format!("float: {v}"));
        }
        if self.rng.chance(20) {
            let mut names = self.outputs.clone();
            names.retain(|_| self.rng.chance(60));
            if self.wrong() {
                names.push(self.rng.pick(ODD_NAMES).to_string());
            }
            entries.push(format!("outputs: [{}]", names.join(", ")));
        }
        if self.wrong() {
            entries.push(format!(
                "{}: 1",
                self.rng.pick(&["thresh", "float", "mass", "outputs"])
            ));
        }
        format!("settings {{ {} }}", entries.join(", "))
    }

    /// The parameters: one `parameters` block, or one item each.
    fn parameter_items(&mut self, items: &mut Vec<String>) {
        if self.params.is_empty() {
            return;
        }
        let params = self.params.clone();
        if self.rng.chance(70) {
            let mut s = String::from("parameters {\n");
            for p in &params {
                let _ = writeln!(
                    s,
                    "    /// Doc.\n    {p} = {}{},",
                    self.value(),
                    self.unit()
                );
            }
            s.push('}');
            items.push(s);
        } else {
            for p in &params {
                items.push(format!("parameter {p} = {}{};", self.value(), self.unit()));
            }
        }
    }

    /// Extern functions, then extern subroutines (whose arguments name
    /// scalars declared before them).
    fn extern_items(&mut self, names: &Names, items: &mut Vec<String>) {
        for (name, arity) in self.fns.clone() {
            let args: Vec<String> = (0..arity).map(|k| format!("a{k}")).collect();
            items.push(format!("extern fn {name}({});", args.join(", ")));
        }
        for (name, outs) in &names.subs {
            let args: Vec<String> = (0..self.rng.range(0, 2))
                .map(|_| {
                    if self.wrong() {
                        self.scalar(2)
                    } else {
                        self.rng.pick(&names.scalar_args).clone()
                    }
                })
                .collect();
            let outs: Vec<String> = outs.iter().map(|o| format!("{o}{}", self.unit())).collect();
            items.push(format!(
                "extern sub {name}({}) -> ({});",
                args.join(", "),
                outs.join(", ")
            ));
        }
    }

    /// Points, then `let`s (each seeing only the ones before it, unless
    /// going wrong).
    fn point_and_let_items(&mut self, items: &mut Vec<String>) {
        for (name, body) in self.points.clone() {
            let label = if self.rng.chance(30) {
                " \"a point\""
            } else {
                ""
            };
            let at = if self.wrong() {
                self.any(2)
            } else {
                self.list3(false, "m")
            };
            items.push(format!("point {name}{label} in {body} at {at};"));
        }
        for (i, (name, kind)) in self.lets.clone().into_iter().enumerate() {
            self.visible_lets = if self.wrong() { self.lets.len() } else { i };
            let value = match kind {
                _ if self.wrong() => self.any(3),
                LetKind::Scalar => self.scalar(3),
                LetKind::Vector => self.vector(3),
                LetKind::Point => self.point(1),
            };
            items.push(format!("let {name} = {value};"));
        }
        self.visible_lets = self.lets.len();
    }

    fn state(&mut self, name: &str) -> String {
        let unit = self.unit();
        let mut entries = Vec::new();
        if self.rng.chance(80) {
            let v = self.constant(1);
            let v = self.in_unit(v, unit_text(&unit));
            entries.push(format!("initial: {v}"));
        }
        if !self.wrong() {
            let v = self.scalar(3);
            let v = self.in_unit(v, &format!("({})/s", unit_text(&unit)));
            entries.push(format!("derivative: {v}"));
        }
        format!("state {name}{unit} {{ {} }}", entries.join(", "))
    }
}

/// The text inside the brackets of a unit from [`UNITS`] (`1` for none).
fn unit_text(unit: &str) -> &str {
    let inner = unit.trim().trim_start_matches('[').trim_end_matches(']');
    if inner.is_empty() { "1" } else { inner }
}
