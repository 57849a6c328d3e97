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
/// (without visibility or docs, for an impl of the caller's choice), and
/// the two copies (private inherent methods).
pub(super) struct Versions {
    pub caller: TokenStream,
    pub copies: TokenStream,
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

/// A multiversioned function's signature: its name, generic parameters
/// (`<const L: usize>` or nothing), receiver (`&self`, `&mut self`),
/// parameters and return type (`-> T` or nothing).
pub(super) struct Signature<'a> {
    pub name: &'a str,
    pub generics: TokenStream,
    pub receiver: TokenStream,
    pub params: &'a [Param],
    pub ret: TokenStream,
}

/// `name` with `receiver` (`&self`, `&mut self`), `params` and `ret` (`->
/// T` or nothing), computing `body`: [`versions_of`] without generics.
pub(super) fn versions(
    rt: &TokenStream,
    two_copies: bool,
    name: &str,
    receiver: TokenStream,
    params: &[Param],
    ret: TokenStream,
    body: TokenStream,
) -> Versions {
    let signature = Signature {
        name,
        generics: TokenStream::new(),
        receiver,
        params,
        ret,
    };
    versions_of(rt, two_copies, &signature, body)
}

/// The function of `signature` computing `body`: the body once,
/// `#[inline(always)]`, in `<name>_baseline`; `<name>_fast` compiled for
/// x86-64-v3 calling it, so both copies are the same operations in the
/// same order; `name` calls one of them. With `two_copies` false, `name`
/// computes `body` itself.
pub(super) fn versions_of(
    rt: &TokenStream,
    two_copies: bool,
    signature: &Signature<'_>,
    body: TokenStream,
) -> Versions {
    let Signature {
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
    let patterns = params.iter().map(|p| &p.pattern);
    let names: Vec<&Ident> = params.iter().map(|p| &p.name).collect();
    let types: Vec<&TokenStream> = params.iter().map(|p| &p.ty).collect();
    if !two_copies {
        let patterns = params.iter().map(|p| &p.pattern);
        return Versions {
            caller: quote! {
                fn #call #generics(#receiver, #(#patterns: #types),*) #ret {
                    #body
                }
            },
            copies: TokenStream::new(),
        };
    }
    let baseline_doc = format!(" `{name}` compiled for the target's baseline.");
    let fast_doc = format!(" `{name}` compiled for x86-64-v3 (AVX2, FMA): the same operations.");
    Versions {
        caller: quote! {
            fn #call #generics(#receiver, #(#names: #types),*) #ret {
                #rt::__private::dispatch!(self.#fast(#(#names),*), self.#baseline(#(#names),*))
            }
        },
        copies: quote! {
            #[doc = #baseline_doc]
            #[inline(always)]
            fn #baseline #generics(#receiver, #(#patterns: #types),*) #ret {
                #body
            }

            #rt::__private::fast_path! {
                #[doc = #fast_doc]
                fn #fast #generics(#receiver, #(#names: #types),*) #ret {
                    self.#baseline(#(#names),*)
                }
            }
        },
    }
}
