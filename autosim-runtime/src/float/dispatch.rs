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
//! Both copies inline the same `#[inline(always)]` body, so they compute
//! the same operations in the same order: [`MulAdd`](super::MulAdd)
//! decides fusing by the *crate's* target features, which the fast copy
//! does not change, so it does not fuse either, and the compiler never
//! contracts a multiply and an add on its own. The two paths therefore
//! give the same bits (`tests/dispatch.rs` compares them); what the fast
//! copy gains is the instruction set (three-operand AVX encodings, 256-bit
//! vectors for the sines in lanes, BMI), not a different rounding. A build
//! with FMA in its target features fuses where generated code asks for it,
//! as before, and then gives different bits from a default build.

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
    /// The fast copy of a generated function, compiled for x86-64-v3.
    #[doc(hidden)]
    #[macro_export]
    macro_rules! fast_path {
        ($(#[$attr:meta])* fn $($rest:tt)*) => {
            $(#[$attr])*
            #[target_feature(enable = "avx,avx2,fma,bmi1,bmi2,f16c,lzcnt,movbe,popcnt")]
            fn $($rest)*
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
