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
            let g = self.in_unit(g, "m/s^2");
            items.push(format!("gravity = {g};"));
        }
    }

    fn force(&mut self, i: usize) -> String {
        let name = self.name("F", i);
        let entries = self.load_entries(
            |g| g.point(1),
            ["vector", "along", "magnitude", "about"],
            ("along", 2),
            "N",
        );
        format!("force {name} {{ {} }}", entries.join(", "))
    }

    fn moment(&mut self, i: usize) -> String {
        let name = self.name("M", i);
        let entries = self.load_entries(
            |g| g.body_ref(),
            ["vector", "about", "magnitude", "along"],
            ("about", 1),
            "N m",
        );
        format!("moment {name} {{ {} }}", entries.join(", "))
    }

    /// A load's entries: what it acts on (`target`), a reaction, then a
    /// vector or a direction (`axis`: its key and depth) with a
    /// magnitude (in `unit`); going wrong, any of `wrong_keys` with any expression.
    fn load_entries(
        &mut self,
        target: impl Fn(&mut Self) -> String,
        wrong_keys: [&str; 4],
        axis: (&str, usize),
        unit: &str,
    ) -> Vec<String> {
        let mut entries = Vec::new();
        if !self.wrong() {
            let on = target(self);
            entries.push(format!("on: {on}"));
        }
        if self.rng.chance(40) {
            let r = target(self);
            entries.push(format!("reaction: {r}"));
        }
        if self.wrong() {
            for key in wrong_keys {
                if self.rng.chance(40) {
                    let v = self.any(2);
                    entries.push(format!("{key}: {v}"));
                }
            }
        } else if self.rng.chance(50) {
            let v = self.vector(3);
            let v = self.in_unit(v, unit);
            entries.push(format!("vector: {v}"));
        } else {
            let a = self.vector(axis.1);
            let m = self.scalar(3);
            let m = self.in_unit(m, unit);
            entries.push(format!("{}: {a}", axis.0));
            entries.push(format!("magnitude: {m}"));
        }
        entries
    }
}
