//! Body items: parent, joint, rotations and translations, mass properties,
//! coordinate and speed names, initial values, and `small`/`lock` flags.

use super::super::vocab::*;
use super::Grammar;

impl Grammar<'_> {
    pub(super) fn body(&mut self, i: usize) -> String {
        let name = self.bodies[i].name.clone();
        let mut entries: Vec<String> = Vec::new();
        if self.rng.chance(80) {
            let parent = self.parent(i, &name);
            entries.push(format!("parent: {parent}"));
        }
        if self.rng.chance(50) {
            let v = self.list3(true, "m");
            entries.push(format!("joint: {v}"));
        }
        let r = self.bodies[i].rotations;
        if r > 0 || self.wrong() {
            let v = self.rotate(i);
            entries.push(format!("rotate: {v}"));
        }
        let tr = self.bodies[i].translations;
        if tr > 0 || self.wrong() {
            let v = self.translate(tr);
            entries.push(format!("translate: {v}"));
        }
        self.mass_entries(&mut entries);
        self.coordinate_entries(i, &mut entries);
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

    /// Parent: an earlier body (a tree); going wrong, a later one, itself
    /// (cycles), an unknown name or not a name at all.
    fn parent(&mut self, i: usize, name: &str) -> String {
        if self.wrong() {
            match self.rng.below(4) {
                0 => self.rng.pick(ODD_NAMES).to_string(),
                1 => name.to_string(),
                2 => self.any(1),
                _ => self.rng.pick(BODY_NAMES).to_string(),
            }
        } else if i == 0 || self.rng.chance(20) {
            "N".to_string()
        } else {
            self.bodies[self.rng.below(i)].name.clone()
        }
    }

    /// The value of `rotate` for body `i`.
    fn rotate(&mut self, i: usize) -> String {
        let r = self.bodies[i].rotations;
        if self.wrong() {
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
        }
    }

    /// The value of `translate` for `tr` translations.
    fn translate(&mut self, tr: usize) -> String {
        if self.wrong() {
            self.any(1)
        } else if tr == 1 && self.rng.chance(50) {
            self.axis()
        } else if tr == 1 && self.rng.chance(50) {
            // A direction.
            let d = if self.wrong() {
                "[0, 0, 0]".to_string()
            } else {
                self.list3(true, "1")
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
        }
    }

    /// `mass`, `inertia` and `cm`, each sometimes.
    fn mass_entries(&mut self, entries: &mut Vec<String>) {
        if self.rng.chance(60) {
            let v = match self.rng.below(6) {
                0 => "0".to_string(),
                _ => self.positive(),
            };
            let v = self.in_unit(v, "kg");
            entries.push(format!("mass: {v}"));
        }
        if self.rng.chance(60) {
            let v = self.inertia();
            entries.push(format!("inertia: {v}"));
        }
        if self.rng.chance(50) {
            let v = self.list3(true, "m");
            entries.push(format!("cm: {v}"));
        }
    }

    /// The names of body `i`'s coordinates and speeds (`q`, `u`; going
    /// wrong, one too few or an odd one more), and their initial values.
    fn coordinate_entries(&mut self, i: usize, entries: &mut Vec<String>) {
        let dofs = self.bodies[i].rotations + self.bodies[i].translations;
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
                let translations = self.bodies[i].translations;
                let units = match key {
                    "initial" => ["m", "rad"],
                    _ => ["m/s", "rad/s"],
                };
                let vals: Vec<String> = (0..n)
                    .map(|k| {
                        let v = self.constant(1);
                        self.in_unit(v, units[usize::from(k >= translations)])
                    })
                    .collect();
                entries.push(format!("{key}: [{}]", vals.join(", ")));
            }
        }
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
                    let rows: Vec<String> = (0..3).map(|_| self.list3(true, "kg m^2")).collect();
                    format!("[{}]", rows.join(", "))
                }
                _ => self.any(1),
            };
        }
        match self.rng.below(6) {
            0 => "0".to_string(),
            1 | 2 => {
                let args: Vec<String> = (0..3).map(|_| self.positive_inertia()).collect();
                format!("diag({})", args.join(", "))
            }
            3 | 4 => {
                let mut m: [[String; 3]; 3] = Default::default();
                for r in 0..3 {
                    for c in r..3 {
                        m[r][c] = if r == c {
                            self.positive_inertia()
                        } else {
                            let v = self.constant(1);
                            self.in_unit(v, "kg m^2")
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
                let items: Vec<String> = (0..3).map(|_| self.positive_inertia()).collect();
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

    /// A positive constant, in kg m^2 in trust mode.
    fn positive_inertia(&mut self) -> String {
        let v = self.positive();
        self.in_unit(v, "kg m^2")
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
}
