//! Names for generated code: readable hints (`sin_q4`, `m2_1`, `u5_dot`)
//! and the names generated ones must avoid.

use crate::expr::Func;
use crate::opt::interface::{Interface, StateLayout};
use crate::opt::ir::{Ir, Leaf, Nid, Op};
use crate::opt::lower::equations::Lowered;
use rustc_hash::{FxHashMap, FxHashSet};

/// Names for generated code: hints for readable values, and the names the
/// generated ones must avoid.
pub(crate) struct Naming {
    pub hints: FxHashMap<Nid, String>,
    /// Names taken in every block.
    pub reserved: FxHashSet<String>,
    /// Names taken in the outputs block (the accelerations too).
    pub output_reserved: FxHashSet<String>,
}

impl Naming {
    pub fn new(ir: &Ir, interface: &Interface, lowered: &Lowered) -> Naming {
        let layout = &interface.states;
        let mut reserved: FxHashSet<String> = layout.states().map(|s| s.name.clone()).collect();
        reserved.extend(interface.model.inputs.iter().map(|i| i.name.clone()));
        reserved.extend(interface.model.discrete.iter().map(|d| d.name.clone()));
        for sub in &interface.model.subroutines {
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
