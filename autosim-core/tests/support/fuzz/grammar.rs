//! Grammar-aware models: names first, then items whose values are mostly
//! of the right kind, each choice going wrong with the model's `chaos`
//! percentage. The names are declared here; the items are written in
//! `items` (bodies in `bodies`, forces, moments and gravity in `loads`,
//! constraints and motions in `constraints`),
//! expressions in `exprs`.
//!
//! Every choice draws from the one seeded [`Rng`] in a fixed order, so a
//! seed always gives the same model: keep the order of the draws when
//! changing the code.

use std::fmt::Write;

use super::Rng;
use super::vocab::*;

mod bodies;
mod constraints;
mod events;
mod exprs;
mod items;
mod loads;

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

/// The declared names that only their own items use (the others are kept
/// in [`Grammar`]).
struct Names {
    inputs: Vec<String>,
    states: Vec<String>,
    /// Extern subroutines and their outputs.
    subs: Vec<(String, Vec<String>)>,
    /// The scalars an extern subroutine's arguments may name: those
    /// declared before the inputs, states and subroutine outputs.
    scalar_args: Vec<String>,
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
    /// Every expression is wrapped in the unit check's escape (`(e) as
    /// [1]`, and the unit its item needs around an item's value), so that
    /// random formulas pass the check and reach the later phases; without
    /// it, most models mix units and stop at the check.
    trust: bool,
}

impl<'r> Grammar<'r> {
    pub(crate) fn new(rng: &'r mut Rng) -> Grammar<'r> {
        let chaos = *rng.pick(&[0, 0, 0, 1, 2, 5, 10, 30]);
        let trust = rng.chance(60);
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
            trust,
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
        let names = self.declare();
        // Then the items.
        let items = self.items(&names);
        self.text(items)
    }

    /// Chooses the names of everything the model declares.
    fn declare(&mut self) -> Names {
        self.declare_bodies();
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
        self.declare_functions_points_lets();
        let scalar_args = self.scalars.clone();
        self.scalars.extend(inputs.iter().cloned());
        self.scalars.extend(states.iter().cloned());
        for (_, outs) in &subs {
            self.scalars.extend(outs.iter().cloned());
        }
        Names {
            inputs,
            states,
            subs,
            scalar_args,
        }
    }

    /// The bodies: names, numbers of rotations and translations, and
    /// (sometimes) the names of their coordinates and speeds.
    fn declare_bodies(&mut self) {
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
    }

    /// Extern functions (with their arities), points (with their bodies)
    /// and `let`s (with their kinds).
    fn declare_functions_points_lets(&mut self) {
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
    }

    /// The model's text: the items mostly in order, sometimes shuffled
    /// (uses before declarations), under a header.
    fn text(&mut self, mut items: Vec<String>) -> String {
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

    /// A unit to declare (or none); going wrong, one the check refuses.
    fn unit(&mut self) -> String {
        match self.wrong() {
            true => self.rng.pick(BAD_UNITS).to_string(),
            false => self.rng.pick(UNITS).to_string(),
        }
    }

    /// `e` taken to be in `unit` (in trust mode, unless going wrong).
    fn in_unit(&mut self, e: String, unit: &str) -> String {
        if self.trust && !self.wrong() {
            format!("({e}) as [{unit}]")
        } else {
            e
        }
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
}
