//! The equations of constraints and prescribed motions, beside Kane's
//! equations of the tree.
//!
//! Every constraint becomes a row at the speed level, `Σ_k A_k u_k + b = 0`
//! (a position constraint `g` through its time derivative), with the terms
//! of the row's own time derivative that hold no acceleration
//! (`bias = Ȧ u + ḃ`), so that `A u̇ + bias = 0`. Each row has a dependent
//! speed, and each position constraint a dependent coordinate; where the
//! model does not name them they are chosen by complete pivoting on the
//! numbers the matrices take at the initial state, preferring (as the
//! paper's `constant-part` rule) entries whose constant part is not zero.
//! The order of elimination is kept for the generated solve, which checks
//! each pivot at run time.

use super::LocatedError;
use crate::expr::{Bindings, ExprId, NoUserFunctions, SymId};
use crate::mech::constraint::ConstraintKind;
use crate::mech::error::{ItemRef, ModelError};
use crate::mech::system::System;
use rustc_hash::FxHashMap;

/// One constraint at the speed level.
#[derive(Clone, Debug)]
pub struct ConstraintRow {
    /// `A_k`: the coefficient of each speed.
    pub coefficients: Vec<ExprId>,
    /// `b`: the part without speeds.
    pub offset: ExprId,
    /// `Ȧ u + ḃ`: the time derivative of the row without accelerations.
    pub bias: ExprId,
}

/// The constraint equations of a system (empty without constraints).
#[derive(Clone, Debug, Default)]
pub struct ConstraintEquations {
    /// One row per constraint, in declaration order.
    pub rows: Vec<ConstraintRow>,
    /// The dependent speed of each row (speed index).
    pub dependent_speeds: Vec<usize>,
    /// The order in which the rows are eliminated (each on its dependent
    /// speed).
    pub order: Vec<usize>,
    /// The position constraints (row indices).
    pub positions: Vec<usize>,
    /// `g` of each position constraint.
    pub residuals: Vec<ExprId>,
    /// The dependent coordinate of each position constraint (coordinate
    /// index).
    pub dependent_coordinates: Vec<usize>,
    /// `∂g_i/∂q_j` for the position constraints `i` and the dependent
    /// coordinates `j`.
    pub jacobian: Vec<Vec<ExprId>>,
    /// The order in which the position constraints are eliminated in
    /// assembly (each on its dependent coordinate).
    pub assembly_order: Vec<usize>,
    /// The multipliers the outputs read (`constraint_force`): (row, the
    /// symbol that stands for it).
    pub forces: Vec<(usize, SymId)>,
}

impl ConstraintEquations {
    /// Whether there are constraints.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }
}

/// A prescribed coordinate: its value, rate and acceleration in time.
#[derive(Clone, Debug)]
pub struct Prescribed {
    /// The speed (= coordinate) index.
    pub speed: usize,
    /// `q(t)`.
    pub value: ExprId,
    /// `dq/dt`.
    pub rate: ExprId,
    /// `d²q/dt²`.
    pub acceleration: ExprId,
}

impl System {
    /// The prescribed motions with their time derivatives.
    pub(super) fn prescribed(&mut self) -> Result<Vec<Prescribed>, LocatedError> {
        let mut out = Vec::with_capacity(self.motions.len());
        for (k, m) in self.motions.clone().into_iter().enumerate() {
            let at = |e| LocatedError::new(ItemRef::Motion(k), e);
            let rate = self.arena.dxdt(m.value).map_err(at)?;
            let acceleration = self.arena.dxdt(rate).map_err(at)?;
            out.push(Prescribed {
                speed: m.coordinate,
                value: m.value,
                rate,
                acceleration,
            });
        }
        Ok(out)
    }

    /// The constraint equations, with their dependents chosen.
    pub(super) fn constraint_equations(
        &mut self,
        prescribed: &[Prescribed],
    ) -> Result<ConstraintEquations, LocatedError> {
        let mut eqs = ConstraintEquations::default();
        if self.constraints.is_empty() {
            return Ok(eqs);
        }
        let n = self.coordinates.len();
        let free = n - prescribed.len();
        if self.constraints.len() > free {
            let e = ModelError::Option {
                item: self.constraints[free].name.clone(),
                key: "",
                message: format!(
                    "{} constraints on {free} speeds that are not prescribed: this one is too many",
                    self.constraints.len()
                ),
                help: "each constraint takes one speed: remove redundant constraints (the time derivative of a position constraint is already a speed constraint)".to_string(),
            };
            return Err(LocatedError::new(ItemRef::Constraint(free), e));
        }
        for k in 0..self.constraints.len() {
            let row = self
                .constraint_row(k)
                .map_err(|e| LocatedError::new(ItemRef::Constraint(k), e))?;
            eqs.rows.push(row);
        }
        for (k, c) in self.constraints.clone().iter().enumerate() {
            if c.kind == ConstraintKind::Position {
                eqs.positions.push(k);
                eqs.residuals.push(c.value);
            }
        }
        let nominal = self.nominal_bindings(prescribed);
        self.choose_dependent_coordinates(&mut eqs, &nominal, prescribed)?;
        self.choose_dependent_speeds(&mut eqs, &nominal, prescribed)?;
        eqs.forces = self.constraint_forces.clone();
        Ok(eqs)
    }

    /// Constraint `k` at the speed level, with its bias.
    fn constraint_row(&mut self, k: usize) -> Result<ConstraintRow, ModelError> {
        let c = self.constraints[k].clone();
        let value = match c.kind {
            ConstraintKind::Position => self.arena.dxdt(c.value)?,
            ConstraintKind::Speed => c.value,
        };
        let speeds: Vec<SymId> = self.coordinates.iter().map(|c| c.u).collect();
        let mut coefficients = Vec::with_capacity(speeds.len());
        for u in &speeds {
            coefficients.push(self.arena.partial(value, *u)?);
        }
        let zero = self.arena.zero();
        let no_speeds: FxHashMap<SymId, ExprId> = speeds.iter().map(|u| (*u, zero)).collect();
        let offset = self.arena.substitute(value, &no_speeds);
        let rate = self.arena.dxdt(value)?;
        let no_accelerations: FxHashMap<SymId, ExprId> =
            self.coordinates.iter().map(|c| (c.du, zero)).collect();
        let bias = self.arena.substitute(rate, &no_accelerations);
        Ok(ConstraintRow {
            coefficients,
            offset,
            bias,
        })
    }

    /// Values of every symbol at the model's initial state (parameters at
    /// their defaults, prescribed coordinates at `t = 0`): where the
    /// dependents are chosen.
    fn nominal_bindings(&mut self, prescribed: &[Prescribed]) -> Bindings {
        let mut b = Bindings::with_defaults(&self.arena);
        b.set(self.time, 0.0);
        let values: Vec<(SymId, ExprId)> = self
            .coordinates
            .iter()
            .flat_map(|c| [(c.q, c.initial_q), (c.u, c.initial_u)])
            .chain(self.states.iter().map(|s| (s.sym, s.initial)))
            .collect();
        for (s, e) in values {
            let v = self.arena.eval(e, &b, &mut NoUserFunctions);
            b.set(s, v);
        }
        for p in prescribed {
            let c = &self.coordinates[p.speed];
            let (q, u) = (c.q, c.u);
            let value = self.arena.eval(p.value, &b, &mut NoUserFunctions);
            let rate = self.arena.eval(p.rate, &b, &mut NoUserFunctions);
            b.set(q, value);
            b.set(u, rate);
        }
        b
    }

    /// One dependent coordinate per position constraint: the user's, then
    /// by complete pivoting on `∂g/∂q` at the nominal state.
    fn choose_dependent_coordinates(
        &mut self,
        eqs: &mut ConstraintEquations,
        nominal: &Bindings,
        prescribed: &[Prescribed],
    ) -> Result<(), LocatedError> {
        let np = eqs.positions.len();
        if np == 0 {
            return Ok(());
        }
        let n = self.coordinates.len();
        let mut g = vec![vec![self.arena.zero(); n]; np];
        for (i, &row) in eqs.positions.iter().enumerate() {
            for j in 0..n {
                let q = self.coordinates[j].q;
                g[i][j] = self
                    .arena
                    .partial(eqs.residuals[i], q)
                    .map_err(|e| LocatedError::new(ItemRef::Constraint(row), e))?;
            }
        }
        let forced: Vec<Option<usize>> = eqs
            .positions
            .iter()
            .map(|&row| {
                let d = self.constraints[row].dependent?;
                self.coordinates.iter().position(|c| c.q == d)
            })
            .collect();
        let excluded: Vec<usize> = prescribed.iter().map(|p| p.speed).collect();
        let item = |i: usize| ItemRef::Constraint(eqs.positions[i]);
        self.check_named_rows(&g, nominal, &forced, &excluded, item)?;
        // Assembly moves the dependent coordinates: choose them among the
        // coordinates without a declared `initial:` where that closes the
        // constraints, so a declared value stays as written.
        let declared =
            (0..n).filter(|&j| self.coordinates[j].initial_declared && !forced.contains(&Some(j)));
        let avoiding: Vec<usize> = excluded.iter().copied().chain(declared).collect();
        let order = match self.pivot(&g, nominal, &forced, &avoiding, item) {
            Ok(order) => order,
            Err(_) => self.pivot(&g, nominal, &forced, &excluded, item)?,
        };
        eqs.dependent_coordinates = vec![0; np];
        for &(i, j) in &order {
            eqs.dependent_coordinates[i] = j;
        }
        eqs.jacobian = g
            .iter()
            .map(|row| eqs.dependent_coordinates.iter().map(|&j| row[j]).collect())
            .collect();
        eqs.assembly_order = order.iter().map(|&(i, _)| i).collect();
        Ok(())
    }

    /// One dependent speed per row: the user's, the speed of a position
    /// constraint's dependent coordinate, then by complete pivoting on `A`
    /// at the nominal state.
    fn choose_dependent_speeds(
        &mut self,
        eqs: &mut ConstraintEquations,
        nominal: &Bindings,
        prescribed: &[Prescribed],
    ) -> Result<(), LocatedError> {
        let a: Vec<Vec<ExprId>> = eqs.rows.iter().map(|r| r.coefficients.clone()).collect();
        let mut forced: Vec<Option<usize>> = self
            .constraints
            .iter()
            .map(|c| {
                let d = c.dependent?;
                self.coordinates.iter().position(|k| k.u == d)
            })
            .collect();
        for (i, &row) in eqs.positions.iter().enumerate() {
            let j = eqs.dependent_coordinates[i];
            let c = &self.coordinates[j];
            if forced[row].is_none() && c.qdot == self.arena.sym(c.u) {
                forced[row] = Some(j);
            }
        }
        let excluded: Vec<usize> = prescribed.iter().map(|p| p.speed).collect();
        let order = self.pivot(&a, nominal, &forced, &excluded, ItemRef::Constraint)?;
        eqs.dependent_speeds = vec![0; eqs.rows.len()];
        for &(i, j) in &order {
            eqs.dependent_speeds[i] = j;
        }
        eqs.order = order.iter().map(|&(i, _)| i).collect();
        Ok(())
    }

    /// Gaussian elimination with complete pivoting on the numbers `m` takes
    /// at `nominal`: the `(row, column)` pairs in elimination order. Forced
    /// columns are taken first, `excluded` columns never; an entry whose
    /// constant part is not zero counts ten times its size.
    fn pivot(
        &mut self,
        m: &[Vec<ExprId>],
        nominal: &Bindings,
        forced: &[Option<usize>],
        excluded: &[usize],
        item: impl Fn(usize) -> ItemRef,
    ) -> Result<Vec<(usize, usize)>, LocatedError> {
        let rows = m.len();
        let cols = m.first().map_or(0, Vec::len);
        let mut v = self.values_at(m, nominal);
        let mut weight = vec![vec![1.0; cols]; rows];
        for (i, r) in m.iter().enumerate() {
            for (j, e) in r.iter().enumerate() {
                let cp = self.arena.constant_part(*e);
                if !self.arena.is_zero(cp) {
                    weight[i][j] = 10.0;
                }
            }
        }
        let scale = v
            .iter()
            .flatten()
            .fold(0.0f64, |a, x| a.max(x.abs()))
            .max(1e-300);
        let mut row_done = vec![false; rows];
        let mut col_done = vec![false; cols];
        for &j in excluded {
            col_done[j] = true;
        }
        let mut order = Vec::with_capacity(rows);
        for _ in 0..rows {
            let forced_pick = (0..rows)
                .filter(|&i| !row_done[i])
                .find_map(|i| forced[i].filter(|&j| !col_done[j]).map(|j| (i, j)));
            let pick = forced_pick.or_else(|| {
                let mut best: Option<(usize, usize, f64)> = None;
                for i in (0..rows).filter(|&i| !row_done[i]) {
                    for j in (0..cols).filter(|&j| !col_done[j]) {
                        let s = v[i][j].abs() * weight[i][j];
                        if best.is_none_or(|b| s > b.2) {
                            best = Some((i, j, s));
                        }
                    }
                }
                best.filter(|b| b.2 > 1e-10 * scale).map(|b| (b.0, b.1))
            });
            let Some((i, j)) = pick else {
                let i = (0..rows).find(|&i| !row_done[i]).unwrap_or(0);
                let e = self.why_no_pivot(m, nominal, excluded, i);
                return Err(LocatedError::new(item(i), e));
            };
            row_done[i] = true;
            col_done[j] = true;
            order.push((i, j));
            let p = v[i][j];
            if p != 0.0 {
                for r in (0..rows).filter(|&r| !row_done[r]) {
                    let f = v[r][j] / p;
                    for c in 0..cols {
                        v[r][c] -= f * v[i][c];
                    }
                }
            }
        }
        Ok(order)
    }

    /// The numbers the entries of `m` take at `nominal` (NaN where they
    /// call user code).
    fn values_at(&self, m: &[Vec<ExprId>], nominal: &Bindings) -> Vec<Vec<f64>> {
        m.iter()
            .map(|r| {
                r.iter()
                    .map(|e| self.arena.eval(*e, nominal, &mut NoUserFunctions))
                    .collect()
            })
            .collect()
    }

    /// A row of `g` whose dependent is named (`forced`) is taken without
    /// pivoting: one that is zero at the nominal state (every coordinate
    /// but the `excluded`) is singular there whatever the dependent, as
    /// pivoting would have found. (A named dependent whose own coefficient
    /// alone is zero there is left to assembly, which starts from guesses.)
    fn check_named_rows(
        &self,
        g: &[Vec<ExprId>],
        nominal: &Bindings,
        forced: &[Option<usize>],
        excluded: &[usize],
        item: impl Fn(usize) -> ItemRef,
    ) -> Result<(), LocatedError> {
        let values = self.values_at(g, nominal);
        let scale = values.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
        for (i, row) in values.iter().enumerate() {
            // NaN (user code the compiler cannot evaluate) is not zero.
            let mut live = row
                .iter()
                .enumerate()
                .filter(|(j, _)| !excluded.contains(j));
            let zero = live.all(|(_, x)| x.abs() <= 1e-10 * scale);
            if forced[i].is_some() && zero {
                let e = self.why_no_pivot(g, nominal, excluded, i);
                return Err(LocatedError::new(item(i), e));
            }
        }
        Ok(())
    }

    /// Why row `i` of `m` found no pivot at the nominal state: the row is
    /// zero whatever the state (it constrains nothing), the rows are
    /// dependent at every configuration (one repeats the others), or only
    /// at this one (a singular initial guess). The second and third are
    /// told apart by the rank at another configuration.
    fn why_no_pivot(
        &self,
        m: &[Vec<ExprId>],
        nominal: &Bindings,
        excluded: &[usize],
        i: usize,
    ) -> ModelError {
        let option = |message: &str, help: &str| ModelError::Option {
            item: String::new(),
            key: "",
            message: message.to_string(),
            help: help.to_string(),
        };
        if m[i].iter().all(|e| self.arena.is_zero(*e)) {
            return option(
                "this constraint is identically zero: it restricts nothing, whatever the state",
                "remove it (it holds for every motion: e.g. the vertical component of a rolling contact's slip when the body cannot leave the ground)",
            );
        }
        let mut elsewhere = nominal.clone();
        for (k, c) in self.coordinates.iter().enumerate() {
            let shift = 0.37 + 0.11 * k as f64;
            elsewhere.set(c.q, nominal.get(c.q) + shift);
            elsewhere.set(c.u, nominal.get(c.u) + shift);
        }
        let values: Vec<Vec<f64>> = m
            .iter()
            .map(|r| {
                let row = r.iter().enumerate().filter(|(j, _)| !excluded.contains(j));
                row.map(|(_, e)| self.arena.eval(*e, &elsewhere, &mut NoUserFunctions))
                    .collect()
            })
            .collect();
        if numeric_rank(values) == m.len() {
            option(
                "the constraints are singular at the initial configuration: here this one restricts no speed, or only what the others do (elsewhere they are independent)",
                "start from another configuration (the coordinates' `initial:`), or name other dependents with `dependent:`",
            )
        } else {
            option(
                "this constraint is redundant or contradicts the others: at every configuration it restricts no speed the others do not",
                "remove it if it repeats the others (a position constraint's time derivative is already a speed constraint: do not declare that again); if it asks for another position along the same direction, the two cannot both hold: keep one",
            )
        }
    }
}

/// The rank of a matrix by Gaussian elimination with complete pivoting
/// (entries below 1e-10 of the largest count as zero).
fn numeric_rank(mut v: Vec<Vec<f64>>) -> usize {
    let scale = v.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
    if !(scale > 0.0 && scale.is_finite()) {
        return 0;
    }
    let mut rank = 0;
    while !v.is_empty() {
        let best = v
            .iter()
            .enumerate()
            .flat_map(|(i, r)| r.iter().enumerate().map(move |(j, x)| (i, j, x.abs())))
            .fold((0, 0, 0.0), |b, c| if c.2 > b.2 { c } else { b });
        if best.2 <= 1e-10 * scale || best.2.is_nan() {
            break;
        }
        let pivot_row = v.swap_remove(best.0);
        for r in &mut v {
            let f = r[best.1] / pivot_row[best.1];
            for (x, p) in r.iter_mut().zip(&pivot_row) {
                *x -= f * p;
            }
        }
        rank += 1;
    }
    rank
}
