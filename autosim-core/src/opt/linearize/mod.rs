//! The linearization `dx/dt ≈ A δx + B δw`, `y ≈ C δx + D δw` about a
//! state and inputs, from forward derivatives of the program IR
//! (`tangent.rs`).
//!
//! The accelerations are never differentiated through the unrolled solve:
//! from `M u̇ = f`, `∂u̇/∂x_j = M⁻¹ (∂f/∂x_j − (∂M/∂x_j) u̇)`, solved with the
//! factor the derivatives already built. For a constrained model `M` and
//! `f` are the reduced `Pᵀ M P` and `Pᵀ (f − M w)`, so the same formula
//! holds. The linear model is in the independent states: the dependent
//! coordinates of the position constraints follow the independent ones,
//! `∂q_d/∂q_j = −G_d⁻¹ G_j` (`G = ∂g/∂q`), and their rows are dropped.

pub(super) mod tangent;

use crate::opt::ir::{Ir, Leaf, Nid};
use crate::opt::linearize::tangent::{Tangent, with_accelerations};
use crate::opt::solve::Solver;
use crate::opt::solve::elim::Elimination;

/// What the linearization differentiates: the program's derivatives and
/// outputs and the pieces of their solve. Everything that reads the
/// accelerations reads them as `Leaf::Accel` (leaves are never rewritten,
/// so their derivatives can be seeded reliably); the accelerations' values
/// are put in afterwards.
pub(crate) struct Linearizable<'a> {
    /// dq/dt of the state's coordinates.
    pub kinematics: &'a [Nid],
    /// d/dt of the extra states, reading `Leaf::Accel`.
    pub extra: &'a [Nid],
    /// The accelerations of the state's speeds.
    pub du: &'a [Nid],
    /// Lower triangle of the (reduced) mass matrix.
    pub mass: &'a [Vec<Option<Nid>>],
    /// The (reduced) forcing.
    pub forcing: &'a [Nid],
    /// Its factor.
    pub factor: &'a Solver,
    /// The outputs (reading `Leaf::Accel`).
    pub outputs: &'a [Nid],
    /// The position constraints' residuals, their dependent coordinates'
    /// state slots and the factor of `G_d` (none without them).
    pub closure: Option<(&'a [Nid], Vec<usize>, &'a Elimination)>,
    /// Number of inputs.
    pub inputs: usize,
    /// The relative step of user functions' central differences (the
    /// cube root of the float type's epsilon).
    pub user_step: f64,
}

/// The linear model's entries: `A` (row-major over the linear states),
/// then `B`, `C`, `D`, and the states it is in.
pub(crate) struct Linear {
    pub values: Vec<Nid>,
    pub states: Vec<usize>,
}

/// The columns of one leaf: d(rates)/d leaf and d(outputs)/d leaf.
struct Column {
    rates: Vec<Nid>,
    outputs: Vec<Nid>,
}

impl Linearizable<'_> {
    /// Builds the linear model.
    pub fn linearize(&self, ir: &mut Ir) -> Linear {
        let accel: Vec<Nid> = (0..self.du.len())
            .map(|k| ir.leaf(Leaf::Accel(k)))
            .collect();
        // The recursion never forms M: its rate along x comes from
        // differentiating M u̇ with u̇ held (leaves: derivative zero).
        let mass_du = match self.factor {
            Solver::Articulated(a) => Some(a.times_mass(ir, &accel)),
            Solver::Ldlt(_) => None,
        };
        let n_states = self.kinematics.len() + self.du.len() + self.extra.len();
        let dependent: Vec<usize> = self.closure.as_ref().map_or(Vec::new(), |c| c.1.clone());
        let states: Vec<usize> = (0..n_states).filter(|k| !dependent.contains(k)).collect();
        let mut columns: Vec<Option<Column>> = (0..n_states).map(|_| None).collect();
        let mut closure_terms: Vec<Vec<Nid>> = vec![Vec::new(); n_states];
        for j in 0..n_states {
            let (column, g) = self.column(ir, Leaf::State(j), &accel, mass_du.as_deref());
            columns[j] = Some(column);
            closure_terms[j] = g;
        }
        let input_columns: Vec<Column> = (0..self.inputs)
            .map(|k| {
                self.column(ir, Leaf::Input(k), &accel, mass_du.as_deref())
                    .0
            })
            .collect();
        // The independent coordinates move the dependent ones.
        let total: Vec<Column> = states
            .iter()
            .map(|&j| self.through_closure(ir, j, &columns, &closure_terms[j], &dependent))
            .collect();
        let mut values = Vec::new();
        for &i in &states {
            values.extend(total.iter().map(|c| c.rates[i]));
        }
        for &i in &states {
            values.extend(input_columns.iter().map(|c| c.rates[i]));
        }
        for y in 0..self.outputs.len() {
            values.extend(total.iter().map(|c| c.outputs[y]));
        }
        for y in 0..self.outputs.len() {
            values.extend(input_columns.iter().map(|c| c.outputs[y]));
        }
        // The accelerations' values for their leaves.
        let values = with_accelerations(ir, &values, self.du);
        Linear { values, states }
    }

    /// The derivatives of the rates and outputs with respect to `leaf`,
    /// and of the position constraints' residuals (`G_j`), still reading
    /// the accelerations as leaves.
    fn column(
        &self,
        ir: &mut Ir,
        leaf: Leaf,
        accel: &[Nid],
        mass_du: Option<&[Nid]>,
    ) -> (Column, Vec<Nid>) {
        let mut t = Tangent::new(leaf, self.user_step);
        let n = self.forcing.len();
        let mut rhs = Vec::with_capacity(n);
        for i in 0..n {
            let mut neg = Vec::new();
            match mass_du {
                Some(mdu) => neg.push(t.d(ir, mdu[i])),
                None => {
                    for k in 0..n {
                        let Some(m) = self.mass[i.max(k)][i.min(k)] else {
                            continue;
                        };
                        let dm = t.d(ir, m);
                        if ir.as_num(dm) != Some(0.0) {
                            neg.push(ir.mul(dm, accel[k]));
                        }
                    }
                }
            }
            let df = t.d(ir, self.forcing[i]);
            rhs.push(ir.sum(vec![df], neg));
        }
        let ddu = self.factor.solve(ir, &rhs);
        // From here on the accelerations move with the leaf.
        let mut t = Tangent::new(leaf, self.user_step);
        for (k, d) in ddu.iter().enumerate() {
            t.seed(accel[k], *d);
        }
        let mut rates: Vec<Nid> = self.kinematics.iter().map(|r| t.d(ir, *r)).collect();
        rates.extend(&ddu);
        rates.extend(self.extra.iter().map(|r| t.d(ir, *r)));
        let outputs = self.outputs.iter().map(|y| t.d(ir, *y)).collect();
        let g = match &self.closure {
            Some((residuals, _, _)) => residuals.iter().map(|g| t.d(ir, *g)).collect(),
            None => Vec::new(),
        };
        (Column { rates, outputs }, g)
    }
    /// The column of state `j` with the dependent coordinates following
    /// it: `col_j + Σ_d col_d s_d`, `G_d s = −G_j`.
    fn through_closure(
        &self,
        ir: &mut Ir,
        j: usize,
        columns: &[Option<Column>],
        g_j: &[Nid],
        dependent: &[usize],
    ) -> Column {
        let own = columns[j]
            .as_ref()
            .map_or_else(Vec::new, |c| c.rates.clone());
        let own_out = columns[j]
            .as_ref()
            .map_or_else(Vec::new, |c| c.outputs.clone());
        let Some((_, _, elim)) = &self.closure else {
            return Column {
                rates: own,
                outputs: own_out,
            };
        };
        if g_j.iter().all(|g| ir.as_num(*g) == Some(0.0)) {
            return Column {
                rates: own,
                outputs: own_out,
            };
        }
        let rhs: Vec<Nid> = g_j.iter().map(|g| ir.neg(*g)).collect();
        let s = elim.solve(ir, &rhs);
        let add = |ir: &mut Ir, base: &[Nid], pick: &dyn Fn(&Column) -> &[Nid]| -> Vec<Nid> {
            (0..base.len())
                .map(|i| {
                    let mut terms = vec![base[i]];
                    for (d, &slot) in dependent.iter().enumerate() {
                        if let Some(c) = &columns[slot] {
                            terms.push(ir.mul(pick(c)[i], s[d]));
                        }
                    }
                    ir.sum(terms, Vec::new())
                })
                .collect()
        };
        Column {
            rates: add(ir, &own, &|c: &Column| &c.rates),
            outputs: add(ir, &own_out, &|c: &Column| &c.outputs),
        }
    }
}
