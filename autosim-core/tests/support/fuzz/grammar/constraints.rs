//! Constraints and prescribed motions: position constraints on a point or
//! between coordinates, speed constraints on a point's velocity or between
//! speeds, with or without a named dependent, and motions of a coordinate.

use super::Grammar;

impl Grammar<'_> {
    /// Usually none; sometimes a constraint or two and a motion.
    pub(super) fn constraint_items(&mut self, items: &mut Vec<String>) {
        let coordinates: Vec<String> = self.bodies.iter().flat_map(|b| b.q.clone()).collect();
        let speeds: Vec<String> = self.bodies.iter().flat_map(|b| b.u.clone()).collect();
        if coordinates.is_empty() || !self.rng.chance(30) {
            return;
        }
        for i in 0..self.rng.range(1, 2) {
            let item = self.constraint(i, &coordinates, &speeds);
            items.push(item);
        }
        if self.rng.chance(30) {
            let item = self.motion(&coordinates);
            items.push(item);
        }
    }

    fn constraint(&mut self, i: usize, coordinates: &[String], speeds: &[String]) -> String {
        let name = self.name("Con", i);
        let position = self.rng.chance(50);
        let value = if self.wrong() {
            self.any(2)
        } else if position {
            match self.points.is_empty() || self.rng.chance(40) {
                true => {
                    let (a, b) = (
                        self.rng.pick(coordinates).clone(),
                        self.rng.pick(coordinates).clone(),
                    );
                    let c = self.number();
                    format!("{a} - {c}*{b}")
                }
                false => {
                    let p = self.point(1);
                    let axis = self.rng.range(1, 3);
                    let c = self.number();
                    format!("dot(pos({p}), n{axis}) - {c}")
                }
            }
        } else {
            match self.points.is_empty() || self.rng.chance(40) {
                true => {
                    let (a, b) = (self.rng.pick(speeds).clone(), self.rng.pick(speeds).clone());
                    let c = self.scalar(1);
                    format!("{a} + {c}*{b}")
                }
                false => {
                    let p = self.point(1);
                    let axis = self.rng.range(1, 3);
                    format!("dot(vel({p}), n{axis})")
                }
            }
        };
        let value = self.in_unit(value, "m");
        let key = if position != self.wrong() {
            "position"
        } else {
            "speed"
        };
        let mut entries = vec![format!("{key}: {value}")];
        if self.rng.chance(30) {
            let d = match position {
                true => self.rng.pick(coordinates).clone(),
                false => self.rng.pick(speeds).clone(),
            };
            entries.push(format!("dependent: {d}"));
        }
        format!("constraint {name} [m] {{ {} }}", entries.join(", "))
    }

    fn motion(&mut self, coordinates: &[String]) -> String {
        let name = self.name("Mot", 0);
        let q = self.rng.pick(coordinates).clone();
        let value = if self.wrong() {
            self.any(2)
        } else {
            let c = self.number();
            format!("{c}*sin(2*t)")
        };
        format!("motion {name} {{ coordinate: {q}, value: {value} }}")
    }
}
