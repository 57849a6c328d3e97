//! Dimensional analysis at compile time.
//!
//! Every quantity of a model has a dimension (exponents over kg, m, s, A,
//! K, mol, cd, and the radian, tracked but dimensionless as in SI): the
//! declared unit of a parameter, input, added state, subroutine output or
//! user function; m or rad for a coordinate and m/s or rad/s for its
//! speed; N for a force, N m for a moment, m/s^2 for gravity. The
//! dimensions of `let`s, outputs and constraints are inferred from their
//! expressions, and a quantity declared without a unit gets an unknown
//! dimension that its uses determine (`infer.rs`). Sums, `min`/`max`/
//! `atan2`, the arguments of functions and each item's value are checked;
//! a mismatch is a diagnostic at the expression that names both
//! dimensions.
//!
//! The check reads the model's text (the AST) with the resolver's names,
//! not the expressions the resolver builds: those are hash-consed and
//! simplified (`x - x` folds to 0), so a mismatch could vanish before it
//! is seen, and its span with it.
//!
//! `dim.rs` is the algebra, `table.rs` the units and their parsing,
//! `infer.rs` the unknowns, `check.rs` expressions, `operations.rs` the
//! paper's operations, `items.rs` what each item needs.

mod check;
mod dim;
mod infer;
mod items;
mod operations;
mod table;
#[cfg(test)]
mod tests;

pub use dim::{BASES, Dim, Ratio};
pub use table::{NamedUnit, PREFIXES, UNITS, UnitError, UnitMeaning, parse_unit};

use super::scope::{Lazy, Resolver};
use crate::diag::Diagnostic;
use crate::syntax::ast;
use check::Checker;
use rustc_hash::FxHashMap;

/// What the check found: its diagnostics, and the unit of each quantity
/// declared without one whose uses determine it (for the documentation).
#[derive(Debug, Default)]
pub struct UnitReport {
    /// The mismatches and unreadable units, in model order.
    pub diagnostics: Vec<Diagnostic>,
    /// Name → inferred unit (`N/m`), for parameters, inputs, added states,
    /// subroutine outputs, outputs and constraints declared without a
    /// unit.
    pub inferred: FxHashMap<String, String>,
}

/// Checks the dimensions of every item of `model`, resolved by `r`.
pub(crate) fn check(r: &Resolver<'_>, model: &ast::Model) -> UnitReport {
    let mut c = Checker {
        r,
        solver: Default::default(),
        vars: FxHashMap::default(),
        lets: vec![Lazy::Pending; r.lets.len()],
        signatures: FxHashMap::default(),
        diags: Vec::new(),
        pending: 0,
    };
    c.signatures(model);
    let mut inferred = Vec::new();
    for item in &model.items {
        c.item(item, &mut inferred);
    }
    let mut report = UnitReport {
        diagnostics: std::mem::take(&mut c.diags),
        inferred: FxHashMap::default(),
    };
    let symbols = c
        .vars
        .iter()
        .map(|(&s, &v)| (r.sys.arena.symbol(s).name.clone(), infer::Affine::var(v)));
    for (name, a) in inferred.into_iter().chain(symbols.collect::<Vec<_>>()) {
        if let Some(dim) = c.solver.known(&a) {
            report.inferred.insert(name, dim.to_string());
        }
    }
    report
}

/// The meaning of a unit as declared, if it reads (the check reports it
/// otherwise).
pub fn unit_meaning(text: &str) -> Option<UnitMeaning> {
    parse_unit(text).ok()
}
