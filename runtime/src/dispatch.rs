//! The hot loops compiled twice on x86-64: once for the target the crate is built for, once
//! for the x86-64-v3 level (AVX2 and BMI2, as on every x86-64 CPU since 2013–2015), chosen at
//! run time by the CPU ([`fastest`]). The twins: Newton's method (`newton.rs`), the chord
//! correction's residual and solve (`correction.rs`), the tracker's fast path (`tracker.rs`;
//! [`fastest_or`], for its plain build calls two solves that the twin inlines) and the
//! all-modes sparse LU's factorisation and solve (`modes/sparse_lu.rs`).
//!
//! Why: the default x86-64 target has SSE2's two-operand instructions only, and an operation
//! that must keep its source costs a register copy first; the generated factorisation keeps
//! about forty values live on sixteen registers. AVX's three-operand forms need no copies.
//! Measured with `count` under callgrind (BENCHMARKS.md, Instruction counts): Newton–Raphson
//! 694 797 → 616 593 instructions on the 100 normal Table V points, the tracker 5 856 448 →
//! 5 110 252 on the 2 s trajectory.
//!
//! The twin performs the same operations in the same order: FMA is not enabled, and Rust
//! never fuses a·b + c by itself, so both give the same results, bit for bit
//! (`linkage_examples::twins` compares them: in the tests, and in a release build by CI).
//!
//! Only with the `std` feature, whose `is_x86_feature_detected!` knows whether the operating
//! system saves the AVX registers; a `no_std` build runs the code it was built for (choose
//! it with `-C target-cpu`), as does a build whose target already has AVX2.

/// Runs `f` compiled for x86-64-v3 where the CPU has that level, else as built. `f` should be
/// a closure marked `#[inline(always)]` around a function marked so too: only what is inlined
/// into the twin is compiled for it.
#[inline(always)]
pub(crate) fn fastest<R>(f: impl FnOnce() -> R) -> R {
    if v3::TWIN && v3::chosen() {
        // SAFETY: the one condition of calling a `#[target_feature]` function, that the CPU
        // has its features, is what `chosen` has checked (it is never true otherwise). Worth
        // its `unsafe`: see the measurements above. (Where there is no twin, `run` is a safe
        // function and this branch is compiled out.)
        #[allow(unsafe_code, unused_unsafe)]
        return unsafe { v3::run(f) };
    }
    f()
}

/// Runs `twin` compiled for x86-64-v3 where the CPU has that level, and `plain` as built where
/// it has not: [`fastest`] for work best written differently for the two (both should be
/// `#[inline(always)]` closures), given `args` (what both would borrow). Where there is no
/// twin (a `no_std` build, another architecture, a build for AVX2) `twin` runs as built: the
/// plain x86-64 level is the one `plain` was measured on.
#[inline(always)]
pub(crate) fn fastest_or<A, R>(
    args: A,
    twin: impl FnOnce(A) -> R,
    plain: impl FnOnce(A) -> R,
) -> R {
    if v3::TWIN && !v3::chosen() {
        return plain(args);
    }
    fastest(
        #[inline(always)]
        || twin(args),
    )
}

/// Whether the solvers run their x86-64-v3 twin on this machine: `true` on an x86-64 CPU
/// with AVX2 and BMI2 in a build with the `std` feature (or one built for that level).
///
/// ```
/// // Either way the answers are the same, bit for bit; only the speed differs.
/// println!("x86-64-v3 twin: {}", linkage::uses_x86_64_v3());
/// ```
pub fn uses_x86_64_v3() -> bool {
    v3::chosen()
}

/// Runs the twin (`true`, where the CPU has it) or the code as built (`false`) from now on,
/// in every thread; returns whether the twin is chosen. For the tests that compare the two.
pub fn prefer_x86_64_v3(twin: bool) -> bool {
    v3::prefer(twin)
}

/// Where there is no twin: a `no_std` build, another architecture, or a build whose target
/// already has AVX2 (it is then what runs).
#[cfg(not(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2"))))]
mod v3 {
    pub(super) const TWIN: bool = false;

    pub(super) fn chosen() -> bool {
        cfg!(all(target_arch = "x86_64", target_feature = "avx2"))
    }

    pub(super) fn prefer(twin: bool) -> bool {
        twin && chosen()
    }

    #[inline(always)]
    pub(super) fn run<R>(f: impl FnOnce() -> R) -> R {
        f()
    }
}

#[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
mod v3 {
    use core::sync::atomic::{AtomicU8, Ordering};

    pub(super) const TWIN: bool = true;

    const UNKNOWN: u8 = 0;
    const NO: u8 = 1;
    const YES: u8 = 2;

    /// Checked once, then one load per call instead of the ten checks of
    /// `is_x86_feature_detected!`.
    static CHOICE: AtomicU8 = AtomicU8::new(UNKNOWN);

    #[inline(always)]
    pub(super) fn chosen() -> bool {
        match CHOICE.load(Ordering::Relaxed) {
            UNKNOWN => detect(),
            choice => choice == YES,
        }
    }

    pub(super) fn prefer(twin: bool) -> bool {
        let yes = twin && detect();
        CHOICE.store(if yes { YES } else { NO }, Ordering::Relaxed);
        yes
    }

    #[cold]
    #[inline(never)]
    fn detect() -> bool {
        use std::is_x86_feature_detected as has;
        // Every feature `run` is compiled with.
        let yes = has!("avx")
            && has!("avx2")
            && has!("bmi1")
            && has!("bmi2")
            && has!("lzcnt")
            && has!("popcnt")
            && has!("sse3")
            && has!("ssse3")
            && has!("sse4.1")
            && has!("sse4.2");
        CHOICE.store(if yes { YES } else { NO }, Ordering::Relaxed);
        yes
    }

    /// `f`, with what is inlined into it, compiled for x86-64-v3 without FMA.
    #[target_feature(enable = "avx,avx2,bmi1,bmi2,lzcnt,popcnt,sse3,ssse3,sse4.1,sse4.2")]
    pub(super) fn run<R>(f: impl FnOnce() -> R) -> R {
        f()
    }
}
