//! The events of the generated model: the `Discrete` struct of its
//! discrete variables, and the `Model` items of events
//! (`EVENT_INDICATORS`, `DISCRETE_NAMES`, `DISCRETE_UNITS`,
//! `event_indicators`, `event`, `discrete_values`,
//! `set_discrete_values`). A model without events or discrete variables
//! generates none of it (the trait's defaults).

use super::{by_index, functions, structs};
use crate::emit::block::{BlockEmitter, Target};
use crate::emit::expr::{float_type, ident};
use crate::mech::EventDirection;
use crate::opt::{Assigned, BlockKind, Interface};
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
    let body = be.emit(
        prog.block(BlockKind::EventIndicators),
        true,
        Target::Array(ly),
    );
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

/// `event`: every action's new value from the values before the event
/// (one block), then the assignments of the event that fired.
fn event(be: &BlockEmitter<'_>) -> TokenStream {
    let prog = be.prog;
    let i = &prog.interface;
    let rt = &be.rt;
    let ty = float_type(be.float);
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    let ly = &be.locals.y;
    let lx = &be.locals.x;
    let n_values = prog.slots(BlockKind::EventActions);
    let functions::Args { t, x } = functions::args(prog, BlockKind::EventActions, be.locals);
    let resets = prog
        .event_assignments
        .iter()
        .flatten()
        .any(|(a, _)| matches!(a, Assigned::State(_)));
    let x = if resets { quote!(#lx) } else { x };
    let values = if n_values == 0 {
        TokenStream::new()
    } else {
        let len = Literal::usize_unsuffixed(n_values);
        let body = be.emit(prog.block(BlockKind::EventActions), true, Target::Array(ly));
        quote!(let mut #ly = [0.0; #len]; #body)
    };
    let arms = prog
        .event_assignments
        .iter()
        .zip(&i.model.events)
        .enumerate()
        .map(|(k, (list, e))| {
            let k = Literal::usize_unsuffixed(k);
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
            let outcome = match e.stop {
                true => quote!(#rt::EventOutcome::Stop),
                false => quote!(#rt::EventOutcome::Continue),
            };
            quote!(#k => { #(#assign)* Ok(#outcome) })
        });
    quote! {
        fn event(&mut self, index: usize, #t: #ty, #x: &mut [#ty; #n_states]) -> Result<#rt::EventOutcome, #rt::ModelError> {
            #values
            match index {
                #(#arms)*
                _ => Ok(#rt::EventOutcome::Continue),
            }
        }
    }
}
