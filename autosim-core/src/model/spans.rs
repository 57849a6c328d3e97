//! Where each item of a resolved model was declared, so that errors found
//! by later phases (Kane's equations, the program) point at the body,
//! load or output that caused them rather than at the model's name.

use crate::diag::Span;
use crate::mech::{ItemRef, System};
use rustc_hash::FxHashMap;

/// The declaration span of every named item of a model.
#[derive(Clone, Debug)]
pub struct ItemSpans {
    model: Span,
    names: FxHashMap<String, Span>,
}

impl ItemSpans {
    /// Spans of a model whose name is at `model`.
    pub fn new(model: Span) -> ItemSpans {
        ItemSpans {
            model,
            names: FxHashMap::default(),
        }
    }

    /// Records where `name` is declared.
    pub fn insert(&mut self, name: &str, span: Span) {
        self.names.insert(name.to_string(), span);
    }

    /// Where `name` is declared (the model's name if nowhere).
    pub fn named(&self, name: &str) -> Span {
        self.names.get(name).copied().unwrap_or(self.model)
    }

    /// Where an item of `sys` is declared.
    pub fn item(&self, sys: &System, item: ItemRef) -> Span {
        let name = match item {
            ItemRef::Model => return self.model,
            ItemRef::Body(b) => sys.body(b).name.as_str(),
            ItemRef::Force(k) => sys.forces()[k].name.as_str(),
            ItemRef::Moment(k) => sys.moments()[k].name.as_str(),
            ItemRef::State(s) => sys.arena.symbol(s).name.as_str(),
            ItemRef::Output(k) => sys.outputs()[k].name.as_str(),
            ItemRef::Subroutine(k) => sys.subroutines()[k].name.as_str(),
            ItemRef::Constraint(k) => sys.constraints()[k].name.as_str(),
            ItemRef::Motion(k) => sys.motions()[k].name.as_str(),
            ItemRef::Event(k) => sys.events()[k].name.as_str(),
        };
        self.named(name)
    }
}
