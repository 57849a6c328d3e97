//! Lowering a tree's equations: kinematics, mass matrix, forcing, the
//! solve of the accelerations (the mass matrix's LDLᵀ or the
//! articulated-body recursion), extra states, outputs and initial values,
//! in the order that numbers the IR.

use super::Lowering;
use super::context::binding_rates;
use super::equations::Lowered;
use crate::expr::ExprId;
use crate::mech::{BodyKinetics, ItemRef};
use crate::opt::error::ProgramError;
use crate::opt::ir::{Ir, Leaf, Nid};
use crate::opt::solve::articulated::TreeBody;
use crate::opt::solve::{ldlt_solve, recursive_solve};

/// Lowers every equation, in the order that numbers the IR (and so the
/// generated constants): kinematics, mass matrix, forcing, subroutine
/// arguments, the solve, extra states, outputs, initial values.
pub(crate) fn lower(lw: &mut Lowering<'_>, recursive: bool) -> Result<Lowered, ProgramError> {
    let given = lw.given;
    let eqs = given.eqs;
    let body = |k: usize| given.declared.coordinate_items[k];
    let kinematics = lw.all(&eqs.kinematics, body)?;
    let mass = lw.mass_matrix()?;
    // Kane's forcing as derived feeds the mass matrix's solve; the
    // recursion sums it body by body instead.
    let kane_forcing = match recursive {
        false => Some(lw.forcing()?),
        true => None,
    };
    let sub_args = lw.sub_args()?;
    let (solve, forcing) = match kane_forcing {
        Some(forcing) => (ldlt_solve(&mut lw.ir, &mass, &forcing), forcing),
        None => {
            let bodies = tree_bodies(lw, &eqs.tree.bodies)?;
            let joint_forcing = lw.all(&eqs.tree.joint_forcing, body)?;
            recursive_solve(&mut lw.ir, bodies, &joint_forcing)
        }
    };
    // Extra states and outputs read the accelerations as leaves; the
    // extra states' are replaced by the solve's values (the linearization
    // differentiates the leaf form), the outputs read du/dt from the
    // derivatives.
    let accel: Vec<Nid> = (0..eqs.speed_rates.len())
        .map(|i| lw.ir.leaf(Leaf::Accel(i)))
        .collect();
    let with_accel = binding_rates(lw.env(), eqs, &accel);
    let (extra, extra_in_rates) = lw.extra(with_accel, &solve.du)?;
    let outputs = lw.outputs()?;
    let initial = lw.initial()?;
    Ok(Lowered {
        kinematics,
        mass,
        forcing,
        solve,
        constraint_checks: Vec::new(),
        extra,
        extra_in_rates,
        outputs,
        initial,
        sub_args,
        call_order: lw.call_order(),
        named: Vec::new(),
        assembly: None,
    })
}

/// The bodies' data for the recursive solve, lowered (each an expression
/// of its body).
fn tree_bodies(
    lw: &mut Lowering<'_>,
    tree: &[BodyKinetics],
) -> Result<Vec<TreeBody>, ProgramError> {
    let mut out = Vec::with_capacity(tree.len());
    for b in tree {
        let mut one = |e: ExprId| lw.one(e, ItemRef::Body(b.body));
        let mut rotation = [[Nid(0); 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                rotation[i][j] = one(b.rotation[i][j])?;
            }
        }
        let offset = [one(b.offset[0])?, one(b.offset[1])?, one(b.offset[2])?];
        let m = one(b.mass)?;
        let h = [
            one(b.first_moment[0])?,
            one(b.first_moment[1])?,
            one(b.first_moment[2])?,
        ];
        let mut j = [[Nid(0); 3]; 3];
        for r in 0..3 {
            for c in 0..3 {
                j[r][c] = one(b.inertia[r][c])?;
            }
        }
        let mut speeds = Vec::with_capacity(b.speeds.len());
        for (k, s) in &b.speeds {
            let mut v = [Nid(0); 6];
            for r in 0..6 {
                v[r] = one(s[r])?;
            }
            speeds.push((*k, v));
        }
        let mut bias = [Nid(0); 6];
        for r in 0..6 {
            bias[r] = one(b.bias[r])?;
        }
        out.push(TreeBody {
            parent: b.parent,
            rotation,
            offset,
            inertia: rigid_inertia(&mut lw.ir, m, &h, &j),
            speeds,
            unit_axes: b.unit_axes.clone(),
            turn: b.turn.map(|a| a.index()),
            bias,
        });
    }
    Ok(out)
}

/// `[[J, h̃], [h̃ᵀ, m 1]]` about the origin (`h = m c`).
fn rigid_inertia(ir: &mut Ir, m: Nid, h: &[Nid; 3], j: &[[Nid; 3]; 3]) -> [[Nid; 6]; 6] {
    let zero = ir.num(0.0);
    let (n0, n1, n2) = (ir.neg(h[0]), ir.neg(h[1]), ir.neg(h[2]));
    let skew = [[zero, n2, h[1]], [h[2], zero, n0], [n1, h[0], zero]];
    let mut out = [[zero; 6]; 6];
    for r in 0..3 {
        for c in 0..3 {
            out[r][c] = j[r][c];
            out[r][3 + c] = skew[r][c];
            out[3 + c][r] = skew[r][c];
        }
        out[3 + r][3 + r] = m;
    }
    out
}
