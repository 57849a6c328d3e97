//! Which states and inputs each state derivative and each output depends
//! on: reachability in the optimized program's IR, from the values the
//! derivatives and outputs blocks store down to the leaves they read.
//!
//! This is the exact structural sparsity of the generated code (what FMI
//! calls the `ModelStructure`): a value depends on a state or an input when
//! the operations that compute it read that leaf, through any chain of
//! intermediate values, subroutine arguments (`Leaf::SubOut`) and
//! accelerations read by outputs (`Leaf::Accel`). For a model with position
//! constraints the dependent coordinates are no free variables: they are
//! solved from the constraints, so a value that reads one depends on every
//! independent coordinate that the constraint solved for it reads
//! (transitively through the other dependent coordinates its residual
//! reads). What user code keeps between calls is not seen; only its
//! arguments are. It also gives the parameters each state's initial
//! value reads.

use super::ir::{Leaf, Nid, Op};
use super::program::{BlockKind, Program};
use super::schedule::Stmt;
use std::collections::BTreeSet;

/// What one value depends on: state-vector positions (independent states
/// only), input indices and parameter indices, each sorted.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Depends {
    /// Positions in the state vector of the states it reads.
    pub states: Vec<usize>,
    /// Indices of the inputs it reads.
    pub inputs: Vec<usize>,
    /// Indices of the parameters it reads (directly or through the
    /// constants computed from them and the constraints solved for the
    /// dependent coordinates it reads).
    pub parameters: Vec<usize>,
}

/// The dependencies of a model's state derivatives and outputs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Dependencies {
    /// Slot `i`: what `dx[i]/dt` depends on (every state slot, the
    /// dependent coordinates included).
    pub derivatives: Vec<Depends>,
    /// Output `k`: what it depends on.
    pub outputs: Vec<Depends>,
    /// The state-vector positions of the dependent coordinates (solved
    /// from position constraints; they appear in no `Depends`).
    pub dependent: Vec<usize>,
    /// Slot `i`: the parameters the initial value of state `i` reads
    /// (sorted; empty for a value written as a number).
    pub initial: Vec<Vec<usize>>,
}

/// The leaves a value reads, by state and input.
#[derive(Clone, Debug, Default)]
struct Reads {
    states: BTreeSet<usize>,
    inputs: BTreeSet<usize>,
    parameters: BTreeSet<usize>,
    accels: BTreeSet<usize>,
}

impl Dependencies {
    /// The dependencies of every derivative and output of `program`.
    pub fn of(program: &Program) -> Dependencies {
        let nq = program.states().coordinates.len();
        let closures = &program.interface.closures;
        let dependent: Vec<usize> = closures.iter().map(|c| c.slot).collect();
        let residuals = program
            .try_block(BlockKind::Assembly)
            .map(|b| stored(&b.stmts, closures.len()..2 * closures.len()))
            .unwrap_or_default();
        let solved = solved_coordinates(program, &dependent, &residuals);
        let resolve = |reads: Reads| -> Depends {
            let mut states = BTreeSet::new();
            let mut parameters = reads.parameters;
            for s in reads.states {
                match dependent.iter().position(|&d| d == s) {
                    Some(j) => {
                        states.extend(&solved[j].states);
                        parameters.extend(&solved[j].parameters);
                    }
                    None => {
                        states.insert(s);
                    }
                }
            }
            Depends {
                states: states.into_iter().collect(),
                inputs: reads.inputs.into_iter().collect(),
                parameters: parameters.into_iter().collect(),
            }
        };
        let n = program.slots(BlockKind::Derivatives);
        let derivative_reads: Vec<Reads> =
            stored(&program.block(BlockKind::Derivatives).stmts, 0..n)
                .into_iter()
                .map(|v| reads(program, v))
                .collect();
        let ny = program.interface.model.outputs.len();
        let outputs = stored(&program.block(BlockKind::Outputs).stmts, 0..ny)
            .into_iter()
            .map(|v| {
                let mut r = reads(program, v);
                for k in std::mem::take(&mut r.accels) {
                    let du = &derivative_reads[nq + k];
                    r.states.extend(&du.states);
                    r.inputs.extend(&du.inputs);
                    r.parameters.extend(&du.parameters);
                }
                resolve(r)
            })
            .collect();
        let initial = stored(&program.block(BlockKind::Initial).stmts, 0..n)
            .into_iter()
            .map(|v| reads(program, v).parameters.into_iter().collect())
            .collect();
        Dependencies {
            derivatives: derivative_reads.into_iter().map(resolve).collect(),
            outputs,
            dependent,
            initial,
        }
    }
}

/// The values a block stores into `slots`, in slot order (`None` where a
/// slot is never written).
fn stored(stmts: &[Stmt], slots: std::ops::Range<usize>) -> Vec<Option<Nid>> {
    let mut values = vec![None; slots.len()];
    for s in stmts {
        if let Stmt::Store { slot, value } = s
            && slots.contains(slot)
        {
            values[slot - slots.start] = Some(*value);
        }
    }
    values
}

/// The states, inputs and accelerations `roots` read, through subroutine
/// arguments.
fn reads(program: &Program, root: Option<Nid>) -> Reads {
    let ir = &program.ir;
    let mut out = Reads::default();
    let mut seen = vec![false; ir.len()];
    let mut stack: Vec<Nid> = root.into_iter().collect();
    while let Some(n) = stack.pop() {
        if n.index() >= ir.len() || std::mem::replace(&mut seen[n.index()], true) {
            continue;
        }
        match ir.op(n) {
            Op::Leaf(Leaf::State(i)) => {
                out.states.insert(*i);
            }
            Op::Leaf(Leaf::Input(i)) => {
                out.inputs.insert(*i);
            }
            Op::Leaf(Leaf::Param(i)) => {
                out.parameters.insert(*i);
            }
            Op::Leaf(Leaf::Accel(k)) => {
                out.accels.insert(*k);
            }
            Op::Leaf(Leaf::SubOut(s, _)) => {
                stack.extend(program.sub_args.get(*s).into_iter().flatten());
            }
            _ => stack.extend(ir.children(n)),
        }
    }
    out
}

/// For each dependent coordinate (closure order), the independent
/// coordinates and the parameters it is solved from: those its
/// constraint's residual reads, and those of every other dependent
/// coordinate the residual reads (to a fixed point).
fn solved_coordinates(
    program: &Program,
    dependent: &[usize],
    residuals: &[Option<Nid>],
) -> Vec<Reads> {
    let direct: Vec<Reads> = residuals.iter().map(|r| reads(program, *r)).collect();
    let mut solved: Vec<Reads> = direct
        .iter()
        .map(|r| Reads {
            states: r
                .states
                .iter()
                .filter(|q| !dependent.contains(q))
                .copied()
                .collect(),
            parameters: r.parameters.clone(),
            ..Reads::default()
        })
        .collect();
    loop {
        let mut changed = false;
        for j in 0..dependent.len() {
            for (i, d) in dependent.iter().enumerate() {
                if i != j && direct[j].states.contains(d) {
                    let (from, to) = (solved[i].clone(), &mut solved[j]);
                    let before = (to.states.len(), to.parameters.len());
                    to.states.extend(from.states);
                    to.parameters.extend(from.parameters);
                    changed |= before != (to.states.len(), to.parameters.len());
                }
            }
        }
        if !changed {
            return solved;
        }
    }
}
