//! What a lanes function reads besides the time and the states: one array
//! `v` of `Lanes<L>`, lane `l` from the `l`-th model (a study's cases in
//! lockstep each have their own parameters and inputs; one model's batch
//! gives every lane the same), in the order the generated `values_in_lanes`
//! fills it: the parameters, the constants computed from them, the inputs,
//! the discrete variables. A read is one vector load, as cheap as the
//! broadcast of a value from one model.

use crate::opt::{Block, BlockKind, Leaf, Program};
use proc_macro2::TokenStream;
use quote::quote;

/// A value of the array `v`.
#[derive(Clone, Copy, Debug)]
pub enum LaneValue {
    Parameter(usize),
    Constant(usize),
    Input(usize),
    Discrete(usize),
}

/// The lengths of the array's four parts.
fn counts(prog: &Program) -> [usize; 4] {
    let m = &prog.interface.model;
    [
        m.parameters.len(),
        prog.hoisted.len(),
        m.inputs.len(),
        m.discrete.len(),
    ]
}

impl LaneValue {
    /// The value's index in the array.
    pub fn index(self, prog: &Program) -> usize {
        let [p, c, u, _] = counts(prog);
        match self {
            LaneValue::Parameter(k) => k,
            LaneValue::Constant(k) => p + k,
            LaneValue::Input(k) => p + c + k,
            LaneValue::Discrete(k) => p + c + u + k,
        }
    }
}

/// The array's length.
pub fn len(prog: &Program) -> usize {
    counts(prog).iter().sum()
}

/// The expressions reading each value of the array from a model `m`, in
/// the array's order.
pub fn reads(prog: &Program, m: &TokenStream) -> Vec<TokenStream> {
    let model = &prog.interface.model;
    let field = |name: &str| crate::emit::expr::ident(name);
    let parameters = model.parameters.iter().map(|q| {
        let id = field(&q.name);
        quote!(#m.parameters.#id)
    });
    let constants = (0..prog.hoisted.len()).map(|k| {
        let k = proc_macro2::Literal::usize_unsuffixed(k);
        quote!(#m.constants.p[#k])
    });
    let inputs = model.inputs.iter().map(|q| {
        let id = field(&q.name);
        quote!(#m.inputs.#id)
    });
    let discrete = model.discrete.iter().map(|d| {
        let id = field(&d.name);
        quote!(#m.discrete.#id)
    });
    parameters
        .chain(constants)
        .chain(inputs)
        .chain(discrete)
        .collect()
}

/// Whether `derivatives` (with the common block it reads) reads any lane
/// value.
pub fn read_by_derivatives(prog: &Program) -> bool {
    let reads = |b: &Block| {
        !b.hoisted.is_empty()
            || b.leaves
                .iter()
                .any(|l| matches!(l, Leaf::Param(_) | Leaf::Input(_) | Leaf::Discrete(_)))
    };
    let derivatives = prog.block(BlockKind::Derivatives);
    reads(derivatives) || (!derivatives.common.is_empty() && reads(prog.block(BlockKind::Common)))
}
