//! Loads: forces on points, moments on bodies, and gravity.

use super::Grammar;

impl Grammar<'_> {
    /// The forces, the moments, then the gravity items (usually none or
    /// one; two going wrong).
    pub(super) fn load_items(&mut self, items: &mut Vec<String>) {
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
}
