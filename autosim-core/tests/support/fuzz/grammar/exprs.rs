//! Expressions: each typed generator returns an expression of its kind,
//! or (going wrong) anything at all.

use super::super::vocab::*;
use super::{Grammar, LetKind};

impl Grammar<'_> {
    // Expressions: each typed generator returns an expression of its kind,
    // or (going wrong) anything at all.

    fn constant_expr(&mut self, depth: usize) -> String {
        if self.wrong() {
            return self.scalar(depth);
        }
        if depth == 0 || self.rng.chance(50) {
            if !self.params.is_empty() && self.rng.chance(50) {
                return self.rng.pick(&self.params).clone();
            }
            return self.number();
        }
        let a = self.constant(depth - 1);
        let mut b = self.constant(depth - 1);
        if matches!(b.as_str(), "0" | "0.0") {
            b = "2".to_string();
        }
        match self.rng.below(6) {
            0 => format!("-{a}"),
            1 => format!("{a} + {b}"),
            2 => format!("{a}*{b}"),
            3 => format!("{a}/({b})"),
            4 => format!("({a})^{}", self.rng.pick(EXPONENTS)),
            _ => format!(
                "{}({a})",
                self.rng.pick(&["sin", "cos", "sqrt", "exp", "abs"])
            ),
        }
    }

    pub(super) fn let_of(&mut self, kind: LetKind) -> Option<String> {
        let names: Vec<&String> = self.lets[..self.visible_lets]
            .iter()
            .filter(|(_, k)| *k == kind)
            .map(|(n, _)| n)
            .collect();
        (!names.is_empty()).then(|| (*self.rng.pick(&names)).clone())
    }

    fn scalar_expr(&mut self, depth: usize) -> String {
        if self.wrong() {
            return self.any(depth);
        }
        if depth == 0 {
            return match self.rng.below(10) {
                0..=2 => self.number(),
                3 => self
                    .let_of(LetKind::Scalar)
                    .unwrap_or_else(|| "t".to_string()),
                _ => self.rng.pick(&self.scalars).clone(),
            };
        }
        let d = depth - 1;
        match self.rng.below(24) {
            0..=3 => self.scalar(0),
            4 => format!("-{}", self.scalar(d)),
            5 => format!("({} + {})", self.scalar(d), self.scalar(d)),
            6 => format!("({} - {})", self.scalar(d), self.scalar(d)),
            7 => format!("{}*{}", self.scalar(d), self.scalar(d)),
            8 => {
                let (a, b) = (self.scalar(d), self.scalar(d));
                let b = if matches!(b.as_str(), "0" | "0.0") && !self.wrong() {
                    "2".to_string()
                } else {
                    b
                };
                format!("{a}/{b}")
            }
            9 => format!("({})^{}", self.scalar(d), self.rng.pick(EXPONENTS)),
            10 => format!("({})", self.scalar(d)),
            11 => {
                let f = *self.rng.pick(SCALAR_FUNCS);
                let n = match f {
                    "atan2" | "min" | "max" => 2,
                    _ => 1,
                };
                let n = if self.wrong() {
                    self.rng.range(0, 3)
                } else {
                    n
                };
                self.call(f, n, d, Self::scalar)
            }
            12 if !self.fns.is_empty() => {
                let (f, arity) = self.rng.pick(&self.fns).clone();
                let n = if self.wrong() {
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
                let moving: Vec<(String, usize)> = self
                    .bodies
                    .iter()
                    .map(|b| (b.name.clone(), b.rotations + b.translations))
                    .filter(|(_, dofs)| *dofs > 0)
                    .collect();
                let (b, dofs) = if self.wrong() {
                    (self.body_ref(), 1)
                } else if moving.is_empty() {
                    return "t".to_string();
                } else {
                    self.rng.pick(&moving).clone()
                };
                if dofs == 1 && !self.wrong() {
                    format!("{f}({b})")
                } else if self.wrong() {
                    let k = *self
                        .rng
                        .pick(&["0", "-1", "7", "k", "1.5", "99999999999999999999"]);
                    format!("{f}({b}, {k})")
                } else {
                    format!("{f}({b}, {})", self.rng.range(1, dofs.max(1)))
                }
            }
            18 if self.accelerations => format!("dxdt({})", self.scalar(d)),
            19 => {
                let x = self.rng.pick(&self.scalars).clone();
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

    pub(super) fn unit_vector(&mut self) -> String {
        let k = if self.wrong() {
            *self.rng.pick(&["0", "4", "99"])
        } else {
            *self.rng.pick(&["1", "2", "3"])
        };
        match self.rng.below(3) {
            0 => format!("n{k}"),
            1 if !self.bodies.is_empty() => {
                let i = self.rng.below(self.bodies.len());
                format!("{}{k}", self.bodies[i].name.to_lowercase())
            }
            _ => format!("{}.{k}", self.body_name()),
        }
    }

    fn vector_expr(&mut self, depth: usize) -> String {
        if self.wrong() {
            return self.any(depth);
        }
        if depth == 0 {
            return match self.let_of(LetKind::Vector) {
                Some(v) if self.rng.chance(20) => v,
                _ => self.unit_vector(),
            };
        }
        let d = depth - 1;
        match self.rng.below(16) {
            0..=2 => self.vector(0),
            3 | 4 => format!("{}*{}", self.scalar(d), self.vector(d)),
            5 => format!("({} + {})", self.vector(d), self.vector(d)),
            6 => format!("({} - {})", self.vector(d), self.vector(d)),
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
            14 if self.accelerations => format!("dxdt({})", self.vector(d)),
            _ => {
                let x = self.rng.pick(&self.scalars).clone();
                format!("partial({}, {x})", self.vector(d))
            }
        }
    }

    pub(super) fn point(&mut self, depth: usize) -> String {
        if self.wrong() {
            return self.any(depth);
        }
        match self.rng.below(6) {
            0 | 1 if !self.points.is_empty() => self.rng.pick(&self.points).0.clone(),
            2 => format!("{}.cm", self.body_name()),
            3 => format!("{}.origin", self.body_name()),
            4 => self
                .let_of(LetKind::Point)
                .unwrap_or_else(|| self.body_name()),
            _ => self.body_name(),
        }
    }

    pub(super) fn body_ref(&mut self) -> String {
        if self.wrong() {
            return self.any(1);
        }
        self.body_name()
    }

    /// Three constants (or scalars) in brackets: a point's or a mass
    /// center's coordinates, a joint's position, a direction; going wrong,
    /// anything, or a list of another length.
    /// A constant scalar (dimensionless in trust mode).
    pub(super) fn constant(&mut self, depth: usize) -> String {
        let e = self.constant_expr(depth);
        self.in_unit(e, "1")
    }

    /// A scalar (dimensionless in trust mode).
    pub(super) fn scalar(&mut self, depth: usize) -> String {
        let e = self.scalar_expr(depth);
        self.in_unit(e, "1")
    }

    /// A vector (dimensionless in trust mode).
    pub(super) fn vector(&mut self, depth: usize) -> String {
        let e = self.vector_expr(depth);
        self.in_unit(e, "1")
    }

    /// `[x, y, z]`, each entry in `unit` in trust mode.
    pub(super) fn list3(&mut self, constant: bool, unit: &str) -> String {
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
                let e = if constant {
                    self.constant(1)
                } else {
                    self.scalar(1)
                };
                self.in_unit(e, unit)
            })
            .collect();
        format!("[{}]", items.join(", "))
    }

    pub(super) fn call(
        &mut self,
        f: &str,
        n: usize,
        depth: usize,
        arg: fn(&mut Self, usize) -> String,
    ) -> String {
        let args: Vec<String> = (0..n).map(|_| arg(self, depth)).collect();
        format!("{f}({})", args.join(", "))
    }

    /// Anything: an expression of a random kind, or one of no kind at all.
    pub(super) fn any(&mut self, depth: usize) -> String {
        if depth == 0 {
            return match self.rng.below(4) {
                0 => self.rng.pick(ODD_NAMES).to_string(),
                1 => self.rng.pick(EXTREME_NUMBERS).to_string(),
                2 => self.body_name(),
                _ => self.rng.pick(&self.scalars).clone(),
            };
        }
        let d = depth - 1;
        match self.rng.below(14) {
            0 => self.scalar(d),
            1 => self.vector(d),
            2 => self.point(d),
            3 => self.body_name(),
            4 => self.rng.pick(ODD_NAMES).to_string(),
            5 => self.rng.pick(EXTREME_NUMBERS).to_string(),
            6 => {
                let n = self.rng.range(0, 3);
                let items: Vec<String> = (0..n).map(|_| self.any(d)).collect();
                format!("[{}]", items.join(", "))
            }
            7 => {
                let f = *self.rng.pick(OPERATIONS);
                let n = self.rng.range(0, 3);
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
