//! Seeded generators of model texts for the pipeline fuzzer, and the run of
//! one text through the whole compiler with panics caught.
//!
//! Shared by `examples/fuzz.rs` (long runs) and `tests/fuzz_pipeline.rs`
//! (a few hundred cases in CI) through `#[path]`. Three kinds of input:
//!
//! - [`Kind::Grammar`]: random models written with the grammar in mind —
//!   bodies with random parents (cycles, unknown ones), random options with
//!   valid and invalid values, expressions over declared and undeclared names
//!   calling every operation with random arity and argument kinds, and every
//!   other item; sometimes a few mutations on top;
//! - [`Kind::Mutation`]: the example models with tokens or lines deleted,
//!   duplicated or swapped, numbers made huge, tiny, zero or negative, and
//!   identifiers renamed;
//! - [`Kind::Soup`]: raw bytes, random characters and keyword/punctuation soups.
//!
//! Sizes stay small: a case takes milliseconds in a release build.

#![allow(dead_code)]

use std::fmt::Write;
use std::panic::{AssertUnwindSafe, catch_unwind};

use autosim_core::diag::SourceFile;
use autosim_core::emit::{EmitOptions, format_tokens, markdown, model_tokens};
use autosim_core::pipeline::{compile_source, compile_tokens};

/// A small deterministic generator (SplitMix64): no dependency, the same
/// sequence on every platform.
pub struct Rng(u64);

impl Rng {
    /// The generator of case `case` of a run seeded with `seed`: each case
    /// can be replayed alone.
    pub fn for_case(seed: u64, case: u64) -> Rng {
        let mut rng = Rng(seed ^ case.wrapping_mul(0xA24B_AED4_963E_E407));
        rng.next();
        rng
    }

    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    /// A number in `lo..=hi`.
    pub fn range(&mut self, lo: usize, hi: usize) -> usize {
        lo + self.below(hi - lo + 1)
    }

    /// True with probability `percent`/100.
    pub fn chance(&mut self, percent: u64) -> bool {
        self.next() % 100 < percent
    }

    /// One element of a non-empty slice.
    pub fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len())]
    }
}

/// What a generated input is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A random model following the grammar (maybe mutated a little).
    Grammar,
    /// A mutated example model.
    Mutation,
    /// Bytes, characters or tokens at random.
    Soup,
}

/// The example models, mutated by [`Kind::Mutation`] (the large chains are
/// left out: their bodies are already in the smaller ones).
pub const EXAMPLES: &[(&str, &str)] = &[
    (
        "features",
        include_str!("../../../examples/models/features.sim"),
    ),
    (
        "satellite",
        include_str!("../../../examples/models/satellite.sim"),
    ),
    (
        "satellite_small",
        include_str!("../../../examples/models/satellite_small.sim"),
    ),
    (
        "chain_planar_1",
        include_str!("../../../examples/models/chain_planar_1.sim"),
    ),
    (
        "chain_planar_2",
        include_str!("../../../examples/models/chain_planar_2.sim"),
    ),
    (
        "chain_planar_2_f32",
        include_str!("../../../examples/models/chain_planar_2_f32.sim"),
    ),
    (
        "chain_planar_3",
        include_str!("../../../examples/models/chain_planar_3.sim"),
    ),
    (
        "chain_spatial_1",
        include_str!("../../../examples/models/chain_spatial_1.sim"),
    ),
    (
        "chain_spatial_2",
        include_str!("../../../examples/models/chain_spatial_2.sim"),
    ),
    (
        "chain_spatial_3",
        include_str!("../../../examples/models/chain_spatial_3.sim"),
    ),
    (
        "chain_spatial_3_stiff",
        include_str!("../../../examples/models/chain_spatial_3_stiff.sim"),
    ),
];

/// Case `case` of the run seeded with `seed`: its kind and text.
pub fn generate(seed: u64, case: u64) -> (Kind, String) {
    let mut rng = Rng::for_case(seed, case);
    match rng.below(10) {
        0..=4 => {
            let mut text = Grammar::new(&mut rng).model();
            if rng.chance(20) {
                text = mutate(&mut rng, &text);
            }
            (Kind::Grammar, text)
        }
        5..=7 => {
            let base = rng.pick(EXAMPLES).1;
            (Kind::Mutation, mutate(&mut rng, base))
        }
        _ => (Kind::Soup, soup(&mut rng)),
    }
}

// ---------------------------------------------------------------------------
// Grammar-aware models.

/// Numbers, ordinary and extreme (digits beyond 38, exponents beyond 308,
/// underscores, leading zeros).
const NUMBERS: &[&str] = &[
    "0",
    "1",
    "2",
    "3",
    "0.5",
    "1.5",
    "10",
    "9.81",
    "1e-3",
    "3.1415926",
    "0.0",
    "00007",
    "1_000",
    "2.5e+2",
    "1e0",
    "1e38",
    "1e39",
    "1e-38",
    "1e-39",
    "1e300",
    "1e-300",
    "1e400",
    "1e-400",
    "12345678901234567890123456789012345678",
    "123456789012345678901234567890123456789012",
    "0.1234567890123456789012345678901234567890",
    "170141183460469231731687303715884105727",
    "340282366920938463463374607431768211456",
    "4294967296",
    "0.000001",
    "65536",
];

/// Exponents for `^`.
const EXPONENTS: &[&str] = &[
    "2", "3", "0", "-1", "-2", "0.5", "(1/2)", "(1/3)", "(-1/2)", "10", "64", "100", "1000000",
    "1e30", "-3", "1.5", "(2^10)", "(10^10)",
];

const BODY_NAMES: &[&str] = &["A", "B", "C", "D", "E", "Arm", "Bus", "W"];
const ODD_NAMES: &[&str] = &[
    "N",
    "t",
    "n1",
    "b2",
    "x",
    "k",
    "r#x",
    "_",
    "self",
    "fn",
    "q",
    "u",
    "dot",
    "sin",
    "all",
    "cm",
    "origin",
    "Model",
    "B",
    "undeclared",
    "é",
    "ẞ",
];
const PARAM_NAMES: &[&str] = &["k", "m", "g", "L", "c", "I1", "I2", "p", "tau", "mu"];
const UNITS: &[&str] = &[
    "",
    " [m]",
    " [kg]",
    " [N m/rad]",
    " [m/s^2]",
    " [rad]",
    " [1/s]",
];
const SCALAR_FUNCS: &[&str] = &[
    "sin", "cos", "tan", "asin", "acos", "atan2", "exp", "ln", "abs", "sign", "min", "max", "sqrt",
];
const OPERATIONS: &[&str] = &[
    "dot",
    "cross",
    "mag",
    "dir",
    "angle",
    "dot_plane",
    "pos",
    "vel",
    "rot",
    "q",
    "u",
    "dxdt",
    "partial",
    "nominal",
    "constant_part",
    "sqrt",
    "diag",
    "frob",
];

struct BodyInfo {
    name: String,
    rotations: usize,
    translations: usize,
    q: Vec<String>,
    u: Vec<String>,
}

/// A random model: names are chosen first, so that expressions can refer to
/// anything declared anywhere in the model (and to things never declared).
struct Grammar<'r> {
    rng: &'r mut Rng,
    bodies: Vec<BodyInfo>,
    params: Vec<String>,
    scalars: Vec<String>,
    points: Vec<(String, String)>,
    lets: Vec<String>,
    fns: Vec<(String, usize)>,
}

impl<'r> Grammar<'r> {
    fn new(rng: &'r mut Rng) -> Grammar<'r> {
        Grammar {
            rng,
            bodies: Vec::new(),
            params: Vec::new(),
            scalars: vec!["t".to_string()],
            points: Vec::new(),
            lets: Vec::new(),
            fns: Vec::new(),
        }
    }

    /// A name: usually a fresh one built from `prefix`, sometimes an odd one
    /// (keywords, built-ins, clashes).
    fn name(&mut self, prefix: &str, i: usize) -> String {
        if self.rng.chance(4) {
            self.rng.pick(ODD_NAMES).to_string()
        } else {
            format!("{prefix}{i}")
        }
    }

    fn model(mut self) -> String {
        // Names first.
        let n_bodies = self.rng.range(0, 5);
        for i in 0..n_bodies {
            let name = if self.rng.chance(5) {
                self.rng.pick(ODD_NAMES).to_string()
            } else if self.rng.chance(70) {
                BODY_NAMES[i].to_string()
            } else {
                self.rng.pick(BODY_NAMES).to_string()
            };
            let rotations = *self.rng.pick(&[0, 1, 1, 1, 3, 3, 2]);
            let translations = *self.rng.pick(&[0, 0, 0, 1, 2, 3]);
            let dofs = rotations + translations;
            let explicit = self.rng.chance(60);
            let (mut q, mut u) = (Vec::new(), Vec::new());
            for k in 0..dofs {
                if explicit {
                    q.push(self.name(&format!("q{}_", name.to_lowercase()), k));
                    u.push(self.name(&format!("u{}_", name.to_lowercase()), k));
                }
            }
            self.scalars.extend(q.iter().cloned());
            self.scalars.extend(u.iter().cloned());
            self.bodies.push(BodyInfo {
                name,
                rotations,
                translations,
                q,
                u,
            });
        }
        for i in 0..self.rng.range(0, 6) {
            let name = if self.rng.chance(90) {
                PARAM_NAMES[i].to_string()
            } else {
                self.name("p", i)
            };
            self.params.push(name.clone());
            self.scalars.push(name);
        }
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
            self.lets.push(name);
        }
        self.scalars.extend(inputs.iter().cloned());
        self.scalars.extend(states.iter().cloned());
        for (_, outs) in &subs {
            self.scalars.extend(outs.iter().cloned());
        }

        // Then the items.
        let mut items: Vec<String> = Vec::new();
        for _ in 0..self.rng.range(0, 2) {
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
            let args: Vec<String> = (0..self.rng.range(0, 2)).map(|_| self.scalar(2)).collect();
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
            let at = if self.rng.chance(85) {
                self.list3(false)
            } else {
                self.any(2)
            };
            items.push(format!("point {name}{label} in {body} at {at};"));
        }
        for name in self.lets.clone() {
            let value = self.any(3);
            items.push(format!("let {name} = {value};"));
        }
        for i in 0..self.rng.range(0, 3) {
            items.push(self.force(i));
        }
        for i in 0..self.rng.range(0, 3) {
            items.push(self.moment(i));
        }
        for _ in 0..*self.rng.pick(&[0, 1, 1, 1, 2]) {
            let g = self.vector(2);
            items.push(format!("gravity = {g};"));
        }
        for s in &states {
            items.push(self.state(s));
        }
        for i in 0..self.rng.range(0, 4) {
            let name = self.name("y", i);
            let value = if self.rng.chance(60) {
                self.scalar(3)
            } else {
                self.any(3)
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
        let mut out = String::from("//! A generated model.\n\n/// Its doc.\n");
        if self.rng.chance(97) {
            let _ = writeln!(
                out,
                "model {};\n",
                self.rng
                    .pick(&["M", "Fuzz", "M2", "Model", "fn", "r#M", "m_m"])
            );
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
            let v = *self.rng.pick(&[
                "0",
                "1",
                "2",
                "3",
                "-1",
                "100",
                "1e40",
                "99999999999999999999",
                "x",
                "1.5",
                "[1]",
            ]);
            entries.push(format!("threshold: {v}"));
        }
        if self.rng.chance(70) {
            let v = *self.rng.pick(&["f64", "f32", "f16", "i32", "1", "\"f64\""]);
            entries.push(format!("float: {v}"));
        }
        if self.rng.chance(10) {
            entries.push(format!(
                "{}: 1",
                self.rng.pick(&["thresh", "float", "mass"])
            ));
        }
        format!("settings {{ {} }}", entries.join(", "))
    }

    fn value(&mut self) -> String {
        let sign = if self.rng.chance(20) { "-" } else { "" };
        format!("{sign}{}", self.rng.pick(NUMBERS))
    }

    fn body_name(&mut self) -> String {
        match self.rng.below(10) {
            0 => "N".to_string(),
            1 => self.rng.pick(ODD_NAMES).to_string(),
            _ if self.bodies.is_empty() => "N".to_string(),
            _ => {
                let i = self.rng.below(self.bodies.len());
                self.bodies[i].name.clone()
            }
        }
    }

    fn body(&mut self, i: usize) -> String {
        let name = self.bodies[i].name.clone();
        let dofs = self.bodies[i].rotations + self.bodies[i].translations;
        let mut entries: Vec<String> = Vec::new();
        // Parent: mostly an earlier body (a tree), sometimes a later one, itself
        // (cycles), an unknown name or not a name at all.
        if self.rng.chance(80) {
            let parent = match self.rng.below(12) {
                0 => self.rng.pick(ODD_NAMES).to_string(),
                1 => name.clone(),
                2 => self.any(1),
                3 | 4 => self.body_name(),
                _ if i == 0 => "N".to_string(),
                _ => self.bodies[self.rng.below(i)].name.clone(),
            };
            entries.push(format!("parent: {parent}"));
        }
        if self.rng.chance(50) {
            let v = if self.rng.chance(85) {
                self.list3(true)
            } else {
                self.any(1)
            };
            entries.push(format!("joint: {v}"));
        }
        let r = self.bodies[i].rotations;
        if r > 0 || self.rng.chance(10) {
            let v = if r == 1 && self.rng.chance(50) {
                self.axis()
            } else if self.rng.chance(90) {
                let axes: Vec<String> = (0..r).map(|_| self.axis()).collect();
                format!("[{}]", axes.join(", "))
            } else {
                self.any(1)
            };
            entries.push(format!("rotate: {v}"));
        }
        let tr = self.bodies[i].translations;
        if tr > 0 || self.rng.chance(10) {
            let v = if tr == 1 && self.rng.chance(50) {
                self.axis()
            } else if self.rng.chance(90) {
                let dirs: Vec<String> = (0..tr)
                    .map(|_| match self.rng.below(3) {
                        0 => self.list3(true),
                        1 => "[0, 0, 0]".to_string(),
                        _ => self.axis(),
                    })
                    .collect();
                format!("[{}]", dirs.join(", "))
            } else {
                self.any(1)
            };
            entries.push(format!("translate: {v}"));
        }
        if self.rng.chance(60) {
            let v = match self.rng.below(6) {
                0 => "0".to_string(),
                1 => self.any(1),
                _ => self.constant(1),
            };
            entries.push(format!("mass: {v}"));
        }
        if self.rng.chance(60) {
            let v = self.inertia();
            entries.push(format!("inertia: {v}"));
        }
        if self.rng.chance(50) {
            let v = if self.rng.chance(85) {
                self.list3(true)
            } else {
                self.any(1)
            };
            entries.push(format!("cm: {v}"));
        }
        let (q, u) = (self.bodies[i].q.clone(), self.bodies[i].u.clone());
        for (key, names) in [("q", q), ("u", u)] {
            if names.is_empty() && !self.rng.chance(5) {
                continue;
            }
            let mut names = names;
            if self.rng.chance(10) {
                names.pop();
            }
            if self.rng.chance(10) {
                names.push(self.rng.pick(ODD_NAMES).to_string());
            }
            entries.push(format!("{key}: [{}]", names.join(", ")));
        }
        for key in ["initial", "initial_speeds"] {
            if self.rng.chance(25) {
                let n = if self.rng.chance(80) {
                    dofs
                } else {
                    self.rng.range(0, 4)
                };
                let vals: Vec<String> = (0..n).map(|_| self.constant(1)).collect();
                entries.push(format!("{key}: [{}]", vals.join(", ")));
            }
        }
        if self.rng.chance(25) {
            let v = self.small(i);
            entries.push(format!("small: {v}"));
        }
        if self.rng.chance(5) {
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
        self.rng
            .pick(&[
                "1",
                "2",
                "3",
                "1",
                "2",
                "3",
                "0",
                "4",
                "-1",
                "1.0",
                "x",
                "n1",
                "99999999999999999999",
            ])
            .to_string()
    }

    fn inertia(&mut self) -> String {
        match self.rng.below(8) {
            0 => "0".to_string(),
            1 | 2 => {
                let args: Vec<String> = (0..3).map(|_| self.constant(1)).collect();
                format!("diag({})", args.join(", "))
            }
            3 => {
                let args: Vec<String> = (0..self.rng.range(0, 4))
                    .map(|_| self.constant(1))
                    .collect();
                format!("diag({})", args.join(", "))
            }
            4 | 5 => {
                let mut m = [
                    [String::new(), String::new(), String::new()],
                    [String::new(), String::new(), String::new()],
                    [String::new(), String::new(), String::new()],
                ];
                for r in 0..3 {
                    for c in r..3 {
                        m[r][c] = self.constant(1);
                        m[c][r] = if self.rng.chance(90) {
                            m[r][c].clone()
                        } else {
                            self.constant(1)
                        };
                    }
                }
                let rows: Vec<String> = m
                    .iter()
                    .map(|row| format!("[{}]", row.join(", ")))
                    .collect();
                format!("[{}]", rows.join(", "))
            }
            6 => self.list3(true),
            _ => self.any(1),
        }
    }

    fn small(&mut self, i: usize) -> String {
        let mut words: Vec<String> = [
            "all",
            "none",
            "translations",
            "rotations",
            "angles",
            "q",
            "xyz",
            "1",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        words.extend(self.bodies[i].q.iter().cloned());
        if self.rng.chance(50) {
            self.rng.pick(&words).clone()
        } else {
            let n = self.rng.range(0, 3);
            let picked: Vec<String> = (0..n).map(|_| self.rng.pick(&words).clone()).collect();
            format!("[{}]", picked.join(", "))
        }
    }

    fn list3(&mut self, constant: bool) -> String {
        let n = if self.rng.chance(92) {
            3
        } else {
            self.rng.range(0, 4)
        };
        let items: Vec<String> = (0..n)
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
        if self.rng.chance(90) {
            let on = self.point(1);
            entries.push(format!("on: {on}"));
        }
        if self.rng.chance(40) {
            let r = self.point(1);
            entries.push(format!("reaction: {r}"));
        }
        match self.rng.below(5) {
            0 | 1 => {
                let v = self.vector(3);
                entries.push(format!("vector: {v}"));
            }
            2 | 3 => {
                let a = self.vector(2);
                let m = self.scalar(3);
                entries.push(format!("along: {a}"));
                entries.push(format!("magnitude: {m}"));
            }
            _ => {
                for key in ["vector", "along", "magnitude", "about"] {
                    if self.rng.chance(40) {
                        let v = self.any(2);
                        entries.push(format!("{key}: {v}"));
                    }
                }
            }
        }
        format!("force {name} {{ {} }}", entries.join(", "))
    }

    fn moment(&mut self, i: usize) -> String {
        let name = self.name("M", i);
        let mut entries = Vec::new();
        if self.rng.chance(90) {
            let on = if self.rng.chance(85) {
                self.body_name()
            } else {
                self.any(1)
            };
            entries.push(format!("on: {on}"));
        }
        if self.rng.chance(40) {
            let r = self.body_name();
            entries.push(format!("reaction: {r}"));
        }
        match self.rng.below(5) {
            0 | 1 => {
                let v = self.vector(3);
                entries.push(format!("vector: {v}"));
            }
            2 | 3 => {
                let a = self.vector(1);
                let m = self.scalar(3);
                entries.push(format!("about: {a}"));
                entries.push(format!("magnitude: {m}"));
            }
            _ => {
                for key in ["vector", "about", "magnitude", "along"] {
                    if self.rng.chance(40) {
                        let v = self.any(2);
                        entries.push(format!("{key}: {v}"));
                    }
                }
            }
        }
        format!("moment {name} {{ {} }}", entries.join(", "))
    }

    fn state(&mut self, name: &str) -> String {
        let mut entries = Vec::new();
        if self.rng.chance(80) {
            let v = if self.rng.chance(85) {
                self.constant(1)
            } else {
                self.any(1)
            };
            entries.push(format!("initial: {v}"));
        }
        if self.rng.chance(90) {
            let v = self.scalar(3);
            entries.push(format!("derivative: {v}"));
        }
        format!(
            "state {name}{} {{ {} }}",
            self.rng.pick(UNITS),
            entries.join(", ")
        )
    }

    // Expressions. Each typed generator returns, most of the time, an
    // expression of its kind; sometimes anything at all.

    fn constant(&mut self, depth: usize) -> String {
        if depth == 0 || self.rng.chance(50) {
            if !self.params.is_empty() && self.rng.chance(50) {
                return self.rng.pick(&self.params).clone();
            }
            return self.rng.pick(NUMBERS).to_string();
        }
        let a = self.constant(depth - 1);
        let b = self.constant(depth - 1);
        match self.rng.below(6) {
            0 => format!("-{a}"),
            1 => format!("{a} + {b}"),
            2 => format!("{a}*{b}"),
            3 => format!("{a}/{b}"),
            4 => format!("({a})^{}", self.rng.pick(EXPONENTS)),
            _ => format!(
                "{}({a})",
                self.rng.pick(&["sin", "cos", "sqrt", "exp", "abs"])
            ),
        }
    }

    fn scalar(&mut self, depth: usize) -> String {
        if self.rng.chance(8) {
            return self.any(depth);
        }
        if depth == 0 {
            return match self.rng.below(10) {
                0..=2 => self.rng.pick(NUMBERS).to_string(),
                3 => self.rng.pick(ODD_NAMES).to_string(),
                4 if !self.lets.is_empty() => self.rng.pick(&self.lets).clone(),
                _ => self.rng.pick(&self.scalars).clone(),
            };
        }
        let d = depth - 1;
        match self.rng.below(24) {
            0..=3 => self.scalar(0),
            4 => format!("-{}", self.scalar(d)),
            5 => format!("{} + {}", self.scalar(d), self.scalar(d)),
            6 => format!("{} - {}", self.scalar(d), self.scalar(d)),
            7 => format!("{}*{}", self.scalar(d), self.scalar(d)),
            8 => format!("{}/{}", self.scalar(d), self.scalar(d)),
            9 => format!("({})^{}", self.scalar(d), self.rng.pick(EXPONENTS)),
            10 => format!("({})", self.scalar(d)),
            11 => {
                let f = *self.rng.pick(SCALAR_FUNCS);
                let n = match f {
                    "atan2" | "min" | "max" => 2,
                    _ => 1,
                };
                let n = if self.rng.chance(10) {
                    self.rng.range(0, 3)
                } else {
                    n
                };
                self.call(f, n, d, Self::scalar)
            }
            12 if !self.fns.is_empty() => {
                let (f, arity) = self.rng.pick(&self.fns).clone();
                let n = if self.rng.chance(10) {
                    self.rng.range(0, 3)
                } else {
                    arity
                };
                self.call(&f, n, d, Self::scalar)
            }
            13 => format!("dot({}, {})", self.vector(d), self.vector(d)),
            14 => format!("mag({})", self.vector(d)),
            15 => {
                let third = if self.rng.chance(50) {
                    format!(", {}", self.vector(d))
                } else {
                    String::new()
                };
                format!("angle({}, {}{third})", self.vector(d), self.vector(d))
            }
            16 | 17 => {
                let f = *self.rng.pick(&["q", "u"]);
                let b = self.body_ref();
                if self.rng.chance(50) {
                    format!("{f}({b})")
                } else {
                    format!(
                        "{f}({b}, {})",
                        self.rng.pick(&[
                            "1",
                            "2",
                            "3",
                            "4",
                            "6",
                            "0",
                            "-1",
                            "k",
                            "1.5",
                            "99999999999999999999"
                        ])
                    )
                }
            }
            18 => format!("dxdt({})", self.scalar(d)),
            19 => {
                let x = if self.rng.chance(80) {
                    self.scalar(0)
                } else {
                    self.scalar(d)
                };
                format!("partial({}, {x})", self.scalar(d))
            }
            20 => format!(
                "{}({})",
                self.rng.pick(&["nominal", "constant_part", "sqrt"]),
                self.scalar(d)
            ),
            21 => format!(
                "dot({}, {})",
                self.vector(d),
                self.rng.pick(&["n1", "n2", "n3"])
            ),
            _ => self.rng.pick(&self.scalars).clone(),
        }
    }

    fn unit_vector(&mut self) -> String {
        let k = *self.rng.pick(&["1", "2", "3", "1", "2", "3", "0", "4"]);
        match self.rng.below(3) {
            0 => format!("n{k}"),
            1 if !self.bodies.is_empty() => {
                let i = self.rng.below(self.bodies.len());
                format!("{}{k}", self.bodies[i].name.to_lowercase())
            }
            _ => format!("{}.{k}", self.body_name()),
        }
    }

    fn vector(&mut self, depth: usize) -> String {
        if self.rng.chance(8) {
            return self.any(depth);
        }
        if depth == 0 {
            return self.unit_vector();
        }
        let d = depth - 1;
        match self.rng.below(16) {
            0..=2 => self.unit_vector(),
            3 | 4 => format!("{}*{}", self.scalar(d), self.vector(d)),
            5 => format!("{} + {}", self.vector(d), self.vector(d)),
            6 => format!("{} - {}", self.vector(d), self.vector(d)),
            7 => format!("cross({}, {})", self.vector(d), self.vector(d)),
            8 => format!("dir({})", self.vector(d)),
            9 => format!("pos({})", self.point(d)),
            10 => format!("pos({}, {})", self.point(d), self.point(d)),
            11 => {
                if self.rng.chance(50) {
                    format!("vel({})", self.point(d))
                } else {
                    format!("vel({}, {})", self.point(d), self.point(d))
                }
            }
            12 => format!("rot({})", self.body_ref()),
            13 => format!("dot_plane({}, {})", self.vector(d), self.vector(d)),
            14 => format!("dxdt({})", self.vector(d)),
            _ => {
                let x = self.scalar(0);
                format!("partial({}, {x})", self.vector(d))
            }
        }
    }

    fn point(&mut self, depth: usize) -> String {
        if self.rng.chance(6) {
            return self.any(depth);
        }
        match self.rng.below(6) {
            0 | 1 if !self.points.is_empty() => self.rng.pick(&self.points).0.clone(),
            2 => format!("{}.cm", self.body_name()),
            3 => format!("{}.origin", self.body_name()),
            4 if !self.lets.is_empty() => self.rng.pick(&self.lets).clone(),
            _ => self.body_name(),
        }
    }

    fn body_ref(&mut self) -> String {
        if self.rng.chance(8) {
            return self.any(1);
        }
        self.body_name()
    }

    fn call(
        &mut self,
        f: &str,
        n: usize,
        depth: usize,
        arg: fn(&mut Self, usize) -> String,
    ) -> String {
        let args: Vec<String> = (0..n).map(|_| arg(self, depth)).collect();
        format!("{f}({})", args.join(", "))
    }

    /// Anything: an expression of a random kind, or one that is no kind.
    fn any(&mut self, depth: usize) -> String {
        let d = depth.saturating_sub(1);
        match self.rng.below(14) {
            0 => self.scalar(d),
            1 => self.vector(d),
            2 => self.point(d),
            3 => self.body_name(),
            4 => self.rng.pick(ODD_NAMES).to_string(),
            5 => self.rng.pick(NUMBERS).to_string(),
            6 => {
                let n = self.rng.range(0, 4);
                let items: Vec<String> = (0..n).map(|_| self.any(d)).collect();
                format!("[{}]", items.join(", "))
            }
            7 => {
                let f = *self.rng.pick(OPERATIONS);
                let n = self.rng.range(0, 4);
                self.call(f, n, d, Self::any)
            }
            8 => {
                let base = if self.rng.chance(50) {
                    self.body_name()
                } else {
                    self.any(d)
                };
                let member =
                    *self
                        .rng
                        .pick(&["1", "2", "3", "0", "4", "cm", "origin", "foo", "4294967296"]);
                format!("{base}.{member}")
            }
            9 => format!("{}*{}", self.any(d), self.any(d)),
            10 => format!("{} + {}", self.any(d), self.any(d)),
            11 => format!("{}/{}", self.any(d), self.any(d)),
            12 => format!("({})^{}", self.any(d), self.any(d)),
            _ => format!("-{}", self.any(d)),
        }
    }
}

// ---------------------------------------------------------------------------
// Mutations.

/// Splits text into tokens: identifiers and numbers (with `.`), whitespace
/// runs, and single other characters. Concatenating the pieces gives the text.
fn pieces(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut chars = text.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        let word = |c: char| c.is_alphanumeric() || c == '_' || c == '.';
        let mut end = i + c.len_utf8();
        if word(c) || c.is_whitespace() {
            let same = |d: char| if word(c) { word(d) } else { d.is_whitespace() };
            while let Some(&(j, d)) = chars.peek() {
                if !same(d) {
                    break;
                }
                end = j + d.len_utf8();
                chars.next();
            }
        }
        out.push(&text[start.max(i)..end]);
        start = end;
    }
    out
}

/// Replacements for numbers.
const NUMBER_SWAPS: &[&str] = &[
    "0",
    "-0",
    "0.0",
    "-1",
    "1e38",
    "1e39",
    "1e-38",
    "1e-39",
    "1e308",
    "1e309",
    "1e-320",
    "99999999999999999999999999999999999999999",
    "0.00000000000000000000000000000000000000001",
    "-99999",
    "3",
    "4",
    "-3",
    "1000000",
    "170141183460469231731687303715884105728",
    "1.5",
    "2.",
    "1e",
    "0x10",
    "1u8",
    "1f32",
];

/// One to five random edits of `base`.
pub fn mutate(rng: &mut Rng, base: &str) -> String {
    let mut text = base.to_string();
    for _ in 0..rng.range(1, 5) {
        text = mutate_once(rng, &text);
    }
    text
}

fn mutate_once(rng: &mut Rng, text: &str) -> String {
    let mut toks: Vec<String> = pieces(text).into_iter().map(String::from).collect();
    let significant: Vec<usize> = (0..toks.len())
        .filter(|&i| !toks[i].trim().is_empty())
        .collect();
    if significant.is_empty() {
        return format!("{text}{}", rng.pick(NUMBER_SWAPS));
    }
    let at = *rng.pick(&significant);
    let is_number = |s: &str| s.starts_with(|c: char| c.is_ascii_digit());
    let is_ident = |s: &str| s.starts_with(|c: char| c.is_alphabetic() || c == '_');
    match rng.below(12) {
        0 => toks[at].clear(),
        1 => {
            let t = toks[at].clone();
            toks.insert(at, t);
        }
        2 => {
            let other = *rng.pick(&significant);
            toks.swap(at, other);
        }
        3..=5 => {
            // A number changed (the nearest number after `at`).
            if let Some(i) = (at..toks.len()).chain(0..at).find(|&i| is_number(&toks[i])) {
                toks[i] = rng.pick(NUMBER_SWAPS).to_string();
            }
        }
        6 | 7 => {
            // An identifier renamed: everywhere or once, to another one in the
            // file, a fresh one or an odd one.
            if let Some(i) = (at..toks.len()).chain(0..at).find(|&i| is_ident(&toks[i])) {
                let old = toks[i].clone();
                let idents: Vec<&String> = toks.iter().filter(|t| is_ident(t)).collect();
                let new = match rng.below(3) {
                    0 => (*rng.pick(&idents)).clone(),
                    1 => format!("{old}2"),
                    _ => rng.pick(ODD_NAMES).to_string(),
                };
                if rng.chance(50) {
                    for t in toks.iter_mut().filter(|t| **t == old) {
                        *t = new.clone();
                    }
                } else {
                    toks[i] = new;
                }
            }
        }
        8 => {
            let insert = *rng.pick(&[
                "(", ")", "[", "]", "{", "}", ",", ";", ":", "=", "-", "*", "^", ".", "N", "all",
                "body", "let", "0", "1e39", "dxdt(", "B.cm", "q(B)", "\"", "//", "/*", "///",
            ]);
            toks.insert(at, insert.to_string());
        }
        _ => {
            // Line edits.
            let mut lines: Vec<String> = text.lines().map(String::from).collect();
            let i = rng
                .below(lines.len().max(1))
                .min(lines.len().saturating_sub(1));
            if lines.is_empty() {
                return String::new();
            }
            match rng.below(3) {
                0 => {
                    lines.remove(i);
                }
                1 => {
                    let l = lines[i].clone();
                    lines.insert(i, l);
                }
                _ => {
                    let j = rng.below(lines.len());
                    lines.swap(i, j);
                }
            }
            return lines.join("\n");
        }
    }
    toks.concat()
}

// ---------------------------------------------------------------------------
// Soups.

const SOUP_WORDS: &[&str] = &[
    "model",
    "M",
    ";",
    "body",
    "B",
    "{",
    "}",
    "parent",
    ":",
    "N",
    ",",
    "rotate",
    "translate",
    "1",
    "[",
    "]",
    "mass",
    "inertia",
    "diag",
    "(",
    ")",
    "force",
    "moment",
    "on",
    "vector",
    "n1",
    "let",
    "=",
    "point",
    "in",
    "at",
    "output",
    "state",
    "input",
    "extern",
    "fn",
    "sub",
    "->",
    "gravity",
    "-",
    "+",
    "*",
    "/",
    "^",
    "q",
    "u",
    "dot",
    "pos",
    "vel",
    "dxdt",
    "1e39",
    "0",
    "settings",
    "threshold",
    "float",
    "f32",
    "small",
    "all",
    "parameters",
    "parameter",
    "\"x\"",
    "///",
    "\n",
    ".",
    "cm",
    "t",
];

fn soup(rng: &mut Rng) -> String {
    let n = rng.range(0, 120);
    match rng.below(3) {
        0 => {
            let bytes: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
            String::from_utf8_lossy(&bytes).into_owned()
        }
        1 => (0..n)
            .map(|_| match rng.below(10) {
                0 => char::from_u32(rng.below(0x11_0000) as u32).unwrap_or('\u{fffd}'),
                1 => *rng.pick(&['\u{0}', '\u{feff}', '\u{202e}', 'é', '°', '🚀', '\r', '\t']),
                _ => (b' ' + rng.below(95) as u8) as char,
            })
            .collect(),
        _ => {
            let mut s = String::from(if rng.chance(70) { "model M; " } else { "" });
            for _ in 0..n {
                s.push_str(*rng.pick(SOUP_WORDS));
                s.push(' ');
            }
            s
        }
    }
}

// ---------------------------------------------------------------------------
// Running a case.

/// How the compiler answered one input.
#[derive(Debug)]
pub enum Outcome {
    /// Compiled, emitted and formatted.
    Ok,
    /// Rejected with this many diagnostics (rendered without panicking).
    Diagnostics(usize),
    /// Generated tokens that do not parse as a Rust file.
    BadEmit(String),
    /// A panic, with its message and location.
    Panic(String),
}

thread_local! {
    static LAST_PANIC: std::cell::RefCell<Option<String>> = const { std::cell::RefCell::new(None) };
}

/// Replaces the panic hook with one that records the message and location
/// for [`run`] instead of printing it (`std::panic::take_hook` restores
/// the default).
pub fn silence_panics() {
    std::panic::set_hook(Box::new(|info| {
        let message = info.to_string();
        LAST_PANIC.with(|p| *p.borrow_mut() = Some(message));
    }));
}

/// Runs `text` through the whole pipeline (parse, resolve, equations,
/// program, tokens, formatting, Markdown; with `tokens_too`, also the
/// macro's Rust-token front end when the text lexes), catching panics.
pub fn run(text: &str, tokens_too: bool) -> Outcome {
    LAST_PANIC.with(|p| p.borrow_mut().take());
    match catch_unwind(AssertUnwindSafe(|| run_unguarded(text, tokens_too))) {
        Ok(outcome) => outcome,
        Err(payload) => {
            let message = LAST_PANIC
                .with(|p| p.borrow_mut().take())
                .unwrap_or_else(|| {
                    payload
                        .downcast_ref::<&str>()
                        .map(|s| s.to_string())
                        .or_else(|| payload.downcast_ref::<String>().cloned())
                        .unwrap_or_else(|| "panic".to_string())
                });
            Outcome::Panic(message)
        }
    }
}

fn run_unguarded(text: &str, tokens_too: bool) -> Outcome {
    let file = SourceFile::new("fuzz.sim", text);
    let outcome = match compile_source(&file) {
        Ok(compiled) => {
            let tokens = model_tokens(&compiled, &EmitOptions::default());
            let formatted = format_tokens(&tokens);
            let _ = markdown(&compiled, "fuzz.sim");
            match syn::parse2::<syn::File>(tokens) {
                Ok(_) => Outcome::Ok,
                Err(e) => Outcome::BadEmit(format!(
                    "{e}: {}",
                    formatted.chars().take(2000).collect::<String>()
                )),
            }
        }
        Err(diags) => {
            let rendered = diags.render(&file);
            assert!(!diags.is_empty(), "an error without diagnostics");
            assert!(!rendered.is_empty(), "diagnostics rendered as nothing");
            Outcome::Diagnostics(diags.len())
        }
    };
    // The token front end (the macro's) on the same text, when it lexes.
    if let Some(Ok(tokens)) = tokens_too.then(|| text.parse::<proc_macro2::TokenStream>()) {
        match compile_tokens(tokens) {
            Ok(compiled) => {
                let _ = model_tokens(&compiled, &EmitOptions::default());
            }
            Err(diags) => {
                let _ = diags.to_syn_error();
            }
        }
    }
    outcome
}
