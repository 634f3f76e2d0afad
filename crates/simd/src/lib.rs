//! Explicit SIMD for zline: the one crate of the workspace where `unsafe`
//! is allowed, and only for `std::arch` intrinsics chosen at run time.
//!
//! Policy:
//! - Every other crate forbids `unsafe` (`[workspace.lints.rust]
//!   unsafe_code = "forbid"`). This crate denies it too, and allows it only
//!   on the modules that call `std::arch` (`#[allow(unsafe_code, reason =
//!   …)]`), today just `avx2`.
//! - Every `unsafe` block carries a `// SAFETY:` comment saying why its
//!   preconditions hold (`clippy::undocumented_unsafe_blocks` is on). The
//!   two preconditions are always the same: the CPU has the instructions
//!   (a detection token, see below) and every memory access is inside its
//!   slice (indices checked in safe code first).
//! - Every public function is safe and has a scalar twin in [`scalar`]
//!   that defines its result; the explicit SIMD version returns the same
//!   bits for every input (property tests compare them bit for bit, edge
//!   indices included). Where the safe precondition check fails (an index
//!   out of range), the function runs the scalar twin, which panics like
//!   slice indexing.
//! - The instruction set is detected at run time, once ([`Isa::current`]),
//!   so a binary built for plain x86-64 uses AVX2 where the CPU has it:
//!   the functions here need no `-C target-cpu` flag. The AVX2 code is
//!   compiled only for `x86_64` (`#[cfg(target_arch = "x86_64")]`); other
//!   targets (aarch64) build the scalar twins alone.
//! - `ZLINE_SIMD=scalar` in the environment makes [`Isa::current`] return
//!   [`Isa::Scalar`], to compare both paths in one binary. It can only
//!   turn explicit SIMD off, never on.
//!
//! The functions move data (loads, gathers, transposes); they do no
//! arithmetic, so equality with the twins is exact by construction, NaN
//! payloads included.

use std::sync::atomic::{AtomicU8, Ordering};

#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code, reason = "the AVX2 kernels call std::arch intrinsics (see the crate policy)")]
mod avx2;
pub mod scalar;

/// [`Isa::current`] once known: [`SCALAR`] or [`AVX2`]; 0 before.
static CURRENT: AtomicU8 = AtomicU8::new(0);
const SCALAR: u8 = 1;
const AVX2: u8 = 2;

/// The explicit SIMD instruction set the functions of this crate use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Isa {
    /// No explicit SIMD: the portable [`scalar`] twins.
    Scalar,
    /// x86-64 with AVX2 (Intel Haswell, AMD Excavator and later).
    Avx2,
}

impl Isa {
    /// The instruction set in use: the best one this CPU has, or
    /// [`Isa::Scalar`] when the environment sets `ZLINE_SIMD=scalar`.
    /// Detected on the first call, then cached (one relaxed atomic load).
    #[inline]
    pub fn current() -> Isa {
        match CURRENT.load(Ordering::Relaxed) {
            SCALAR => Isa::Scalar,
            AVX2 => Isa::Avx2,
            _ => Isa::detect(),
        }
    }

    /// The first [`Isa::current`]: reads the environment and the CPU, and
    /// caches the answer (threads racing here all store the same value).
    #[cold]
    #[inline(never)]
    fn detect() -> Isa {
        let isa = if std::env::var_os("ZLINE_SIMD").is_some_and(|v| v == "scalar") {
            Isa::Scalar
        } else {
            Isa::best()
        };
        CURRENT.store(
            match isa {
                Isa::Scalar => SCALAR,
                Isa::Avx2 => AVX2,
            },
            Ordering::Relaxed,
        );
        isa
    }

    /// The best instruction set this CPU has, ignoring the environment.
    pub fn best() -> Isa {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            return Isa::Avx2;
        }
        Isa::Scalar
    }

    /// A short lower-case name: "scalar", "avx2".
    pub fn name(self) -> &'static str {
        match self {
            Isa::Scalar => "scalar",
            Isa::Avx2 => "avx2",
        }
    }
}

/// The four channels of texel `idx[k]` in lane k: channel c of the result
/// holds `texels[idx[k]][c]` at position k. Panics, like slice indexing,
/// when an index is negative or not below `texels.len()`.
#[inline(always)]
pub fn gather_texels_x8(texels: &[[f32; 4]], idx: [i32; 8]) -> [[f32; 8]; 4] {
    #[cfg(target_arch = "x86_64")]
    return match avx2::token() {
        Some(avx2) => avx2.gather_texels_x8(texels, idx),
        None => out_of_line(|| scalar::gather_texels_x8(texels, idx)),
    };
    #[cfg(not(target_arch = "x86_64"))]
    scalar::gather_texels_x8(texels, idx)
}

/// Two texels per lane, as channel vectors: element c (0 ≤ c < 4) of the
/// result holds channel c of `texels[a[k]]` at position k, element 4 + c
/// channel c of `texels[b[k]]`. Panics, like slice indexing, when an index
/// is negative or not below `texels.len()`.
#[inline(always)]
pub fn gather_texel_pairs_x8(texels: &[[f32; 4]], a: [i32; 8], b: [i32; 8]) -> [[f32; 8]; 8] {
    #[cfg(target_arch = "x86_64")]
    return match avx2::token() {
        Some(avx2) => avx2.gather_texel_pairs_x8(texels, a, b),
        None => out_of_line(|| scalar::gather_texel_pairs_x8(texels, a, b)),
    };
    #[cfg(not(target_arch = "x86_64"))]
    scalar::gather_texel_pairs_x8(texels, a, b)
}

/// Texels `a[k]` and `a[k] + 1` of every lane k: the same as
/// [`gather_texel_pairs_x8`] with `b[k] = a[k] + 1`, in half the loads.
/// Panics, like slice indexing, when an `a[k]` is negative or `a[k] + 1`
/// not below `texels.len()`.
#[inline(always)]
pub fn gather_adjacent_texels_x8(texels: &[[f32; 4]], a: [i32; 8]) -> [[f32; 8]; 8] {
    #[cfg(target_arch = "x86_64")]
    return match avx2::token() {
        Some(avx2) => avx2.gather_adjacent_texels_x8(texels, a),
        None => out_of_line(|| scalar::gather_adjacent_texels_x8(texels, a)),
    };
    #[cfg(not(target_arch = "x86_64"))]
    scalar::gather_adjacent_texels_x8(texels, a)
}

/// The scalar twin where AVX2 is missing, kept out of line: the callers
/// then keep the AVX2 results in registers instead of merging both paths'
/// results in memory.
#[cfg(target_arch = "x86_64")]
#[inline(never)]
fn out_of_line<T>(twin: impl FnOnce() -> T) -> T {
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
