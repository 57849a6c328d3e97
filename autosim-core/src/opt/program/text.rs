//! The program's text form (like cranelift's): each block's statements as
//! `name = expression` lines, constants as `pK`, values of the common
//! block as `sK`, intermediates as `zK`, time derivatives as `x'`. The Markdown documentation prints the same
//! text, and snapshot tests of it show optimizer changes apart from
//! emitter changes.

use crate::expr::Func;
use crate::opt::ir::{Ir, Leaf, Nid, Op};
use crate::opt::program::{Assigned, BlockKind, MassLayout, Program};
use crate::opt::schedule::{Guard, Stmt};
use rustc_hash::FxHashMap;
use std::fmt::{self, Write};

impl Program {
    /// The name of slot `k` of a block of this kind, as the text form
    /// prints it (`q1'`, `M[2,1]`, `f[1]`, an output's name, `p3`, an
    /// event's indicator `g_bounce`, the new value `v⁺` of an action, ...).
    pub fn slot_name(&self, kind: BlockKind, k: usize) -> String {
        let n = self.n().max(1);
        match kind {
            BlockKind::Derivatives => format!("{}'", self.states().state(k).name),
            BlockKind::Initial => format!("{}(0)", self.states().state(k).name),
            BlockKind::Outputs => self.interface.model.outputs[k].name.clone(),
            BlockKind::Constants => format!("p{}", k + 1),
            BlockKind::Common => format!("s{}", k + 1),
            BlockKind::MassMatrix => {
                let m = self.unused_name("M", "MassMatrix");
                match self.mass_layout {
                    MassLayout::Entries => format!("{m}[{},{}]", k / n + 1, k % n + 1),
                    MassLayout::Products => format!("({m} du/dt)[{}]", k + 1),
                }
            }
            BlockKind::Forcing => format!("{}[{}]", self.unused_name("f", "forcing"), k + 1),
            BlockKind::Linearize => self.linear_slot_name(k),
            BlockKind::EventIndicators => format!("g_{}", self.interface.model.events[k].name),
            BlockKind::EventAction(e) => format!("{}⁺", self.assigned_name(e, k)),
            BlockKind::Assembly => {
                let closures = &self.interface.closures;
                match closures.get(k) {
                    Some(c) => format!("Δ{}", self.states().state(c.slot).name),
                    None => {
                        let c = closures[k - closures.len()].constraint;
                        format!("{}(residual)", self.interface.model.constraints[c].name)
                    }
                }
            }
        }
    }

    /// The name of the state or discrete variable that value `k` of event
    /// `e`'s action assigns.
    pub fn assigned_name(&self, e: usize, k: usize) -> &str {
        match self.event_assignments[e][k].0 {
            Assigned::State(s) => &self.states().state(s).name,
            Assigned::Discrete(d) => &self.interface.model.discrete[d].name,
        }
    }

    /// `short`, or `long` when the model has a quantity named `short` (a
    /// parameter `M` and the mass matrix `M[1,1]` must not read alike).
    fn unused_name<'a>(&self, short: &'a str, long: &'a str) -> &'a str {
        let i = &self.interface;
        let quantities = i
            .model
            .parameters
            .iter()
            .chain(&i.model.inputs)
            .chain(&i.model.outputs);
        let states = (0..self.states().len()).map(|k| &self.states().state(k).name);
        let taken = quantities
            .map(|q| &q.name)
            .chain(states)
            .any(|n| n == short);
        if taken { long } else { short }
    }

    /// `A[i,j]`, `B[i,j]`, `C[i,j]` or `D[i,j]` (1-based) of linearize slot
    /// `k`.
    fn linear_slot_name(&self, k: usize) -> String {
        let i = &self.interface;
        let nl = i.linear_states.as_ref().map_or(0, Vec::len);
        let (nw, ny) = (i.model.inputs.len(), i.model.outputs.len());
        let mut k = k;
        for (name, rows, cols) in [("A", nl, nl), ("B", nl, nw), ("C", ny, nl), ("D", ny, nw)] {
            if k < rows * cols {
                return format!("{name}[{},{}]", k / cols + 1, k % cols + 1);
            }
            k -= rows * cols;
        }
        format!("linear[{k}]")
    }

    /// Writes the statements of one block, one per line.
    pub fn write_block(&self, out: &mut impl Write, kind: BlockKind) -> fmt::Result {
        let block = self.block(kind);
        let slots = self.constant_slots();
        let common_slots = match kind {
            BlockKind::Common => FxHashMap::default(),
            _ => self.common_slots(),
        };
        let p = TextPrinter {
            prog: self,
            names: &block.names,
            hoisted: kind.reads_constants(),
            slots: &slots,
            common_slots: &common_slots,
        };
        for st in &block.stmts {
            match st {
                Stmt::Let(n) => writeln!(out, "{} = {}", block.names[n], p.def(*n))?,
                Stmt::SinCos { sin, cos } => {
                    writeln!(out, "{} = {}", block.names[sin], p.def(*sin))?;
                    writeln!(out, "{} = {}", block.names[cos], p.def(*cos))?;
                }
                Stmt::CallSub(k) => {
                    let sub = &self.interface.model.subroutines[*k];
                    let args: Vec<String> =
                        self.sub_args[*k].iter().map(|a| p.expr(*a, 0)).collect();
                    writeln!(
                        out,
                        "({}) = {}({})",
                        sub.outputs.join(", "),
                        sub.name,
                        args.join(", ")
                    )?;
                }
                Stmt::Check { pivot, guard } => {
                    let condition = match guard {
                        Guard::Positive { speed } => format!(
                            "> 0   (mass matrix pivot of {})",
                            self.states().speeds[*speed].name
                        ),
                        Guard::Regular { constraint } => format!(
                            "!= 0   (pivot of constraint {})",
                            self.interface.model.constraints[*constraint].name
                        ),
                    };
                    writeln!(out, "require {} {condition}", p.expr(*pivot, 0))?
                }
                Stmt::Store { slot, value } => writeln!(
                    out,
                    "{} = {}",
                    self.slot_name(kind, *slot),
                    p.expr(*value, 0)
                )?,
            }
        }
        Ok(())
    }
}

impl fmt::Display for Program {
    /// The whole program: the state layout, then every block.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "program {}", self.interface.model.name)?;
        let names = |v: &[crate::opt::interface::StateVar]| {
            v.iter()
                .map(|s| s.name.as_str())
                .collect::<Vec<_>>()
                .join(" ")
        };
        let layout = self.states();
        writeln!(f, "coordinates: {}", names(&layout.coordinates))?;
        writeln!(f, "speeds: {}", names(&layout.speeds))?;
        writeln!(f, "extra states: {}", names(&layout.extra))?;
        for (kind, block) in &self.blocks {
            writeln!(f, "\nblock {} ({}):", kind.name(), block.ops)?;
            self.write_block(f, *kind)?;
        }
        Ok(())
    }
}

/// Prints IR nodes of one block as text.
struct TextPrinter<'a> {
    prog: &'a Program,
    names: &'a FxHashMap<Nid, String>,
    hoisted: bool,
    slots: &'a FxHashMap<Nid, usize>,
    /// Values read from the common block (`sK`).
    common_slots: &'a FxHashMap<Nid, usize>,
}

impl TextPrinter<'_> {
    fn ir(&self) -> &Ir {
        &self.prog.ir
    }

    fn expr(&self, n: Nid, min: u8) -> String {
        if let Some(name) = self.names.get(&n) {
            return name.clone();
        }
        if self.hoisted
            && let Some(k) = self.slots.get(&n)
        {
            return format!("p{}", k + 1);
        }
        if let Some(k) = self.common_slots.get(&n) {
            return format!("s{}", k + 1);
        }
        let (text, prec) = self.def_prec(n);
        if prec < min {
            format!("({text})")
        } else {
            text
        }
    }

    fn def(&self, n: Nid) -> String {
        self.def_prec(n).0
    }

    fn def_prec(&self, n: Nid) -> (String, u8) {
        match self.ir().op(n).clone() {
            Op::Num(b) => {
                let x = f64::from_bits(b);
                (format!("{x}"), if x < 0.0 { 2 } else { 4 })
            }
            Op::Leaf(l) => (self.leaf(l), 4),
            Op::Sum { pos, neg } => {
                let mut t = String::new();
                for (i, x) in pos.iter().enumerate() {
                    if i > 0 {
                        t.push_str(" + ");
                    }
                    t.push_str(&self.expr(*x, 1));
                }
                for x in neg.iter() {
                    t.push_str(" - ");
                    t.push_str(&self.expr(*x, 2));
                }
                (t, 1)
            }
            Op::Mul(a, b) => (format!("{}*{}", self.expr(a, 2), self.expr(b, 3)), 2),
            Op::Div(a, b) => (format!("{}/{}", self.expr(a, 2), self.expr(b, 3)), 2),
            Op::Neg(a) => (format!("-{}", self.expr(a, 3)), 2),
            Op::Powi(a, k) => (format!("{}^{k}", self.expr(a, 4)), 3),
            Op::Sqrt(a) => (format!("sqrt({})", self.expr(a, 0)), 4),
            Op::Powf(a, b) => (format!("{}^{}", self.expr(a, 4), self.expr(b, 4)), 3),
            Op::Call(f, args) => {
                let xs: Vec<String> = args.iter().map(|a| self.expr(*a, 0)).collect();
                let name = match f {
                    Func::User(u) => self.prog.interface.model.extern_fns[u.index()].name.clone(),
                    other => other.builtin_name().unwrap_or("?").to_string(),
                };
                (format!("{name}({})", xs.join(", ")), 4)
            }
        }
    }

    fn leaf(&self, l: Leaf) -> String {
        let i = &self.prog.interface;
        match l {
            Leaf::Param(k) => i.model.parameters[k].name.clone(),
            Leaf::State(k) => i.states.state(k).name.clone(),
            Leaf::Input(k) => i.model.inputs[k].name.clone(),
            Leaf::Discrete(k) => i.model.discrete[k].name.clone(),
            Leaf::Time => "t".to_string(),
            Leaf::SubOut(s, k) => i.model.subroutines[s].outputs[k].clone(),
            Leaf::Accel(k) => format!("{}'", i.states.speeds[k].name),
        }
    }
}
