//! One build, three instruction sets: the hot generated functions are
//! compiled for the target's baseline and, on x86-64 with `std`, twice
//! more, for x86-64-v3 (AVX2, FMA, BMI1/2, F16C, LZCNT, MOVBE) and for
//! x86-64-v4 (v3 with AVX-512 F, BW, CD, DQ, VL), and each call takes the
//! most capable copy the running processor can run.
//!
//! Generated code writes the fast copies inside [`fast_path!`](crate::fast_path)
//! and calls through [`dispatch!`](crate::dispatch); both are macros of this
//! crate so that *its* configuration decides: with the `std` feature on an
//! x86-64 target that does not already assume AVX2 and FMA (a default
//! build: `x86-64` baseline, SSE2), `fast_path!` compiles its function
//! with `#[target_feature]` and `dispatch!` branches on [`path`]; in every
//! other build (`no_std`, aarch64 and other targets, or a build whose
//! target already has AVX2 and FMA, e.g. `-C target-cpu=native` on a
//! recent x86-64, which compiles its one copy for that processor)
//! `fast_path!` emits nothing and `dispatch!` calls the baseline copy.
//! `is_x86_feature_detected!` needs `std`, which is why `no_std` builds
//! keep one copy.
//!
//! The copies are one body (the model module's `<name>_copy!` macro,
//! expanded three times), so they compute the same operations in the same
//! order. The baseline copy, in the model's module, calls
//! [`MulAdd`](super::MulAdd), which fuses by the *crate's* target
//! features (not in a default build), and the compiler never contracts a
//! multiply and an add on its own. The fast copies are expanded in child
//! modules that import [`fused`](super::fused)'s `MulAdd`, `math` and
//! `lanes_math` by name: each `add_mul` and `sub_mul` there, and each in
//! the branch-free sines, is one fused multiply-add. So each path gives
//! fixed bits: the x86-64-v3 and x86-64-v4 copies the same ones, those of
//! a build whose target has FMA (`-C target-cpu=x86-64-v3` or `native`),
//! which keeps one copy and fuses the same products; the baseline those
//! of a plain x86-64 build; the two kinds differ in the last bits
//! (`tests/dispatch.rs` checks that they agree to a few roundings and
//! give the same errors, and that the two fast copies agree to the bit).
//! The x86-64-v3 copy gains the fused multiply-adds and the instruction
//! set (three-operand AVX encodings, 256-bit vectors for the sines in
//! lanes, BMI); the x86-64-v4 copy, in addition, 32 vector registers
//! instead of 16 (fewer spills in long bodies) and AVX-512's
//! instructions. With the runtime's `libm` feature no copy fuses (the bits
//! of a `no_std` build).

#[cfg(all(feature = "std", target_arch = "x86_64"))]
pub use detect::{Path, limit_path, path};

/// Which copy the processor can run, asked once.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
mod detect {
    use core::sync::atomic::{AtomicU8, Ordering};

    /// A copy of a generated function, least capable first.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
    pub enum Path {
        /// The target's baseline (a default build: SSE2).
        Baseline,
        /// x86-64-v3: AVX2, FMA, BMI1/2, F16C, LZCNT, MOVBE.
        V3,
        /// x86-64-v4: x86-64-v3 with AVX-512 F, BW, CD, DQ, VL.
        V4,
    }

    /// What [`path`] found: `UNKNOWN` (not yet asked) or a [`Path`] as
    /// [`encode`] writes it.
    static LEVEL: AtomicU8 = AtomicU8::new(UNKNOWN);
    /// The most capable copy calls may take ([`limit_path`]), encoded.
    static LIMIT: AtomicU8 = AtomicU8::new(V4);
    const UNKNOWN: u8 = 0;
    const BASELINE: u8 = 1;
    const V3: u8 = 2;
    const V4: u8 = 3;

    /// `path` as [`LEVEL`] and [`LIMIT`] hold it.
    const fn encode(path: Path) -> u8 {
        match path {
            Path::Baseline => BASELINE,
            Path::V3 => V3,
            Path::V4 => V4,
        }
    }

    /// The path [`encode`] wrote, `None` for `UNKNOWN`.
    #[inline(always)]
    const fn decode(level: u8) -> Option<Path> {
        match level {
            V4 => Some(Path::V4),
            V3 => Some(Path::V3),
            BASELINE => Some(Path::Baseline),
            _ => None,
        }
    }

    /// The most capable copy the running processor has every feature of
    /// (within [`limit_path`]'s limit): asked once (`std`'s
    /// `is_x86_feature_detected!`), then one relaxed atomic load per call.
    #[inline(always)]
    pub fn path() -> Path {
        match decode(LEVEL.load(Ordering::Relaxed)) {
            Some(path) => path,
            None => detect(),
        }
    }

    /// Asks the processor and caches the answer (two threads asking at
    /// once store the same value).
    #[cold]
    #[inline(never)]
    fn detect() -> Path {
        let v3 = std::is_x86_feature_detected!("avx")
            && std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("fma")
            && std::is_x86_feature_detected!("bmi1")
            && std::is_x86_feature_detected!("bmi2")
            && std::is_x86_feature_detected!("f16c")
            && std::is_x86_feature_detected!("lzcnt")
            && std::is_x86_feature_detected!("movbe")
            && std::is_x86_feature_detected!("popcnt");
        let v4 = v3
            && std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512bw")
            && std::is_x86_feature_detected!("avx512cd")
            && std::is_x86_feature_detected!("avx512dq")
            && std::is_x86_feature_detected!("avx512vl");
        let found = match (v4, v3) {
            (true, _) => Path::V4,
            (false, true) => Path::V3,
            (false, false) => Path::Baseline,
        };
        let limit = decode(LIMIT.load(Ordering::Relaxed)).unwrap_or(Path::V4);
        let chosen = found.min(limit);
        LEVEL.store(encode(chosen), Ordering::Relaxed);
        chosen
    }

    /// Lets calls take no copy more capable than `limit` for the rest of
    /// the process (`Path::V4`: whatever the processor has): for tests
    /// that compare the paths. A limit above what the processor has
    /// changes nothing.
    pub fn limit_path(limit: Path) {
        LIMIT.store(encode(limit), Ordering::Relaxed);
        LEVEL.store(UNKNOWN, Ordering::Relaxed);
    }
}

/// How the multiversioned functions write their results,
/// `results::set(&mut dx[3], a)` (a module, so that no name of the model
/// can shadow it), except in the x86-64-v4 copy, which takes
/// [`results_alone`] under that name.
pub mod results {
    /// `*slot = value`.
    #[inline(always)]
    pub fn set<T>(slot: &mut T, value: T) {
        *slot = value;
    }
}

/// The x86-64-v4 copy's [`results`]: each value a store of its own.
pub mod results_alone {
    /// Writes `value` to `slot` as a store of its own (a volatile write,
    /// which the compiler neither merges with its neighbours nor removes).
    ///
    /// In a function compiled with AVX-512 (`#[target_feature]`), LLVM's
    /// vectorizer merges runs of eight neighbouring stores (`dx[0] = u1;
    /// … dx[7] = u8;`, the accelerations as they are finished) into
    /// 512-bit vectors, and no stable attribute asks it for 256 bits at
    /// most (`-C target-cpu=x86-64-v4` does); on Intel's cores a 512-bit
    /// instruction in flight closes a vector port, and the whole function
    /// runs slower: chain-planar-10 212 → 158 ns per call with this, in a
    /// default-flags build on a Xeon (Sapphire Rapids), the speed of a
    /// `-C target-cpu=native` build (`bench/results/compiler-choices.md`).
    #[inline(always)]
    pub fn set<T>(slot: &mut T, value: T) {
        // SAFETY: `slot` is a valid, aligned, exclusive reference.
        unsafe { core::ptr::write_volatile(slot, value) }
    }
}

/// The macros where this build has three copies: `std`, x86-64, a target
/// without AVX2 and FMA.
#[cfg(all(
    feature = "std",
    target_arch = "x86_64",
    not(all(target_feature = "avx2", target_feature = "fma"))
))]
mod three_copies {
    /// A fast copy of a generated function: `fast_path!(#[doc = ".."] v3
    /// copy => name in mod module for impl <G> Type<G> where ..)` (or
    /// `v4`) declares `module`, a child of the model's module that sees
    /// its items (`use super::*`) but imports the fused
    /// [`MulAdd`](crate::float::fused::MulAdd), `math` and `lanes_math` by
    /// name, shadowing the model module's plain ones (and, for `v4`,
    /// [`results_alone`](super::results_alone) as `results`), and expands there
    /// the model's `copy!` macro, which writes the whole function
    /// (signature and body) under the name `name`, `pub(super)`, with
    /// `#[target_feature]` of x86-64-v3 (or x86-64-v4).
    #[doc(hidden)]
    #[macro_export]
    macro_rules! fast_path {
        ($(#[$attr:meta])* v3 $($rest:tt)*) => {
            $crate::fast_path! {
                @features "avx,avx2,fma,bmi1,bmi2,f16c,lzcnt,movbe,popcnt"
                @results results
                $(#[$attr])* $($rest)*
            }
        };
        ($(#[$attr:meta])* v4 $($rest:tt)*) => {
            $crate::fast_path! {
                @features "avx,avx2,fma,bmi1,bmi2,f16c,lzcnt,movbe,popcnt,\
                           avx512f,avx512bw,avx512cd,avx512dq,avx512vl"
                @results results_alone
                $(#[$attr])* $($rest)*
            }
        };
        (
            @features $features:literal
            @results $results:ident
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
                #[allow(unused_imports)]
                use $crate::__private::$results as results;

                impl $($head)* {
                    $copy! {
                        $(#[$attr])*
                        #[target_feature(enable = $features)]
                        pub(super) $fast
                    }
                }
            }
        };
    }

    /// `dispatch!(v4_call, v3_call, baseline_call)`: the most capable copy
    /// the processor can run (asked once); `dispatch!(v3_call,
    /// baseline_call)` for a function without an x86-64-v4 copy.
    #[doc(hidden)]
    #[macro_export]
    macro_rules! dispatch {
        ($v3:expr, $baseline:expr) => {
            match $crate::__private::path() {
                // SAFETY: the processor has every feature of x86-64-v3,
                // which the copy was compiled for (`path`).
                $crate::__private::Path::V4 | $crate::__private::Path::V3 => unsafe { $v3 },
                $crate::__private::Path::Baseline => $baseline,
            }
        };
        ($v4:expr, $v3:expr, $baseline:expr) => {
            match $crate::__private::path() {
                // SAFETY: the processor has every feature of x86-64-v4,
                // which the copy was compiled for (`path`).
                $crate::__private::Path::V4 => unsafe { $v4 },
                // SAFETY: as above, x86-64-v3.
                $crate::__private::Path::V3 => unsafe { $v3 },
                $crate::__private::Path::Baseline => $baseline,
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
    /// A fast copy of a generated function: nothing in this build.
    #[doc(hidden)]
    #[macro_export]
    macro_rules! fast_path {
        ($($item:tt)*) => {};
    }

    /// `dispatch!(v4_call, v3_call, baseline_call)` or `dispatch!(v3_call,
    /// baseline_call)`: the baseline call.
    #[doc(hidden)]
    #[macro_export]
    macro_rules! dispatch {
        ($v3:expr, $baseline:expr) => {
            $baseline
        };
        ($v4:expr, $v3:expr, $baseline:expr) => {
            $baseline
        };
    }
}
