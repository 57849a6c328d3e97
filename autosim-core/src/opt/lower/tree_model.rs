//! Lowering a tree's equations: kinematics, mass matrix, forcing, the
//! solve of the accelerations (the mass matrix's LDLᵀ or the
//! articulated-body recursion), extra states, outputs and initial values,
//! in the order that numbers the IR.

use crate::expr::{ExprId, SymId};
use crate::mech::{BodyKinetics, Equations, ItemRef};
use crate::model::ResolvedModel;
use crate::opt::ir::{Ir, Leaf, Nid};
use crate::opt::lower::equations::{
    Lowered, binding_rates, collect_calls, lower_all, lower_extra, lower_one,
};
use crate::opt::lower::expr::Lowering;
use crate::opt::program::ProgramError;
use crate::opt::solve::articulated::TreeBody;
use crate::opt::solve::{ldlt_solve, recursive_solve};
use rustc_hash::FxHashMap;

/// Lowers every equation, in the order that numbers the IR (and so the
/// generated constants): kinematics, mass matrix, forcing, subroutine
/// arguments, the solve, extra states, outputs, initial values.
pub(crate) fn lower(
    model: &mut ResolvedModel,
    eqs: &Equations,
    ir: &mut Ir,
    leaves: &FxHashMap<SymId, Nid>,
    recursive: bool,
) -> Result<Lowered, ProgramError> {
    let sys = &mut model.system;
    let n = eqs.coordinates.len();
    let coordinate_bodies: Vec<ItemRef> = sys
        .coordinates()
        .iter()
        .map(|c| ItemRef::Body(c.body))
        .collect();
    let subs = sys.subroutines().to_vec();
    let mut user_calls: Vec<(ExprId, Nid)> = Vec::new();

    let mut lw = Lowering::new(&mut sys.arena, ir, leaves);
    let kinematics = lower_all(&mut lw, &eqs.kinematics, |k| coordinate_bodies[k])?;
    let mut mass: Vec<Vec<Option<Nid>>> = vec![vec![None; n]; n];
    for i in 0..n {
        for j in 0..=i {
            let e = eqs.mass_matrix[i][j];
            if !lw.is_zero(e) {
                mass[i][j] = Some(lower_all(&mut lw, &[e], |_| coordinate_bodies[i])?[0]);
            }
        }
    }
    // Kane's forcing as derived feeds the mass matrix's solve; the
    // recursion sums it body by body instead.
    let kane_forcing = match recursive {
        false => Some(lower_all(&mut lw, &eqs.forcing, |_| ItemRef::Model)?),
        true => None,
    };
    let mut sub_args = Vec::with_capacity(subs.len());
    for (k, s) in subs.iter().enumerate() {
        sub_args.push(lower_all(&mut lw, &s.args, |_| ItemRef::Subroutine(k))?);
    }
    user_calls.extend(lw.user_calls());

    let (solve, forcing) = match kane_forcing {
        Some(forcing) => (ldlt_solve(ir, &mass, &forcing), forcing),
        None => {
            let mut lw = Lowering::new(&mut sys.arena, ir, leaves);
            let bodies = tree_bodies(&mut lw, &eqs.tree.bodies)?;
            let joint_forcing = lower_all(&mut lw, &eqs.tree.joint_forcing, |_| ItemRef::Model)?;
            user_calls.extend(lw.user_calls());
            recursive_solve(ir, bodies, &joint_forcing)
        }
    };
    // Extra states and outputs read the accelerations as leaves; the
    // extra states' are replaced by the solve's values (the linearization
    // differentiates the leaf form), the outputs read du/dt from the
    // derivatives.
    let rates = eqs.speed_rates.len();
    let accel: Vec<Nid> = (0..rates).map(|i| ir.leaf(Leaf::Accel(i))).collect();
    let with_accel = binding_rates(leaves, eqs, &accel);
    let (extra, extra_in_rates) = lower_extra(
        &mut sys.arena,
        ir,
        &with_accel,
        eqs,
        &solve.du,
        &mut user_calls,
    )?;
    let output_exprs: Vec<ExprId> = sys.outputs().iter().map(|o| o.expr).collect();
    let mut lw = Lowering::new(&mut sys.arena, ir, &with_accel);
    let outputs = lower_all(&mut lw, &output_exprs, ItemRef::Output)?;
    user_calls.extend(lw.user_calls());

    let mut initial_exprs: Vec<ExprId> = sys.coordinates().iter().map(|c| c.initial_q).collect();
    initial_exprs.extend(sys.coordinates().iter().map(|c| c.initial_u));
    initial_exprs.extend(sys.states().iter().map(|s| s.initial));
    let mut lw = Lowering::new(&mut sys.arena, ir, leaves);
    let initial = lower_all(&mut lw, &initial_exprs, |_| ItemRef::Model)?;

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
        call_order: collect_calls(user_calls),
        named: Vec::new(),
        assembly: None,
    })
}

/// The bodies' data for the recursive solve, lowered.
fn tree_bodies(
    lw: &mut Lowering<'_>,
    tree: &[BodyKinetics],
) -> Result<Vec<TreeBody>, ProgramError> {
    let mut out = Vec::with_capacity(tree.len());
    for b in tree {
        let mut one = |e: ExprId| lower_one(lw, e, ItemRef::Model);
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
            inertia: rigid_inertia(lw.ir(), m, &h, &j),
            speeds,
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
