//! Explicit SIMD for zline: the one crate of the workspace where `unsafe`
//! is allowed, and only to call `std::arch` intrinsics.
//!
//! Policy:
//! - Every other crate forbids `unsafe` (`[workspace.lints.rust]
//!   unsafe_code = "forbid"`). This crate denies it too (its own `[lints]`
//!   table) and allows it only on the modules that call `std::arch`,
//!   `avx2` and `sse2`, on `prefetch` (the cache hint) and on `opaque`, whose one volatile read keeps
//!   LLVM from turning a kernel's read-blend-write into a masked store
//!   (`#[allow(unsafe_code, reason = …)]`).
//! - Every `unsafe` block carries a `// SAFETY:` comment saying why its
//!   preconditions hold (`clippy::undocumented_unsafe_blocks` is on), and
//!   every `unsafe fn` a `# Safety` section. The preconditions are always
//!   the same two: the CPU has the instructions, and every memory access
//!   lies inside its slice. The first is proved by a token that only run
//!   time detection makes (AVX2) or by the target itself (SSE2 is part of
//!   x86-64); the second by checking every index in safe code first.
//! - Every public function is safe and has a scalar twin in [`scalar`]
//!   that defines its result. The SIMD versions return the same bits for
//!   every input; property tests compare each kernel with its twin bit for
//!   bit, the ends of the slice included. When an index is out of range,
//!   the function runs the twin, which panics like slice indexing.
//! - The instruction set is detected at run time, once ([`Isa::current`]),
//!   so these functions need no `-C target-cpu` flag: a binary built for
//!   plain x86-64 runs the AVX2 kernels where the CPU has AVX2 and the
//!   SSE2 ones elsewhere. Only `x86_64` compiles the kernels
//!   (`#[cfg(target_arch = "x86_64")]`); other targets (aarch64) build the
//!   scalar twins alone.
//! - `ZLINE_SIMD=scalar` or `ZLINE_SIMD=sse2` in the environment lowers
//!   [`Isa::current`], to compare paths in one binary; it never raises it.
//!
//! The functions move data (loads and transposes); they do no arithmetic,
//! so equality with the twins is exact by construction, NaN payloads
//! included. Measurements: BENCHMARKS.md as of `138c02a^` ("Explicit SIMD";
//! `git show 138c02a^:BENCHMARKS.md`).

#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code, reason = "the AVX2 kernels call std::arch intrinsics (see the crate policy)")]
mod avx2;
mod bounds;
mod isa;
mod job;
#[allow(unsafe_code, reason = "the x86-64-v3 lanes call std::arch intrinsics (see the module)")]
pub mod lanes;
#[allow(
    unsafe_code,
    reason = "one volatile read that keeps LLVM from forming masked stores (see the module)"
)]
mod opaque;
#[allow(unsafe_code, reason = "the prefetch hint is an std::arch intrinsic (see the module)")]
mod prefetch;
pub mod scalar;
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
#[allow(unsafe_code, reason = "the SSE2 kernels call std::arch intrinsics (see the crate policy)")]
mod sse2;

/// Calls `$avx2` with the AVX2 token, `$sse2` or `$scalar` as
/// [`Isa::current`] says; where SSE2 (x86-64) or AVX2 code does not
/// exist, the scalar twin.
///
/// Only the path a build normally takes is inlined into the caller: a
/// build that targets AVX2 cannot run without it, so there the SSE2 path
/// (reachable only through `ZLINE_SIMD`) stays out of line. Inlining both
/// made the sampler 12 % slower (textured floor, x86-64-v3 build).
macro_rules! dispatch {
    (|$token:ident| $avx2:expr, $sse2:expr, $scalar:expr) => {{
        #[cfg(target_arch = "x86_64")]
        if let Some($token) = avx2::token() {
            return $avx2;
        }
        #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
        if Isa::current() == Isa::Sse2 {
            return if cfg!(target_feature = "avx2") { out_of_line(|| $sse2) } else { $sse2 };
        }
        out_of_line(|| $scalar)
    }};
}

/// The four channels of texel `idx[k]` in lane k: channel c of the result
/// holds `texels[idx[k]][c]` at position k. Panics, like slice indexing,
/// when an index is negative or not below `texels.len()`.
#[inline(always)]
pub fn gather_texels_x8(texels: &[[f32; 4]], idx: [i32; 8]) -> [[f32; 8]; 4] {
    dispatch!(
        |avx2| avx2.gather_texels_x8(texels, idx),
        sse2::gather_texels_x8(texels, idx),
        scalar::gather_texels_x8(texels, idx)
    )
}

/// Two texels per lane, as channel vectors: element c (0 ≤ c < 4) of the
/// result holds channel c of `texels[a[k]]` at position k, element 4 + c
/// channel c of `texels[b[k]]`. Panics, like slice indexing, when an index
/// is negative or not below `texels.len()`.
#[inline(always)]
pub fn gather_texel_pairs_x8(texels: &[[f32; 4]], a: [i32; 8], b: [i32; 8]) -> [[f32; 8]; 8] {
    dispatch!(
        |avx2| avx2.gather_texel_pairs_x8(texels, a, b),
        sse2::gather_texel_pairs_x8(texels, a, b),
        scalar::gather_texel_pairs_x8(texels, a, b)
    )
}

/// Texels `a[k]` and `a[k] + 1` of every lane k: the same as
/// [`gather_texel_pairs_x8`] with `b[k] = a[k] + 1`, in half the loads
/// where the instruction set allows. Panics, like slice indexing, when an
/// `a[k]` is negative or `a[k] + 1` not below `texels.len()`.
#[inline(always)]
pub fn gather_adjacent_texels_x8(texels: &[[f32; 4]], a: [i32; 8]) -> [[f32; 8]; 8] {
    dispatch!(
        |avx2| avx2.gather_adjacent_texels_x8(texels, a),
        sse2::gather_adjacent_texels_x8(texels, a),
        scalar::gather_adjacent_texels_x8(texels, a)
    )
}

/// [`gather_texels_x8`] at level `L` (the AVX2 loads, inlined, at the
/// x86-64-v3 level).
#[inline(always)]
pub fn gather_texels_x8_at<L: lanes::Level>(texels: &[[f32; 4]], idx: [i32; 8]) -> [[f32; 8]; 4] {
    #[cfg(target_arch = "x86_64")]
    if L::V3 {
        return avx2::Avx2::at_v3().gather_texels_x8(texels, idx);
    }
    gather_texels_x8(texels, idx)
}

/// [`gather_texel_pairs_x8`] at level `L`.
#[inline(always)]
pub fn gather_texel_pairs_x8_at<L: lanes::Level>(
    texels: &[[f32; 4]],
    a: [i32; 8],
    b: [i32; 8],
) -> [[f32; 8]; 8] {
    #[cfg(target_arch = "x86_64")]
    if L::V3 {
        return avx2::Avx2::at_v3().gather_texel_pairs_x8(texels, a, b);
    }
    gather_texel_pairs_x8(texels, a, b)
}

/// [`gather_adjacent_texels_x8`] at level `L`.
#[inline(always)]
pub fn gather_adjacent_texels_x8_at<L: lanes::Level>(texels: &[[f32; 4]], a: [i32; 8]) -> [[f32; 8]; 8] {
    #[cfg(target_arch = "x86_64")]
    if L::V3 {
        return avx2::Avx2::at_v3().gather_adjacent_texels_x8(texels, a);
    }
    gather_adjacent_texels_x8(texels, a)
}

/// A path that is rare in this build (forced by `ZLINE_SIMD` on x86-64),
/// kept out of line so callers keep the usual path's results in
/// registers; inline where the scalar twin is the only path.
#[cfg_attr(target_arch = "x86_64", inline(never))]
#[cfg_attr(not(target_arch = "x86_64"), inline(always))]
fn out_of_line<T>(twin: impl FnOnce() -> T) -> T {
    twin()
}

/// Runs `job` at the x86-64-v4 level (AVX-512) or the x86-64-v3 level
/// (AVX2, FMA) when the CPU has it and [`Isa::current`] allows it
/// (`ZLINE_SIMD` may lower it), else at [`lanes::Baseline`]. All give the
/// same results bit for bit.
#[inline(always)]
pub fn vectorize<V: Vectorized>(job: V) -> V::Output {
    #[cfg(target_arch = "x86_64")]
    if let Some(v4) = avx2::v4_token() {
        return v4.vectorize(job);
    }
    #[cfg(target_arch = "x86_64")]
    if let Some(v3) = avx2::v3_token() {
        return v3.vectorize(job);
    }
    job.run::<lanes::Baseline>()
}

/// Chooses the level as [`vectorize`] does, but runs `job` where it is,
/// without entering a `#[target_feature]` function: for a loop whose own
/// work is light and which hands each heavy part to [`vectorize_at`]. The
/// tile passes do this with each primitive's kernel, so that every kernel
/// is compiled once per level, as a function of its own, instead of all of
/// them being inlined into one pass body per level (which made the release
/// build of `zline-pipeline` run past 40 minutes). Lane operations in
/// `job`'s own body run out of line at the v3 level: correct, but slow.
#[inline(always)]
pub fn dispatch<V: Vectorized>(job: V) -> V::Output {
    #[cfg(target_arch = "x86_64")]
    if avx2::v4_token().is_some() {
        return job.run::<lanes::private::V4>();
    }
    #[cfg(target_arch = "x86_64")]
    if avx2::v3_token().is_some() {
        return job.run::<lanes::private::V3>();
    }
    job.run::<lanes::Baseline>()
}

/// Runs `job` at level `L` as a function of its own: the job's body is
/// compiled for its level (inlined into a `#[target_feature]` function at
/// the v3 level, into a plain one otherwise), once per job type, apart from
/// its caller. For the parts a [`dispatch`]ed loop hands over, and for parts
/// of a job kept out of line on purpose, such as a rare kernel.
#[inline(always)]
pub fn vectorize_at<L: lanes::Level, V: Vectorized>(job: V) -> V::Output {
    #[cfg(target_arch = "x86_64")]
    if L::V4 {
        return avx2::V4Token::within_v4().vectorize(job);
    }
    #[cfg(target_arch = "x86_64")]
    if L::V3 {
        return avx2::V3Token::within_v3().vectorize(job);
    }
    run_apart::<V>(job)
}

/// [`Vectorized::run`] at [`lanes::Baseline`], never inlined: the
/// baseline twin of the v3 trampoline's function boundary.
#[inline(never)]
fn run_apart<V: Vectorized>(job: V) -> V::Output {
    job.run::<lanes::Baseline>()
}

/// Returns `f`: lets a closure bound by `let` carry `#[inline(always)]` on
/// stable Rust, which accepts the attribute on a closure in argument
/// position only. A vectorized job's closures must be inlined into it to run
/// at its level (a closure left out of line reaches each lane operation
/// through a call).
#[inline(always)]
pub fn inlined<F>(f: F) -> F {
    f
}

/// The x86-64-v4 level when [`vectorize`] would choose it (for tests and
/// reports).
pub fn v4_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    if avx2::v4_token().is_some() {
        return true;
    }
    false
}

/// The x86-64-v3 level or better when [`vectorize`] would choose it (for
/// tests and reports).
pub fn v3_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    if avx2::v3_token().is_some() {
        return true;
    }
    false
}

pub use isa::Isa;
pub use job::{Call, Vectorized};
pub use opaque::read_opaque;
pub use prefetch::prefetch;

#[cfg(test)]
mod tests;
