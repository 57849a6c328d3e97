//! A hot function in two copies, one compiled for the target's baseline and
//! one for x86-64-v3, and the function that calls the right one (the
//! runtime's `fast_path!` and `dispatch!`, which reduce to the baseline
//! copy in builds that keep one: `no_std`, other targets, a target that
//! already has AVX2 and FMA).

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

/// A parameter of a multiversioned function: its pattern in the body's
/// signature (`_` when the body does not read it), the name the calling
/// function gives it, and its type.
pub(super) struct Param {
    pub pattern: TokenStream,
    pub name: Ident,
    pub ty: TokenStream,
}

/// What [`versions`] writes: the calling function's signature and body
/// (without visibility or docs, for an impl of the caller's choice), the
/// baseline copy (an inherent method, for the model's inherent impl), and
/// the items that go into the model's module before that impl: the macro
/// writing either copy, and the fast copy's module (`fast_path!`).
pub(super) struct Versions {
    pub caller: TokenStream,
    pub copies: TokenStream,
    pub items: TokenStream,
}

/// Functions of fewer operations keep one copy: there the instruction set
/// gains less than the dispatch costs. Measured with the chains of
/// `bench/peers` at default flags, both copies of one build, the baseline
/// forced with `allow_fast_path(false)`, ns per call, two interleaved runs
/// agreeing to 0.1 ns: chain-planar-2 16.9 on the baseline copy against
/// 17.7 dispatched to the x86-64-v3 copy, chain-spatial-2 20.9 against 21.7,
/// chain-spatial-3 (194 operations) 42.5 against 43.5; chain-planar-5
/// (317) 79.6 against 78.6, and from there up the x86-64-v3 copy wins
/// (chain-spatial-10, 2 046 operations: 329 against 287).
pub(super) const MIN_OPS_FOR_TWO_COPIES: usize = 200;

/// Whether the model's hot functions (`derivatives`, its `shared_terms`
/// and `derivatives_lanes`) have two copies: all or none, by the size of
/// `derivatives`, since the fast copy fuses and the baseline does not (a
/// lanes function gives the bits of single calls, on either copy).
pub(super) fn two_copies(prog: &crate::opt::Program) -> bool {
    let ops = prog.block(crate::opt::BlockKind::Derivatives).ops.total();
    ops >= MIN_OPS_FOR_TWO_COPIES
}

/// A multiversioned function's signature: its name, generic parameters
/// (`<const L: usize>` or nothing), receiver (`&self`, `&mut self`),
/// parameters and return type (`-> T` or nothing); and the head of the
/// impl it is a method in (`<E: Externs> Model<E>`, for the fast copy's).
pub(super) struct Signature<'a> {
    pub impl_head: &'a TokenStream,
    pub name: &'a str,
    pub generics: TokenStream,
    pub receiver: TokenStream,
    pub params: &'a [Param],
    pub ret: TokenStream,
}

/// `name` with `receiver` (`&self`, `&mut self`), `params` and `ret` (`->
/// T` or nothing), computing `body`: [`versions_of`] without generics.
#[allow(clippy::too_many_arguments)]
pub(super) fn versions(
    rt: &TokenStream,
    two_copies: bool,
    impl_head: &TokenStream,
    name: &str,
    receiver: TokenStream,
    params: &[Param],
    ret: TokenStream,
    body: TokenStream,
) -> Versions {
    let signature = Signature {
        impl_head,
        name,
        generics: TokenStream::new(),
        receiver,
        params,
        ret,
    };
    versions_of(rt, two_copies, &signature, body)
}

/// The function of `signature` computing `body`: a module-level macro
/// `<name>_copy!(#[attrs] vis fn_name)` writing the whole function (the
/// signature with the body, so that `self` and the parameters are the
/// macro's own names); `<name>_baseline`, `#[inline(always)]`, the macro
/// in the model's inherent impl; `<name>_fast`, the macro expanded by the
/// runtime's `fast_path!` in a child module `<name>_v3` that imports the
/// fused `MulAdd` and math functions (the same operations, each
/// `add_mul` and `sub_mul` rounded once, as in a build whose target has
/// FMA); `name` calls one of them. With `two_copies` false, `name`
/// computes `body` itself.
pub(super) fn versions_of(
    rt: &TokenStream,
    two_copies: bool,
    signature: &Signature<'_>,
    body: TokenStream,
) -> Versions {
    let Signature {
        impl_head,
        name,
        generics,
        receiver,
        params,
        ret,
    } = signature;
    let (call, baseline, fast) = (
        format_ident!("{name}"),
        format_ident!("{name}_baseline"),
        format_ident!("{name}_fast"),
    );
    let (copy, module) = (format_ident!("{name}_copy"), format_ident!("{name}_v3"));
    let patterns = params.iter().map(|p| &p.pattern);
    let names: Vec<&Ident> = params.iter().map(|p| &p.name).collect();
    let types: Vec<&TokenStream> = params.iter().map(|p| &p.ty).collect();
    if !two_copies {
        return Versions {
            caller: quote! {
                fn #call #generics(#receiver, #(#patterns: #types),*) #ret {
                    #body
                }
            },
            copies: TokenStream::new(),
            items: TokenStream::new(),
        };
    }
    let baseline_doc = format!(" `{name}` compiled for the target's baseline.");
    let fast_doc = format!(
        " `{name}` compiled for x86-64-v3 (AVX2, FMA): the same operations, \
         each `add_mul` fused."
    );
    Versions {
        caller: quote! {
            fn #call #generics(#receiver, #(#names: #types),*) #ret {
                #rt::__private::dispatch!(self.#fast(#(#names),*), self.#baseline(#(#names),*))
            }
        },
        copies: quote! {
            #copy! {
                #[doc = #baseline_doc]
                #[inline(always)]
                #baseline
            }
        },
        items: quote! {
            macro_rules! #copy {
                ($(#[$attr:meta])* $vis:vis $name:ident) => {
                    $(#[$attr])*
                    $vis fn $name #generics(#receiver, #(#patterns: #types),*) #ret {
                        #body
                    }
                };
            }

            #rt::__private::fast_path! {
                #[doc = #fast_doc]
                #copy => #fast in mod #module for impl #impl_head
            }
        },
    }
}
