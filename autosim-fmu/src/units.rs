//! Units of the model's text (`m/s^2`, `N m s/rad`, `kg m^2`) as FMI 2.0
//! unit definitions: each factor's SI base-unit exponents (`BaseUnit`),
//! the unit of a derivative (`/s` more), and `deg` display units for
//! angles.

use std::collections::BTreeMap;

/// A unit as factors with integer exponents, in the order written.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Unit {
    factors: Vec<(String, i32)>,
}

/// SI base units in the order of FMI's `BaseUnit` attributes.
const BASE: [&str; 8] = ["kg", "m", "s", "A", "K", "mol", "cd", "rad"];

/// Derived and scaled units: name, exponents over [`BASE`], factor.
const DERIVED: [(&str, [i32; 8], f64); 12] = [
    ("N", [1, 1, -2, 0, 0, 0, 0, 0], 1.0),
    ("J", [1, 2, -2, 0, 0, 0, 0, 0], 1.0),
    ("W", [1, 2, -3, 0, 0, 0, 0, 0], 1.0),
    ("Pa", [1, -1, -2, 0, 0, 0, 0, 0], 1.0),
    ("Hz", [0, 0, -1, 0, 0, 0, 0, 0], 1.0),
    ("V", [1, 2, -3, -1, 0, 0, 0, 0], 1.0),
    ("g", [1, 0, 0, 0, 0, 0, 0, 0], 1e-3),
    ("mm", [0, 1, 0, 0, 0, 0, 0, 0], 1e-3),
    ("cm", [0, 1, 0, 0, 0, 0, 0, 0], 1e-2),
    ("km", [0, 1, 0, 0, 0, 0, 0, 0], 1e3),
    ("min", [0, 0, 1, 0, 0, 0, 0, 0], 60.0),
    (
        "deg",
        [0, 0, 0, 0, 0, 0, 0, 1],
        std::f64::consts::PI / 180.0,
    ),
];

impl Unit {
    /// Reads a unit: factors separated by spaces, `^n` exponents, and
    /// everything after a `/` in the denominator. `1` is no factor.
    pub fn parse(text: &str) -> Unit {
        let (num, den) = text.split_once('/').unwrap_or((text, ""));
        let mut factors = Vec::new();
        for (part, sign) in [(num, 1), (den, -1)] {
            for token in part
                .split([' ', '*'])
                .filter(|t| !t.is_empty() && *t != "1")
            {
                let (name, exp) = match token.split_once('^') {
                    Some((n, e)) => (n, e.trim_matches(['(', ')']).parse().unwrap_or(1)),
                    None => (token, 1),
                };
                factors.push((name.to_string(), sign * exp));
            }
        }
        Unit { factors }
    }

    /// This unit divided by seconds (the unit of a time derivative).
    pub fn per_second(&self) -> Unit {
        let mut factors = self.factors.clone();
        match factors.iter_mut().find(|(n, _)| n == "s") {
            Some(s) => s.1 -= 1,
            None => factors.push(("s".to_string(), -1)),
        }
        factors.retain(|(_, e)| *e != 0);
        Unit { factors }
    }

    /// The unit's text, numerator then `/` denominator (`1/s` when the
    /// numerator is empty).
    pub fn text(&self) -> String {
        let side = |positive: bool| {
            self.factors
                .iter()
                .filter(|(_, e)| (*e > 0) == positive)
                .map(|(n, e)| match e.abs() {
                    1 => n.clone(),
                    k => format!("{n}^{k}"),
                })
                .collect::<Vec<_>>()
                .join(" ")
        };
        match (side(true), side(false)) {
            (n, d) if d.is_empty() => n,
            (n, d) if n.is_empty() => format!("1/{d}"),
            (n, d) => format!("{n}/{d}"),
        }
    }

    /// Exponents over the SI base units and the factor to them, when every
    /// factor is a known unit.
    pub fn base(&self) -> Option<([i32; 8], f64)> {
        let mut exps = [0; 8];
        let mut factor = 1.0;
        for (name, e) in &self.factors {
            if let Some(k) = BASE.iter().position(|b| b == name) {
                exps[k] += e;
            } else {
                let (_, d, f) = DERIVED.iter().find(|(n, _, _)| n == name)?;
                for k in 0..8 {
                    exps[k] += e * d[k];
                }
                factor *= f.powi(*e);
            }
        }
        Some((exps, factor))
    }

    /// Whether the unit is an angle or an angle over time (`rad`, `rad/s`):
    /// such units are also shown in degrees.
    pub fn is_angular(&self) -> bool {
        self.factors.iter().any(|(n, e)| n == "rad" && *e == 1)
            && self.factors.iter().all(|(n, _)| n == "rad" || n == "s")
    }
}

/// `<UnitDefinitions>` for these unit texts (empty ones left out).
pub fn unit_definitions<'a>(units: impl IntoIterator<Item = &'a str>) -> String {
    let unique: BTreeMap<&str, Unit> = units
        .into_iter()
        .filter(|u| !u.is_empty())
        .map(|u| (u, Unit::parse(u)))
        .collect();
    let mut out = String::from("  <UnitDefinitions>\n");
    for (name, unit) in unique {
        out += &format!("    <Unit name=\"{}\">\n", crate::description::escape(name));
        if let Some((exps, factor)) = unit.base() {
            let mut attrs: String = BASE
                .iter()
                .zip(exps)
                .filter(|(_, e)| *e != 0)
                .map(|(b, e)| format!(" {b}=\"{e}\""))
                .collect();
            if factor != 1.0 {
                attrs += &format!(" factor=\"{factor:e}\"");
            }
            out += &format!("      <BaseUnit{attrs}/>\n");
        }
        if unit.is_angular() {
            let shown = name.replacen("rad", "deg", 1);
            let factor = 180.0 / std::f64::consts::PI;
            out += &format!(
                "      <DisplayUnit name=\"{}\" factor=\"{factor:e}\"/>\n",
                crate::description::escape(&shown)
            );
        }
        out += "    </Unit>\n";
    }
    out + "  </UnitDefinitions>\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_read_as_written_and_reduce_to_base_units() {
        let accel = Unit::parse("m/s^2");
        assert_eq!(accel.base(), Some(([0, 1, -2, 0, 0, 0, 0, 0], 1.0)));
        assert_eq!(Unit::parse("m/s").per_second().text(), "m/s^2");
        assert_eq!(Unit::parse("rad").per_second().text(), "rad/s");
        assert_eq!(Unit::parse("").per_second().text(), "1/s");
        assert_eq!(Unit::parse("s").per_second().text(), "");
        let damping = Unit::parse("N m s/rad");
        assert_eq!(damping.base(), Some(([1, 2, -1, 0, 0, 0, 0, -1], 1.0)));
        assert_eq!(
            Unit::parse("kg m^2").base(),
            Some(([1, 2, 0, 0, 0, 0, 0, 0], 1.0))
        );
        assert!(Unit::parse("rad/s").is_angular());
        assert!(!Unit::parse("N m/rad").is_angular());
        assert_eq!(Unit::parse("furlong").base(), None);
    }
}
