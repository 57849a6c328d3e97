//! Which speeds are states: in a tree all of them; with constraints the
//! dependent speeds are solved from the constraints, and a prescribed
//! coordinate (with its speed) is known in time.

use crate::mech::Equations;

/// How the coordinates and speeds of a model split.
#[derive(Clone, Debug)]
pub struct Split {
    /// Coordinates in the state (all but the prescribed), coordinate index.
    pub coordinates: Vec<usize>,
    /// Independent speeds (states), speed index.
    pub free: Vec<usize>,
    /// The dependent speed of each constraint row.
    pub dependent: Vec<usize>,
    /// Prescribed speeds, in the order of `Equations::prescribed`.
    pub prescribed: Vec<usize>,
}

impl Split {
    /// The split of `eqs`.
    pub fn new(eqs: &Equations) -> Split {
        let n = eqs.coordinates.len();
        let prescribed: Vec<usize> = eqs.prescribed.iter().map(|p| p.speed).collect();
        let dependent = eqs.constraints.dependent_speeds.clone();
        Split {
            coordinates: (0..n).filter(|k| !prescribed.contains(k)).collect(),
            free: (0..n)
                .filter(|k| !prescribed.contains(k) && !dependent.contains(k))
                .collect(),
            dependent,
            prescribed,
        }
    }

    /// Whether every speed is a state (no constraints, no motions).
    pub fn is_tree(&self) -> bool {
        self.dependent.is_empty() && self.prescribed.is_empty()
    }

    /// The row of the constraint whose dependent speed is `k`, if any.
    pub fn dependent_row(&self, k: usize) -> Option<usize> {
        self.dependent.iter().position(|&d| d == k)
    }
}
