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
/// gains less than the dispatch costs (chain-spatial-1: 7 operations and a
/// libm sine). With the fast copy fusing, small models gain too; measured
/// with the chains of `bench/peers` at default flags, three interleaved
/// runs, ns per call, this threshold against 200 against a
/// `-C target-cpu=x86-64-v3` build: chain-planar-2 15.1 / 16.6–17.5 /
/// 14.8, chain-spatial-2 18.2 / 21.0 / 18.0, chain-spatial-3 (194
/// operations) 39.5–41.7 / 44.0–44.5 / 38.9–40.8, chain-planar-5 (317)
/// and chain-spatial-10 equal. (Before the fast copy fused, the baseline
/// copy won below about 200 operations.)
pub(super) const MIN_OPS_FOR_TWO_COPIES: usize = 40;

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
