//! The linearization of a model generated with `linearize: true`: the
//! inherent `linearize` (from the program's linearize block) returning the
//! runtime's `Linear`, and the runtime's `Linearize` trait for generic
//! analysis code.

use super::functions;
use crate::emit::block::BlockEmitter;
use crate::emit::expr::float_type;
use crate::opt::BlockKind;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// `LINEAR_STATES` and `linearize` (nothing unless asked for).
pub(super) fn inherent(be: &BlockEmitter<'_>) -> TokenStream {
    let prog = be.prog;
    if prog.try_block(BlockKind::Linearize).is_none() {
        return TokenStream::new();
    }
    let ty = float_type(be.float);
    let rt = &be.rt;
    let (nl, nw, ny) = functions::linear_sizes(prog);
    let [nl_lit, nw_lit, ny_lit] = [nl, nw, ny].map(Literal::usize_unsuffixed);
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    let states = prog.interface.linear_states.clone().unwrap_or_default();
    let slots: Vec<Literal> = states
        .iter()
        .map(|k| Literal::usize_unsuffixed(*k))
        .collect();
    let names: Vec<String> = states
        .iter()
        .map(|k| format!("`{}`", prog.states().state(*k).name))
        .collect();
    let doc_states = format!(" The linear states, in order: {}.", names.join(", "));
    let functions::Args { t, x } = functions::args(prog, BlockKind::Linearize, be.locals);
    let body = functions::body(be, BlockKind::Linearize);
    quote! {
        /// Positions in the state vector of the linear model's states (all
        /// but the dependent coordinates of position constraints).
        #[doc = #doc_states]
        pub const LINEAR_STATES: [usize; #nl_lit] = [#(#slots),*];

        /// The linear model about `(t, x)` with the current inputs:
        /// `dx/dt ≈ A δx + B δw`, `y ≈ C δx + D δw` over the
        /// `LINEAR_STATES`, the inputs and the outputs, from symbolic
        /// derivatives of the equations (user functions and subroutines
        /// are held: their derivatives are taken as zero).
        pub fn linearize(&mut self, #t: #ty, #x: &[#ty; #n_states]) -> Result<#rt::Linear<#ty, #nl_lit, #nw_lit, #ny_lit>, #rt::ModelError> {
            #body
        }
    }
}

/// `impl Linearize` (nothing unless asked for).
pub(super) fn trait_impl(be: &BlockEmitter<'_>, header: &TokenStream) -> TokenStream {
    let prog = be.prog;
    if prog.try_block(BlockKind::Linearize).is_none() {
        return TokenStream::new();
    }
    let ty = float_type(be.float);
    let rt = &be.rt;
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    quote! {
        #header {
            const LINEAR_STATES: &'static [usize] = &Self::LINEAR_STATES;

            fn linearize_into(&mut self, t: #ty, x: &[#ty; #n_states], a: &mut [#ty], b: &mut [#ty], c: &mut [#ty], d: &mut [#ty]) -> Result<(), #rt::ModelError> {
                let lin = self.linearize(t, x)?;
                #rt::linear::copy_rows(&lin.a, a);
                #rt::linear::copy_rows(&lin.b, b);
                #rt::linear::copy_rows(&lin.c, c);
                #rt::linear::copy_rows(&lin.d, d);
                Ok(())
            }
        }
    }
}
