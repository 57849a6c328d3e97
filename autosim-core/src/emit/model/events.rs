//! The events of the generated model: the `Discrete` struct of its
//! discrete variables, and the `Model` items of events
//! (`EVENT_INDICATORS`, `DISCRETE_NAMES`, `DISCRETE_UNITS`,
//! `event_indicators`, `event`, `discrete_values`,
//! `set_discrete_values`) with the inherent `EVENT_OPS`. A model without
//! events or discrete variables generates none of it (the trait's
//! defaults).

use super::{by_index, functions, structs};
use crate::emit::block::BlockEmitter;
use crate::emit::expr::{float_type, ident};
use crate::mech::EventDirection;
use crate::opt::{Assigned, Block, BlockKind, Interface};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// Whether the model has anything of events to generate.
pub(super) fn has_events(i: &Interface) -> bool {
    !i.model.events.is_empty() || !i.model.discrete.is_empty()
}

/// `Discrete` and its `Default` (the initial values), if the model
/// declares discrete variables.
pub(super) fn discrete_struct(i: &Interface) -> TokenStream {
    if i.model.discrete.is_empty() {
        return TokenStream::new();
    }
    let doc = quote!(#[doc = r" Discrete variables of the model (modes the equations read), changed only by its events; `Default` holds their initial values."]);
    structs::values_struct("Discrete", doc, &i.model.discrete, i.float)
}

/// The `Model` items of events and discrete variables.
pub(super) fn trait_items(be: &BlockEmitter<'_>) -> TokenStream {
    let i = &be.prog.interface;
    if !has_events(i) {
        return TokenStream::new();
    }
    let rt = &be.rt;
    let ty = float_type(be.float);
    let indicators = i.model.events.iter().map(|e| {
        let name = &e.name;
        match e.direction {
            EventDirection::Rising => quote!(#rt::EventIndicator::rising(#name)),
            EventDirection::Falling => quote!(#rt::EventIndicator::falling(#name)),
            EventDirection::Either => quote!(#rt::EventIndicator::either(#name)),
        }
    });
    let names = i.model.discrete.iter().map(|d| &d.name);
    let units = i.model.discrete.iter().map(|d| &d.unit);
    let functions = if i.model.events.is_empty() {
        TokenStream::new()
    } else {
        let g = event_indicators(be);
        let e = event(be);
        quote!(#g #e)
    };
    let access = if i.model.discrete.is_empty() {
        TokenStream::new()
    } else {
        let (get, set) = by_index(&i.model.discrete, &quote!(self.discrete));
        quote! {
            fn discrete_values(&self, values: &mut [#ty]) {
                #get
            }

            fn set_discrete_values(&mut self, values: &[#ty]) {
                #set
            }
        }
    };
    quote! {
        const EVENT_INDICATORS: &'static [#rt::EventIndicator] = &[#(#indicators),*];
        const DISCRETE_NAMES: &'static [&'static str] = &[#(#names),*];
        const DISCRETE_UNITS: &'static [&'static str] = &[#(#units),*];

        #functions

        #access
    }
}

/// `event_indicators`: the block into a local array, copied into `g`
/// (what fits: no index can fail).
fn event_indicators(be: &BlockEmitter<'_>) -> TokenStream {
    let prog = be.prog;
    let rt = &be.rt;
    let ty = float_type(be.float);
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    let functions::Args { t, x } = functions::args(prog, BlockKind::EventIndicators, be.locals);
    let ly = &be.locals.y;
    let len = Literal::usize_unsuffixed(prog.interface.model.events.len());
    let body = functions::body(be, BlockKind::EventIndicators);
    quote! {
        fn event_indicators(&mut self, #t: #ty, #x: &[#ty; #n_states], g: &mut [#ty]) -> Result<(), #rt::ModelError> {
            let mut #ly = [0.0; #len];
            #body
            for (slot, value) in g.iter_mut().zip(#ly) {
                *slot = value;
            }
            Ok(())
        }
    }
}

/// `event`: one arm per event, computing only the firing event's new
/// values (its block, from the values before the event), then assigning
/// them.
fn event(be: &BlockEmitter<'_>) -> TokenStream {
    let prog = be.prog;
    let i = &prog.interface;
    let rt = &be.rt;
    let ty = float_type(be.float);
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    let lx = &be.locals.x;
    let kinds: Vec<BlockKind> = (0..i.model.events.len())
        .map(BlockKind::EventAction)
        .collect();
    let reads = |f: fn(&Block) -> bool| kinds.iter().any(|k| f(prog.block(*k)));
    let resets = prog
        .event_assignments
        .iter()
        .flatten()
        .any(|(a, _)| matches!(a, Assigned::State(_)));
    let t = if reads(Block::reads_time) {
        quote!(t)
    } else {
        quote!(_)
    };
    let x = if reads(Block::reads_state) || resets {
        quote!(#lx)
    } else {
        quote!(_)
    };
    let arms = kinds
        .iter()
        .zip(&i.model.events)
        .enumerate()
        .map(|(k, (kind, e))| {
            let values = action(be, *kind, &prog.event_assignments[k]);
            let k = Literal::usize_unsuffixed(k);
            let outcome = match e.stop {
                true => quote!(#rt::EventOutcome::Stop),
                false => quote!(#rt::EventOutcome::Continue),
            };
            quote!(#k => { #values Ok(#outcome) })
        });
    quote! {
        fn event(&mut self, index: usize, #t: #ty, #x: &mut [#ty; #n_states]) -> Result<#rt::EventOutcome, #rt::ModelError> {
            match index {
                #(#arms)*
                _ => Ok(#rt::EventOutcome::Continue),
            }
        }
    }
}

/// The statements of one event's action: its new values into a local
/// array, then each assigned to its state or discrete variable.
fn action(be: &BlockEmitter<'_>, kind: BlockKind, list: &[(Assigned, usize)]) -> TokenStream {
    if list.is_empty() {
        return TokenStream::new();
    }
    let i = &be.prog.interface;
    let (ly, lx) = (&be.locals.y, &be.locals.x);
    let len = Literal::usize_unsuffixed(list.len());
    let body = functions::body(be, kind);
    let assign = list.iter().map(|(target, slot)| {
        let slot = Literal::usize_unsuffixed(*slot);
        match target {
            Assigned::State(s) => {
                let s = Literal::usize_unsuffixed(*s);
                quote!(#lx[#s] = #ly[#slot];)
            }
            Assigned::Discrete(d) => {
                let id = ident(&i.model.discrete[*d].name);
                quote!(self.discrete.#id = #ly[#slot];)
            }
        }
    });
    quote!(let mut #ly = [0.0; #len]; #body #(#assign)*)
}

/// `EVENT_OPS`: the operations of each event's action (one `event` call
/// for it), in declaration order.
pub(super) fn ops_constant(be: &BlockEmitter<'_>) -> TokenStream {
    let prog = be.prog;
    let rt = &be.rt;
    let n = prog.interface.model.events.len();
    if n == 0 {
        return TokenStream::new();
    }
    let values = (0..n).map(|k| super::ops_tokens(rt, &prog.block(BlockKind::EventAction(k)).ops));
    let len = Literal::usize_unsuffixed(n);
    quote! {
        /// Operations of one `event` call for each event (its action's
        /// new values), in declaration order.
        pub const EVENT_OPS: [#rt::OpCount; #len] = [#(#values),*];
    }
}
