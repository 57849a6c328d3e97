//! Grammar-aware models: names first, then items whose values are mostly
//! of the right kind, each choice going wrong with the model's `chaos`
//! percentage. Expressions are in `exprs`.

use std::fmt::Write;

use super::Rng;
use super::vocab::*;

mod exprs;

struct BodyInfo {
    name: String,
    rotations: usize,
    translations: usize,
    /// `rotate: quaternion` (three rotations, four coordinates).
    quaternion: bool,
    q: Vec<String>,
    u: Vec<String>,
}

/// What a `let` holds, so that uses can match it.
#[derive(Clone, Copy, PartialEq)]
enum LetKind {
    Scalar,
    Vector,
    Point,
}

/// A random model. Names are chosen first, so that expressions can refer
/// to anything declared anywhere in the model. `chaos` is the percentage of
/// choices that go wrong (unknown names, wrong kinds, wrong counts, extreme
/// numbers): at 0 most models compile, at 30 none do.
pub(crate) struct Grammar<'r> {
    rng: &'r mut Rng,
    pub(crate) chaos: u64,
    /// Accelerations (`dxdt` of a speed) are allowed: outputs and states.
    accelerations: bool,
    bodies: Vec<BodyInfo>,
    params: Vec<String>,
    scalars: Vec<String>,
    points: Vec<(String, String)>,
    lets: Vec<(String, LetKind)>,
    /// How many of `lets` expressions may use (while `let` number `i` is
    /// written, only those before it: no cycles unless going wrong).
    visible_lets: usize,
    fns: Vec<(String, usize)>,
    outputs: Vec<String>,
}

impl<'r> Grammar<'r> {
    pub(crate) fn new(rng: &'r mut Rng) -> Grammar<'r> {
        let chaos = *rng.pick(&[0, 0, 0, 1, 2, 5, 10, 30]);
        Grammar {
            rng,
            chaos,
            accelerations: false,
            bodies: Vec::new(),
            params: Vec::new(),
            scalars: vec!["t".to_string()],
            points: Vec::new(),
            lets: Vec::new(),
            visible_lets: 0,
            fns: Vec::new(),
            outputs: Vec::new(),
        }
    }

    /// True when this choice should go wrong.
    fn wrong(&mut self) -> bool {
        self.rng.chance(self.chaos)
    }

    /// A fresh name built from `prefix`, or (going wrong) an odd one.
    fn name(&mut self, prefix: &str, i: usize) -> String {
        if self.wrong() {
            self.rng.pick(ODD_NAMES).to_string()
        } else {
            format!("{prefix}{i}")
        }
    }

    fn number(&mut self) -> String {
        if self.wrong() {
            self.rng.pick(EXTREME_NUMBERS).to_string()
        } else {
            self.rng.pick(NUMBERS).to_string()
        }
    }

    pub(crate) fn model(mut self) -> String {
        // Names first.
        let n_bodies = self.rng.range(0, 5);
        for i in 0..n_bodies {
            let name = if self.wrong() {
                self.rng.pick(ODD_NAMES).to_string()
            } else if self.wrong() {
                self.rng.pick(BODY_NAMES).to_string()
            } else {
                BODY_NAMES[i].to_string()
            };
            let mut rotations = *self.rng.pick(&[0, 1, 1, 1, 3, 3]);
            if self.wrong() {
                rotations = *self.rng.pick(&[2, 4]);
            }
            let translations = *self.rng.pick(&[0, 0, 0, 1, 2, 3]);
            let quaternion = rotations == 3 && self.rng.chance(25);
            let dofs = rotations + translations;
            let explicit = self.rng.chance(60);
            let (mut q, mut u) = (Vec::new(), Vec::new());
            if explicit {
                for k in 0..dofs + usize::from(quaternion) {
                    q.push(self.name(&format!("q{}_", name.to_lowercase()), k));
                }
                for k in 0..dofs {
                    u.push(self.name(&format!("u{}_", name.to_lowercase()), k));
                }
            }
            self.scalars.extend(q.iter().cloned());
            self.scalars.extend(u.iter().cloned());
            self.bodies.push(BodyInfo {
                name,
                rotations,
                translations,
                quaternion,
                q,
                u,
            });
        }
        for i in 0..self.rng.range(0, 6) {
            let name = if self.wrong() {
                self.name("p", i)
            } else {
                PARAM_NAMES[i].to_string()
            };
            self.params.push(name.clone());
            self.scalars.push(name);
        }
        self.outputs = (0..self.rng.range(0, 4))
            .map(|i| self.name("y", i))
            .collect();
        let inputs: Vec<String> = (0..self.rng.range(0, 2))
            .map(|i| self.name("inp", i))
            .collect();
        let states: Vec<String> = (0..self.rng.range(0, 2))
            .map(|i| self.name("s", i))
            .collect();
        let subs: Vec<(String, Vec<String>)> = (0..self.rng.range(0, 1))
            .map(|i| {
                let outs = (0..self.rng.range(0, 3))
                    .map(|j| self.name("out", 10 * i + j))
                    .collect();
                (self.name("sub", i), outs)
            })
            .collect();
        for i in 0..self.rng.range(0, 2) {
            let arity = self.rng.range(0, 3);
            let name = self.name("f", i);
            self.fns.push((name, arity));
        }
        for i in 0..self.rng.range(0, 3) {
            let name = self.name("P", i);
            let body = self.body_name();
            self.points.push((name, body));
        }
        for i in 0..self.rng.range(0, 3) {
            let name = self.name("r", i);
            let kind = *self
                .rng
                .pick(&[LetKind::Scalar, LetKind::Vector, LetKind::Point]);
            self.lets.push((name, kind));
        }
        let scalar_args = self.scalars.clone();
        self.scalars.extend(inputs.iter().cloned());
        self.scalars.extend(states.iter().cloned());
        for (_, outs) in &subs {
            self.scalars.extend(outs.iter().cloned());
        }

        // Then the items.
        let mut items: Vec<String> = Vec::new();
        let settings = if self.wrong() {
            2
        } else {
            self.rng.range(0, 1)
        };
        for _ in 0..settings {
            items.push(self.settings());
        }
        if !self.params.is_empty() {
            let params = self.params.clone();
            if self.rng.chance(70) {
                let mut s = String::from("parameters {\n");
                for p in &params {
                    let _ = writeln!(
                        s,
                        "    /// Doc.\n    {p} = {}{},",
                        self.value(),
                        self.rng.pick(UNITS)
                    );
                }
                s.push('}');
                items.push(s);
            } else {
                for p in &params {
                    items.push(format!(
                        "parameter {p} = {}{};",
                        self.value(),
                        self.rng.pick(UNITS)
                    ));
                }
            }
        }
        for input in &inputs {
            let default = if self.rng.chance(50) {
                format!(" = {}", self.value())
            } else {
                String::new()
            };
            items.push(format!("input {input}{}{default};", self.rng.pick(UNITS)));
        }
        for (name, arity) in self.fns.clone() {
            let args: Vec<String> = (0..arity).map(|k| format!("a{k}")).collect();
            items.push(format!("extern fn {name}({});", args.join(", ")));
        }
        for (name, outs) in &subs {
            let args: Vec<String> = (0..self.rng.range(0, 2))
                .map(|_| {
                    if self.wrong() {
                        self.scalar(2)
                    } else {
                        self.rng.pick(&scalar_args).clone()
                    }
                })
                .collect();
            let outs: Vec<String> = outs
                .iter()
                .map(|o| format!("{o}{}", self.rng.pick(UNITS)))
                .collect();
            items.push(format!(
                "extern sub {name}({}) -> ({});",
                args.join(", "),
                outs.join(", ")
            ));
        }
        for i in 0..self.bodies.len() {
            items.push(self.body(i));
        }
        for (name, body) in self.points.clone() {
            let label = if self.rng.chance(30) {
                " \"a point\""
            } else {
                ""
            };
            let at = if self.wrong() {
                self.any(2)
            } else {
                self.list3(false)
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
        for i in 0..self.rng.range(0, 3) {
            items.push(self.force(i));
        }
        for i in 0..self.rng.range(0, 3) {
            items.push(self.moment(i));
        }
        let gravities = if self.wrong() {
            2
        } else {
            *self.rng.pick(&[0, 1, 1])
        };
        for _ in 0..gravities {
            let g = self.vector(2);
            items.push(format!("gravity = {g};"));
        }
        self.accelerations = true;
        for s in &states {
            items.push(self.state(s));
        }
        for name in self.outputs.clone() {
            let value = if self.wrong() {
                self.any(3)
            } else {
                self.scalar(3)
            };
            items.push(format!("output {name}{} = {value};", self.rng.pick(UNITS)));
        }
        // Mostly in order; sometimes shuffled (uses before declarations).
        if self.rng.chance(25) {
            for i in (1..items.len()).rev() {
                let j = self.rng.below(i + 1);
                items.swap(i, j);
            }
        }
        let mut out = format!(
            "//! A generated model ({}% of choices wrong).\n\n/// Its doc.\n",
            self.chaos
        );
        if !self.wrong() {
            let name = if self.wrong() {
                *self.rng.pick(&["fn", "r#M", "m_m", "N", "self", "Model"])
            } else {
                *self.rng.pick(&["M", "Fuzz", "M2", "CartPole"])
            };
            let _ = writeln!(out, "model {name};\n");
        }
        for item in items {
            out.push_str(&item);
            out.push('\n');
        }
        out
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

    fn value(&mut self) -> String {
        let sign = if self.rng.chance(20) { "-" } else { "" };
        format!("{sign}{}", self.number())
    }

    fn body_name(&mut self) -> String {
        if self.wrong() {
            return self.rng.pick(ODD_NAMES).to_string();
        }
        if self.bodies.is_empty() || self.rng.chance(10) {
            return "N".to_string();
        }
        let i = self.rng.below(self.bodies.len());
        self.bodies[i].name.clone()
    }

    fn body(&mut self, i: usize) -> String {
        let name = self.bodies[i].name.clone();
        let dofs = self.bodies[i].rotations + self.bodies[i].translations;
        let mut entries: Vec<String> = Vec::new();
        // Parent: an earlier body (a tree); going wrong, a later one, itself
        // (cycles), an unknown name or not a name at all.
        if self.rng.chance(80) {
            let parent = if self.wrong() {
                match self.rng.below(4) {
                    0 => self.rng.pick(ODD_NAMES).to_string(),
                    1 => name.clone(),
                    2 => self.any(1),
                    _ => self.rng.pick(BODY_NAMES).to_string(),
                }
            } else if i == 0 || self.rng.chance(20) {
                "N".to_string()
            } else {
                self.bodies[self.rng.below(i)].name.clone()
            };
            entries.push(format!("parent: {parent}"));
        }
        if self.rng.chance(50) {
            let v = self.list3(true);
            entries.push(format!("joint: {v}"));
        }
        let r = self.bodies[i].rotations;
        if r > 0 || self.wrong() {
            let v = if self.wrong() {
                if self.rng.chance(30) {
                    "quaternion".to_string()
                } else {
                    self.any(1)
                }
            } else if self.bodies[i].quaternion {
                "quaternion".to_string()
            } else if r == 1 && self.rng.chance(50) {
                self.axis()
            } else {
                // Consecutive axes differ.
                let mut axes: Vec<String> = Vec::new();
                while axes.len() < r {
                    let a = self.axis();
                    if axes.last() != Some(&a) {
                        axes.push(a);
                    }
                }
                format!("[{}]", axes.join(", "))
            };
            entries.push(format!("rotate: {v}"));
        }
        let tr = self.bodies[i].translations;
        if tr > 0 || self.wrong() {
            let v = if self.wrong() {
                self.any(1)
            } else if tr == 1 && self.rng.chance(50) {
                self.axis()
            } else if tr == 1 && self.rng.chance(50) {
                // A direction.
                let d = if self.wrong() {
                    "[0, 0, 0]".to_string()
                } else {
                    self.list3(true)
                };
                format!("[{d}]")
            } else {
                // Distinct axes.
                let mut axes: Vec<String> = Vec::new();
                while axes.len() < tr {
                    let a = self.axis();
                    if !axes.contains(&a) || self.wrong() {
                        axes.push(a);
                    }
                }
                format!("[{}]", axes.join(", "))
            };
            entries.push(format!("translate: {v}"));
        }
        if self.rng.chance(60) {
            let v = match self.rng.below(6) {
                0 => "0".to_string(),
                _ => self.positive(),
            };
            entries.push(format!("mass: {v}"));
        }
        if self.rng.chance(60) {
            let v = self.inertia();
            entries.push(format!("inertia: {v}"));
        }
        if self.rng.chance(50) {
            let v = self.list3(true);
            entries.push(format!("cm: {v}"));
        }
        let (q, u) = (self.bodies[i].q.clone(), self.bodies[i].u.clone());
        for (key, names) in [("q", q), ("u", u)] {
            if names.is_empty() && !self.wrong() {
                continue;
            }
            let mut names = names;
            if self.wrong() {
                names.pop();
            }
            if self.wrong() {
                names.push(self.rng.pick(ODD_NAMES).to_string());
            }
            entries.push(format!("{key}: [{}]", names.join(", ")));
        }
        let coordinates = dofs + usize::from(self.bodies[i].quaternion);
        for (key, count) in [("initial", coordinates), ("initial_speeds", dofs)] {
            if (dofs > 0 && self.rng.chance(25)) || self.wrong() {
                let n = if self.wrong() {
                    self.rng.range(0, 4)
                } else {
                    count
                };
                let vals: Vec<String> = (0..n).map(|_| self.constant(1)).collect();
                entries.push(format!("{key}: [{}]", vals.join(", ")));
            }
        }
        for key in ["small", "lock"] {
            if self.rng.chance(20) {
                let v = self.flags(i, key == "lock");
                entries.push(format!("{key}: {v}"));
            }
        }
        if self.wrong() {
            let key = *self
                .rng
                .pick(&["rotat", "mass", "parent", "Mass", "weight"]);
            let v = self.any(1);
            entries.push(format!("{key}: {v}"));
        }
        if self.rng.chance(15) {
            for k in (1..entries.len()).rev() {
                let j = self.rng.below(k + 1);
                entries.swap(k, j);
            }
        }
        let label = if self.rng.chance(30) {
            " \"a body\""
        } else {
            ""
        };
        format!("body {name}{label} {{ {} }}", entries.join(", "))
    }

    fn axis(&mut self) -> String {
        if self.wrong() {
            self.rng
                .pick(&["0", "4", "-1", "1.0", "x", "n1", "99999999999999999999"])
                .to_string()
        } else {
            self.rng.pick(&["1", "2", "3"]).to_string()
        }
    }

    fn inertia(&mut self) -> String {
        if self.wrong() {
            return match self.rng.below(3) {
                0 => {
                    let n = *self.rng.pick(&[0, 1, 2, 4]);
                    let args: Vec<String> = (0..n).map(|_| self.constant(1)).collect();
                    format!("diag({})", args.join(", "))
                }
                1 => {
                    let rows: Vec<String> = (0..3).map(|_| self.list3(true)).collect();
                    format!("[{}]", rows.join(", "))
                }
                _ => self.any(1),
            };
        }
        match self.rng.below(6) {
            0 => "0".to_string(),
            1 | 2 => {
                let args: Vec<String> = (0..3).map(|_| self.positive()).collect();
                format!("diag({})", args.join(", "))
            }
            3 | 4 => {
                let mut m: [[String; 3]; 3] = Default::default();
                for r in 0..3 {
                    for c in r..3 {
                        m[r][c] = if r == c {
                            self.positive()
                        } else {
                            self.constant(1)
                        };
                        m[c][r] = m[r][c].clone();
                    }
                }
                let rows: Vec<String> = m
                    .iter()
                    .map(|row| format!("[{}]", row.join(", ")))
                    .collect();
                format!("[{}]", rows.join(", "))
            }
            _ => {
                let items: Vec<String> = (0..3).map(|_| self.positive()).collect();
                format!("[{}]", items.join(", "))
            }
        }
    }

    /// A constant that is not a negative number (masses, moments of inertia).
    fn positive(&mut self) -> String {
        if self.wrong() {
            return self.constant(1);
        }
        let a = self.positive_leaf();
        if self.rng.chance(30) {
            format!("{a}*{}", self.positive_leaf())
        } else {
            a
        }
    }

    fn positive_leaf(&mut self) -> String {
        if !self.params.is_empty() && self.rng.chance(50) {
            self.rng.pick(&self.params).clone()
        } else {
            self.rng.pick(NUMBERS).to_string()
        }
    }

    /// The value of `small` or `lock`: words and coordinate names. A
    /// quaternion's rotation can be neither; locked rotations go together.
    fn flags(&mut self, i: usize, lock: bool) -> String {
        let body = &self.bodies[i];
        let nt = body.translations;
        let mut words: Vec<String> = vec!["none".into(), "translations".into()];
        words.extend(body.q.iter().take(nt).cloned());
        if !body.quaternion {
            words.extend(["all".into(), "rotations".into()]);
            if !lock || body.rotations == 1 {
                words.push("angles".into());
                words.extend(body.q.iter().skip(nt).cloned());
            }
        }
        if self.wrong() {
            words.extend(["q", "xyz", "1", "N", "all", "rotations"].map(String::from));
            words.extend(self.bodies[i].q.iter().cloned());
        }
        if self.rng.chance(50) {
            self.rng.pick(&words).clone()
        } else {
            let n = self.rng.range(0, 3);
            let picked: Vec<String> = (0..n).map(|_| self.rng.pick(&words).clone()).collect();
            format!("[{}]", picked.join(", "))
        }
    }

    fn list3(&mut self, constant: bool) -> String {
        if self.wrong() {
            return match self.rng.below(2) {
                0 => self.any(1),
                _ => {
                    let n = *self.rng.pick(&[0, 1, 2, 4]);
                    let items: Vec<String> = (0..n).map(|_| self.scalar(1)).collect();
                    format!("[{}]", items.join(", "))
                }
            };
        }
        let items: Vec<String> = (0..3)
            .map(|_| {
                if constant {
                    self.constant(1)
                } else {
                    self.scalar(1)
                }
            })
            .collect();
        format!("[{}]", items.join(", "))
    }

    fn force(&mut self, i: usize) -> String {
        let name = self.name("F", i);
        let mut entries = Vec::new();
        if !self.wrong() {
            let on = self.point(1);
            entries.push(format!("on: {on}"));
        }
        if self.rng.chance(40) {
            let r = self.point(1);
            entries.push(format!("reaction: {r}"));
        }
        if self.wrong() {
            for key in ["vector", "along", "magnitude", "about"] {
                if self.rng.chance(40) {
                    let v = self.any(2);
                    entries.push(format!("{key}: {v}"));
                }
            }
        } else if self.rng.chance(50) {
            let v = self.vector(3);
            entries.push(format!("vector: {v}"));
        } else {
            let a = self.vector(2);
            let m = self.scalar(3);
            entries.push(format!("along: {a}"));
            entries.push(format!("magnitude: {m}"));
        }
        format!("force {name} {{ {} }}", entries.join(", "))
    }

    fn moment(&mut self, i: usize) -> String {
        let name = self.name("M", i);
        let mut entries = Vec::new();
        if !self.wrong() {
            let on = self.body_ref();
            entries.push(format!("on: {on}"));
        }
        if self.rng.chance(40) {
            let r = self.body_ref();
            entries.push(format!("reaction: {r}"));
        }
        if self.wrong() {
            for key in ["vector", "about", "magnitude", "along"] {
                if self.rng.chance(40) {
                    let v = self.any(2);
                    entries.push(format!("{key}: {v}"));
                }
            }
        } else if self.rng.chance(50) {
            let v = self.vector(3);
            entries.push(format!("vector: {v}"));
        } else {
            let a = self.vector(1);
            let m = self.scalar(3);
            entries.push(format!("about: {a}"));
            entries.push(format!("magnitude: {m}"));
        }
        format!("moment {name} {{ {} }}", entries.join(", "))
    }

    fn state(&mut self, name: &str) -> String {
        let mut entries = Vec::new();
        if self.rng.chance(80) {
            let v = self.constant(1);
            entries.push(format!("initial: {v}"));
        }
        if !self.wrong() {
            let v = self.scalar(3);
            entries.push(format!("derivative: {v}"));
        }
        format!(
            "state {name}{} {{ {} }}",
            self.rng.pick(UNITS),
            entries.join(", ")
        )
    }
}
