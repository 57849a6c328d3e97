//! The one lowering context every lowering writes through: what it lowers
//! (`Given`), the arena, the IR being built, the environment (the IR value
//! of each symbol), the memo of what is lowered under it, and the user
//! calls met so far; its errors name the item whose expression failed.
//! It lowers the pieces both lowerings share (mass matrix, forcing,
//! subroutine arguments, added states, outputs, initial state).

use super::Given;
use crate::expr::{Arena, ExprId, Func, Node, SymId};
use crate::mech::{Equations, ItemRef};
use crate::opt::error::ProgramError;
use crate::opt::ir::{Ir, Leaf, Nid};
use crate::opt::linearize::tangent::with_accelerations;
use rustc_hash::FxHashMap;

/// A symbol with no value in the program (e.g. a free symbol).
pub(super) struct UnboundSymbol(pub String);

/// The IR values of symbols.
pub(crate) type Env = FxHashMap<SymId, Nid>;

/// Lowers the expressions of one model into one IR, memoized per
/// expression under the current environment.
pub(crate) struct Lowering<'a> {
    /// What is lowered.
    pub given: Given<'a>,
    pub(super) arena: &'a mut Arena,
    /// The IR being built (for operations beside lowering).
    pub ir: Ir,
    pub(super) env: Env,
    pub(super) memo: FxHashMap<ExprId, Nid>,
    /// User-function calls lowered under earlier environments.
    calls: Vec<(ExprId, Nid)>,
    /// The environment of the state (what events are lowered under).
    base: Env,
}

impl<'a> Lowering<'a> {
    /// A new IR whose leaves are every symbol with a value at run time
    /// (parameters, the state: the coordinates but the prescribed, the
    /// independent speeds and the extra states; inputs, time, subroutine
    /// outputs), and the prescribed coordinates and speeds as functions of
    /// time.
    pub fn start(arena: &'a mut Arena, given: Given<'a>) -> Result<Self, ProgramError> {
        let (eqs, declared, split) = (given.eqs, given.declared, given.split);
        let mut ir = Ir::new();
        let mut env = Env::default();
        for (i, s) in declared.parameters.iter().enumerate() {
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
        for (i, s) in declared.inputs.iter().enumerate() {
            env.insert(*s, ir.leaf(Leaf::Input(i)));
        }
        for (i, s) in declared.discrete.iter().enumerate() {
            env.insert(*s, ir.leaf(Leaf::Discrete(i)));
        }
        env.insert(declared.time, ir.leaf(Leaf::Time));
        for (k, sub) in declared.subroutines.iter().enumerate() {
            for (j, o) in sub.outputs.iter().enumerate() {
                env.insert(*o, ir.leaf(Leaf::SubOut(k, j)));
            }
        }
        let mut lw = Lowering {
            given,
            arena,
            ir,
            env,
            memo: FxHashMap::default(),
            calls: Vec::new(),
            base: Env::default(),
        };
        let mut known = Vec::new();
        for (i, p) in eqs.prescribed.iter().enumerate() {
            let value = lw.one(p.value, ItemRef::Motion(i))?;
            let rate = lw.one(p.rate, ItemRef::Motion(i))?;
            known.push((eqs.coordinates[p.speed], value));
            known.push((eqs.speeds[p.speed], rate));
        }
        lw.extend(known);
        lw.base = lw.env.clone();
        Ok(lw)
    }

    /// Lowers from now on under the environment of the state alone (the
    /// time, the state, inputs, parameters and discrete variables, the
    /// prescribed motions; no solved value).
    pub fn bind_state(&mut self) {
        let base = self.base.clone();
        self.bind(base);
    }

    /// The current environment.
    pub fn env(&self) -> &Env {
        &self.env
    }

    /// Lowers from now on under `env`.
    pub fn bind(&mut self, env: Env) {
        self.forget();
        self.env = env;
    }

    /// Lowers from now on with `values` bound too.
    pub fn extend(&mut self, values: impl IntoIterator<Item = (SymId, Nid)>) {
        let mut values = values.into_iter().peekable();
        if values.peek().is_some() {
            self.forget();
            self.env.extend(values);
        }
    }

    /// Empties the memo (it holds values under the old environment),
    /// keeping its user calls.
    fn forget(&mut self) {
        let arena = &*self.arena;
        self.calls.extend(
            self.memo
                .drain()
                .filter(|(e, _)| matches!(arena.node(*e), Node::Func(Func::User(_), _))),
        );
    }

    /// `true` if `e` is exactly zero.
    pub fn is_zero(&self, e: ExprId) -> bool {
        self.arena.is_zero(e)
    }

    /// The name of a symbol.
    pub fn name(&self, s: SymId) -> &str {
        &self.arena.symbol(s).name
    }

    /// The IR node computing `e`, an expression of `item`.
    pub fn one(&mut self, e: ExprId, item: ItemRef) -> Result<Nid, ProgramError> {
        self.lower(e)
            .map_err(|UnboundSymbol(name)| ProgramError::Unbound { name, item })
    }

    /// The IR nodes computing `exprs`, expression `k` of `item(k)`.
    pub fn all(
        &mut self,
        exprs: &[ExprId],
        item: impl Fn(usize) -> ItemRef,
    ) -> Result<Vec<Nid>, ProgramError> {
        exprs
            .iter()
            .enumerate()
            .map(|(k, e)| self.one(*e, item(k)))
            .collect()
    }

    /// The lower triangle of the mass matrix (`None`: structurally zero),
    /// each row an expression of its speed's body.
    pub fn mass_matrix(&mut self) -> Result<Vec<Vec<Option<Nid>>>, ProgramError> {
        let g = self.given;
        let m = &g.eqs.mass_matrix;
        let mut mass: Vec<Vec<Option<Nid>>> = vec![vec![None; m.len()]; m.len()];
        for i in 0..m.len() {
            for j in 0..=i {
                if !self.is_zero(m[i][j]) {
                    mass[i][j] = Some(self.one(m[i][j], g.declared.coordinate_items[i])?);
                }
            }
        }
        Ok(mass)
    }

    /// The forcing vector (each entry an expression of its speed's body).
    pub fn forcing(&mut self) -> Result<Vec<Nid>, ProgramError> {
        let g = self.given;
        self.all(&g.eqs.forcing, |k| g.declared.coordinate_items[k])
    }

    /// The arguments of each subroutine.
    pub fn sub_args(&mut self) -> Result<Vec<Vec<Nid>>, ProgramError> {
        let subs = &self.given.declared.subroutines;
        let mut args = Vec::with_capacity(subs.len());
        for (k, s) in subs.iter().enumerate() {
            args.push(self.all(&s.args, |_| ItemRef::Subroutine(k))?);
        }
        Ok(args)
    }

    /// The added states' derivatives lowered under `rates` (the speeds'
    /// rates bound: the form the linearization differentiates), and the
    /// same with the solve's accelerations `du` in place of `Leaf::Accel`.
    pub fn extra(&mut self, rates: Env, du: &[Nid]) -> Result<(Vec<Nid>, Vec<Nid>), ProgramError> {
        let eqs = self.given.eqs;
        self.bind(rates);
        let in_rates = self.all(&eqs.state_derivatives, |k| ItemRef::State(eqs.states[k]))?;
        let extra = with_accelerations(&mut self.ir, &in_rates, du);
        Ok((extra, in_rates))
    }

    /// The model's outputs, under the environment bound.
    pub fn outputs(&mut self) -> Result<Vec<Nid>, ProgramError> {
        self.all(&self.given.declared.outputs, ItemRef::Output)
    }

    /// The initial state, from the parameters alone: the state's
    /// coordinates and independent speeds and the extra states (each an
    /// expression of its body or state).
    pub fn initial(&mut self) -> Result<Vec<Nid>, ProgramError> {
        let Given {
            eqs,
            declared,
            split,
        } = self.given;
        let params: Env = declared
            .parameters
            .iter()
            .filter_map(|p| Some((*p, *self.env.get(p)?)))
            .collect();
        self.bind(params);
        let body = |k: usize| declared.coordinate_items[k];
        let mut out = Vec::new();
        for &k in &split.coordinates {
            out.push(self.one(declared.initial_q[k], body(k))?);
        }
        for &k in &split.free {
            out.push(self.one(declared.initial_u[k], body(k))?);
        }
        out.extend(self.all(&declared.initial_states, |k| ItemRef::State(eqs.states[k]))?);
        Ok(out)
    }

    /// The user-function calls lowered so far in model order (their
    /// creation order), once each.
    pub fn call_order(&mut self) -> Vec<Nid> {
        self.forget();
        let mut calls = self.calls.clone();
        calls.sort();
        let mut order: Vec<Nid> = Vec::new();
        for (_, nid) in calls {
            if !order.contains(&nid) {
                order.push(nid);
            }
        }
        order
    }

    /// The IR built.
    pub fn into_ir(self) -> Ir {
        self.ir
    }
}

/// `env` with the symbol of each speed's rate (`du_k/dt`) bound to
/// `rates[k]`.
pub(crate) fn binding_rates(env: &Env, eqs: &Equations, rates: &[Nid]) -> Env {
    let mut bound = env.clone();
    for (s, r) in eqs.speed_rates.iter().zip(rates) {
        bound.insert(*s, *r);
    }
    bound
}
