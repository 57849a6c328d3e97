//! An interpreter of scheduled programs: runs the statements of a block the
//! way generated code does, so the optimizer can be checked against the
//! symbolic equations without compiling anything.

use super::ir::{Leaf, Nid, Op};
use super::program::{BlockKind, Program};
use super::schedule::{Block, Stmt};
use crate::expr::Func;
use rustc_hash::FxHashMap;

/// A failed pivot of the mass matrix.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveError {
    /// The speed whose pivot was not positive.
    pub speed: usize,
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
        let mut user = |_: usize, _: &[f64]| f64::NAN;
        let mut sub = |_: usize, _: &[f64]| Vec::new();
        let c = it
            .run(
                prog.block(BlockKind::Constants),
                0.0,
                &[],
                &[],
                &[],
                prog.hoisted.len(),
                false,
                &mut user,
                &mut sub,
            )
            .unwrap_or_default();
        it.constants = c;
        it
    }

    /// The initial state.
    pub fn initial_state(&self) -> Vec<f64> {
        let mut user = |_: usize, _: &[f64]| f64::NAN;
        let mut sub = |_: usize, _: &[f64]| Vec::new();
        let len = self.prog.states().len();
        self.run(
            self.prog.block(BlockKind::Initial),
            0.0,
            &[],
            &[],
            &[],
            len,
            false,
            &mut user,
            &mut sub,
        )
        .unwrap_or_default()
    }

    /// dx/dt at `(t, x)` with `inputs`; `user(f, args)` evaluates user
    /// function `f`, `sub(s, args)` user subroutine `s`.
    pub fn derivatives(
        &self,
        t: f64,
        x: &[f64],
        inputs: &[f64],
        user: &mut dyn FnMut(usize, &[f64]) -> f64,
        sub: &mut dyn FnMut(usize, &[f64]) -> Vec<f64>,
    ) -> Result<Vec<f64>, SolveError> {
        let len = self.prog.states().len();
        self.run(
            self.prog.block(BlockKind::Derivatives),
            t,
            x,
            inputs,
            &[],
            len,
            true,
            user,
            sub,
        )
    }

    /// The outputs (computing the derivatives first if they need them).
    pub fn outputs(
        &self,
        t: f64,
        x: &[f64],
        inputs: &[f64],
        user: &mut dyn FnMut(usize, &[f64]) -> f64,
        sub: &mut dyn FnMut(usize, &[f64]) -> Vec<f64>,
    ) -> Result<Vec<f64>, SolveError> {
        let accel = if self.prog.outputs_need_derivatives {
            let dx = self.derivatives(t, x, inputs, user, sub)?;
            let n = self.prog.n();
            dx[n..2 * n].to_vec()
        } else {
            Vec::new()
        };
        let len = self.prog.interface.outputs.len();
        self.run(
            self.prog.block(BlockKind::Outputs),
            t,
            x,
            inputs,
            &accel,
            len,
            true,
            user,
            sub,
        )
    }

    /// The mass matrix (row-major) and the forcing vector.
    pub fn mass_matrix_and_forcing(
        &self,
        t: f64,
        x: &[f64],
        inputs: &[f64],
        user: &mut dyn FnMut(usize, &[f64]) -> f64,
        sub: &mut dyn FnMut(usize, &[f64]) -> Vec<f64>,
    ) -> (Vec<f64>, Vec<f64>) {
        let n = self.prog.n();
        let m = self
            .run(
                self.prog.block(BlockKind::MassMatrix),
                t,
                x,
                inputs,
                &[],
                n * n,
                true,
                user,
                sub,
            )
            .unwrap_or_default();
        let f = self
            .run(
                self.prog.block(BlockKind::Forcing),
                t,
                x,
                inputs,
                &[],
                n,
                true,
                user,
                sub,
            )
            .unwrap_or_default();
        (m, f)
    }

    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        block: &Block,
        t: f64,
        x: &[f64],
        inputs: &[f64],
        accel: &[f64],
        len: usize,
        hoisted: bool,
        user: &mut dyn FnMut(usize, &[f64]) -> f64,
        sub: &mut dyn FnMut(usize, &[f64]) -> Vec<f64>,
    ) -> Result<Vec<f64>, SolveError> {
        let mut env = Env {
            values: FxHashMap::default(),
            leaves: FxHashMap::default(),
            constants: hoisted.then_some(self.constants.as_slice()),
            hoisted: &self.prog.hoisted,
        };
        env.leaves.insert(Leaf::Time, t);
        for (i, v) in self.params.iter().enumerate() {
            env.leaves.insert(Leaf::Param(i), *v);
        }
        for (i, v) in x.iter().enumerate() {
            env.leaves.insert(Leaf::State(i), *v);
        }
        for (i, v) in inputs.iter().enumerate() {
            env.leaves.insert(Leaf::Input(i), *v);
        }
        for (i, v) in accel.iter().enumerate() {
            env.leaves.insert(Leaf::Accel(i), *v);
        }
        let mut out = vec![0.0; len];
        for st in &block.stmts {
            match st {
                Stmt::Let(n) => {
                    let v = self.eval(*n, &mut env, user);
                    env.values.insert(*n, v);
                }
                Stmt::SinCos { sin, cos } => {
                    for n in [*sin, *cos] {
                        let v = self.eval(n, &mut env, user);
                        env.values.insert(n, v);
                    }
                }
                Stmt::CallSub(k) => {
                    let args: Vec<f64> = self.prog.sub_args[*k]
                        .iter()
                        .map(|a| self.eval(*a, &mut env, user))
                        .collect();
                    let r = sub(*k, &args);
                    for (j, v) in r.iter().enumerate() {
                        env.leaves.insert(Leaf::SubOut(*k, j), *v);
                    }
                }
                Stmt::Check { pivot, speed } => {
                    let v = self.eval(*pivot, &mut env, user);
                    if v.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                        return Err(SolveError { speed: *speed });
                    }
                }
                Stmt::Store { slot, value } => {
                    let v = self.eval(*value, &mut env, user);
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
