//! One build, two instruction sets: the hot generated functions are
//! compiled for the target's baseline and, on x86-64 with `std`, once more
//! for x86-64-v3 (AVX2, FMA, BMI1/2, F16C, LZCNT, MOVBE), and each call
//! takes the second where the running processor has it.
//!
//! Generated code writes the fast copy inside [`fast_path!`](crate::fast_path)
//! and calls through [`dispatch!`](crate::dispatch); both are macros of this
//! crate so that *its* configuration decides: with the `std` feature on an
//! x86-64 target that does not already assume AVX2 and FMA (a default
//! build: `x86-64` baseline, SSE2), `fast_path!` compiles its function
//! with `#[target_feature]` and `dispatch!` branches on [`has_v3`]; in every
//! other build (`no_std`, aarch64 and other targets, or a build whose
//! target already has AVX2 and FMA, e.g. `-C target-cpu=native` on a
//! recent x86-64) `fast_path!` emits nothing and `dispatch!` calls the
//! baseline copy. `is_x86_feature_detected!` needs `std`, which is why
//! `no_std` builds keep one copy.
//!
//! Both copies are one body (the model module's `<name>_copy!` macro,
//! expanded twice), so they compute the same operations in the same
//! order. The baseline copy, in the model's module, calls
//! [`MulAdd`](super::MulAdd), which fuses by the *crate's* target
//! features (not in a default build), and the compiler never contracts a
//! multiply and an add on its own. The fast copy is expanded in a child
//! module that imports [`fused`](super::fused)'s `MulAdd`, `math` and
//! `lanes_math` by name: each `add_mul` and `sub_mul` there, and each in
//! the branch-free sines, is one fused multiply-add. So each path gives
//! fixed bits: the fast copy those of a build whose target has FMA
//! (`-C target-cpu=x86-64-v3` or `native`), which keeps one copy and
//! fuses the same products, the baseline those of a plain x86-64 build;
//! the two differ in the last bits (`tests/dispatch.rs` checks that they
//! agree to a few roundings and give the same errors). The fast copy
//! gains the fused multiply-adds and the instruction set (three-operand
//! AVX encodings, 256-bit vectors for the sines in lanes, BMI). With the
//! runtime's `libm` feature neither copy fuses (the bits of a `no_std`
//! build).

#[cfg(all(feature = "std", target_arch = "x86_64"))]
pub use detect::{allow_fast_path, has_v3};

/// Which copy the processor can run, asked once.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
mod detect {
    use core::sync::atomic::{AtomicU8, Ordering};

    /// What [`has_v3`] found: not yet asked, no, yes.
    static LEVEL: AtomicU8 = AtomicU8::new(UNKNOWN);
    const UNKNOWN: u8 = 0;
    const BASELINE: u8 = 1;
    const V3: u8 = 2;

    /// Whether the running processor has every feature of x86-64-v3 that
    /// [`fast_path!`](crate::fast_path) enables: asked once (`std`'s
    /// `is_x86_feature_detected!`), then one relaxed atomic load per call.
    #[inline(always)]
    pub fn has_v3() -> bool {
        match LEVEL.load(Ordering::Relaxed) {
            V3 => true,
            BASELINE => false,
            _ => detect(),
        }
    }

    /// Asks the processor and caches the answer (two threads asking at
    /// once store the same value).
    #[cold]
    #[inline(never)]
    fn detect() -> bool {
        let v3 = std::is_x86_feature_detected!("avx")
            && std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("fma")
            && std::is_x86_feature_detected!("bmi1")
            && std::is_x86_feature_detected!("bmi2")
            && std::is_x86_feature_detected!("f16c")
            && std::is_x86_feature_detected!("lzcnt")
            && std::is_x86_feature_detected!("movbe")
            && std::is_x86_feature_detected!("popcnt");
        LEVEL.store(if v3 { V3 } else { BASELINE }, Ordering::Relaxed);
        v3
    }

    /// Forces the baseline copy (`false`) or lets detection decide
    /// (`true`) for the rest of the process: for tests that compare the
    /// two paths. Asking for the fast copy on a processor without it keeps
    /// the baseline.
    pub fn allow_fast_path(allow: bool) {
        LEVEL.store(if allow { UNKNOWN } else { BASELINE }, Ordering::Relaxed);
    }
}

/// The macros where this build has two copies: `std`, x86-64, a target
/// without AVX2 and FMA.
#[cfg(all(
    feature = "std",
    target_arch = "x86_64",
    not(all(target_feature = "avx2", target_feature = "fma"))
))]
mod two_copies {
    /// The fast copy of a generated function, compiled for x86-64-v3:
    /// `fast_path!(#[doc = ".."] copy => name in mod module for impl <G>
    /// Type<G> where ..)` declares `module`, a child of the model's module
    /// that sees its items (`use super::*`) but imports the fused
    /// [`MulAdd`](crate::float::fused::MulAdd), `math` and `lanes_math` by
    /// name, shadowing the model module's plain ones, and expands there
    /// the model's `copy!` macro, which writes the whole function
    /// (signature and body) under the name `name`, `pub(super)`, with
    /// `#[target_feature]`.
    #[doc(hidden)]
    #[macro_export]
    macro_rules! fast_path {
        (
            $(#[$attr:meta])*
            $copy:ident => $fast:ident in mod $module:ident for impl $($head:tt)*
        ) => {
            // Dead where the model is (a model a program never builds):
            // the baseline copy, in the model's impl, is not warned there.
            #[allow(dead_code)]
            mod $module {
                #[allow(unused_imports)]
                use super::*;
                #[allow(unused_imports)]
                use $crate::__private::fused::{MulAdd, lanes_math, math};

                impl $($head)* {
                    $copy! {
                        $(#[$attr])*
                        #[target_feature(enable = "avx,avx2,fma,bmi1,bmi2,f16c,lzcnt,movbe,popcnt")]
                        pub(super) $fast
                    }
                }
            }
        };
    }

    /// `dispatch!(fast_call, baseline_call)`: the fast copy's call where
    /// the processor has x86-64-v3 (asked once), the baseline's otherwise.
    #[doc(hidden)]
    #[macro_export]
    macro_rules! dispatch {
        ($fast:expr, $baseline:expr) => {
            if $crate::__private::has_v3() {
                // SAFETY: the processor has every feature the fast copy
                // was compiled for (`has_v3`).
                unsafe { $fast }
            } else {
                $baseline
            }
        };
    }
}

/// The macros where this build keeps one copy.
#[cfg(not(all(
    feature = "std",
    target_arch = "x86_64",
    not(all(target_feature = "avx2", target_feature = "fma"))
)))]
mod one_copy {
    /// The fast copy of a generated function: nothing in this build.
    #[doc(hidden)]
    #[macro_export]
    macro_rules! fast_path {
        ($($item:tt)*) => {};
    }

    /// `dispatch!(fast_call, baseline_call)`: the baseline call.
    #[doc(hidden)]
    #[macro_export]
    macro_rules! dispatch {
        ($fast:expr, $baseline:expr) => {
            $baseline
        };
    }
}
