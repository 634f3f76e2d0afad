//! The SSE2 kernels, for x86-64 processors without AVX2 and for builds
//! whose callers lack AVX2. SSE2 is part of x86-64 itself (every such
//! processor has it, and the compiler enables it for the target), so these
//! need no detection: the module is compiled only where `target_feature =
//! "sse2"` holds. They inline into callers built for plain x86-64, which
//! the AVX2 kernels cannot (a call, results through memory).
//!
//! Four texels become four channel vectors by four 16-byte loads and one
//! 4×4 transpose (`_MM_TRANSPOSE4_PS`); eight lanes take two of each.

use std::arch::x86_64::{
    __m128, _mm_loadu_ps, _mm_movehl_ps, _mm_movelh_ps, _mm_setzero_ps, _mm_unpackhi_ps, _mm_unpacklo_ps,
};

use crate::bounds::{all_in_range, cold};
use crate::scalar;

/// [`crate::gather_texels_x8`].
#[inline(always)]
pub(crate) fn gather_texels_x8(texels: &[[f32; 4]], idx: [i32; 8]) -> [[f32; 8]; 4] {
    if all_in_range(&[idx], texels.len()) {
        // SAFETY: SSE2 is enabled (module cfg); every index is in 0..texels.len().
        unsafe { gather_texels_x8_unchecked(texels, idx) }
    } else {
        cold(|| scalar::gather_texels_x8(texels, idx))
    }
}

/// [`crate::gather_texel_pairs_x8`].
#[inline(always)]
pub(crate) fn gather_texel_pairs_x8(texels: &[[f32; 4]], a: [i32; 8], b: [i32; 8]) -> [[f32; 8]; 8] {
    if all_in_range(&[a, b], texels.len()) {
        // SAFETY: SSE2 is enabled (module cfg); every index is in 0..texels.len().
        let ([a0, a1, a2, a3], [b0, b1, b2, b3]) =
            unsafe { (gather_texels_x8_unchecked(texels, a), gather_texels_x8_unchecked(texels, b)) };
        [a0, a1, a2, a3, b0, b1, b2, b3]
    } else {
        cold(|| scalar::gather_texel_pairs_x8(texels, a, b))
    }
}

/// [`crate::gather_adjacent_texels_x8`].
#[inline(always)]
pub(crate) fn gather_adjacent_texels_x8(texels: &[[f32; 4]], a: [i32; 8]) -> [[f32; 8]; 8] {
    // a[k] + 1 < len for every lane, so both texels of a lane are inside
    // (and a[k] + 1 cannot overflow).
    if all_in_range(&[a], texels.len().saturating_sub(1)) {
        let b = a.map(|i| i + 1);
        // SAFETY: SSE2 is enabled (module cfg); every a[k] and a[k] + 1 is
        // in 0..texels.len().
        let ([a0, a1, a2, a3], [b0, b1, b2, b3]) =
            unsafe { (gather_texels_x8_unchecked(texels, a), gather_texels_x8_unchecked(texels, b)) };
        [a0, a1, a2, a3, b0, b1, b2, b3]
    } else {
        cold(|| scalar::gather_adjacent_texels_x8(texels, a))
    }
}

/// Lanes 0–3 and 4–7 each by [`quad`].
///
/// # Safety
/// The CPU has SSE2 and every `idx[k]` is in `0..texels.len()`.
#[target_feature(enable = "sse2")]
#[inline]
unsafe fn gather_texels_x8_unchecked(texels: &[[f32; 4]], idx: [i32; 8]) -> [[f32; 8]; 4] {
    // SAFETY: as this function's contract requires.
    let (lo, hi) = unsafe {
        (quad(texels, [idx[0], idx[1], idx[2], idx[3]]), quad(texels, [idx[4], idx[5], idx[6], idx[7]]))
    };
    [join(lo[0], hi[0]), join(lo[1], hi[1]), join(lo[2], hi[2]), join(lo[3], hi[3])]
}

/// The four channel vectors of texels `idx[0..4]`: four loads, one 4×4
/// transpose.
///
/// # Safety
/// The CPU has SSE2 and every `idx[k]` is in `0..texels.len()`.
#[target_feature(enable = "sse2")]
#[inline]
unsafe fn quad(texels: &[[f32; 4]], idx: [i32; 4]) -> [__m128; 4] {
    let base = texels.as_ptr();
    let mut r = [_mm_setzero_ps(); 4];
    for (row, &i) in r.iter_mut().zip(&idx) {
        // SAFETY: 0 ≤ i < texels.len() by the contract (the casts keep the
        // value), so the 16-byte load reads exactly one texel of the slice;
        // unaligned loads need no alignment.
        *row = unsafe { _mm_loadu_ps(base.add(i as u32 as usize).cast::<f32>()) };
    }
    let xy01 = _mm_unpacklo_ps(r[0], r[1]); // x0 x1 y0 y1
    let xy23 = _mm_unpacklo_ps(r[2], r[3]); // x2 x3 y2 y3
    let zw01 = _mm_unpackhi_ps(r[0], r[1]); // z0 z1 w0 w1
    let zw23 = _mm_unpackhi_ps(r[2], r[3]); // z2 z3 w2 w3
    [
        _mm_movelh_ps(xy01, xy23),
        _mm_movehl_ps(xy23, xy01),
        _mm_movelh_ps(zw01, zw23),
        _mm_movehl_ps(zw23, zw01),
    ]
}

/// Lanes 0–3 from `lo`, 4–7 from `hi`.
#[inline(always)]
fn join(lo: __m128, hi: __m128) -> [f32; 8] {
    // SAFETY: two 16-byte vectors and eight floats are the same 32 bytes
    // of plain data, and every bit pattern is a valid value of either.
    unsafe { std::mem::transmute::<[__m128; 2], [f32; 8]>([lo, hi]) }
}
