//! Index checks done in safe code before any intrinsic reads memory, and
//! the out-of-line fallback when they fail.

/// The scalar twin on an index out of range (it panics), out of line so
/// that callers keep the kernels' results in registers.
#[cfg(target_arch = "x86_64")]
#[cold]
#[inline(never)]
pub(crate) fn cold<T>(twin: impl FnOnce() -> T) -> T {
    twin()
}

/// Whether every index lies in `0..len`: as `u32`, a negative index is at
/// least 2^31, and `len` is capped at 2^31, so one unsigned maximum over
/// the lanes decides (a few vector instructions).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn all_in_range(idx: &[[i32; 8]], len: usize) -> bool {
    let cap = len.min(1 << 31) as u32;
    idx.iter().flatten().fold(0, |max, &i| max.max(i as u32)) < cap
}
