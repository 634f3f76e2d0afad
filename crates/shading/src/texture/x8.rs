//! Texture sampling for eight lanes at once (`wide::f32x8`): the texel
//! choice, wrapping and weights as vector integer and float operations,
//! the texels gathered per lane, the lerps as vector operations.
//!
//! Contract: lane k of [`Texture::sample_x8`] is bit for bit
//! [`Texture::sample`] of lane k's inputs, for every input (a property test
//! checks it, NaN, infinite and huge coordinates included). Each lane runs
//! the scalar path's float operations in the same order — IEEE products,
//! sums and `floor` round alike in vector form, and Rust never fuses a·b + c
//! — and the integer steps reproduce the scalar ones exactly: the saturating
//! float-to-int cast (`trunc_int`), `saturating_add`, and `rem_euclid`
//! (computed with two float divisions, see [`rem_euclid`]).
//!
//! Texels stay four `f32` per texel: eight 8-bit texels would gather with
//! fewer loads, but turning a byte into byte/255 exactly needs a division
//! per channel (x·(1/255) differs from x/255 for 126 of the 256 bytes),
//! sixteen vector divisions per bilinear lookup, more than the transposes
//! that the `f32` texels need.
//!
//! Trilinear lanes may sit on different mip levels; a block whose lanes
//! share one level (the usual case: the level of detail changes slowly over
//! a screen) reads that level's size once instead of per lane. Where no
//! lane's two columns wrap apart, each lane's texel pair is one 8-float
//! load instead of two 4-float ones (~5 % of a textured frame).
//!
//! Measured on the textured floor benchmark (BENCHMARKS.md): 45 → 27 ms
//! per frame on one thread, 24.6 → 14.4 ms on two, against eight calls of
//! the scalar sampler per block.
//!
//! The texels move into lanes through `zline_simd`, the workspace's one
//! crate with explicit SIMD (AVX2 chosen at run time, else SSE2 on x86-64,
//! else scalar twins that define the results): with AVX2 a texel pair per
//! lane is two 16-byte loads and a 4×4 transpose inside each 128-bit half,
//! or, where no lane's columns wrap apart, one 32-byte load and an 8×8
//! transpose. Against the same moves built from `wide` (each lane's
//! texels inserted element by element, with a bounds check per index) the
//! textured floor went from 20.1 to 18.1 ms per frame on one thread (ratio
//! 0.90 over eight alternating runs), the transparent spheres over it from
//! 25.0 to 23.0 ms (0.92). AVX2's `vgatherdps`, one gather per channel,
//! measured 2–3× slower than these loads and transposes.

use zline_simd::lanes::{f32x8, i32x8, Baseline, Level as LaneLevel};

use super::{Filter, Level, Sampler, Texture, Wrap};

/// One mip level per lane: size as integers and floats, and first texel.
#[derive(Clone, Copy)]
struct Levels<L: LaneLevel = Baseline> {
    offset: i32x8<L>,
    width: i32x8<L>,
    height: i32x8<L>,
    width_f: f32x8<L>,
    height_f: f32x8<L>,
}

impl<L: LaneLevel> Levels<L> {
    /// The same level in every lane.
    #[inline(always)]
    fn splat(lv: Level) -> Levels<L> {
        // Sizes are at most MAX_TEXTURE_SIZE and the whole chain fits in
        // i32 (16384² · 4/3 texels), so these casts are exact.
        let (w, h) = (lv.width as i32, lv.height as i32);
        Levels {
            offset: i32x8::splat(lv.offset as i32),
            width: i32x8::splat(w),
            height: i32x8::splat(h),
            width_f: f32x8::splat(lv.width as f32),
            height_f: f32x8::splat(lv.height as f32),
        }
    }

    /// Level `index[k]` in lane k.
    #[inline(always)]
    fn gather(levels: &[Level], index: [i32; 8]) -> Levels<L> {
        let lv = index.map(
            #[inline(always)]
            |i| levels[i as usize],
        );
        Levels {
            offset: i32x8::from(lv.map(
                #[inline(always)]
                |l| l.offset as i32,
            )),
            width: i32x8::from(lv.map(
                #[inline(always)]
                |l| l.width as i32,
            )),
            height: i32x8::from(lv.map(
                #[inline(always)]
                |l| l.height as i32,
            )),
            width_f: f32x8::from(lv.map(
                #[inline(always)]
                |l| l.width as f32,
            )),
            height_f: f32x8::from(lv.map(
                #[inline(always)]
                |l| l.height as f32,
            )),
        }
    }
}

impl Texture {
    /// [`Texture::sample`] for eight lanes: lane k of the result (R, G, B,
    /// A) is bit for bit `self.sample(sampler, s[k], t[k], lod[k])`.
    #[inline(always)]
    pub fn sample_x8<L: LaneLevel>(
        &self,
        sampler: &Sampler,
        s: f32x8<L>,
        t: f32x8<L>,
        lod: f32x8<L>,
    ) -> [f32x8<L>; 4] {
        match sampler.filter {
            Filter::Nearest => self.nearest_x8(Levels::splat(self.levels[0]), sampler, s, t),
            Filter::Bilinear => self.bilinear_x8(Levels::splat(self.levels[0]), sampler, s, t),
            Filter::Trilinear => self.trilinear_x8(sampler, s, t, lod),
        }
    }

    /// [`Self::sample_x8`] at level 0 for a nearest or bilinear sampler
    /// (a trilinear one is read as bilinear, which at level 0 is the same
    /// filter): the same lanes, without the trilinear code, for callers
    /// that read a map at its base level only (bump and normal maps).
    #[inline(always)]
    pub fn sample_base_x8<L: LaneLevel>(&self, sampler: &Sampler, s: f32x8<L>, t: f32x8<L>) -> [f32x8<L>; 4] {
        match sampler.filter {
            Filter::Nearest => self.nearest_x8(Levels::splat(self.levels[0]), sampler, s, t),
            Filter::Bilinear | Filter::Trilinear => {
                self.bilinear_x8(Levels::splat(self.levels[0]), sampler, s, t)
            }
        }
    }

    #[inline(always)]
    fn nearest_x8<L: LaneLevel>(
        &self,
        lv: Levels<L>,
        sampler: &Sampler,
        s: f32x8<L>,
        t: f32x8<L>,
    ) -> [f32x8<L>; 4] {
        let x = nearest_index(s, lv.width_f, lv.width, sampler.wrap_s);
        let y = nearest_index(t, lv.height_f, lv.height, sampler.wrap_t);
        let idx = (lv.offset + y * lv.width + x).to_array();
        let [r, g, b, a] = zline_simd::gather_texels_x8_at::<L>(self.texel_array(), idx);
        [r.into(), g.into(), b.into(), a.into()]
    }

    /// The scalar bilinear's two-step interpolation, per lane.
    #[inline(always)]
    fn bilinear_x8<L: LaneLevel>(
        &self,
        lv: Levels<L>,
        sampler: &Sampler,
        s: f32x8<L>,
        t: f32x8<L>,
    ) -> [f32x8<L>; 4] {
        let (x0, x1, fs) = linear_taps(s, lv.width_f, lv.width, sampler.wrap_s);
        let (y0, y1, ft) = linear_taps(t, lv.height_f, lv.height, sampler.wrap_t);
        let (row0, row1) = (lv.offset + y0 * lv.width, lv.offset + y1 * lv.width);
        let ((t00, t10), (t01, t11)) = if (x1 - x0).cmp_eq(i32x8::splat(1)).all() {
            // No lane wraps between its columns: each pair is 8 contiguous floats.
            (self.gather_adjacent((row0 + x0).to_array()), self.gather_adjacent((row1 + x0).to_array()))
        } else {
            (
                self.gather_pair((row0 + x0).to_array(), (row0 + x1).to_array()),
                self.gather_pair((row1 + x0).to_array(), (row1 + x1).to_array()),
            )
        };
        let below = lerp4(t00, t10, fs);
        let above = lerp4(t01, t11, fs);
        lerp4(below, above, ft)
    }

    /// The texels at buffer indices `a[k]` and `b[k]` of every lane k, as
    /// channel vectors.
    #[inline(always)]
    fn gather_pair<L: LaneLevel>(&self, a: [i32; 8], b: [i32; 8]) -> ([f32x8<L>; 4], [f32x8<L>; 4]) {
        split(zline_simd::gather_texel_pairs_x8_at::<L>(self.texel_array(), a, b))
    }

    /// [`Self::gather_pair`] for b = a + 1: one 8-float load per lane.
    /// Always inlined: the usual case, and out of line (as the compiler
    /// chose once) its eight result vectors went through memory.
    #[inline(always)]
    fn gather_adjacent<L: LaneLevel>(&self, a: [i32; 8]) -> ([f32x8<L>; 4], [f32x8<L>; 4]) {
        split(zline_simd::gather_adjacent_texels_x8_at::<L>(self.texel_array(), a))
    }

    /// The texel buffer as `zline_simd` reads it.
    #[inline(always)]
    fn texel_array(&self) -> &[[f32; 4]] {
        bytemuck::cast_slice(&self.texels)
    }

    /// The scalar trilinear's three cases per lane: the last level at or
    /// beyond it, a blend of the two levels around a positive lod, level 0
    /// otherwise (NaN included). Every lane computes the finer level; the
    /// coarser one only when some lane blends.
    #[inline(always)]
    fn trilinear_x8<L: LaneLevel>(
        &self,
        sampler: &Sampler,
        s: f32x8<L>,
        t: f32x8<L>,
        lod: f32x8<L>,
    ) -> [f32x8<L>; 4] {
        let last = self.levels.len() - 1;
        let beyond = lod.cmp_ge(f32x8::splat(last as f32));
        let between = lod.cmp_gt(f32x8::ZERO) & !beyond;
        let level = between.blend(floor(lod), f32x8::ZERO);
        // Lanes beyond the chain read the last level; `level` < last
        // elsewhere, so `finer + 1` stays in the chain.
        let finer = beyond.blend(f32x8::splat(last as f32), level).trunc_int();
        let fine = self.bilinear_x8(self.levels_of(finer), sampler, s, t);
        if between.none() {
            return fine;
        }
        let coarser = self.levels_of((finer + i32x8::splat(1)).min(i32x8::splat(last as i32)));
        let coarse = self.bilinear_x8(coarser, sampler, s, t);
        let blended = lerp4(fine, coarse, lod - level);
        let pick = zline_simd::inlined(
            #[inline(always)]
            |c: usize| between.blend(blended[c], fine[c]),
        );
        [pick(0), pick(1), pick(2), pick(3)]
    }

    /// The levels `index[k]` per lane, read once when all lanes agree.
    #[inline(always)]
    fn levels_of<L: LaneLevel>(&self, index: i32x8<L>) -> Levels<L> {
        let first = index.to_array()[0];
        if index.cmp_eq(i32x8::splat(first)).all() {
            Levels::splat(self.levels[first as usize])
        } else {
            Levels::gather(&self.levels, index.to_array())
        }
    }
}

/// Two texels' channel vectors, from the eight vectors of `zline_simd`.
/// Element by element, not `map(f32x8::from)`: with that, the plain
/// x86-64 build stopped inlining the tile kernels' own
/// `attrs.map(f32x8::from)` (a 224-byte copy per block), and Phong frames
/// took 7–16 % longer.
#[inline(always)]
fn split<L: LaneLevel>(c: [[f32; 8]; 8]) -> ([f32x8<L>; 4], [f32x8<L>; 4]) {
    let [r0, g0, b0, a0, r1, g1, b1, a1] = c;
    ([r0.into(), g0.into(), b0.into(), a0.into()], [r1.into(), g1.into(), b1.into(), a1.into()])
}

/// `f32::floor` per lane, bit for bit. `wide` rounds with one instruction
/// where the target has one (SSE4.1, as in x86-64-v3; NEON), but plain
/// x86-64 has none and `wide` then calls libm's `floorf` once per lane:
/// there [`floor_sse2`] does it with conversions.
#[inline(always)]
fn floor<L: LaneLevel>(x: f32x8<L>) -> f32x8<L> {
    if !L::V3 && cfg!(all(target_arch = "x86_64", not(target_feature = "sse4.1"))) {
        floor_sse2(x)
    } else {
        x.floor()
    }
}

/// ⌊x⌋ from SSE2 conversions: below 2^23 in magnitude, truncation to an
/// integer and back is exact, minus one where that rounded up (negative
/// non-integers); the sign of x is ORed back in, which gives −0.0 for
/// −0.0 and changes nothing else (a negative x has a negative floor). At
/// 2^23 and beyond every float is an integer, and infinities and NaN stay
/// as they are: x itself. (`f32::floor` of a signalling NaN is quiet or not
/// depending on the build; the sampler discards non-finite lanes anyway.)
#[inline(always)]
fn floor_sse2<L: LaneLevel>(x: f32x8<L>) -> f32x8<L> {
    let small = x.abs().cmp_lt(f32x8::splat(8_388_608.0)); // 2^23; false for NaN
    let t = f32x8::from_i32x8(x.trunc_int());
    let down = t - (t.cmp_gt(x) & f32x8::ONE);
    small.blend(down | (x & f32x8::splat(-0.0)), x)
}

/// Whether `got` is `f32::floor(v)`: bit for bit, except that a NaN only
/// has to stay NaN (see [`floor_sse2`]).
#[cfg(test)]
fn is_floor_of(got: f32, v: f32) -> bool {
    if v.is_nan() {
        got.is_nan()
    } else {
        got.to_bits() == v.floor().to_bits()
    }
}

/// a + (b − a)·f per channel, as the scalar `lerp`.
#[inline(always)]
fn lerp4<L: LaneLevel>(a: [f32x8<L>; 4], b: [f32x8<L>; 4], f: f32x8<L>) -> [f32x8<L>; 4] {
    let lerp = zline_simd::inlined(
        #[inline(always)]
        |c: usize| a[c] + (b[c] - a[c]) * f,
    );
    [lerp(0), lerp(1), lerp(2), lerp(3)]
}

/// The scalar `nearest_index` per lane: ⌊coord·size⌋ wrapped, 0 where
/// coord·size is not finite.
#[inline(always)]
fn nearest_index<L: LaneLevel>(coord: f32x8<L>, size_f: f32x8<L>, size: i32x8<L>, wrap: Wrap) -> i32x8<L> {
    let u = coord * size_f;
    let i = u.is_finite().blend(floor(u), f32x8::ZERO).trunc_int();
    match wrap {
        Wrap::Repeat => repeat(i, size),
        Wrap::ClampToEdge => i.max(i32x8::ZERO).min(size - i32x8::splat(1)),
    }
}

/// The scalar `linear_taps` per lane: the two texels around the sample,
/// wrapped, and the weight of the second.
#[inline(always)]
fn linear_taps<L: LaneLevel>(
    coord: f32x8<L>,
    size_f: f32x8<L>,
    size: i32x8<L>,
    wrap: Wrap,
) -> (i32x8<L>, i32x8<L>, f32x8<L>) {
    let u = coord * size_f - f32x8::splat(0.5);
    let finite = u.is_finite();
    let below = floor(u);
    let i = finite.blend(below, f32x8::ZERO).trunc_int();
    let f = finite.blend(u - below, f32x8::ZERO);
    let one = i32x8::splat(1);
    let last = size - one;
    match wrap {
        Wrap::Repeat => {
            let a = repeat(i, size);
            let b = a + one;
            (a, b.cmp_eq(size).blend(i32x8::ZERO, b), f)
        }
        // clamp(i + 1 saturating, 0, last) = clamp(i, −1, last − 1) + 1,
        // which cannot overflow.
        Wrap::ClampToEdge => (i.max(i32x8::ZERO).min(last), i.max(-one).min(last - one) + one, f),
    }
}

/// The scalar `repeat` per lane: i modulo size in [0, size). Power-of-two
/// sizes mask; other sizes keep indices already inside and take
/// [`rem_euclid`] only when some lane lies outside.
#[inline(always)]
fn repeat<L: LaneLevel>(i: i32x8<L>, size: i32x8<L>) -> i32x8<L> {
    let one = i32x8::splat(1);
    let pow2 = (size & (size - one)).cmp_eq(i32x8::ZERO);
    let inside = !i.cmp_lt(i32x8::ZERO) & i.cmp_lt(size);
    let masked = i & (size - one);
    let easy = pow2 | inside;
    let fast = pow2.blend(masked, i);
    if easy.all() {
        fast
    } else {
        easy.blend(fast, rem_euclid(i, size))
    }
}

/// `i.rem_euclid(size)` per lane for 1 ≤ size ≤ 16384, in two float steps.
/// Step one: q = ⌊i/size⌋ in `f32` (i rounded to 24 bits) and r = i − q·size
/// (wrapping), which leaves |r| < 3·size + 256 < 2^24, so r is exact in
/// `f32`. Step two: r/size is within 2^-15 of its exact value, closer than
/// the 1/size ≥ 2^-14 between a non-integer quotient and the next integer,
/// so ⌊r/size⌋ is exact and r − ⌊r/size⌋·size lies in [0, size).
#[inline(always)]
fn rem_euclid<L: LaneLevel>(i: i32x8<L>, size: i32x8<L>) -> i32x8<L> {
    let size_f = f32x8::from_i32x8(size);
    // Inlined like every lane operation: a closure left out of line runs
    // at the baseline and reaches the level's intrinsics through calls
    // (`cargo xtask kernels` finds such calls in the binary).
    let step = zline_simd::inlined(
        #[inline(always)]
        |v: i32x8<L>| {
            let q = floor(f32x8::from_i32x8(v) / size_f).trunc_int();
            v - q * size
        },
    );
    step(step(i))
}

#[cfg(test)]
mod tests {
    use super::*;
    type F = f32x8<Baseline>;
    type I = i32x8<Baseline>;
    use proptest::prelude::*;

    #[test]
    fn rem_euclid_matches_the_scalar_one_at_the_extremes() {
        let sizes = [1, 3, 5, 7, 255, 1000, 16383, 16384];
        let values = [i32::MIN, i32::MIN + 1, -16385, -16384, -1, 0, 1, 16383, 16384, i32::MAX - 1, i32::MAX];
        for size in sizes {
            for chunk in values.chunks(8) {
                let mut lanes = [0; 8];
                lanes[..chunk.len()].copy_from_slice(chunk);
                let got = rem_euclid(I::from(lanes), I::splat(size)).to_array();
                for (k, v) in lanes.iter().enumerate() {
                    assert_eq!(got[k], v.rem_euclid(size), "{v} mod {size}");
                }
            }
        }
    }

    /// Floats where floor is delicate: zeros, halves, the 2^23 boundary,
    /// the i32 range, infinities and NaNs (signalling included).
    const FLOOR_EDGES: [f32; 24] = [
        0.0,
        -0.0,
        0.5,
        -0.5,
        1.0,
        -1.0,
        1.5,
        -1.5,
        8_388_607.5,
        -8_388_607.5,
        8_388_608.0,
        -8_388_608.0,
        16_777_217.0,
        2.147_483_6e9,
        -2.147_483_6e9,
        3.0e9,
        -3.0e9,
        f32::MAX,
        -f32::MAX,
        f32::MIN_POSITIVE,
        -1.0e-45,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ];

    #[test]
    fn sse2_floor_matches_f32_floor_at_the_edges() {
        let snan = f32::from_bits(0x7f80_0001);
        let mut values = FLOOR_EDGES.to_vec();
        values.extend([snan, -snan, f32::from_bits(0xffc0_1234), -0.999_999_94, 0.999_999_94]);
        for chunk in values.chunks(8) {
            let mut lanes = [0.0; 8];
            lanes[..chunk.len()].copy_from_slice(chunk);
            let got = floor_sse2(F::from(lanes)).to_array();
            for (k, v) in lanes.iter().enumerate() {
                assert!(is_floor_of(got[k], *v), "floor({v:e}) = {}", got[k]);
            }
        }
    }

    proptest! {
        #[test]
        fn sse2_floor_matches_f32_floor(bits in any::<u32>(), small in -1.0e7f32..1.0e7) {
            for v in [f32::from_bits(bits), small] {
                let got = floor_sse2(F::splat(v)).to_array()[0];
                prop_assert!(is_floor_of(got, v), "floor({:e}) = {}", v, got);
            }
        }

        #[test]
        fn rem_euclid_matches_the_scalar_one(i in any::<i32>(), size in 1i32..=16384) {
            let got = rem_euclid(I::splat(i), I::splat(size)).to_array()[0];
            prop_assert_eq!(got, i.rem_euclid(size));
        }
    }
}
