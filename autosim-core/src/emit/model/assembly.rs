//! The assembly of a model with position constraints: the generated
//! `assembly_step` (one Newton step, from the program's assembly block),
//! and the `Model` methods `assemble` and `project` that run the
//! runtime's Newton loop on it.

use super::functions;
use crate::emit::block::BlockEmitter;
use crate::emit::expr::float_type;
use crate::opt::BlockKind;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// `assembly_step` and the constants naming what it solves (nothing
/// without position constraints).
pub(super) fn inherent(be: &BlockEmitter<'_>) -> TokenStream {
    let prog = be.prog;
    if prog.try_block(BlockKind::Assembly).is_none() {
        return TokenStream::new();
    }
    let i = &prog.interface;
    let ty = float_type(be.float);
    let rt = &be.rt;
    let k = i.closures.len();
    let k_lit = Literal::usize_unsuffixed(k);
    let slots_lit = Literal::usize_unsuffixed(2 * k);
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    let names: Vec<&String> = i
        .closures
        .iter()
        .map(|c| &i.model.constraints[c.constraint].name)
        .collect();
    let slots: Vec<Literal> = i
        .closures
        .iter()
        .map(|c| Literal::usize_unsuffixed(c.slot))
        .collect();
    let functions::Args { t, x } = functions::args(prog, BlockKind::Assembly, be.locals);
    let body = functions::body(be, BlockKind::Assembly);
    let ls = &be.locals.step;
    quote! {
        /// The position constraints, in the order of `assembly_step`'s
        /// residuals.
        pub const POSITION_CONSTRAINTS: [&'static str; #k_lit] = [#(#names),*];
        /// The state index of the dependent coordinate of each position
        /// constraint.
        pub const DEPENDENT_COORDINATES: [usize; #k_lit] = [#(#slots),*];

        /// One Newton step of assembly at `x`: `step[..K]` the corrections
        /// of the dependent coordinates (`DEPENDENT_COORDINATES`),
        /// `step[K..]` the residuals of the position constraints
        /// (`POSITION_CONSTRAINTS`).
        pub fn assembly_step(&mut self, #t: #ty, #x: &[#ty; #n_states], #ls: &mut [#ty; #slots_lit]) -> Result<(), #rt::ModelError> {
            #body
            Ok(())
        }
    }
}

/// `assemble` and `project` of the `Model` impl (the trait's defaults
/// without position constraints).
pub(super) fn trait_methods(be: &BlockEmitter<'_>) -> TokenStream {
    let prog = be.prog;
    if prog.try_block(BlockKind::Assembly).is_none() {
        return TokenStream::new();
    }
    let ty = float_type(be.float);
    let rt = &be.rt;
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    let solve = |tolerance: TokenStream, limit: TokenStream| {
        quote! {
            #rt::assembly::solve_positions(
                x,
                &Self::DEPENDENT_COORDINATES,
                &Self::POSITION_CONSTRAINTS,
                <Self as #rt::Model>::STATE_NAMES,
                #tolerance,
                #limit,
                |x, step| self.assembly_step(t, x, step),
            )
        }
    };
    let assemble = solve(quote!(0.0), quote!(None));
    let project = solve(quote!(tolerance), quote!(Some(#rt::assembly::BRANCH_LIMIT)));
    quote! {
        fn assemble(&mut self, t: #ty, x: &mut [#ty; #n_states]) -> Result<(), #rt::ModelError> {
            #assemble.map(|_| ())
        }

        fn project(&mut self, t: #ty, x: &mut [#ty; #n_states], tolerance: #ty) -> Result<bool, #rt::ModelError> {
            #project
        }
    }
}
