//! The equation program of a model: the blocks generated code runs
//! (constants once per parameter set; derivatives, with the unrolled solve
//! of the mass matrix; outputs; the mass matrix and forcing alone; the
//! initial state), all over one shared IR.

use super::ir::{Ir, Leaf, Nid, Op};
use super::lower::{Lowering, UnboundSymbol};
use super::schedule::{Block, Options, Task, schedule};
use super::solve::ldlt_solve;
use crate::expr::{ExprId, Func, SymId};
use crate::mech::Equations;
use crate::model::ResolvedModel;
use rustc_hash::{FxHashMap, FxHashSet};

/// The scheduled program of a model.
#[derive(Clone, Debug)]
pub struct Program {
    /// All operations.
    pub ir: Ir,
    /// Number of generalized coordinates (= speeds).
    pub n: usize,
    /// Number of added state variables.
    pub n_extra: usize,
    /// Names of the states: coordinates, speeds, added states.
    pub state_names: Vec<String>,
    /// Units of the states.
    pub state_units: Vec<String>,
    /// Names of the parameters (declaration order).
    pub parameter_names: Vec<String>,
    /// Names of the inputs.
    pub input_names: Vec<String>,
    /// Names of user functions, by `UserFnId` index.
    pub user_fn_names: Vec<String>,
    /// User subroutines: name and output names.
    pub subroutines: Vec<(String, Vec<String>)>,
    /// Output names.
    pub output_names: Vec<String>,
    /// dx/dt: slots `0..n` dq/dt, `n..2n` du/dt, then added states.
    pub derivatives: Block,
    /// Outputs; reads `Leaf::Accel` if it needs du/dt.
    pub outputs: Block,
    /// `true` if the outputs need du/dt (generated code computes the
    /// derivatives first).
    pub outputs_need_derivatives: bool,
    /// The mass matrix, slot `i*n + j`.
    pub mass_matrix: Block,
    /// The forcing vector.
    pub forcing: Block,
    /// Constants computed once per parameter set: slot `k` is `hoisted[k]`.
    pub constants: Block,
    /// The constant nodes the other blocks read.
    pub hoisted: Vec<Nid>,
    /// Initial state from the parameters.
    pub initial: Block,
    /// Arguments of each subroutine (declaration order).
    pub sub_args: Vec<Vec<Nid>>,
}

/// Why a program could not be built.
#[derive(Clone, Debug, PartialEq)]
pub enum ProgramError {
    /// An expression uses a symbol that has no value at run time.
    Unbound(String),
}

impl std::fmt::Display for ProgramError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ProgramError::Unbound(n) => write!(f, "`{n}` has no value in the generated program"),
        }
    }
}

impl From<UnboundSymbol> for ProgramError {
    fn from(u: UnboundSymbol) -> Self {
        ProgramError::Unbound(u.0)
    }
}

/// Builds the program of a resolved model from its equations.
pub fn build(model: &mut ResolvedModel, eqs: &Equations) -> Result<Program, ProgramError> {
    let sys = &mut model.system;
    let n = eqs.coordinates.len();
    let n_extra = eqs.states.len();
    let mut ir = Ir::new();

    // Leaves.
    let mut leaves: FxHashMap<SymId, Nid> = FxHashMap::default();
    let params: Vec<SymId> = sys.parameters().to_vec();
    for (i, s) in params.iter().enumerate() {
        leaves.insert(*s, ir.leaf(Leaf::Param(i)));
    }
    for (i, s) in eqs
        .coordinates
        .iter()
        .chain(&eqs.speeds)
        .chain(&eqs.states)
        .enumerate()
    {
        leaves.insert(*s, ir.leaf(Leaf::State(i)));
    }
    let inputs: Vec<SymId> = sys.inputs().to_vec();
    for (i, s) in inputs.iter().enumerate() {
        leaves.insert(*s, ir.leaf(Leaf::Input(i)));
    }
    leaves.insert(sys.time(), ir.leaf(Leaf::Time));
    let subs = sys.subroutines().to_vec();
    for (k, sub) in subs.iter().enumerate() {
        for (j, o) in sub.outputs.iter().enumerate() {
            leaves.insert(*o, ir.leaf(Leaf::SubOut(k, j)));
        }
    }

    let mut user_calls: Vec<(ExprId, Nid)> = Vec::new();

    // Derivatives: kinematics, mass matrix, forcing, solve.
    let (kin, mass, forcing, sub_args) = {
        let mut lw = Lowering::new(&mut sys.arena, &mut ir, &leaves);
        let kin: Vec<Nid> = eqs
            .kinematics
            .iter()
            .map(|e| lw.lower(*e))
            .collect::<Result<_, _>>()?;
        let mut mass: Vec<Vec<Option<Nid>>> = vec![vec![None; n]; n];
        for i in 0..n {
            for j in 0..=i {
                let e = eqs.mass_matrix[i][j];
                if !lw.is_zero(e) {
                    mass[i][j] = Some(lw.lower(e)?);
                }
            }
        }
        let forcing: Vec<Nid> = eqs
            .forcing
            .iter()
            .map(|e| lw.lower(*e))
            .collect::<Result<_, _>>()?;
        let sub_args: Vec<Vec<Nid>> = subs
            .iter()
            .map(|s| {
                s.args
                    .iter()
                    .map(|a| lw.lower(*a))
                    .collect::<Result<Vec<_>, _>>()
            })
            .collect::<Result<_, _>>()?;
        user_calls.extend(lw.user_calls());
        (kin, mass, forcing, sub_args)
    };
    let solve = ldlt_solve(&mut ir, &mass, &forcing);
    let mut with_du = leaves.clone();
    for (i, s) in eqs.speed_rates.iter().enumerate() {
        with_du.insert(*s, solve.du[i]);
    }
    let extra: Vec<Nid> = {
        let mut lw = Lowering::new(&mut sys.arena, &mut ir, &with_du);
        let v: Vec<Nid> = eqs
            .state_derivatives
            .iter()
            .map(|e| lw.lower(*e))
            .collect::<Result<_, _>>()?;
        user_calls.extend(lw.user_calls());
        v
    };

    // Outputs (du/dt read from the derivatives).
    let mut with_accel = leaves.clone();
    for (i, s) in eqs.speed_rates.iter().enumerate() {
        with_accel.insert(*s, ir.leaf(Leaf::Accel(i)));
    }
    let outputs_exprs: Vec<ExprId> = sys.outputs().iter().map(|o| o.expr).collect();
    let outs: Vec<Nid> = {
        let mut lw = Lowering::new(&mut sys.arena, &mut ir, &with_accel);
        let v: Vec<Nid> = outputs_exprs
            .iter()
            .map(|e| lw.lower(*e))
            .collect::<Result<_, _>>()?;
        user_calls.extend(lw.user_calls());
        v
    };

    // Initial state.
    let mut initial_exprs: Vec<ExprId> = sys.coordinates().iter().map(|c| c.initial_q).collect();
    initial_exprs.extend(sys.coordinates().iter().map(|c| c.initial_u));
    initial_exprs.extend(sys.states().iter().map(|s| s.initial));
    let initial: Vec<Nid> = {
        let mut lw = Lowering::new(&mut sys.arena, &mut ir, &leaves);
        initial_exprs
            .iter()
            .map(|e| lw.lower(*e))
            .collect::<Result<_, _>>()?
    };

    // User-function calls in model order (their creation order).
    user_calls.sort();
    let mut call_order: Vec<Nid> = Vec::new();
    for (_, nid) in user_calls {
        if !call_order.contains(&nid) {
            call_order.push(nid);
        }
    }

    // Names.
    let state_names: Vec<String> = eqs
        .coordinates
        .iter()
        .chain(&eqs.speeds)
        .chain(&eqs.states)
        .map(|s| sys.arena.symbol(*s).name.clone())
        .collect();
    let state_units: Vec<String> = eqs
        .coordinates
        .iter()
        .chain(&eqs.speeds)
        .chain(&eqs.states)
        .map(|s| sys.arena.symbol(*s).unit.clone().unwrap_or_default())
        .collect();
    let mut reserved: FxHashSet<String> = state_names.iter().cloned().collect();
    for s in &inputs {
        reserved.insert(sys.arena.symbol(*s).name.clone());
    }
    for sub in &subs {
        for o in &sub.outputs {
            reserved.insert(sys.arena.symbol(*o).name.clone());
        }
    }
    for r in [
        "t", "x", "dx", "y", "p", "c", "m", "f", "e", "self", "externs", "inputs",
    ] {
        reserved.insert(r.to_string());
    }

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
            hint(nid, format!("{pre}_{}", state_names[*i]));
        }
    }
    for i in 0..n {
        for j in 0..=i {
            if let Some(m) = mass[i][j] {
                hint(m, format!("m{}_{}", i + 1, j + 1));
            }
        }
        hint(forcing[i], format!("f{}", i + 1));
        hint(solve.du[i], format!("{}_dot", state_names[n + i]));
        hint(kin[i], format!("{}_dot", state_names[i]));
    }
    for (h, nid) in &solve.hints {
        hint(*nid, h.clone());
    }

    let opts = |hoist: bool| Options {
        hoist_constants: hoist,
        hints: &hints,
        call_order: &call_order,
        sub_args: &sub_args,
        reserved: &reserved,
    };

    let mut tasks: Vec<Task> = kin
        .iter()
        .enumerate()
        .map(|(i, v)| Task::Store { slot: i, value: *v })
        .collect();
    for (pivot, speed) in &solve.pivots {
        tasks.push(Task::Check {
            pivot: *pivot,
            speed: *speed,
        });
    }
    for (i, v) in solve.du.iter().enumerate() {
        tasks.push(Task::Store {
            slot: n + i,
            value: *v,
        });
    }
    for (i, v) in extra.iter().enumerate() {
        tasks.push(Task::Store {
            slot: 2 * n + i,
            value: *v,
        });
    }
    let derivatives = schedule(&ir, &tasks, &opts(true));

    let mut out_reserved = reserved.clone();
    for i in 0..n {
        out_reserved.insert(format!("{}_dot", state_names[n + i]));
    }
    let out_opts = Options {
        hoist_constants: true,
        hints: &hints,
        call_order: &call_order,
        sub_args: &sub_args,
        reserved: &out_reserved,
    };
    let out_tasks: Vec<Task> = outs
        .iter()
        .enumerate()
        .map(|(i, v)| Task::Store { slot: i, value: *v })
        .collect();
    let outputs = schedule(&ir, &out_tasks, &out_opts);
    let outputs_need_derivatives = outputs.leaves.iter().any(|l| matches!(l, Leaf::Accel(_)));

    let zero = ir.num(0.0);
    let mut mm_tasks = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let v = mass[i.max(j)][i.min(j)].unwrap_or(zero);
            mm_tasks.push(Task::Store {
                slot: i * n + j,
                value: v,
            });
        }
    }
    let mass_matrix = schedule(&ir, &mm_tasks, &opts(true));
    let f_tasks: Vec<Task> = forcing
        .iter()
        .enumerate()
        .map(|(i, v)| Task::Store { slot: i, value: *v })
        .collect();
    let forcing_block = schedule(&ir, &f_tasks, &opts(true));

    let mut hoisted: Vec<Nid> = derivatives
        .hoisted
        .iter()
        .chain(&outputs.hoisted)
        .chain(&mass_matrix.hoisted)
        .chain(&forcing_block.hoisted)
        .copied()
        .collect();
    hoisted.sort();
    hoisted.dedup();
    let c_tasks: Vec<Task> = hoisted
        .iter()
        .enumerate()
        .map(|(k, v)| Task::Store { slot: k, value: *v })
        .collect();
    let constants = schedule(&ir, &c_tasks, &opts(false));
    let i_tasks: Vec<Task> = initial
        .iter()
        .enumerate()
        .map(|(k, v)| Task::Store { slot: k, value: *v })
        .collect();
    let initial_block = schedule(&ir, &i_tasks, &opts(false));

    Ok(Program {
        n,
        n_extra,
        state_names,
        state_units,
        parameter_names: params
            .iter()
            .map(|s| sys.arena.symbol(*s).name.clone())
            .collect(),
        input_names: inputs
            .iter()
            .map(|s| sys.arena.symbol(*s).name.clone())
            .collect(),
        user_fn_names: sys.arena.user_fns().map(|(_, f)| f.name.clone()).collect(),
        subroutines: subs
            .iter()
            .map(|s| {
                (
                    s.name.clone(),
                    s.outputs
                        .iter()
                        .map(|o| sys.arena.symbol(*o).name.clone())
                        .collect(),
                )
            })
            .collect(),
        output_names: sys.outputs().iter().map(|o| o.name.clone()).collect(),
        derivatives,
        outputs,
        outputs_need_derivatives,
        mass_matrix,
        forcing: forcing_block,
        constants,
        hoisted,
        initial: initial_block,
        sub_args,
        ir,
    })
}
