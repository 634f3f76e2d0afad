//! The AVX2 kernels. Each `unsafe fn` here has `#[target_feature(enable =
//! "avx2")]` and is reached only through an [`Avx2`] token, which exists
//! only when the CPU has AVX2, and only after the indices were checked in
//! safe code ([`crate::bounds::all_in_range`]).
//!
//! Texels are moved into lanes by 16-byte loads (two texels per 256-bit
//! row: lane k's in the low half, lane k + 4's in the high half) and 4×4
//! transposes inside each 128-bit half. `vgatherdps` (one gather per
//! channel) measured 2–3× slower on the development machine (AMD EPYC,
//! Zen 4): 35 against 18 ns per pair of texels × 8 lanes out of line, 11
//! against 4 ns inlined, in a micro benchmark.

use std::arch::x86_64::{
    __m256, _mm256_and_si256, _mm256_castps128_ps256, _mm256_cmpeq_epi32, _mm256_insertf128_ps,
    _mm256_loadu_ps, _mm256_loadu_si256, _mm256_max_epu32, _mm256_movemask_epi8, _mm256_permute2f128_ps,
    _mm256_set1_epi32, _mm256_setzero_ps, _mm256_shuffle_ps, _mm256_unpackhi_ps, _mm256_unpacklo_ps,
    _mm_loadu_ps,
};

use crate::bounds::cold;
use crate::isa::Isa;
use crate::scalar;

/// Proof that the CPU has AVX2: only [`token`] makes one.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx2(());

/// The token when [`Isa::current`] chose AVX2 or better. The CPU is asked
/// again ([`detect`]), so safety does not rest on how `Isa::current` decided.
#[inline(always)]
pub(crate) fn token() -> Option<Avx2> {
    if Isa::current() >= Isa::Avx2 {
        detect()
    } else {
        None
    }
}

/// The token when the CPU has AVX2, whatever [`Isa::current`] says (the
/// twin tests use it): a cached atomic load in `std`, a constant when the
/// build already targets AVX2.
#[inline(always)]
pub(crate) fn detect() -> Option<Avx2> {
    std::is_x86_feature_detected!("avx2").then_some(Avx2(()))
}

/// Proof that the CPU has the x86-64-v3 features [`run_v3`] enables.
#[derive(Clone, Copy, Debug)]
pub(crate) struct V3Token(());

/// The token when [`Isa::current`] chose AVX2 and the CPU also has FMA.
#[inline(always)]
pub(crate) fn v3_token() -> Option<V3Token> {
    (token().is_some() && std::is_x86_feature_detected!("fma")).then_some(V3Token(()))
}

/// `job.run()` at the x86-64-v3 level, compiled for its instructions:
/// everything inlined into it may use AVX2 and FMA (FMA is never formed on
/// its own: Rust does not contract a·b + c).
///
/// # Safety
/// The CPU has AVX2 and FMA.
#[target_feature(enable = "avx2,fma")]
#[inline(never)]
unsafe fn run_v3<V: crate::job::Vectorized>(job: V) -> V::Output {
    job.run::<crate::lanes::private::V3>()
}

/// Proof that the CPU has the x86-64-v4 features [`run_v4`] enables.
#[derive(Clone, Copy, Debug)]
pub(crate) struct V4Token(());

/// The token when [`Isa::current`] chose AVX-512; the CPU is asked again
/// for every feature [`run_v4`] enables.
#[inline(always)]
pub(crate) fn v4_token() -> Option<V4Token> {
    let ok = Isa::current() == Isa::Avx512
        && v3_token().is_some()
        && std::is_x86_feature_detected!("avx512f")
        && std::is_x86_feature_detected!("avx512vl")
        && std::is_x86_feature_detected!("avx512bw")
        && std::is_x86_feature_detected!("avx512dq");
    ok.then_some(V4Token(()))
}

/// `job.run()` at the x86-64-v4 level: the v3 lane code (its AVX2
/// intrinsics), compiled where LLVM may encode it with AVX-512VL and use
/// its 32 vector registers and mask registers. No operation changes its
/// result: the intrinsics are the same, and FMA is still never formed.
///
/// # Safety
/// The CPU has AVX2, FMA and AVX-512 F, VL, BW and DQ.
#[target_feature(enable = "avx2,fma,avx512f,avx512vl,avx512bw,avx512dq")]
#[inline(never)]
unsafe fn run_v4<V: crate::job::Vectorized>(job: V) -> V::Output {
    job.run::<crate::lanes::private::V4>()
}

impl V4Token {
    /// The token inside code running at the x86-64-v4 level (which
    /// [`crate::vectorize`] and [`crate::dispatch`] enter only with a token).
    #[inline(always)]
    pub(crate) fn within_v4() -> V4Token {
        V4Token(())
    }

    /// [`crate::vectorize`] on this CPU.
    #[inline(always)]
    pub(crate) fn vectorize<V: crate::job::Vectorized>(self, job: V) -> V::Output {
        // SAFETY: the token exists only when the CPU has every feature
        // `run_v4` enables.
        unsafe { run_v4(job) }
    }
}

impl V3Token {
    /// The token inside code running at the x86-64-v3 level (which
    /// [`crate::vectorize`] enters only with a token).
    #[inline(always)]
    pub(crate) fn within_v3() -> V3Token {
        V3Token(())
    }

    /// [`crate::vectorize`] on this CPU.
    #[inline(always)]
    pub(crate) fn vectorize<V: crate::job::Vectorized>(self, job: V) -> V::Output {
        // SAFETY: the token exists only when the CPU has AVX2 and FMA.
        unsafe { run_v3(job) }
    }
}

impl Avx2 {
    /// The token inside a job at the x86-64-v3 level (whose CPU has AVX2).
    #[inline(always)]
    pub(crate) fn at_v3() -> Avx2 {
        Avx2(())
    }

    /// [`crate::bounds::all_in_range`] in vector instructions (its twin,
    /// tested equal): written as the scalar fold, LLVM moved the lanes out
    /// one by one into a chain of compares, about 30 instructions per
    /// eight indices on every texture sample.
    #[inline(always)]
    pub(crate) fn all_in_range(self, idx: &[[i32; 8]], len: usize) -> bool {
        // SAFETY: the token proves AVX2.
        unsafe { all_in_range(idx, len) }
    }

    /// [`crate::gather_texels_x8`].
    #[inline(always)]
    pub(crate) fn gather_texels_x8(self, texels: &[[f32; 4]], idx: [i32; 8]) -> [[f32; 8]; 4] {
        if self.all_in_range(&[idx], texels.len()) {
            // SAFETY: the token proves AVX2; every index is in 0..texels.len().
            unsafe { gather_texels_x8(texels, idx) }
        } else {
            cold(|| scalar::gather_texels_x8(texels, idx))
        }
    }

    /// [`crate::gather_texel_pairs_x8`].
    #[inline(always)]
    pub(crate) fn gather_texel_pairs_x8(
        self,
        texels: &[[f32; 4]],
        a: [i32; 8],
        b: [i32; 8],
    ) -> [[f32; 8]; 8] {
        if self.all_in_range(&[a, b], texels.len()) {
            // SAFETY: the token proves AVX2; every index is in 0..texels.len().
            unsafe { gather_texel_pairs_x8(texels, a, b) }
        } else {
            cold(|| scalar::gather_texel_pairs_x8(texels, a, b))
        }
    }

    /// [`crate::gather_adjacent_texels_x8`].
    #[inline(always)]
    pub(crate) fn gather_adjacent_texels_x8(self, texels: &[[f32; 4]], a: [i32; 8]) -> [[f32; 8]; 8] {
        // a[k] + 1 < len for every lane, so both texels of a lane are inside.
        if self.all_in_range(&[a], texels.len().saturating_sub(1)) {
            // SAFETY: the token proves AVX2; every a[k] is in 0..texels.len() − 1.
            unsafe { gather_adjacent_texels_x8(texels, a) }
        } else {
            cold(|| scalar::gather_adjacent_texels_x8(texels, a))
        }
    }
}

/// Texel `idx[k]` in the low half of row k and texel `idx[k + 4]` in its
/// high half, for k < 4: one 16-byte load per texel.
///
/// # Safety
/// The CPU has AVX2 and every `idx[k]` is in `0..texels.len()`.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn rows(texels: &[[f32; 4]], idx: [i32; 8]) -> [__m256; 4] {
    let base = texels.as_ptr();
    let mut rows = [_mm256_setzero_ps(); 4];
    for (k, row) in rows.iter_mut().enumerate() {
        // SAFETY: idx[k] and idx[k + 4] are in 0..texels.len() (so not
        // negative: the casts keep their values), hence each 16-byte load
        // reads exactly one texel of the slice; unaligned loads need no
        // alignment.
        let (lo, hi) = unsafe {
            (
                _mm_loadu_ps(base.add(idx[k] as u32 as usize).cast::<f32>()),
                _mm_loadu_ps(base.add(idx[k + 4] as u32 as usize).cast::<f32>()),
            )
        };
        *row = _mm256_insertf128_ps::<1>(_mm256_castps128_ps256(lo), hi);
    }
    rows
}

/// A 4×4 transpose inside each 128-bit half: from the texel rows of
/// [`rows`] (lanes 0–3 low, 4–7 high) to the four channel vectors, lanes
/// in order.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn transpose(r: [__m256; 4]) -> [__m256; 4] {
    let xy01 = _mm256_unpacklo_ps(r[0], r[1]); // x0 x1 y0 y1 | x4 x5 y4 y5
    let xy23 = _mm256_unpacklo_ps(r[2], r[3]); // x2 x3 y2 y3 | x6 x7 y6 y7
    let zw01 = _mm256_unpackhi_ps(r[0], r[1]); // z0 z1 w0 w1 | z4 z5 w4 w5
    let zw23 = _mm256_unpackhi_ps(r[2], r[3]); // z2 z3 w2 w3 | z6 z7 w6 w7
    [
        _mm256_shuffle_ps::<0b01_00_01_00>(xy01, xy23), // x0 x1 x2 x3 | x4 x5 x6 x7
        _mm256_shuffle_ps::<0b11_10_11_10>(xy01, xy23), // y0 …
        _mm256_shuffle_ps::<0b01_00_01_00>(zw01, zw23), // z0 …
        _mm256_shuffle_ps::<0b11_10_11_10>(zw01, zw23), // w0 …
    ]
}

/// Eight texel loads and one [`transpose`].
///
/// # Safety
/// The CPU has AVX2 and every `idx[k]` is in `0..texels.len()`.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn gather_texels_x8(texels: &[[f32; 4]], idx: [i32; 8]) -> [[f32; 8]; 4] {
    // SAFETY: AVX2 and the indices as this function's contract requires.
    let c = unsafe { transpose(rows(texels, idx)) };
    c.map(to_array)
}

/// Sixteen texel loads and two [`transpose`]s.
///
/// # Safety
/// The CPU has AVX2 and every `a[k]`, `b[k]` is in `0..texels.len()`.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn gather_texel_pairs_x8(texels: &[[f32; 4]], a: [i32; 8], b: [i32; 8]) -> [[f32; 8]; 8] {
    // SAFETY: AVX2 and the indices as this function's contract requires.
    let ([a0, a1, a2, a3], [b0, b1, b2, b3]) =
        unsafe { (transpose(rows(texels, a)), transpose(rows(texels, b))) };
    [a0, a1, a2, a3, b0, b1, b2, b3].map(to_array)
}

/// Texels `a[k]` and `a[k] + 1` as one 32-byte load per lane, then an 8×8
/// transpose (unpacks and shuffles inside the 128-bit halves, then
/// exchanges of halves).
///
/// [`crate::bounds::all_in_range`]: with the length capped at 2^31 and
/// `last = cap − 1`, an index (as `u32`: a negative one is at least 2^31)
/// is in range exactly when its unsigned maximum with `last` is `last`.
///
/// # Safety
/// The CPU has AVX2.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn all_in_range(idx: &[[i32; 8]], len: usize) -> bool {
    let cap = len.min(1 << 31) as u32;
    if cap == 0 {
        return false;
    }
    let last = _mm256_set1_epi32((cap - 1) as i32);
    let mut all = _mm256_set1_epi32(-1);
    for lanes in idx {
        // SAFETY: `lanes` is 32 bytes; an unaligned load needs no alignment.
        let v = unsafe { _mm256_loadu_si256(lanes.as_ptr().cast()) };
        all = _mm256_and_si256(all, _mm256_cmpeq_epi32(_mm256_max_epu32(v, last), last));
    }
    _mm256_movemask_epi8(all) == -1
}

/// # Safety
/// The CPU has AVX2 and every `a[k]` is in `0..texels.len() - 1`.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn gather_adjacent_texels_x8(texels: &[[f32; 4]], a: [i32; 8]) -> [[f32; 8]; 8] {
    let base = texels.as_ptr();
    let mut d = [_mm256_setzero_ps(); 8];
    for (k, row) in d.iter_mut().enumerate() {
        // SAFETY: 0 ≤ a[k] and a[k] + 1 < texels.len(), so the 32-byte load
        // reads exactly texels a[k] and a[k] + 1 of the slice; unaligned
        // loads need no alignment.
        *row = unsafe { _mm256_loadu_ps(base.add(a[k] as u32 as usize).cast::<f32>()) };
    }
    // Rows: lane k = p.x p.y p.z p.w | q.x q.y q.z q.w (p = texel a, q = a + 1).
    let xy01 = _mm256_unpacklo_ps(d[0], d[1]);
    let zw01 = _mm256_unpackhi_ps(d[0], d[1]);
    let xy23 = _mm256_unpacklo_ps(d[2], d[3]);
    let zw23 = _mm256_unpackhi_ps(d[2], d[3]);
    let xy45 = _mm256_unpacklo_ps(d[4], d[5]);
    let zw45 = _mm256_unpackhi_ps(d[4], d[5]);
    let xy67 = _mm256_unpacklo_ps(d[6], d[7]);
    let zw67 = _mm256_unpackhi_ps(d[6], d[7]);
    // x0..3 | x'0..3 and so on, for lanes 0–3 and 4–7.
    let x03 = _mm256_shuffle_ps::<0b01_00_01_00>(xy01, xy23);
    let y03 = _mm256_shuffle_ps::<0b11_10_11_10>(xy01, xy23);
    let z03 = _mm256_shuffle_ps::<0b01_00_01_00>(zw01, zw23);
    let w03 = _mm256_shuffle_ps::<0b11_10_11_10>(zw01, zw23);
    let x47 = _mm256_shuffle_ps::<0b01_00_01_00>(xy45, xy67);
    let y47 = _mm256_shuffle_ps::<0b11_10_11_10>(xy45, xy67);
    let z47 = _mm256_shuffle_ps::<0b01_00_01_00>(zw45, zw67);
    let w47 = _mm256_shuffle_ps::<0b11_10_11_10>(zw45, zw67);
    [
        _mm256_permute2f128_ps::<0x20>(x03, x47),
        _mm256_permute2f128_ps::<0x20>(y03, y47),
        _mm256_permute2f128_ps::<0x20>(z03, z47),
        _mm256_permute2f128_ps::<0x20>(w03, w47),
        _mm256_permute2f128_ps::<0x31>(x03, x47),
        _mm256_permute2f128_ps::<0x31>(y03, y47),
        _mm256_permute2f128_ps::<0x31>(z03, z47),
        _mm256_permute2f128_ps::<0x31>(w03, w47),
    ]
    .map(to_array)
}

/// The eight floats of a vector.
#[inline(always)]
fn to_array(v: __m256) -> [f32; 8] {
    // SAFETY: both types are 32 bytes of plain data, and every bit pattern
    // is a valid value of either.
    unsafe { std::mem::transmute::<__m256, [f32; 8]>(v) }
}
