//! Many states per call: `derivatives_lanes`, the `derivatives` block
//! printed once more with every value a `Lanes<L>` (one `f64` per state,
//! struct of arrays) as `derivatives_lanes_with`, which reads parameters,
//! constants, inputs and discrete variables from lane values
//! (`values_in_lanes`: lane `l` from the `l`-th of `L` models), and the
//! `Model::derivatives_batch` (one model) and `Model::lane_values` with
//! `Model::derivatives_each` (one model per state) that call it four
//! states at a time. Only for models with the `lanes` option (it costs
//! compile time: a release build of a crate calling chain-spatial-10's
//! model 0.86 → 8.1 s on a 2-core Intel Xeon, `bench/compile`) and `f64`:
//! the others keep the default batch (one call per state).

use super::functions;
use super::versions::{Param, Signature, versions_of};
use crate::emit::block::BlockEmitter;
use crate::emit::lane_values;
use crate::opt::{BlockKind, FloatType, Program};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

/// Whether the model gets a lanes function: asked for (the `lanes`
/// option), `f64`, with states.
pub(super) fn has_lanes(prog: &Program) -> bool {
    let i = &prog.interface;
    i.lanes && i.float == FloatType::F64 && !prog.states().is_empty()
}

/// The inherent items, `derivatives_lanes` (public), `values_in_lanes` and
/// `derivatives_lanes_with` with its baseline copy, and the module-level
/// items of its x86-64-v3 copy (`versions_of`, `lanes_copies`).
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
    let values_ty = values_type(be);
    let functions::Args { t, x } = functions::args(prog, BlockKind::Derivatives, be.locals);
    let ldx = &be.locals.dx;
    let body = functions::body(&lanes, BlockKind::Derivatives);
    let v = &be.locals.values;
    let v_pattern = match lane_values::read_by_derivatives(prog) {
        true => quote!(#v),
        false => quote!(_),
    };
    let params = [
        (v_pattern, "v", quote!(&#values_ty)),
        (t, "t", lane_ty.clone()),
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
        name: "derivatives_lanes_with",
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
            #body
            #rt::__private::check_derivatives_lanes::<Self, #l>(#ldx)
        },
    );
    let (caller, copies) = (versions.caller, versions.copies);
    let values = values_fn(be);
    let inherent = quote! {
        /// `derivatives` at `L` states at once, in struct-of-arrays form:
        /// `x[i].0[l]` is state `i` of the `l`-th state vector, and
        /// `dx[i].0[l]` its derivative. Each lane computes exactly what
        /// `derivatives` computes for its state (the same bits), with the
        /// operations on `L` lanes in vector instructions. An error (a
        /// singular pivot, a non-finite derivative or user result) is that
        /// of some lane: `Model::derivatives` at each state tells which
        /// (`Model::derivatives_batch` does it). It gathers the model's
        /// parameters, constants and inputs into lanes at every call:
        /// `derivatives_lanes_with` takes them gathered once.
        pub fn derivatives_lanes<const #l: usize>(
            &mut self,
            t: f64,
            x: &[#lane_ty; #n_states],
            dx: &mut [#lane_ty; #n_states],
        ) -> Result<(), #rt::ModelError> {
            let v = Self::values_in_lanes([&*self; #l]);
            self.derivatives_lanes_with(&v, #rt::__private::Lanes::splat(t), x, dx)
        }

        #values

        /// `derivatives_lanes` with the values it reads besides the time
        /// and the states given as `v`, what `values_in_lanes` gathers,
        /// and a time per lane: lane `l` computes what the `l`-th model's
        /// `derivatives` computes at time `t.0[l]` (its user code called
        /// on `self`). Gather once for many calls: `derivatives_lanes`
        /// gathers at every call.
        pub #caller

        #copies
    };
    (inherent, versions.items)
}

/// `[Lanes<L>; K]`, the type of the lane values.
fn values_type(be: &BlockEmitter<'_>) -> TokenStream {
    let (rt, l) = (&be.rt, &be.locals.lanes);
    let len = Literal::usize_unsuffixed(lane_values::len(be.prog));
    quote!([#rt::__private::Lanes<#l>; #len])
}

/// `values_in_lanes`: what `derivatives_lanes_with` reads besides the
/// time and the states, lane `l` from `models[l]`.
fn values_fn(be: &BlockEmitter<'_>) -> TokenStream {
    let (rt, l) = (&be.rt, &be.locals.lanes);
    let values_ty = values_type(be);
    let reads = lane_values::reads(be.prog, &quote!(m));
    let model = match reads.is_empty() {
        true => quote!(_),
        false => quote!(m),
    };
    quote! {
        /// The parameters, the constants computed from them, the inputs
        /// and the discrete variables of `models` as lanes (lane `l` is
        /// `models[l]`'s): what `derivatives_lanes_with` reads.
        pub fn values_in_lanes<const #l: usize>(models: [&Self; #l]) -> #values_ty {
            let rows = models.map(|#model| [#(#reads),*]);
            core::array::from_fn(|k| #rt::__private::Lanes(core::array::from_fn(|l| rows[l][k])))
        }
    }
}

/// `Model::derivatives_batch` (one model, its lane values gathered once
/// per call) and, a model per state, `Model::LANE_VALUES`,
/// `Model::lane_values` (gathered once for models whose values do not
/// change, a study's group of cases) and `Model::derivatives_each`,
/// through `derivatives_lanes_with`, four states at a time; and
/// `Model::LOCKSTEP` (nothing for a model without lanes: the default
/// loops, and studies one case at a time).
pub(super) fn batch(be: &BlockEmitter<'_>) -> TokenStream {
    if !has_lanes(be.prog) {
        return TokenStream::new();
    }
    let rt = &be.rt;
    let n_states = Literal::usize_unsuffixed(be.prog.states().len());
    let k = Literal::usize_unsuffixed(lane_values::len(be.prog));
    let lanes = quote!(#rt::batch::LANES);
    let lanes_ty = quote!(#rt::Lanes<{ #lanes }>);
    quote! {
        const LOCKSTEP: bool = true;

        fn derivatives_batch(
            &mut self,
            t: f64,
            x: &[[f64; #n_states]],
            dx: &mut [[f64; #n_states]],
            status: &mut [Result<(), #rt::ModelError>],
        ) {
            let v = Self::values_in_lanes([&*self; #lanes]);
            #rt::__private::in_lanes::<Self, { #lanes }, #n_states>(
                self,
                t,
                x,
                dx,
                status,
                |model, t, x, dx| model.derivatives_lanes_with(&v, t, x, dx),
            )
        }

        const LANE_VALUES: usize = #k;

        fn lane_values(models: &[Self], values: &mut [#lanes_ty]) {
            #rt::__private::values_in_groups::<Self, { #lanes }, #k>(
                models,
                values,
                Self::values_in_lanes::<{ #lanes }>,
            )
        }

        fn derivatives_each(
            models: &mut [Self],
            values: &[#lanes_ty],
            t: &[f64],
            x: &[[f64; #n_states]],
            dx: &mut [[f64; #n_states]],
            status: &mut [Result<(), #rt::ModelError>],
        ) {
            #rt::__private::each_in_lanes::<Self, { #lanes }, #k, #n_states>(
                models,
                values,
                t,
                x,
                dx,
                status,
                |model, v, t, x, dx| model.derivatives_lanes_with(v, t, x, dx),
            )
        }
    }
}
