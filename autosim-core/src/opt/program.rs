//! The equation program of a model: one IR shared by a list of scheduled
//! blocks (constants once per parameter set; derivatives, with the
//! unrolled solve of the mass matrix; outputs; the mass matrix and forcing
//! alone; the initial state), plus the interface generated code exposes.

use super::articulated::TreeBody;
use super::constrained;
use super::elim::Elimination;
use super::interface::{Interface, StateLayout};
use super::ir::{Ir, Leaf, Nid, Op};
use super::linearize::{Linear, Linearizable};
use super::lower::{Lowering, UnboundSymbol};
use super::schedule::{Block, Guard, Options, Task, schedule};
use super::solve::{Solve, ldlt_solve, recursive_solve};
use super::split::Split;
use super::tangent::substitute;
use crate::expr::{ExprId, Func, SymId};
use crate::mech::{BodyKinetics, Equations, ItemRef};
use crate::model::{Formulation, ResolvedModel};
use rustc_hash::{FxHashMap, FxHashSet};

/// What a block computes; each kind is one function of generated code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum BlockKind {
    /// dx/dt: slots `0..n` dq/dt, `n..2n` du/dt, then the extra states.
    Derivatives,
    /// The outputs; reads `Leaf::Accel` if it needs du/dt.
    Outputs,
    /// Constants computed once per parameter set: slot `k` is `hoisted[k]`.
    Constants,
    /// The mass matrix, slot `i*n + j`.
    MassMatrix,
    /// The forcing vector.
    Forcing,
    /// The initial state from the parameters.
    Initial,
    /// One Newton step of assembly (models with position constraints):
    /// slots `0..k` the corrections of the dependent coordinates, `k..2k`
    /// the residuals of the `k` position constraints.
    Assembly,
    /// The linear model (when asked for): `A` row-major over the linear
    /// states, then `B`, `C`, `D`.
    Linearize,
}

impl BlockKind {
    /// The name used in reports, documentation and the program's text form.
    pub fn name(self) -> &'static str {
        match self {
            BlockKind::Derivatives => "derivatives",
            BlockKind::Outputs => "outputs",
            BlockKind::Constants => "constants",
            BlockKind::MassMatrix => "mass_matrix",
            BlockKind::Forcing => "forcing",
            BlockKind::Initial => "initial",
            BlockKind::Assembly => "assembly",
            BlockKind::Linearize => "linearize",
        }
    }

    /// Whether the block reads the hoisted constants (all but the blocks
    /// that compute from the parameters alone).
    pub fn reads_constants(self) -> bool {
        !matches!(self, BlockKind::Constants | BlockKind::Initial)
    }
}

/// The scheduled program of a model: everything code generation needs.
#[derive(Clone, Debug)]
pub struct Program {
    /// All operations.
    pub ir: Ir,
    /// The blocks, in the order generated code lists their costs.
    pub blocks: Vec<(BlockKind, Block)>,
    /// The constant nodes the other blocks read (sorted; slot `k` of the
    /// constants block computes `hoisted[k]`).
    pub hoisted: Vec<Nid>,
    /// Arguments of each user subroutine (declaration order).
    pub sub_args: Vec<Vec<Nid>>,
    /// `true` if the outputs need du/dt (generated code computes the
    /// derivatives first).
    pub outputs_need_derivatives: bool,
    /// Names, units, defaults and docs of everything generated code exposes.
    pub interface: Interface,
}

impl Program {
    /// The block of a kind (every program has one of each, but the
    /// assembly block only with position constraints).
    pub fn block(&self, kind: BlockKind) -> &Block {
        self.try_block(kind)
            .unwrap_or_else(|| unreachable!("the program has no {} block", kind.name()))
    }

    /// The block of a kind, if the program has one.
    pub fn try_block(&self, kind: BlockKind) -> Option<&Block> {
        self.blocks.iter().find(|(k, _)| *k == kind).map(|(_, b)| b)
    }

    /// The state vector's layout.
    pub fn states(&self) -> &StateLayout {
        &self.interface.states
    }

    /// Number of independent generalized speeds.
    pub fn n(&self) -> usize {
        self.interface.states.n_speeds()
    }

    /// The number of values a block of this kind writes.
    pub fn slots(&self, kind: BlockKind) -> usize {
        let n = self.n();
        match kind {
            BlockKind::Derivatives | BlockKind::Initial => self.states().len(),
            BlockKind::Outputs => self.interface.outputs.len(),
            BlockKind::Constants => self.hoisted.len(),
            BlockKind::MassMatrix => n * n,
            BlockKind::Forcing => n,
            BlockKind::Assembly => 2 * self.interface.closures.len(),
            BlockKind::Linearize => {
                let nl = self.interface.linear_states.as_ref().map_or(0, Vec::len);
                let (nw, ny) = (self.interface.inputs.len(), self.interface.outputs.len());
                (nl + ny) * (nl + nw)
            }
        }
    }
}

/// Why a program could not be built.
#[derive(Clone, Debug, PartialEq)]
pub enum ProgramError {
    /// An expression of `item` uses a symbol that has no value at run time.
    Unbound {
        /// The symbol's name.
        name: String,
        /// The item whose expression uses it.
        item: ItemRef,
    },
}

impl ProgramError {
    /// The item whose expression caused the error.
    pub fn item(&self) -> ItemRef {
        match self {
            ProgramError::Unbound { item, .. } => *item,
        }
    }
}

impl std::fmt::Display for ProgramError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ProgramError::Unbound { name, .. } => {
                write!(f, "`{name}` has no value in the generated program")
            }
        }
    }
}

/// Builds the program of a resolved model from its equations.
pub fn build(model: &mut ResolvedModel, eqs: &Equations) -> Result<Program, ProgramError> {
    let split = Split::new(eqs);
    if !split.is_tree() {
        return build_route(model, eqs, &split, Route::Constrained);
    }
    match model.formulation {
        Formulation::MassMatrix => build_route(model, eqs, &split, Route::MassMatrix),
        Formulation::Recursive => build_route(model, eqs, &split, Route::Recursive),
        // With small variables the mass matrix is truncated term by term;
        // the recursion would truncate a different (first-order equal)
        // model, so the choice keeps the mass matrix.
        Formulation::Auto if model.system.arena.has_small_symbols() => {
            build_route(model, eqs, &split, Route::MassMatrix)
        }
        Formulation::Auto => {
            let matrix = build_route(model, eqs, &split, Route::MassMatrix)?;
            let recursive = build_route(model, eqs, &split, Route::Recursive)?;
            let cost = |p: &Program| p.block(BlockKind::Derivatives).ops.total();
            Ok(match cost(&recursive) < cost(&matrix) {
                true => recursive,
                false => matrix,
            })
        }
    }
}

/// How the program solves for the accelerations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Route {
    /// A tree, by the mass matrix's LDLᵀ.
    MassMatrix,
    /// A tree, by the articulated-body recursion.
    Recursive,
    /// With constraints or motions (Kane's method for dependent speeds).
    Constrained,
}

/// The program of one route.
fn build_route(
    model: &mut ResolvedModel,
    eqs: &Equations,
    split: &Split,
    route: Route,
) -> Result<Program, ProgramError> {
    let interface = Interface::new(model, eqs, split);
    let mut ir = Ir::new();
    let lowered = match route {
        Route::Constrained => constrained::lower(model, eqs, split, &mut ir)?,
        tree => {
            let leaves = leaves(model, eqs, split, &mut ir)?;
            lower(model, eqs, &mut ir, &leaves, tree == Route::Recursive)?
        }
    };
    let linear = model
        .linearize
        .then(|| linearizable(&lowered, &interface).linearize(&mut ir));
    let mut interface = interface;
    interface.linear_states = linear.as_ref().map(|l| l.states.clone());
    let names = Naming::new(&ir, &interface, &lowered);
    let program = schedule_blocks(ir, lowered, linear, &names, interface);
    debug_assert_eq!(program.verify(), Ok(()));
    Ok(program)
}

/// The leaf of every symbol with a value at run time (the state holds the
/// coordinates but the prescribed, and the independent speeds), and the
/// prescribed coordinates and speeds as functions of time.
pub(super) fn leaves(
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
pub(super) struct Lowered {
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
pub(super) struct Assembly {
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

/// `nodes` with `Leaf::Accel(k)` replaced by `du[k]`.
pub(super) fn with_accelerations(ir: &mut Ir, nodes: &[Nid], du: &[Nid]) -> Vec<Nid> {
    let map: FxHashMap<Nid, Nid> = du
        .iter()
        .enumerate()
        .map(|(k, d)| (ir.leaf(Leaf::Accel(k)), *d))
        .collect();
    substitute(ir, nodes, &map)
}

/// Lowers `e`, naming `item` on failure.
pub(super) fn lower_one(
    lw: &mut Lowering<'_>,
    e: ExprId,
    item: ItemRef,
) -> Result<Nid, ProgramError> {
    lw.lower(e)
        .map_err(|UnboundSymbol(name)| ProgramError::Unbound { name, item })
}

/// User-function calls in model order (their creation order), once each.
pub(super) fn collect_calls(mut calls: Vec<(ExprId, Nid)>) -> Vec<Nid> {
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
pub(super) fn lower_all(
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

/// Lowers every equation, in the order that numbers the IR (and so the
/// generated constants): kinematics, mass matrix, forcing, subroutine
/// arguments, the solve, extra states, outputs, initial values.
fn lower(
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
    let forcing = lower_all(&mut lw, &eqs.forcing, |_| ItemRef::Model)?;
    let mut sub_args = Vec::with_capacity(subs.len());
    for (k, s) in subs.iter().enumerate() {
        sub_args.push(lower_all(&mut lw, &s.args, |_| ItemRef::Subroutine(k))?);
    }
    user_calls.extend(lw.user_calls());

    let solve = match recursive {
        false => ldlt_solve(ir, &mass, &forcing),
        true => {
            let mut lw = Lowering::new(&mut sys.arena, ir, leaves);
            let bodies = tree_bodies(&mut lw, &eqs.tree)?;
            recursive_solve(ir, bodies, &forcing)
        }
    };
    // Extra states read the accelerations as leaves, replaced by the
    // solve's values (the linearization differentiates the leaf form).
    let mut with_rates = leaves.clone();
    for (i, s) in eqs.speed_rates.iter().enumerate() {
        with_rates.insert(*s, ir.leaf(Leaf::Accel(i)));
    }
    let mut lw = Lowering::new(&mut sys.arena, ir, &with_rates);
    let state_syms = eqs.states.clone();
    let extra_in_rates = lower_all(&mut lw, &eqs.state_derivatives, |k| {
        ItemRef::State(state_syms[k])
    })?;
    user_calls.extend(lw.user_calls());
    let extra = with_accelerations(ir, &extra_in_rates, &solve.du);

    // Outputs read du/dt from the derivatives.
    let mut with_accel = leaves.clone();
    for (i, s) in eqs.speed_rates.iter().enumerate() {
        with_accel.insert(*s, ir.leaf(Leaf::Accel(i)));
    }
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
        out.push(TreeBody {
            parent: b.parent,
            rotation,
            offset,
            inertia: rigid_inertia(lw.ir(), m, &h, &j),
            speeds,
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

/// Names for generated code: hints for readable values, and the names the
/// generated ones must avoid.
struct Naming {
    hints: FxHashMap<Nid, String>,
    /// Names taken in every block.
    reserved: FxHashSet<String>,
    /// Names taken in the outputs block (the accelerations too).
    output_reserved: FxHashSet<String>,
}

impl Naming {
    fn new(ir: &Ir, interface: &Interface, lowered: &Lowered) -> Naming {
        let layout = &interface.states;
        let mut reserved: FxHashSet<String> = layout.states().map(|s| s.name.clone()).collect();
        reserved.extend(interface.inputs.iter().map(|i| i.name.clone()));
        for sub in &interface.subroutines {
            reserved.extend(sub.outputs.iter().cloned());
        }
        for r in [
            "t", "x", "dx", "y", "p", "c", "m", "f", "e", "self", "externs", "inputs",
        ] {
            reserved.insert(r.to_string());
        }
        let mut output_reserved = reserved.clone();
        for k in 0..layout.n_speeds() {
            output_reserved.insert(layout.speed_rate_name(k));
        }
        Naming {
            hints: hints(ir, layout, lowered),
            reserved,
            output_reserved,
        }
    }
}

/// Readable names: `sin_q4`, `m2_1`, `f3`, `u5_dot`, the factor's `d2`, ...
fn hints(ir: &Ir, layout: &StateLayout, lowered: &Lowered) -> FxHashMap<Nid, String> {
    let mut hints: FxHashMap<Nid, String> = FxHashMap::default();
    let mut hint = |n: Nid, h: String| {
        hints.entry(n).or_insert(h);
    };
    for idx in 0..ir.len() {
        let nid = Nid(idx as u32);
        if let Op::Call(f @ (Func::Sin | Func::Cos), args) = ir.op(nid)
            && let Op::Leaf(Leaf::State(i)) = ir.op(args[0])
        {
            let pre = if *f == Func::Sin { "sin" } else { "cos" };
            hint(nid, format!("{pre}_{}", layout.state(*i).name));
        }
    }
    let (nf, nq) = (layout.n_speeds(), layout.coordinates.len());
    for i in 0..nf.max(nq) {
        if i < nf {
            for j in 0..=i {
                if let Some(m) = lowered.mass[i][j] {
                    hint(m, format!("m{}_{}", i + 1, j + 1));
                }
            }
            hint(lowered.forcing[i], format!("f{}", i + 1));
            hint(lowered.solve.du[i], layout.speed_rate_name(i));
        }
        if i < nq {
            let name = &layout.coordinates[i].name;
            hint(lowered.kinematics[i], format!("{name}_dot"));
        }
    }
    for (h, nid) in lowered.solve.hints.iter().chain(&lowered.named) {
        hint(*nid, h.clone());
    }
    hints
}

/// `Store` tasks writing `values` into slots `first..`.
fn stores(values: &[Nid], first: usize) -> impl Iterator<Item = Task> + '_ {
    values.iter().enumerate().map(move |(i, v)| Task::Store {
        slot: first + i,
        value: *v,
    })
}

/// What the linearization differentiates.
fn linearizable<'a>(lowered: &'a Lowered, interface: &Interface) -> Linearizable<'a> {
    let n_outputs = interface.outputs.len();
    Linearizable {
        kinematics: &lowered.kinematics,
        extra: &lowered.extra_in_rates,
        du: &lowered.solve.du,
        mass: &lowered.mass,
        forcing: &lowered.forcing,
        factor: &lowered.solve.factor,
        outputs: &lowered.outputs[..n_outputs],
        closure: lowered.assembly.as_ref().map(|a| {
            let slots = interface.closures.iter().map(|c| c.slot).collect();
            (a.residuals.as_slice(), slots, &a.elim)
        }),
        inputs: interface.inputs.len(),
    }
}

/// `Check` tasks of constraint pivots.
fn regular(checks: &[(Nid, usize)]) -> impl Iterator<Item = Task> + '_ {
    checks.iter().map(|&(pivot, constraint)| Task::Check {
        pivot,
        guard: Guard::Regular { constraint },
    })
}

/// Whether any of `targets` is computed on the way to `roots`.
fn reaches(ir: &Ir, roots: &[Nid], targets: &[Nid]) -> bool {
    let mut seen: FxHashSet<Nid> = FxHashSet::default();
    let mut stack = roots.to_vec();
    while let Some(n) = stack.pop() {
        if targets.contains(&n) {
            return true;
        }
        if seen.insert(n) {
            stack.extend(ir.children(n));
        }
    }
    false
}

/// Schedules every block and assembles the program.
fn schedule_blocks(
    mut ir: Ir,
    lowered: Lowered,
    linear: Option<Linear>,
    names: &Naming,
    interface: Interface,
) -> Program {
    let n = interface.states.n_speeds();
    let nq = interface.states.coordinates.len();
    let options = |hoist: bool, reserved| Options {
        hoist_constants: hoist,
        hints: &names.hints,
        call_order: &lowered.call_order,
        sub_args: &lowered.sub_args,
        reserved,
    };
    let all = options(true, &names.reserved);

    let mut tasks: Vec<Task> = regular(&lowered.constraint_checks).collect();
    tasks.extend(stores(&lowered.kinematics, 0));
    for (pivot, speed) in &lowered.solve.pivots {
        tasks.push(Task::Check {
            pivot: *pivot,
            guard: Guard::Positive { speed: *speed },
        });
    }
    tasks.extend(stores(&lowered.solve.du, nq));
    tasks.extend(stores(&lowered.extra, nq + n));
    let derivatives = schedule(&ir, &tasks, &all);
    let linearize = linear.map(|l| {
        let mut tasks: Vec<Task> = tasks
            .iter()
            .filter(|t| matches!(t, Task::Check { .. }))
            .cloned()
            .collect();
        if let Some(a) = &lowered.assembly {
            tasks.extend(regular(&a.checks));
        }
        tasks.extend(stores(&l.values, 0));
        schedule(&ir, &tasks, &all)
    });

    let pivots: Vec<Nid> = lowered.constraint_checks.iter().map(|c| c.0).collect();
    let mut out_tasks: Vec<Task> = Vec::new();
    if reaches(&ir, &lowered.outputs, &pivots) {
        out_tasks.extend(regular(&lowered.constraint_checks));
    }
    out_tasks.extend(stores(&lowered.outputs, 0));
    let outputs = schedule(&ir, &out_tasks, &options(true, &names.output_reserved));
    let outputs_need_derivatives = outputs.leaves.iter().any(|l| matches!(l, Leaf::Accel(_)));

    let zero = ir.num(0.0);
    let mut mm_tasks = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let v = lowered.mass[i.max(j)][i.min(j)].unwrap_or(zero);
            mm_tasks.push(Task::Store {
                slot: i * n + j,
                value: v,
            });
        }
    }
    // `mass_matrix` and `forcing` return no error: at a state where the
    // constraints are singular their values are not finite.
    let mass_matrix = schedule(&ir, &mm_tasks, &all);
    let f_tasks: Vec<Task> = stores(&lowered.forcing, 0).collect();
    let forcing = schedule(&ir, &f_tasks, &all);
    let assembly = lowered.assembly.as_ref().map(|a| {
        let mut tasks: Vec<Task> = regular(&a.checks).collect();
        tasks.extend(stores(&a.step, 0));
        tasks.extend(stores(&a.residuals, a.step.len()));
        schedule(&ir, &tasks, &all)
    });

    let mut hoisted: Vec<Nid> = [&derivatives, &outputs, &mass_matrix, &forcing]
        .into_iter()
        .chain(assembly.as_ref())
        .chain(linearize.as_ref())
        .flat_map(|b| b.hoisted.iter().copied())
        .collect();
    hoisted.sort();
    hoisted.dedup();
    let c_tasks: Vec<Task> = stores(&hoisted, 0).collect();
    let constants = schedule(&ir, &c_tasks, &options(false, &names.reserved));
    let i_tasks: Vec<Task> = stores(&lowered.initial, 0).collect();
    let initial = schedule(&ir, &i_tasks, &options(false, &names.reserved));

    let mut blocks = vec![
        (BlockKind::Derivatives, derivatives),
        (BlockKind::Outputs, outputs),
        (BlockKind::Constants, constants),
        (BlockKind::MassMatrix, mass_matrix),
        (BlockKind::Forcing, forcing),
        (BlockKind::Initial, initial),
    ];
    blocks.extend(assembly.map(|a| (BlockKind::Assembly, a)));
    blocks.extend(linearize.map(|l| (BlockKind::Linearize, l)));
    Program {
        ir,
        blocks,
        hoisted,
        sub_args: lowered.sub_args,
        outputs_need_derivatives,
        interface,
    }
}
