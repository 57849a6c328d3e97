//! Many states per call: `derivatives_lanes`, the `derivatives` block
//! printed once more with every value a `Lanes<L>` (one `f64` per state,
//! struct of arrays), and the `Model::derivatives_batch` that calls it
//! four states at a time. Only for models with the `lanes` option (it
//! costs compile time: chain-spatial-10's model alone 0.8 → 8.5 s of
//! release rustc) and `f64`: the others keep the default batch (one call
//! per state).

use super::functions;
use super::versions::{Param, Signature, versions_of};
use crate::emit::block::BlockEmitter;
use crate::opt::{BlockKind, FloatType, Program};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

/// Whether the model gets a lanes function: asked for (the `lanes`
/// option), `f64`, with states.
pub(super) fn has_lanes(prog: &Program) -> bool {
    let i = &prog.interface;
    i.lanes && i.float == FloatType::F64 && !prog.states().is_empty()
}

/// The inherent items, `derivatives_lanes` (public) and its baseline copy,
/// and the module-level items of its x86-64-v3 copy (`versions_of`,
/// `lanes_copies`).
pub(super) fn inherent(be: &BlockEmitter<'_>) -> (TokenStream, TokenStream) {
    if !has_lanes(be.prog) {
        return Default::default();
    }
    let lanes = BlockEmitter {
        lanes: true,
        // `lanes_math` as the enclosing module has it: the plain one, or
        // the fused one in the fast copy's module.
        math: quote!(lanes_math),
        rt: be.rt.clone(),
        ..*be
    };
    let prog = be.prog;
    let rt = &be.rt;
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    let l = &be.locals.lanes;
    let lane_ty = quote!(#rt::__private::Lanes<#l>);
    let functions::Args { t, x } = functions::args(prog, BlockKind::Derivatives, be.locals);
    let ldx = &be.locals.dx;
    let body = functions::body(&lanes, BlockKind::Derivatives);
    let bind_t = match t.to_string().as_str() {
        "_" => TokenStream::new(),
        _ => quote!(let t = Lanes::<#l>::splat(t);),
    };
    let params = [
        (t, "t", quote!(f64)),
        (x, "x", quote!(&[#lane_ty; #n_states])),
        (quote!(#ldx), "dx", quote!(&mut [#lane_ty; #n_states])),
    ]
    .map(|(pattern, name, ty)| Param {
        pattern,
        name: format_ident!("{name}"),
        ty,
    });
    let impl_head = super::impl_head(&prog.interface);
    let signature = Signature {
        impl_head: &impl_head,
        name: "derivatives_lanes",
        generics: quote!(<const #l: usize>),
        receiver: quote!(&mut self),
        params: &params,
        ret: quote!(-> Result<(), #rt::ModelError>),
    };
    let versions = versions_of(
        rt,
        super::versions::lanes_copies(prog),
        &signature,
        quote! {
            #[allow(unused_imports)]
            use #rt::__private::Lanes;
            #bind_t
            #body
            #rt::__private::check_derivatives_lanes::<Self, #l>(#ldx)
        },
    );
    let (caller, copies) = (versions.caller, versions.copies);
    let inherent = quote! {
        /// `derivatives` at `L` states at once, in struct-of-arrays form:
        /// `x[i].0[l]` is state `i` of the `l`-th state vector, and
        /// `dx[i].0[l]` its derivative. Each lane computes exactly what
        /// `derivatives` computes for its state (the same bits), with the
        /// operations on `L` lanes in vector instructions. An error (a
        /// singular pivot, a non-finite derivative or user result) is that
        /// of some lane: `Model::derivatives` at each state tells which
        /// (`Model::derivatives_batch` does it).
        pub #caller

        #copies
    };
    (inherent, versions.items)
}

/// `Model::derivatives_batch` through `derivatives_lanes`, four states at
/// a time, and `Model::LOCKSTEP` (nothing for a model without lanes: the
/// default loop, and studies one case at a time).
pub(super) fn batch(be: &BlockEmitter<'_>) -> TokenStream {
    if !has_lanes(be.prog) {
        return TokenStream::new();
    }
    let rt = &be.rt;
    let n_states = Literal::usize_unsuffixed(be.prog.states().len());
    quote! {
        const LOCKSTEP: bool = true;

        fn derivatives_batch(
            &mut self,
            t: f64,
            x: &[[f64; #n_states]],
            dx: &mut [[f64; #n_states]],
            status: &mut [Result<(), #rt::ModelError>],
        ) {
            #rt::__private::in_lanes::<Self, { #rt::batch::LANES }, #n_states>(
                self,
                t,
                x,
                dx,
                status,
                |model, t, x, dx| model.derivatives_lanes(t, x, dx),
            )
        }
    }
}
