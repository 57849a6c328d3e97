//! An interpreter of scheduled programs: runs the statements of a block the
//! way generated code does, so the optimizer can be checked against the
//! symbolic equations without compiling anything.

use crate::expr::Func;
use crate::opt::ir::{Leaf, Nid, Op};
use crate::opt::program::{BlockKind, MassLayout, Program};
use crate::opt::schedule::{Guard, Stmt};
use rustc_hash::FxHashMap;

/// A pivot that failed its guard: the guard says which (the mass matrix's
/// pivot of a speed, or a constraint solve's pivot of a constraint).
#[derive(Clone, Debug, PartialEq)]
pub struct SolveError {
    /// The failed test.
    pub guard: Guard,
}

/// The user code a program calls, for the interpreter: user function
/// `f` at `args` and user subroutine `s` at `args`, by index.
pub struct UserCalls<'u> {
    /// `function(f, args)`: the value of user function `f`.
    pub function: &'u mut dyn FnMut(usize, &[f64]) -> f64,
    /// `subroutine(s, args)`: the outputs of user subroutine `s`.
    pub subroutine: &'u mut dyn FnMut(usize, &[f64]) -> Vec<f64>,
}

/// Where a block is evaluated: the time, the state, the inputs and the
/// discrete variables.
#[derive(Clone, Copy, Debug, Default)]
pub struct At<'x> {
    /// The time.
    pub t: f64,
    /// The state.
    pub x: &'x [f64],
    /// The inputs (declaration order).
    pub inputs: &'x [f64],
    /// The discrete variables (declaration order); those past its end (all
    /// of them for an empty slice) at their initial values.
    pub discrete: &'x [f64],
}

/// Runs a program's blocks with given parameter values.
pub struct Interpreter<'a> {
    prog: &'a Program,
    params: Vec<f64>,
    constants: Vec<f64>,
}

struct Env<'b> {
    values: FxHashMap<Nid, f64>,
    leaves: FxHashMap<Leaf, f64>,
    constants: Option<&'b [f64]>,
    hoisted: &'b [Nid],
}

impl<'a> Interpreter<'a> {
    /// Computes the constants block for `params` (declaration order).
    pub fn new(prog: &'a Program, params: &[f64]) -> Interpreter<'a> {
        let mut it = Interpreter {
            prog,
            params: params.to_vec(),
            constants: Vec::new(),
        };
        it.constants = it.run_alone(BlockKind::Constants);
        it
    }

    /// The initial state.
    pub fn initial_state(&self) -> Vec<f64> {
        self.run_alone(BlockKind::Initial)
    }

    /// dx/dt at `at`.
    pub fn derivatives(
        &self,
        at: At<'_>,
        user: &mut UserCalls<'_>,
    ) -> Result<Vec<f64>, SolveError> {
        self.block_at(BlockKind::Derivatives, at, user)
    }

    /// The slots of a block that reads the state and not the
    /// accelerations (derivatives, forcing, assembly, linearize, the
    /// entries of the mass matrix) at `at`; empty if the program has no
    /// such block.
    pub fn block_at(
        &self,
        kind: BlockKind,
        at: At<'_>,
        user: &mut UserCalls<'_>,
    ) -> Result<Vec<f64>, SolveError> {
        match self.prog.try_block(kind) {
            Some(_) => self.run(kind, at, &[], user),
            None => Ok(Vec::new()),
        }
    }

    /// The outputs (computing the derivatives first if they need them).
    pub fn outputs(&self, at: At<'_>, user: &mut UserCalls<'_>) -> Result<Vec<f64>, SolveError> {
        let accel = match self.prog.outputs_need_derivatives {
            true => {
                let first = self.prog.states().speed_slot(0);
                let rates = first..first + self.prog.n();
                self.derivatives(at, user)?[rates].to_vec()
            }
            false => Vec::new(),
        };
        self.run(BlockKind::Outputs, at, &accel, user)
    }

    /// The mass matrix (row-major) and the forcing vector.
    pub fn mass_matrix_and_forcing(
        &self,
        at: At<'_>,
        user: &mut UserCalls<'_>,
    ) -> (Vec<f64>, Vec<f64>) {
        let m = match self.prog.mass_layout {
            MassLayout::Entries => self.block_at(BlockKind::MassMatrix, at, user),
            MassLayout::Products => self.mass_by_columns(at, user),
        };
        let f = self.block_at(BlockKind::Forcing, at, user);
        (m.unwrap_or_default(), f.unwrap_or_default())
    }

    /// The mass matrix from the products `M e_j`: column `j` is row `j`
    /// (`M` is symmetric), as generated code computes it.
    fn mass_by_columns(
        &self,
        at: At<'_>,
        user: &mut UserCalls<'_>,
    ) -> Result<Vec<f64>, SolveError> {
        let n = self.prog.n();
        let mut m = Vec::with_capacity(n * n);
        for j in 0..n {
            let unit: Vec<f64> = (0..n).map(|k| if k == j { 1.0 } else { 0.0 }).collect();
            m.extend(self.run(BlockKind::MassMatrix, at, &unit, user)?);
        }
        Ok(m)
    }

    /// A block that reads the parameters only.
    fn run_alone(&self, kind: BlockKind) -> Vec<f64> {
        let mut function = |_: usize, _: &[f64]| f64::NAN;
        let mut subroutine = |_: usize, _: &[f64]| Vec::new();
        let mut user = UserCalls {
            function: &mut function,
            subroutine: &mut subroutine,
        };
        self.run(kind, At::default(), &[], &mut user)
            .unwrap_or_default()
    }

    /// Runs the statements of a block at `at` with accelerations `accel`
    /// (read by the outputs and the products `M du/dt`).
    fn run(
        &self,
        kind: BlockKind,
        at: At<'_>,
        accel: &[f64],
        user: &mut UserCalls<'_>,
    ) -> Result<Vec<f64>, SolveError> {
        let mut env = Env {
            values: FxHashMap::default(),
            leaves: FxHashMap::default(),
            constants: kind.reads_constants().then_some(self.constants.as_slice()),
            hoisted: &self.prog.hoisted,
        };
        env.leaves.insert(Leaf::Time, at.t);
        for (i, d) in self.prog.interface.model.discrete.iter().enumerate() {
            let value = at.discrete.get(i).copied().unwrap_or(d.default);
            env.leaves.insert(Leaf::Discrete(i), value);
        }
        let values = [
            (&self.params[..], Leaf::Param as fn(usize) -> Leaf),
            (at.x, Leaf::State),
            (at.inputs, Leaf::Input),
            (accel, Leaf::Accel),
        ];
        for (vals, leaf) in values {
            for (i, v) in vals.iter().enumerate() {
                env.leaves.insert(leaf(i), *v);
            }
        }
        let block = self.prog.block(kind);
        if !block.common.is_empty() {
            let shared = self.run(BlockKind::Common, at, accel, user)?;
            env.values
                .extend(self.prog.common.iter().copied().zip(shared));
        }
        let mut out = vec![0.0; self.prog.slots(kind)];
        for st in &block.stmts {
            match st {
                Stmt::Let(n) => {
                    let v = self.eval(*n, &mut env, user.function);
                    env.values.insert(*n, v);
                }
                Stmt::SinCos { sin, cos } => {
                    for n in [*sin, *cos] {
                        let v = self.eval(n, &mut env, user.function);
                        env.values.insert(n, v);
                    }
                }
                Stmt::CallSub(k) => {
                    let args: Vec<f64> = self.prog.sub_args[*k]
                        .iter()
                        .map(|a| self.eval(*a, &mut env, user.function))
                        .collect();
                    let r = (user.subroutine)(*k, &args);
                    for (j, v) in r.iter().enumerate() {
                        env.leaves.insert(Leaf::SubOut(*k, j), *v);
                    }
                }
                Stmt::Check { pivot, guard } => {
                    let v = self.eval(*pivot, &mut env, user.function);
                    let pass = match guard {
                        Guard::Positive { .. } => v > 0.0,
                        Guard::Regular { .. } => v.is_finite() && v.abs() > 16.0 * f64::EPSILON,
                    };
                    if !pass {
                        return Err(SolveError { guard: *guard });
                    }
                }
                Stmt::Store { slot, value } => {
                    let v = self.eval(*value, &mut env, user.function);
                    if let Some(o) = out.get_mut(*slot) {
                        *o = v;
                    }
                }
            }
        }
        Ok(out)
    }

    fn eval(&self, n: Nid, env: &mut Env<'_>, user: &mut dyn FnMut(usize, &[f64]) -> f64) -> f64 {
        if let Some(v) = env.values.get(&n) {
            return *v;
        }
        let ir = &self.prog.ir;
        if let Some(c) = env.constants
            && ir.is_constant(n)
            && !matches!(ir.op(n), Op::Num(_) | Op::Leaf(_))
            && let Ok(k) = env.hoisted.binary_search(&n)
        {
            return c[k];
        }

        match ir.op(n).clone() {
            Op::Num(b) => f64::from_bits(b),
            Op::Leaf(l) => env.leaves.get(&l).copied().unwrap_or(f64::NAN),
            Op::Sum { pos, neg } => {
                let p: f64 = pos.iter().map(|k| self.eval(*k, env, user)).sum();
                let m: f64 = neg.iter().map(|k| self.eval(*k, env, user)).sum();
                p - m
            }
            Op::Mul(a, b) => self.eval(a, env, user) * self.eval(b, env, user),
            Op::Div(a, b) => self.eval(a, env, user) / self.eval(b, env, user),
            Op::Neg(a) => -self.eval(a, env, user),
            Op::Powi(a, k) => self.eval(a, env, user).powi(k),
            Op::Sqrt(a) => self.eval(a, env, user).sqrt(),
            Op::Powf(a, b) => self.eval(a, env, user).powf(self.eval(b, env, user)),
            Op::Call(f, args) => {
                let xs: Vec<f64> = args.iter().map(|k| self.eval(*k, env, user)).collect();
                match f {
                    Func::User(u) => user(u.index(), &xs),
                    builtin => builtin.eval_builtin(&xs).unwrap_or(f64::NAN),
                }
            }
        }
    }
}
