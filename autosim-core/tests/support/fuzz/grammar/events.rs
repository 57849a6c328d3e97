//! Discrete variables and events: sometimes a `discrete` item and an event
//! or two with an indicator of the state, a direction, a discrete variable
//! set and a coordinate or speed reset (or, going wrong, a bad direction,
//! a parameter reset, an unknown name).

use super::Grammar;

impl Grammar<'_> {
    /// Usually none; sometimes discrete variables and events (after the
    /// outputs: indicators and actions may not use accelerations).
    pub(super) fn event_items(&mut self, items: &mut Vec<String>) {
        if !self.rng.chance(25) {
            return;
        }
        self.accelerations = false;
        let modes: Vec<String> = (0..self.rng.range(1, 2))
            .map(|i| self.name("mode", i))
            .collect();
        let declared: Vec<String> = modes
            .iter()
            .map(|m| format!("{m} = {}", self.number()))
            .collect();
        items.push(format!("discrete {};", declared.join(", ")));
        self.scalars.extend(modes.iter().cloned());
        let states: Vec<String> = self
            .bodies
            .iter()
            .flat_map(|b| b.q.iter().chain(&b.u).cloned())
            .collect();
        for i in 0..self.rng.range(1, 2) {
            let item = self.event(i, &modes, &states);
            items.push(item);
        }
        self.accelerations = true;
    }

    fn event(&mut self, i: usize, modes: &[String], states: &[String]) -> String {
        let name = self.name("ev", i);
        let indicator = self.scalar(2);
        let direction = if self.wrong() {
            "down"
        } else {
            *self.rng.pick(&["rising", "falling", "either"])
        };
        let mut entries = vec![
            format!("indicator: {indicator}"),
            format!("direction: {direction}"),
        ];
        if self.rng.chance(60) {
            let target = match self.wrong() && !self.params.is_empty() {
                true => self.rng.pick(&self.params).clone(),
                false => self.rng.pick(modes).clone(),
            };
            entries.push(format!("set: {{ {target}: {} }}", self.scalar(1)));
        }
        if !states.is_empty() && self.rng.chance(50) {
            let target = self.rng.pick(states).clone();
            entries.push(format!("reset: {{ {target}: -{target} }}"));
        }
        if self.rng.chance(20) {
            entries.push("stop: true".to_string());
        }
        format!("event {name} {{ {} }}", entries.join(", "))
    }
}
