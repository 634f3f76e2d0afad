//! Explicit SIMD for zline: the one crate of the workspace where `unsafe`
//! is allowed, and only to call `std::arch` intrinsics.
//!
//! Policy:
//! - Every other crate forbids `unsafe` (`[workspace.lints.rust]
//!   unsafe_code = "forbid"`). This crate denies it too (its own `[lints]`
//!   table) and allows it only on the modules that call `std::arch`,
//!   `avx2` and `sse2` (`#[allow(unsafe_code, reason = …)]`).
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
//! included. Measurements: BENCHMARKS.md ("Explicit SIMD").

use std::sync::atomic::{AtomicU8, Ordering};

#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code, reason = "the AVX2 kernels call std::arch intrinsics (see the crate policy)")]
mod avx2;
pub mod scalar;
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
#[allow(unsafe_code, reason = "the SSE2 kernels call std::arch intrinsics (see the crate policy)")]
mod sse2;

/// [`Isa::current`] once known: 1 + its position in [`Isa::ALL`]; 0 before.
static CURRENT: AtomicU8 = AtomicU8::new(0);

/// An explicit SIMD instruction set for the functions of this crate,
/// ordered from least to most capable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Isa {
    /// No explicit SIMD: the portable [`scalar`] twins.
    Scalar,
    /// x86-64's own SSE2 (every x86-64 processor; no detection needed).
    Sse2,
    /// x86-64 with AVX2 (Intel Haswell, AMD Excavator and later), detected
    /// at run time.
    Avx2,
}

impl Isa {
    /// Every instruction set, least capable first.
    pub const ALL: [Isa; 3] = [Isa::Scalar, Isa::Sse2, Isa::Avx2];

    /// The instruction set in use: the best one this CPU has, lowered to
    /// `ZLINE_SIMD` when the environment names a less capable one
    /// ("scalar", "sse2"). Detected on the first call, then cached (one
    /// relaxed atomic load).
    #[inline]
    pub fn current() -> Isa {
        match CURRENT.load(Ordering::Relaxed) {
            0 => Isa::detect(),
            n => Isa::ALL[usize::from(n - 1) % Isa::ALL.len()],
        }
    }

    /// The first [`Isa::current`]: reads the environment and the CPU, and
    /// caches the answer (threads racing here all store the same value).
    #[cold]
    #[inline(never)]
    fn detect() -> Isa {
        let wanted =
            std::env::var("ZLINE_SIMD").ok().and_then(|name| Isa::ALL.into_iter().find(|i| i.name() == name));
        let isa = wanted.map_or(Isa::best(), |w| w.min(Isa::best()));
        let index = Isa::ALL.iter().position(|&i| i == isa).unwrap_or(0);
        CURRENT.store(index as u8 + 1, Ordering::Relaxed);
        isa
    }

    /// The best instruction set this CPU has, ignoring the environment.
    pub fn best() -> Isa {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            return Isa::Avx2;
        }
        if cfg!(all(target_arch = "x86_64", target_feature = "sse2")) {
            Isa::Sse2
        } else {
            Isa::Scalar
        }
    }

    /// The name `ZLINE_SIMD` takes: "scalar", "sse2", "avx2".
    pub fn name(self) -> &'static str {
        match self {
            Isa::Scalar => "scalar",
            Isa::Sse2 => "sse2",
            Isa::Avx2 => "avx2",
        }
    }
}

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

/// A path that is rare in this build (forced by `ZLINE_SIMD` on x86-64),
/// kept out of line so callers keep the usual path's results in
/// registers; inline where the scalar twin is the only path.
#[cfg_attr(target_arch = "x86_64", inline(never))]
#[cfg_attr(not(target_arch = "x86_64"), inline(always))]
fn out_of_line<T>(twin: impl FnOnce() -> T) -> T {
    twin()
}

/// The scalar twin on an index out of range (it panics), out of line so
/// that callers keep the kernels' results in registers.
#[cfg(target_arch = "x86_64")]
#[cold]
#[inline(never)]
fn cold<T>(twin: impl FnOnce() -> T) -> T {
    twin()
}

/// Whether every index lies in `0..len`: as `u32`, a negative index is at
/// least 2^31, and `len` is capped at 2^31, so one unsigned maximum over
/// the lanes decides (a few vector instructions).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn all_in_range(idx: &[[i32; 8]], len: usize) -> bool {
    let cap = len.min(1 << 31) as u32;
    idx.iter().flatten().fold(0, |max, &i| max.max(i as u32)) < cap
}

#[cfg(test)]
mod tests;
