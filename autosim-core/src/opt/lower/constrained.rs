//! The program of a model with constraints or prescribed motions: Kane's
//! equations for dependent speeds (Kane & Levinson, ch. 6), unrolled in
//! the IR.
//!
//! The speeds split into independent ones `u_f` (states), dependent ones
//! `u_d` (one per constraint) and prescribed ones `u_p` (known in time).
//! The constraints `A u + b = 0` give `u_d = C u_f + C_p u_p + c` through
//! the factored `A_d` (`elim.rs`), so `u = P u_f + (known)` and, from
//! `A u̇ + bias = 0`, `u̇ = P u̇_f + w`. Kane's equations projected on the
//! independent speeds are `Pᵀ M P u̇_f = Pᵀ (f − M w)`, solved by the
//! unrolled LDLᵀ as for a tree; the generalized force that enforces a
//! prescribed coordinate is `P_pᵀ (M u̇ − f)` (constraint forces do no
//! work in the admissible motions). Nothing is inverted symbolically;
//! every pivot is checked at run time.

use super::Lowering;
use super::context::{Env, binding_rates};
use super::equations::{Assembly, Lowered};
use crate::expr::ExprId;
use crate::mech::{Equations, ItemRef};
use crate::opt::error::ProgramError;
use crate::opt::ir::{Ir, Leaf, Nid};
use crate::opt::solve::elim::Elimination;
use crate::opt::solve::ldlt_solve;
use crate::opt::split::Split;

/// The constraint solve: the factored `A_d` and the matrix rows.
struct ConstraintSolve {
    elim: Elimination,
    /// `A[row][speed]`.
    a: Vec<Vec<Nid>>,
}

impl ConstraintSolve {
    /// `A_d⁻¹ (−A[:, k])`: how the dependent speeds follow speed `k`.
    fn column(&self, ir: &mut Ir, k: usize) -> Vec<Nid> {
        let rhs: Vec<Nid> = self.a.iter().map(|row| ir.neg(row[k])).collect();
        self.elim.solve(ir, &rhs)
    }
}

/// `u̇ = P u̇_f + w` and the columns of the prescribed speeds.
struct Reduction {
    /// The dependent part of the column of each independent speed.
    free_columns: Vec<Vec<Nid>>,
    /// The dependent part of the column of each prescribed speed.
    prescribed_columns: Vec<Vec<Nid>>,
    /// `w`: the accelerations with `u̇_f = 0`.
    w: Vec<Nid>,
}

impl Reduction {
    /// The full column of speed `own` (1 there, `dep` on the dependent
    /// speeds, 0 elsewhere).
    fn full(&self, ir: &mut Ir, split: &Split, own: usize, dep: &[Nid]) -> Vec<Nid> {
        let (one, zero) = (ir.num(1.0), ir.num(0.0));
        (0..self.w.len())
            .map(|k| match split.dependent_row(k) {
                _ if k == own => one,
                Some(r) => dep[r],
                None => zero,
            })
            .collect()
    }

    /// Every acceleration, given the independent ones.
    fn accelerations(&self, ir: &mut Ir, split: &Split, du_free: &[Nid]) -> Vec<Nid> {
        let mut acc = self.w.clone();
        for (i, &f) in split.free.iter().enumerate() {
            acc[f] = du_free[i];
        }
        for (r, &k) in split.dependent.iter().enumerate() {
            let mut terms: Vec<Nid> = self
                .free_columns
                .iter()
                .zip(du_free)
                .map(|(col, du)| ir.mul(col[r], *du))
                .collect();
            terms.push(self.w[k]);
            acc[k] = ir.sum(terms, Vec::new());
        }
        acc
    }
}

/// `M v` for the symmetric `M` given by its lower triangle.
fn times_mass(ir: &mut Ir, mass: &[Vec<Option<Nid>>], v: &[Nid]) -> Vec<Nid> {
    let n = v.len();
    let nonzero: Vec<usize> = (0..n).filter(|&j| ir.as_num(v[j]) != Some(0.0)).collect();
    (0..n)
        .map(|i| {
            let terms: Vec<Nid> = nonzero
                .iter()
                .filter_map(|&j| Some(ir.mul(mass[i.max(j)][i.min(j)]?, v[j])))
                .collect();
            ir.sum(terms, Vec::new())
        })
        .collect()
}

/// `a · b`, skipping literal zeros.
fn dot(ir: &mut Ir, a: &[Nid], b: &[Nid]) -> Nid {
    let pairs: Vec<(Nid, Nid)> = a
        .iter()
        .zip(b)
        .filter(|(x, y)| ir.as_num(**x) != Some(0.0) && ir.as_num(**y) != Some(0.0))
        .map(|(x, y)| (*x, *y))
        .collect();
    let terms: Vec<Nid> = pairs.into_iter().map(|(x, y)| ir.mul(x, y)).collect();
    ir.sum(terms, Vec::new())
}

/// The full equations in the IR, with every speed known.
struct Full {
    mass: Vec<Vec<Option<Nid>>>,
    forcing: Vec<Nid>,
}

/// Lowers the program of a constrained model (IR numbering: constraint
/// matrix, dependent speeds, kinematics, mass matrix and forcing,
/// subroutine arguments, the reduced solve, extra states, outputs, initial
/// state, assembly).
pub(crate) fn lower(lw: &mut Lowering<'_>) -> Result<Lowered, ProgramError> {
    let given = lw.given;
    let (eqs, split) = (given.eqs, given.split);
    let solve_c = constraint_solve(lw, eqs)?;
    let rhs = dependent_rhs(lw, eqs, split, &solve_c.a)?;
    let dependent_speeds = solve_c.elim.solve(&mut lw.ir, &rhs);
    lw.extend(
        split
            .dependent
            .iter()
            .zip(&dependent_speeds)
            .map(|(&k, d)| (eqs.speeds[k], *d)),
    );
    let env = lw.env().clone();

    let kin_exprs: Vec<ExprId> = split
        .coordinates
        .iter()
        .map(|&j| eqs.kinematics[j])
        .collect();
    let kinematics = lw.all(&kin_exprs, |k| {
        given.declared.coordinate_items[split.coordinates[k]]
    })?;
    let full = Full {
        mass: lw.mass_matrix()?,
        forcing: lw.forcing()?,
    };
    let bias = lw.all(&row_biases(eqs), ItemRef::Constraint)?;
    let accel: Vec<ExprId> = eqs.prescribed.iter().map(|p| p.acceleration).collect();
    let prescribed_accel = lw.all(&accel, ItemRef::Motion)?;
    let sub_args = lw.sub_args()?;

    let ir = &mut lw.ir;
    let red = reduction(ir, split, &solve_c, &bias, &prescribed_accel);
    let columns: Vec<Vec<Nid>> = split
        .free
        .iter()
        .zip(&red.free_columns)
        .map(|(&f, dep)| red.full(ir, split, f, dep))
        .collect();
    let mp: Vec<Vec<Nid>> = columns
        .iter()
        .map(|c| times_mass(ir, &full.mass, c))
        .collect();
    let nf = split.free.len();
    let mut mass: Vec<Vec<Option<Nid>>> = vec![vec![None; nf]; nf];
    for i in 0..nf {
        for j in 0..=i {
            let v = dot(ir, &columns[i], &mp[j]);
            mass[i][j] = (ir.as_num(v) != Some(0.0)).then_some(v);
        }
    }
    let mw = times_mass(ir, &full.mass, &red.w);
    let f_minus_mw: Vec<Nid> = (0..full.forcing.len())
        .map(|k| ir.sum(vec![full.forcing[k]], vec![mw[k]]))
        .collect();
    let forcing: Vec<Nid> = columns.iter().map(|c| dot(ir, c, &f_minus_mw)).collect();
    let solve = ldlt_solve(ir, &mass, &forcing);

    // Extra states with every acceleration known (read as leaves, then
    // replaced by the solve's values).
    let rate_leaves: Vec<Nid> = (0..split.free.len())
        .map(|i| ir.leaf(Leaf::Accel(i)))
        .collect();
    let acc = red.accelerations(ir, split, &rate_leaves);
    let with_rates = binding_rates(&env, eqs, &acc);
    let (extra, extra_in_rates) = lw.extra(with_rates, &solve.du)?;

    let outputs = outputs(lw, &env, &red, &full, &solve_c)?;
    let initial = lw.initial()?;
    lw.bind(env);
    let assembly = assembly(lw, eqs)?;
    let named = split
        .dependent
        .iter()
        .zip(&dependent_speeds)
        .map(|(&k, d)| (lw.name(eqs.speeds[k]).to_string(), *d))
        .collect();
    Ok(Lowered {
        kinematics,
        mass,
        forcing,
        solve,
        constraint_checks: solve_c.elim.checks.clone(),
        extra,
        extra_in_rates,
        outputs,
        initial,
        sub_args,
        call_order: lw.call_order(),
        named,
        assembly,
    })
}

/// The constraint matrix `A` lowered and `A_d` factored.
fn constraint_solve(
    lw: &mut Lowering<'_>,
    eqs: &Equations,
) -> Result<ConstraintSolve, ProgramError> {
    let rows = &eqs.constraints.rows;
    let mut a: Vec<Vec<Nid>> = Vec::with_capacity(rows.len());
    for (r, row) in rows.iter().enumerate() {
        a.push(lw.all(&row.coefficients, |_| ItemRef::Constraint(r))?);
    }
    let ir = &mut lw.ir;
    let deps = &eqs.constraints.dependent_speeds;
    let a_d: Vec<Vec<Option<Nid>>> = a
        .iter()
        .map(|line| {
            deps.iter()
                .map(|&k| Some(line[k]).filter(|x| ir.as_num(*x) != Some(0.0)))
                .collect()
        })
        .collect();
    // Row r is eliminated on its own dependent speed (column r of A_d).
    let own: Vec<usize> = (0..rows.len()).collect();
    let elim = Elimination::factor(ir, &a_d, &eqs.constraints.order, &own);
    Ok(ConstraintSolve { elim, a })
}

/// `−(b + Σ A_k u_k)` over the known speeds `k`, per row.
fn dependent_rhs(
    lw: &mut Lowering<'_>,
    eqs: &Equations,
    split: &Split,
    a: &[Vec<Nid>],
) -> Result<Vec<Nid>, ProgramError> {
    let offsets: Vec<ExprId> = eqs.constraints.rows.iter().map(|r| r.offset).collect();
    let offsets = lw.all(&offsets, ItemRef::Constraint)?;
    let known: Vec<(usize, Nid)> = (0..eqs.speeds.len())
        .filter(|k| split.dependent_row(*k).is_none())
        .map(|k| (k, lw.env()[&eqs.speeds[k]]))
        .collect();
    let ir = &mut lw.ir;
    Ok((0..a.len())
        .map(|r| {
            let mut neg = vec![offsets[r]];
            for &(k, u) in &known {
                if ir.as_num(a[r][k]) != Some(0.0) {
                    neg.push(ir.mul(a[r][k], u));
                }
            }
            ir.sum(Vec::new(), neg)
        })
        .collect())
}

fn row_biases(eqs: &Equations) -> Vec<ExprId> {
    eqs.constraints.rows.iter().map(|r| r.bias).collect()
}
/// The columns of `P` and `w`.
fn reduction(
    ir: &mut Ir,
    split: &Split,
    c: &ConstraintSolve,
    bias: &[Nid],
    prescribed_accel: &[Nid],
) -> Reduction {
    let free_columns = split.free.iter().map(|&f| c.column(ir, f)).collect();
    let prescribed_columns = split.prescribed.iter().map(|&p| c.column(ir, p)).collect();
    let rhs: Vec<Nid> = (0..c.a.len())
        .map(|r| {
            let mut neg = vec![bias[r]];
            for (i, &p) in split.prescribed.iter().enumerate() {
                neg.push(ir.mul(c.a[r][p], prescribed_accel[i]));
            }
            ir.sum(Vec::new(), neg)
        })
        .collect();
    let dependent_accel = c.elim.solve(ir, &rhs);
    let n = split.coordinates.len() + split.prescribed.len();
    let mut w = vec![ir.num(0.0); n];
    for (r, &k) in split.dependent.iter().enumerate() {
        w[k] = dependent_accel[r];
    }
    for (i, &p) in split.prescribed.iter().enumerate() {
        w[p] = prescribed_accel[i];
    }
    Reduction {
        free_columns,
        prescribed_columns,
        w,
    }
}

/// The model's outputs, then the residuals of the position constraints and
/// the forces that enforce the motions; accelerations are read from the
/// derivatives (`Leaf::Accel` of the independent speeds), and the
/// multipliers the outputs ask for (`constraint_force`) from them.
fn outputs(
    lw: &mut Lowering<'_>,
    env: &Env,
    red: &Reduction,
    full: &Full,
    c: &ConstraintSolve,
) -> Result<Vec<Nid>, ProgramError> {
    let (eqs, split) = (lw.given.eqs, lw.given.split);
    let du_free: Vec<Nid> = (0..split.free.len())
        .map(|i| lw.ir.leaf(Leaf::Accel(i)))
        .collect();
    let acc = red.accelerations(&mut lw.ir, split, &du_free);
    let mut bound = binding_rates(env, eqs, &acc);
    let forces = &eqs.constraints.forces;
    if !forces.is_empty() {
        let residual = residual(&mut lw.ir, full, &acc);
        let lambda = multipliers(&mut lw.ir, c, eqs, &residual);
        bound.extend(forces.iter().map(|&(row, s)| (s, lambda[row])));
    }
    lw.bind(bound);
    let mut out = lw.outputs()?;
    let positions = &eqs.constraints.positions;
    for (i, g) in eqs.constraints.residuals.iter().enumerate() {
        out.push(lw.one(*g, ItemRef::Constraint(positions[i]))?);
    }
    if split.prescribed.is_empty() {
        return Ok(out);
    }
    let ir = &mut lw.ir;
    let residual = residual(ir, full, &acc);
    for (i, &p) in split.prescribed.iter().enumerate() {
        let column = red.full(ir, split, p, &red.prescribed_columns[i]);
        out.push(dot(ir, &column, &residual));
    }
    Ok(out)
}

/// `M u̇ − f`: the generalized loads the constraints and motions supply.
fn residual(ir: &mut Ir, full: &Full, acc: &[Nid]) -> Vec<Nid> {
    let m_acc = times_mass(ir, &full.mass, acc);
    (0..acc.len())
        .map(|k| ir.sum(vec![m_acc[k]], vec![full.forcing[k]]))
        .collect()
}

/// The multipliers `λ` of the constraints (by row): `M u̇ − f = Aᵀ λ` on
/// the speeds that are not prescribed, solved on the dependent ones,
/// `A_dᵀ λ = (M u̇ − f)_d`. `A_dᵀ` is factored with `A_d`'s pivots (a
/// transpose eliminated in the same order has the same pivots, which the
/// constraint solve already checks).
fn multipliers(ir: &mut Ir, c: &ConstraintSolve, eqs: &Equations, residual: &[Nid]) -> Vec<Nid> {
    let deps = &eqs.constraints.dependent_speeds;
    let a_dt: Vec<Vec<Option<Nid>>> = deps
        .iter()
        .map(|&k| {
            c.a.iter()
                .map(|row| Some(row[k]).filter(|x| ir.as_num(*x) != Some(0.0)))
                .collect()
        })
        .collect();
    let own: Vec<usize> = (0..deps.len()).collect();
    let elim = Elimination::factor(ir, &a_dt, &eqs.constraints.order, &own);
    let rhs: Vec<Nid> = deps.iter().map(|&k| residual[k]).collect();
    elim.solve(ir, &rhs)
}

/// The Newton step of assembly, `Δq_d = −G_d⁻¹ g`, with the residuals `g`
/// of the position constraints (none without them).
fn assembly(lw: &mut Lowering<'_>, eqs: &Equations) -> Result<Option<Assembly>, ProgramError> {
    let c = &eqs.constraints;
    let np = c.positions.len();
    if np == 0 {
        return Ok(None);
    }
    let item = |i: usize| ItemRef::Constraint(c.positions[i]);
    let residuals = lw.all(&c.residuals, item)?;
    let mut jacobian: Vec<Vec<Option<Nid>>> = Vec::with_capacity(np);
    for (i, line) in c.jacobian.iter().enumerate() {
        let mut row = Vec::with_capacity(np);
        for e in line {
            row.push(match lw.is_zero(*e) {
                true => None,
                false => Some(lw.one(*e, item(i))?),
            });
        }
        jacobian.push(row);
    }
    let ir = &mut lw.ir;
    let own: Vec<usize> = (0..np).collect();
    let elim = Elimination::factor(ir, &jacobian, &c.assembly_order, &own);
    let rhs: Vec<Nid> = residuals.iter().map(|g| ir.neg(*g)).collect();
    let step = elim.solve(ir, &rhs);
    let checks = elim
        .checks
        .iter()
        .map(|&(p, i)| (p, c.positions[i]))
        .collect();
    Ok(Some(Assembly {
        step,
        residuals,
        checks,
        elim,
    }))
}
