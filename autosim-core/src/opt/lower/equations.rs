//! What lowering hands to scheduling: the equations as IR nodes
//! (`Lowered`, `Assembly`), and the helpers every lowering uses (the
//! leaves of the symbols, lowering with errors that name the item, user
//! calls in model order, accelerations read as leaves).

use crate::expr::{Arena, ExprId, SymId};
use crate::mech::{Equations, ItemRef};
use crate::model::ResolvedModel;
use crate::opt::ir::{Ir, Leaf, Nid};
use crate::opt::linearize::tangent::substitute;
use crate::opt::lower::expr::{Lowering, UnboundSymbol};
use crate::opt::program::ProgramError;
use crate::opt::solve::Solve;
use crate::opt::solve::elim::Elimination;
use crate::opt::split::Split;
use rustc_hash::FxHashMap;

/// The leaf of every symbol with a value at run time (the state holds the
/// coordinates but the prescribed, and the independent speeds), and the
/// prescribed coordinates and speeds as functions of time.
pub(crate) fn leaves(
    model: &mut ResolvedModel,
    eqs: &Equations,
    split: &Split,
    ir: &mut Ir,
) -> Result<FxHashMap<SymId, Nid>, ProgramError> {
    let sys = &model.system;
    let mut env: FxHashMap<SymId, Nid> = FxHashMap::default();
    for (i, s) in sys.parameters().iter().enumerate() {
        env.insert(*s, ir.leaf(Leaf::Param(i)));
    }
    let states = split
        .coordinates
        .iter()
        .map(|&j| eqs.coordinates[j])
        .chain(split.free.iter().map(|&k| eqs.speeds[k]))
        .chain(eqs.states.iter().copied());
    for (i, s) in states.enumerate() {
        env.insert(s, ir.leaf(Leaf::State(i)));
    }
    for (i, s) in sys.inputs().iter().enumerate() {
        env.insert(*s, ir.leaf(Leaf::Input(i)));
    }
    env.insert(sys.time(), ir.leaf(Leaf::Time));
    for (k, sub) in sys.subroutines().iter().enumerate() {
        for (j, o) in sub.outputs.iter().enumerate() {
            env.insert(*o, ir.leaf(Leaf::SubOut(k, j)));
        }
    }
    if eqs.prescribed.is_empty() {
        return Ok(env);
    }
    let mut lw = Lowering::new(&mut model.system.arena, ir, &env);
    let mut known = Vec::new();
    for (i, p) in eqs.prescribed.iter().enumerate() {
        let value = lower_one(&mut lw, p.value, ItemRef::Motion(i))?;
        let rate = lower_one(&mut lw, p.rate, ItemRef::Motion(i))?;
        known.push((eqs.coordinates[p.speed], value));
        known.push((eqs.speeds[p.speed], rate));
    }
    env.extend(known);
    Ok(env)
}

/// The equations lowered to IR nodes.
pub(crate) struct Lowered {
    /// dq/dt of the state's coordinates.
    pub kinematics: Vec<Nid>,
    /// Lower triangle of the mass matrix of the independent speeds
    /// (`None`: structurally zero).
    pub mass: Vec<Vec<Option<Nid>>>,
    /// The forcing vector of the independent speeds.
    pub forcing: Vec<Nid>,
    /// The solve of `M du/dt = f`.
    pub solve: Solve,
    /// Pivots of the constraint solve, with their constraint.
    pub constraint_checks: Vec<(Nid, usize)>,
    /// d/dt of the extra states.
    pub extra: Vec<Nid>,
    /// The same, reading the state's accelerations as `Leaf::Accel`.
    pub extra_in_rates: Vec<Nid>,
    /// The outputs.
    pub outputs: Vec<Nid>,
    /// The initial state.
    pub initial: Vec<Nid>,
    /// Subroutine arguments.
    pub sub_args: Vec<Vec<Nid>>,
    /// User-function calls in model order.
    pub call_order: Vec<Nid>,
    /// Values named after a symbol (the dependent speeds).
    pub named: Vec<(String, Nid)>,
    /// The Newton step of assembly (models with position constraints).
    pub assembly: Option<Assembly>,
}

/// One Newton step of assembly.
pub(crate) struct Assembly {
    /// The corrections of the dependent coordinates.
    pub step: Vec<Nid>,
    /// The residuals of the position constraints.
    pub residuals: Vec<Nid>,
    /// Pivots of the Jacobian's solve, with their constraint.
    pub checks: Vec<(Nid, usize)>,
    /// The factored Jacobian `G_d` of the residuals by the dependent
    /// coordinates.
    pub elim: Elimination,
}

/// `env` with the symbol of each speed's rate (`du_k/dt`) bound to
/// `rates[k]`.
pub(crate) fn binding_rates(
    env: &FxHashMap<SymId, Nid>,
    eqs: &Equations,
    rates: &[Nid],
) -> FxHashMap<SymId, Nid> {
    let mut bound = env.clone();
    for (s, r) in eqs.speed_rates.iter().zip(rates) {
        bound.insert(*s, *r);
    }
    bound
}

/// The added states' derivatives lowered with the rates bound as `env`
/// says (the form the linearization differentiates), and the same with
/// the solve's accelerations `du` in place of `Leaf::Accel`.
pub(crate) fn lower_extra(
    arena: &mut Arena,
    ir: &mut Ir,
    env: &FxHashMap<SymId, Nid>,
    eqs: &Equations,
    du: &[Nid],
    calls: &mut Vec<(ExprId, Nid)>,
) -> Result<(Vec<Nid>, Vec<Nid>), ProgramError> {
    let mut lw = Lowering::new(arena, ir, env);
    let in_rates = lower_all(&mut lw, &eqs.state_derivatives, |k| {
        ItemRef::State(eqs.states[k])
    })?;
    calls.extend(lw.user_calls());
    let extra = with_accelerations(ir, &in_rates, du);
    Ok((extra, in_rates))
}

/// `nodes` with `Leaf::Accel(k)` replaced by `du[k]`.
pub(crate) fn with_accelerations(ir: &mut Ir, nodes: &[Nid], du: &[Nid]) -> Vec<Nid> {
    let map: FxHashMap<Nid, Nid> = du
        .iter()
        .enumerate()
        .map(|(k, d)| (ir.leaf(Leaf::Accel(k)), *d))
        .collect();
    substitute(ir, nodes, &map)
}

/// Lowers `e`, naming `item` on failure.
pub(crate) fn lower_one(
    lw: &mut Lowering<'_>,
    e: ExprId,
    item: ItemRef,
) -> Result<Nid, ProgramError> {
    lw.lower(e)
        .map_err(|UnboundSymbol(name)| ProgramError::Unbound { name, item })
}

/// User-function calls in model order (their creation order), once each.
pub(crate) fn collect_calls(mut calls: Vec<(ExprId, Nid)>) -> Vec<Nid> {
    calls.sort();
    let mut order: Vec<Nid> = Vec::new();
    for (_, nid) in calls {
        if !order.contains(&nid) {
            order.push(nid);
        }
    }
    order
}

/// Lowers `exprs` of `item` (errors name the item).
pub(crate) fn lower_all(
    lw: &mut Lowering<'_>,
    exprs: &[ExprId],
    item: impl Fn(usize) -> ItemRef,
) -> Result<Vec<Nid>, ProgramError> {
    exprs
        .iter()
        .enumerate()
        .map(|(k, e)| {
            lw.lower(*e)
                .map_err(|UnboundSymbol(name)| ProgramError::Unbound {
                    name,
                    item: item(k),
                })
        })
        .collect()
}
