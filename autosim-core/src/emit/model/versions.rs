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

/// Functions of fewer operations keep one copy: the instruction set has
/// nothing to gain there (chain-spatial-1, 7 operations and a libm sine,
/// measured 6.5 ns with two copies and 6.2 ns with one at default flags,
/// `bench/peers/results-default.md`).
pub(super) const MIN_OPS_FOR_TWO_COPIES: usize = 40;

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
