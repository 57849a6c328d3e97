//! The program verifier (like cranelift's): checks the invariants every
//! pass after scheduling relies on. Run in debug builds after `build` and
//! by the tests on every model.
//!
//! 1. The IR is topologically ordered: children have smaller ids.
//! 2. The state layout has at most one speed per coordinate (fewer with
//!    constraints), and the assembly block solves for coordinates.
//! 3. Every block writes each of its slots exactly once, and only slots
//!    that exist.
//! 4. Every value is defined before it is read: a named node by an
//!    earlier `let` of its block, a hoisted constant by the constants
//!    block (whose slots cover every constant the other blocks read), a
//!    shared value by the common block (likewise), a subroutine's output
//!    by an earlier call of it.
//! 5. A block reads only what its function has: the constants block and
//!    the initial state read parameters only; only the outputs and the
//!    products `M du/dt` (`MassLayout::Products`) read the accelerations.
//! 6. Names a block binds are unique and do not shadow a state, input or
//!    subroutine output.

use crate::opt::ir::{Leaf, Nid, Op};
use crate::opt::program::{BlockKind, MassLayout, Program};
use crate::opt::schedule::{Block, Stmt};
use rustc_hash::FxHashSet;

impl Program {
    /// Checks the program's invariants (listed in this module's docs);
    /// `Err` says which one failed, where.
    pub fn verify(&self) -> Result<(), String> {
        for idx in 0..self.ir.len() {
            let n = Nid(idx as u32);
            if let Some(c) = self.ir.children(n).into_iter().find(|c| *c >= n) {
                return Err(format!("IR node {idx} reads node {}, not before it", c.0));
            }
        }
        let layout = self.states();
        if layout.coordinates.len() < layout.speeds.len() {
            return Err("the state layout has more speeds than coordinates".to_string());
        }
        let nq = layout.coordinates.len();
        if let Some(c) = self.interface.closures.iter().find(|c| c.slot >= nq) {
            return Err(format!(
                "assembly solves state {}, not a coordinate",
                c.slot
            ));
        }
        if self.hoisted.windows(2).any(|w| w[0] >= w[1]) {
            return Err("the hoisted constants are not sorted and unique".to_string());
        }
        if let Some(n) = self.hoisted.iter().find(|n| !self.ir.is_constant(**n)) {
            return Err(format!("hoisted node {} is not constant", n.0));
        }
        let common: rustc_hash::FxHashSet<Nid> = self.common.iter().copied().collect();
        for (kind, block) in &self.blocks {
            if let Some(n) = block.common.iter().find(|n| !common.contains(n)) {
                let what = kind.name();
                return Err(format!(
                    "block {what} reads node {} the common block lacks",
                    n.0
                ));
            }
        }
        for (kind, block) in &self.blocks {
            BlockCheck::new(self, *kind, block)
                .run()
                .map_err(|e| format!("block {}: {e}", kind.name()))?;
        }
        Ok(())
    }
}

/// The check of one block.
struct BlockCheck<'a> {
    prog: &'a Program,
    kind: BlockKind,
    block: &'a Block,
    defined: FxHashSet<Nid>,
    subs_called: FxHashSet<usize>,
}

impl<'a> BlockCheck<'a> {
    fn new(prog: &'a Program, kind: BlockKind, block: &'a Block) -> BlockCheck<'a> {
        BlockCheck {
            prog,
            kind,
            block,
            defined: FxHashSet::default(),
            subs_called: FxHashSet::default(),
        }
    }

    fn run(&mut self) -> Result<(), String> {
        self.names()?;
        let mut written = vec![false; self.prog.slots(self.kind)];
        for st in &self.block.stmts {
            match *st {
                Stmt::Let(n) => self.define(n)?,
                Stmt::SinCos { sin, cos } => {
                    self.define(sin)?;
                    self.define(cos)?;
                }
                Stmt::CallSub(k) => {
                    for a in &self.prog.sub_args[k] {
                        self.read(*a)?;
                    }
                    self.subs_called.insert(k);
                }
                Stmt::Check { pivot, .. } => self.read(pivot)?,
                Stmt::Store { slot, value } => {
                    match written.get_mut(slot) {
                        Some(w) if !*w => *w = true,
                        Some(_) => return Err(format!("slot {slot} is written twice")),
                        None => return Err(format!("slot {slot} does not exist")),
                    }
                    self.read(value)?;
                }
            }
        }
        match written.iter().position(|w| !w) {
            Some(slot) => Err(format!("slot {slot} is never written")),
            None => Ok(()),
        }
    }

    /// Rule 6.
    fn names(&self) -> Result<(), String> {
        let i = &self.prog.interface;
        let mut taken: FxHashSet<&str> = i.states.states().map(|s| s.name.as_str()).collect();
        taken.extend(i.model.inputs.iter().map(|x| x.name.as_str()));
        for sub in &i.model.subroutines {
            taken.extend(sub.outputs.iter().map(String::as_str));
        }
        let mut seen: FxHashSet<&str> = FxHashSet::default();
        for name in self.block.names.values() {
            if taken.contains(name.as_str()) || !seen.insert(name) {
                return Err(format!("the name `{name}` is bound twice"));
            }
        }
        Ok(())
    }

    fn define(&mut self, n: Nid) -> Result<(), String> {
        if !self.block.names.contains_key(&n) {
            return Err(format!("node {} is bound without a name", n.0));
        }
        self.compute(n)?;
        self.defined.insert(n);
        Ok(())
    }

    /// A value read by a statement: defined, hoisted, or computed inline.
    fn read(&self, n: Nid) -> Result<(), String> {
        if self.block.names.contains_key(&n) {
            return match self.defined.contains(&n) {
                true => Ok(()),
                false => Err(format!(
                    "`{}` is read before it is bound",
                    self.block.names[&n]
                )),
            };
        }
        if self.is_hoisted(n) || self.block.common.contains(&n) {
            return Ok(());
        }
        self.compute(n)
    }

    /// The operation of `n` with its operands read (rules 4 and 5).
    fn compute(&self, n: Nid) -> Result<(), String> {
        if let Op::Leaf(l) = self.prog.ir.op(n) {
            return self.leaf(*l);
        }
        for c in self.prog.ir.children(n) {
            self.read(c)?;
        }
        Ok(())
    }

    fn is_hoisted(&self, n: Nid) -> bool {
        self.kind.reads_constants()
            && !matches!(self.prog.ir.op(n), Op::Num(_) | Op::Leaf(_))
            && self.prog.ir.is_constant(n)
            && self.prog.hoisted.binary_search(&n).is_ok()
    }

    /// The outputs may read du/dt, and so do the products `M du/dt`.
    fn reads_accelerations(&self) -> bool {
        match self.kind {
            BlockKind::Outputs => true,
            BlockKind::MassMatrix => self.prog.mass_layout == MassLayout::Products,
            _ => false,
        }
    }

    fn leaf(&self, l: Leaf) -> Result<(), String> {
        let parameters_only = matches!(self.kind, BlockKind::Constants | BlockKind::Initial);
        match l {
            Leaf::Param(_) => Ok(()),
            _ if parameters_only => Err(format!("reads {l:?}, not a parameter")),
            Leaf::Accel(_) if !self.reads_accelerations() => {
                Err(format!("reads the acceleration {l:?}"))
            }
            Leaf::SubOut(s, _) if !self.subs_called.contains(&s) => Err(format!(
                "reads an output of `{}` before calling it",
                self.prog.interface.model.subroutines[s].name
            )),
            _ => Ok(()),
        }
    }
}
