//! The equation program of a model: one IR shared by a list of scheduled
//! blocks (constants once per parameter set; derivatives, with the
//! unrolled solve of the mass matrix; outputs; the mass matrix and forcing
//! alone; the initial state), plus the interface generated code exposes.

pub(super) mod interp;
pub(super) mod text;
pub(super) mod verify;

pub use crate::opt::lower::events::Assigned;

use crate::opt::error::ProgramError;
use crate::opt::input::{FloatType, Formulation, Input};
use crate::opt::interface::{Interface, StateLayout};
use crate::opt::ir::{Ir, Leaf, Nid};
use crate::opt::linearize::{Linear, Linearizable};
use crate::opt::lower::equations::Lowered;
use crate::opt::lower::events::{self, LoweredEvents};
use crate::opt::lower::{Given, Lowering, constrained, tree_model};
use crate::opt::schedule::naming::Naming;
use crate::opt::schedule::{Block, Guard, Options, Task, common, cost, schedule};
use crate::opt::solve::{Solver, ldlt_order, ldlt_varying_products};
use crate::opt::split::Split;
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
    /// The mass matrix: slot `i*n + j` (`MassLayout::Entries`), or the
    /// products `M du/dt` for accelerations read as `Leaf::Accel`
    /// (`MassLayout::Products`).
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
    /// What `derivatives` and `forcing` share, computed once for either
    /// (big models only, `common.rs`): slot `k` is `common[k]`.
    Common,
    /// The event indicators (models with events): slot `k` is event `k`'s.
    EventIndicators,
    /// The new values of the actions of event `k` (models with events;
    /// `Program::event_assignments[k]` says where each goes).
    EventAction(usize),
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
            BlockKind::Common => "common",
            BlockKind::EventIndicators => "event_indicators",
            BlockKind::EventAction(_) => "event_action",
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
    /// The nodes the common block computes for the blocks that read them
    /// (slot `k` computes `common[k]`; empty without a common block).
    pub common: Vec<Nid>,
    /// Arguments of each user subroutine (declaration order).
    pub sub_args: Vec<Vec<Nid>>,
    /// `true` if the outputs need du/dt (generated code computes the
    /// derivatives first).
    pub outputs_need_derivatives: bool,
    /// Names, units, defaults and docs of everything generated code exposes.
    pub interface: Interface,
    /// What the mass matrix block computes.
    pub mass_layout: MassLayout,
    /// For each event, what each value of its action assigns and its
    /// slot in the event's action block (empty without events).
    pub event_assignments: Vec<Vec<(Assigned, usize)>>,
}

/// What the mass matrix block computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MassLayout {
    /// Every entry of `M` (the mass-matrix and constrained routes, which
    /// form `M` anyway).
    Entries,
    /// `M du/dt` in O(n) operations for accelerations read as
    /// `Leaf::Accel` (the recursive route, which never forms `M`):
    /// generated code calls it once per column, O(n) lines instead of
    /// O(n²).
    Products,
}

impl Program {
    /// The block of a kind (every program has one of each, but the
    /// assembly block only with position constraints).
    pub fn block(&self, kind: BlockKind) -> &Block {
        self.try_block(kind)
            .unwrap_or_else(|| unreachable!("the program has no {} block", kind.name()))
    }

    /// The slot of each hoisted constant in the constants block.
    pub fn constant_slots(&self) -> FxHashMap<Nid, usize> {
        slots(&self.hoisted)
    }

    /// The slot of each value of the common block.
    pub fn common_slots(&self) -> FxHashMap<Nid, usize> {
        slots(&self.common)
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
            BlockKind::Outputs => self.interface.model.outputs.len(),
            BlockKind::Constants => self.hoisted.len(),
            BlockKind::Common => self.common.len(),
            BlockKind::MassMatrix => match self.mass_layout {
                MassLayout::Entries => n * n,
                MassLayout::Products => n,
            },
            BlockKind::Forcing => n,
            BlockKind::Assembly => 2 * self.interface.closures.len(),
            BlockKind::EventIndicators => self.interface.model.events.len(),
            BlockKind::EventAction(k) => self.event_assignments.get(k).map_or(0, Vec::len),
            BlockKind::Linearize => {
                let nl = self.interface.linear_states.as_ref().map_or(0, Vec::len);
                let (nw, ny) = (
                    self.interface.model.inputs.len(),
                    self.interface.model.outputs.len(),
                );
                (nl + ny) * (nl + nw)
            }
        }
    }
}

/// Slot `k` of `values` is `values[k]`.
fn slots(values: &[Nid]) -> FxHashMap<Nid, usize> {
    values.iter().enumerate().map(|(k, n)| (*n, k)).collect()
}

/// Builds the program of a model from everything it is given.
pub fn build(mut input: Input) -> Result<Program, ProgramError> {
    let split = Split::new(&input.equations);
    if !split.is_tree() {
        return build_route(&mut input, &split, Route::Constrained);
    }
    match input.options.formulation {
        Formulation::MassMatrix => build_route(&mut input, &split, Route::MassMatrix),
        Formulation::Recursive => build_route(&mut input, &split, Route::Recursive),
        // With small variables the mass matrix is truncated term by term;
        // the recursion would truncate a different (first-order equal)
        // model, so the choice keeps the mass matrix.
        Formulation::Auto if input.arena.has_small_symbols() => {
            build_route(&mut input, &split, Route::MassMatrix)
        }
        Formulation::Auto => {
            let (recursive, matrix_bound) = build_recursive(&mut input, &split)?;
            let cost = |p: &Program| cost::estimated_cycles(&p.ir, p.block(BlockKind::Derivatives));
            let recursive_cost = cost(&recursive);
            if matrix_bound > MATRIX_BOUND_MARGIN * recursive_cost {
                return Ok(recursive);
            }
            let matrix = build_route(&mut input, &split, Route::MassMatrix)?;
            Ok(match recursive_cost < cost(&matrix) {
                true => recursive,
                false => matrix,
            })
        }
    }
}

/// How far a lower bound on the mass matrix's cost must exceed the
/// recursion's whole cost for `auto` to take the recursion without
/// building the mass matrix's route: the bound counts products that are
/// distinct operations unless two entries of the factor coincide as
/// expressions; the margin keeps the choice certain even if half of them
/// did.
const MATRIX_BOUND_MARGIN: usize = 2;

/// The recursive route's program, with a lower bound on the estimated
/// cycles of the mass matrix route's `derivatives`
/// (`ldlt_varying_products` of its factorization, from the mass matrix
/// this route lowers too).
fn build_recursive(input: &mut Input, split: &Split) -> Result<(Program, usize), ProgramError> {
    let mut bound = 0;
    let program = build_route_with(input, split, Route::Recursive, |ir, lowered| {
        let perm = ldlt_order(lowered.mass.len());
        bound = ldlt_varying_products(ir, &lowered.mass, &perm);
    })?;
    Ok((program, bound))
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
fn build_route(input: &mut Input, split: &Split, route: Route) -> Result<Program, ProgramError> {
    build_route_with(input, split, route, |_, _| {})
}

/// The program of one route, showing `inspect` what was lowered before it
/// is scheduled.
fn build_route_with(
    input: &mut Input,
    split: &Split,
    route: Route,
    inspect: impl FnOnce(&Ir, &Lowered),
) -> Result<Program, ProgramError> {
    let interface = Interface::new(input, split);
    let given = Given {
        eqs: &input.equations,
        declared: &input.declared,
        split,
    };
    let mut lw = Lowering::start(&mut input.arena, given)?;
    let lowered = match route {
        Route::Constrained => constrained::lower(&mut lw)?,
        _ => tree_model::lower(&mut lw, route == Route::Recursive)?,
    };
    let events = events::lower(&mut lw)?;
    let mut ir = lw.into_ir();
    inspect(&ir, &lowered);
    let linear = input
        .options
        .linearize
        .then(|| linearizable(&lowered, &interface).linearize(&mut ir));
    let mut interface = interface;
    interface.linear_states = linear.as_ref().map(|l| l.states.clone());
    let names = Naming::new(&ir, &interface, &lowered);
    let program = schedule_blocks(ir, lowered, linear, events, &names, interface);
    debug_assert_eq!(program.verify(), Ok(()));
    Ok(program)
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
    let n_outputs = interface.model.outputs.len();
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
        inputs: interface.model.inputs.len(),
        user_step: match interface.float {
            FloatType::F64 => f64::EPSILON.cbrt(),
            FloatType::F32 => f64::from(f32::EPSILON).cbrt(),
        },
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
    events: Option<LoweredEvents>,
    names: &Naming,
    interface: Interface,
) -> Program {
    let n = interface.states.n_speeds();
    let nq = interface.states.coordinates.len();
    let no_common = FxHashSet::default();
    let options = |hoist: bool, reserved| Options {
        hoist_constants: hoist,
        hints: &names.hints,
        call_order: &lowered.call_order,
        sub_args: &lowered.sub_args,
        reserved,
        common: &no_common,
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
    let mut derivatives = schedule(&ir, &tasks, &all);
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

    let (mass_layout, mm_tasks) = mass_tasks(&mut ir, &lowered);
    // `mass_matrix` and `forcing` return no error: at a state where the
    // constraints are singular their values are not finite.
    let mass_matrix = schedule(&ir, &mm_tasks, &all);
    let f_tasks: Vec<Task> = stores(&lowered.forcing, 0).collect();
    let mut forcing = schedule(&ir, &f_tasks, &all);
    let shared = common::share(
        &ir,
        (&mut derivatives, &tasks),
        (&mut forcing, &f_tasks),
        &all,
    );
    let assembly = lowered.assembly.as_ref().map(|a| {
        let mut tasks: Vec<Task> = regular(&a.checks).collect();
        tasks.extend(stores(&a.step, 0));
        tasks.extend(stores(&a.residuals, a.step.len()));
        schedule(&ir, &tasks, &all)
    });

    let event_blocks: Vec<(BlockKind, Block)> = events.as_ref().map_or(Vec::new(), |e| {
        let in_order = Options {
            call_order: &e.call_order,
            ..all
        };
        let g_tasks: Vec<Task> = stores(&e.indicators, 0).collect();
        let mut blocks = vec![(
            BlockKind::EventIndicators,
            schedule(&ir, &g_tasks, &in_order),
        )];
        for (k, values) in e.actions.iter().enumerate() {
            let a_tasks: Vec<Task> = stores(values, 0).collect();
            blocks.push((
                BlockKind::EventAction(k),
                schedule(&ir, &a_tasks, &in_order),
            ));
        }
        blocks
    });

    let (common, common_values) = shared.unzip();
    let mut hoisted: Vec<Nid> = [&derivatives, &outputs, &mass_matrix, &forcing]
        .into_iter()
        .chain(common.as_ref())
        .chain(assembly.as_ref())
        .chain(linearize.as_ref())
        .chain(event_blocks.iter().map(|(_, b)| b))
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
    blocks.extend(common.map(|c| (BlockKind::Common, c)));
    blocks.extend(event_blocks);
    Program {
        ir,
        blocks,
        hoisted,
        common: common_values.unwrap_or_default(),
        sub_args: lowered.sub_args,
        outputs_need_derivatives,
        interface,
        mass_layout,
        event_assignments: events.map(|e| e.assignments).unwrap_or_default(),
    }
}

/// The mass matrix block's tasks: `M du/dt` with the accelerations as
/// leaves where the recursion solves (no entry of `M` is formed), every
/// entry otherwise.
fn mass_tasks(ir: &mut Ir, lowered: &Lowered) -> (MassLayout, Vec<Task>) {
    if let Solver::Articulated(a) = &lowered.solve.factor {
        let accel: Vec<Nid> = (0..lowered.forcing.len())
            .map(|k| ir.leaf(Leaf::Accel(k)))
            .collect();
        let products = a.times_mass(ir, &accel);
        return (MassLayout::Products, stores(&products, 0).collect());
    }
    let n = lowered.forcing.len();
    let zero = ir.num(0.0);
    let mut tasks = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let v = lowered.mass[i.max(j)][i.min(j)].unwrap_or(zero);
            tasks.push(Task::Store {
                slot: i * n + j,
                value: v,
            });
        }
    }
    (MassLayout::Entries, tasks)
}
