//! The linearization of a model generated with `linearize: true`: the
//! inherent `linearize` (from the program's linearize block) returning the
//! runtime's `Linear`, and the runtime's `Linearize` trait for generic
//! analysis code. A big linearization is cut into parts (`parts.rs`), one
//! private function each, which `linearize` calls in order.

use super::functions;
use crate::emit::block::{BlockEmitter, Target, all_slots};
use crate::emit::expr::float_type;
use crate::emit::parts::{self, Part};
use crate::opt::BlockKind;
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

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
    let (body, part_functions) = match split(be) {
        Some(parts) => parts_body(be, &parts),
        None => (
            functions::body(be, BlockKind::Linearize),
            TokenStream::new(),
        ),
    };
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

        #part_functions
    }
}

/// The parts of the linearize block, if it is cut into parts.
fn split(be: &BlockEmitter<'_>) -> Option<Vec<Part>> {
    let constant = |n| be.constant_slot.contains_key(&n);
    parts::split(be.prog, be.prog.block(BlockKind::Linearize), &constant)
}

/// The body of `linearize` calling its parts in order, and the parts'
/// functions: each takes the array of bound values and the linear model
/// only when it reads or writes them, and returns `Result` only when it
/// checks a pivot.
fn parts_body(be: &BlockEmitter<'_>, parts: &[Part]) -> (TokenStream, TokenStream) {
    let prog = be.prog;
    let ty = float_type(be.float);
    let rt = &be.rt;
    let (nl, nw, ny) = functions::linear_sizes(prog);
    let [nl, nw, ny] = [nl, nw, ny].map(Literal::usize_unsuffixed);
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    let array = all_slots(prog.block(BlockKind::Linearize));
    let len = Literal::usize_unsuffixed(array.len());
    let list = functions::linear_matrices(be);
    let (lx, z, lin) = (&be.locals.x, &be.locals.z, &be.locals.lin);
    let linear = quote!(#rt::Linear<#ty, #nl, #nw, #ny>);
    let (mut calls, mut functions) = (TokenStream::new(), TokenStream::new());
    for (k, part) in parts.iter().enumerate() {
        let name = format_ident!("linearize_part_{}", k + 1);
        let block = &part.block;
        let (mut params, mut args) = (Vec::new(), Vec::new());
        if block.reads_time() {
            params.push(quote!(t: #ty));
            args.push(quote!(t));
        }
        if block.reads_state() {
            params.push(quote!(#lx: &[#ty; #n_states]));
            args.push(quote!(#lx));
        }
        if part.uses_array {
            params.push(quote!(#z: &mut [#ty; #len]));
            args.push(quote!(&mut #z));
        }
        if part.stores {
            params.push(quote!(#lin: &mut #linear));
            args.push(quote!(&mut #lin));
        }
        let statements = be.emit_part(block, &array, Target::Matrices(&list));
        let doc = format!(
            " Part {} of {} of [`Self::linearize`]: {} of its statements.",
            k + 1,
            parts.len(),
            block.stmts.len()
        );
        let (ret, ok, question) = match part.checks {
            true => (
                quote!(-> Result<(), #rt::ModelError>),
                quote!(Ok(())),
                quote!(?),
            ),
            false => (TokenStream::new(), TokenStream::new(), TokenStream::new()),
        };
        functions.extend(quote! {
            #[doc = #doc]
            #[inline(never)]
            fn #name(&mut self, #(#params),*) #ret {
                #statements
                #ok
            }
        });
        calls.extend(quote!(self.#name(#(#args),*)#question;));
    }
    let body = quote! {
        let mut #lin = #rt::Linear::zeros();
        let mut #z = [0.0; #len];
        #calls
        Ok(#lin)
    };
    (body, functions)
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
