//! A hot function in three copies, compiled for the target's baseline, for
//! x86-64-v3 and for x86-64-v4, and the function that calls the right one
//! (the runtime's `fast_path!` and `dispatch!`, which reduce to the
//! baseline copy in builds that keep one: `no_std`, other targets, a
//! target that already has AVX2 and FMA).

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
/// libm sine). Measured with the baseline and x86-64-v3 copies alone
/// (before the x86-64-v4 copy, which gains 3-11 % more from 194
/// operations, chain-spatial-3, up: `copies`'s measurement). With the
/// fast copy fusing, small models gain too; measured with the chains of
/// `bench/peers` at default flags, three interleaved
/// runs, ns per call, this threshold against 200 against a
/// `-C target-cpu=x86-64-v3` build: chain-planar-2 15.1 / 16.6–17.5 /
/// 14.8, chain-spatial-2 18.2 / 21.0 / 18.0, chain-spatial-3 (194
/// operations) 39.5–41.7 / 44.0–44.5 / 38.9–40.8, chain-planar-5 (317)
/// and chain-spatial-10 equal. (Before the fast copy fused, the baseline
/// copy won below about 200 operations.)
pub(super) const MIN_OPS_FOR_FAST_COPIES: usize = 40;

/// Which copies of a hot function a model has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Copies {
    /// The function itself, no dispatch.
    One,
    /// The baseline and x86-64-v3.
    UpToV3,
    /// The baseline, x86-64-v3 and x86-64-v4.
    UpToV4,
}

/// The copies of the model's single-state hot functions (`derivatives` and
/// its `shared_terms`): all or none, by the size of `derivatives`, since
/// the fast copies fuse and the baseline does not. The x86-64-v4 copy
/// (32 vector registers: fewer spills) against the x86-64-v3 copy, ns per
/// call, 512 random states, medians of 60 interleaved rounds in one
/// default-flags build on the AMD EPYC (Zen 4) of 2026-12-05:
/// chain-spatial-3 41.9 against 44.1, chain-planar-10 188 / 198,
/// chain-spatial-10 266 / 300, chain-spatial-20 802 / 870, chain-spatial-50
/// 2 236 / 2 407, the satellite 172 / 179, the bicycle 292 / 307 (the
/// baseline copy: 51, 241, 365, 1 115, 3 098, 205, 516). Its price is
/// compile time: a release build of a crate calling the model's
/// `derivatives` and `derivatives_batch` (`bench/compile`),
/// chain-spatial-10 0.79 → 0.94 s, chain-spatial-50 9.4 → 13.3 s, the
/// bicycle 0.62 → 0.84 s.
pub(super) fn copies(prog: &crate::opt::Program) -> Copies {
    let ops = prog.block(crate::opt::BlockKind::Derivatives).ops.total();
    if ops >= MIN_OPS_FOR_FAST_COPIES {
        Copies::UpToV4
    } else {
        Copies::One
    }
}

/// The copies of `derivatives_lanes_with` (the lanes function): those of
/// `derivatives` but
/// x86-64-v4, whose copy fuses the same products as x86-64-v3's (the same
/// bits) and was no faster in lanes: `derivatives_batch` per state,
/// x86-64-v3 against x86-64-v4 copy, 512 random states, medians of 60
/// interleaved rounds on the AMD EPYC (Zen 4) of 2026-12-05:
/// chain-spatial-10 126 against 147 ns, the satellite 73 against 74 ns
/// (one state per call, the x86-64-v4 copy gains 3-11 %: 300 against 266
/// ns for chain-spatial-10). And each copy costs compile time: with it,
/// a release build of a crate calling chain-spatial-10 with lanes took
/// 12.6 s instead of 8.5 s.
pub(super) fn lanes_copies(prog: &crate::opt::Program) -> Copies {
    match copies(prog) {
        Copies::UpToV4 => Copies::UpToV3,
        copies => copies,
    }
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
    copies: Copies,
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
    versions_of(rt, copies, &signature, body)
}

/// The function of `signature` computing `body`: a module-level macro
/// `<name>_copy!(#[attrs] vis fn_name)` writing the whole function (the
/// signature with the body, so that `self` and the parameters are the
/// macro's own names); `<name>_baseline`, `#[inline(always)]` in builds
/// without debug assertions (in a debug build the dispatcher calls it,
/// so that its frame, big there, is not on the stack under a fast
/// copy's), the macro
/// in the model's inherent impl; `<name>_v3` and `<name>_v4`, the macro
/// expanded by the runtime's `fast_path!` in child modules
/// `<name>_x86_64_v3` and `<name>_x86_64_v4` that import the fused
/// `MulAdd` and math functions (the same operations, each `add_mul` and
/// `sub_mul` rounded once, as in a build whose target has FMA), the last
/// only with [`Copies::UpToV4`]; `name` calls one of them. With
/// [`Copies::One`], `name` computes `body` itself.
pub(super) fn versions_of(
    rt: &TokenStream,
    copies: Copies,
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
    let (call, baseline, v3, v4) = (
        format_ident!("{name}"),
        format_ident!("{name}_baseline"),
        format_ident!("{name}_v3"),
        format_ident!("{name}_v4"),
    );
    let copy = format_ident!("{name}_copy");
    let (v3_module, v4_module) = (
        format_ident!("{name}_x86_64_v3"),
        format_ident!("{name}_x86_64_v4"),
    );
    let patterns = params.iter().map(|p| &p.pattern);
    let names: Vec<&Ident> = params.iter().map(|p| &p.name).collect();
    let types: Vec<&TokenStream> = params.iter().map(|p| &p.ty).collect();
    if copies == Copies::One {
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
    let fast_doc = |level: &str| {
        format!(
            " `{name}` compiled for {level}: the same operations, each \
             `add_mul` fused."
        )
    };
    let (v3_doc, v4_doc) = (
        fast_doc("x86-64-v3 (AVX2, FMA)"),
        fast_doc("x86-64-v4 (AVX-512)"),
    );
    let (fast_calls, v4_item) = match copies {
        Copies::UpToV4 => (
            vec![quote!(self.#v4(#(#names),*)), quote!(self.#v3(#(#names),*))],
            quote! {
                #rt::__private::fast_path! {
                    #[doc = #v4_doc]
                    v4 #copy => #v4 in mod #v4_module for impl #impl_head
                }
            },
        ),
        _ => (vec![quote!(self.#v3(#(#names),*))], TokenStream::new()),
    };
    Versions {
        caller: quote! {
            fn #call #generics(#receiver, #(#names: #types),*) #ret {
                #rt::__private::dispatch!(#(#fast_calls,)* self.#baseline(#(#names),*))
            }
        },
        copies: quote! {
            #copy! {
                #[doc = #baseline_doc]
                #[cfg_attr(not(debug_assertions), inline(always))]
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
                #[doc = #v3_doc]
                v3 #copy => #v3 in mod #v3_module for impl #impl_head
            }

            #v4_item
        },
    }
}
