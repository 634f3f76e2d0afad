//! The resolve: a tile's samples into the packed 8-bit pixels of the image
//! (SPEC §10), box-filtering n×n samples per pixel when supersampling.
//! Samples no fragment reached (depth still at the far value) take the
//! background here, since tiles never clear their colour planes.

use glam::Vec3;
use zline_raster::LANES;
use zline_shading::Vec3x8;
use zline_simd::lanes::{f32x8, i32x8, Level};

use crate::image::ImageRows;
use crate::tile::{load, sample, TileTarget};

impl TileTarget {
    /// Quantizes the tile into `out`, the packed RGBA image rows that hold
    /// it (row 0 is the tile's first row).
    pub fn resolve(&self, out: &mut ImageRows<'_, '_, u32>) {
        zline_simd::vectorize(Resolve { target: self, out });
    }

    /// [`Self::resolve`] at level `S`: the plain loop when the background
    /// is one colour and no tone mapping follows (the common frame, whose
    /// loop must stay as lean as before the sky existed), else the general
    /// one.
    #[inline(always)]
    fn resolve_at<S: Level>(&self, out: &mut ImageRows<'_, '_, u32>) {
        if self.sky_drawn || !self.tone.is_identity() {
            return self.resolve_rows::<S>(
                out,
                #[inline(always)]
                |i| self.background_block(i),
                #[inline(always)]
                |rgb| tone_x8(&self.tone, rgb),
            );
        }
        let bg = Vec3x8::<S>::splat(self.background);
        self.resolve_rows::<S>(
            out,
            #[inline(always)]
            |_| bg,
            #[inline(always)]
            |rgb| rgb,
        )
    }

    /// The resolve's loop, with the background of each block and the
    /// mapping before quantization given.
    #[inline(always)]
    fn resolve_rows<S: Level>(
        &self,
        out: &mut ImageRows<'_, '_, u32>,
        background: impl Fn(usize) -> Vec3x8<S>,
        map: impl Fn([f32x8<S>; 3]) -> [f32x8<S>; 3],
    ) {
        if self.stride == 0 {
            return;
        }
        let [red, green, blue] = &self.rgb;
        let first = out.first() as i32;
        for row in 0..self.rect.height() as usize {
            let line = row * self.stride;
            let out = out.row(row);
            for x in (self.origin..self.origin + self.stride as i32).step_by(LANES) {
                let i = line + (x - self.origin) as usize;
                let bg = background(i);
                let empty = if self.colors_valid {
                    f32x8::ZERO
                } else {
                    load(&self.depth, i).cmp_eq(f32x8::splat(self.far))
                };
                let c = zline_simd::inlined(
                    #[inline(always)]
                    |plane: &[f32x8], b: f32x8<S>| empty.blend(b, load(plane, i)),
                );
                let [r, g, b] = map([c(red, bg.x), c(green, bg.y), c(blue, bg.z)]);
                let px = pack_rgba(r, g, b);
                store_block(out, first, x, &self.rect, &px);
            }
        }
    }

    /// Box-filters the tile's n×n samples per pixel into `out` (the packed
    /// image rows from the tile's first pixel row): each
    /// pixel gets the mean of its samples' colours (the background where a
    /// sample was never drawn), summed in a fixed order, then SPEC §10's
    /// quantization. The tile's rect is in samples and a multiple of n.
    pub fn resolve_supersampled(&self, out: &mut ImageRows<'_, '_, u32>, n: u32) {
        let n = n as i32;
        let scale = 1.0 / (n * n) as f32;
        let [red, green, blue] = &self.rgb;
        let (py0, px0, first) = (self.rect.y0 / n, self.rect.x0 / n, out.first());
        for py in py0..self.rect.y1 / n {
            let out = out.row((py - py0) as usize);
            for px in px0..self.rect.x1 / n {
                let mut sum = Vec3::ZERO;
                for sy in py * n..(py + 1) * n {
                    for sx in px * n..(px + 1) * n {
                        let i = self.index(sx, sy);
                        let drawn = self.colors_valid || sample(&self.depth, i) != self.far;
                        let color = Vec3::new(sample(red, i), sample(green, i), sample(blue, i));
                        sum += if drawn { color } else { self.background_at(i) };
                    }
                }
                let color = if self.tone.is_identity() { sum * scale } else { self.tone.apply(sum * scale) };
                out[px as usize - first] = crate::image::quantize_rgba(color.extend(1.0));
            }
        }
    }
}

/// Writes the eight pixels `px` of image columns `x..x + 8` into the image
/// row `out` (whose index 0 is column `first`), those inside `rect`'s
/// columns only (whole when the block is).
#[inline(always)]
pub(crate) fn store_block(out: &mut [u32], first: i32, x: i32, rect: &zline_raster::Rect, px: &[u32; LANES]) {
    if x >= rect.x0 && x + LANES as i32 <= rect.x1 {
        let at = (x - first) as usize;
        out[at..at + LANES].copy_from_slice(px);
        return;
    }
    for (k, &p) in px.iter().enumerate() {
        let c = x + k as i32;
        if (rect.x0..rect.x1).contains(&c) {
            out[(c - first) as usize] = p;
        }
    }
}

/// [`TileTarget::resolve`] as a job of [`zline_simd::vectorize`].
struct Resolve<'a, 'r, 'b> {
    target: &'a TileTarget,
    out: &'a mut ImageRows<'r, 'b, u32>,
}

impl zline_simd::Vectorized for Resolve<'_, '_, '_> {
    type Output = ();

    #[inline(always)]
    fn run<S: Level>(self) {
        self.target.resolve_at::<S>(self.out);
    }
}

/// SPEC §10 for eight pixels: each channel clamped (NaN to 0), scaled,
/// rounded half up, packed as in [`crate::Image`]. c·255 + 0.5 lies in
/// [0.5, 255.5] after the clamp, where truncation is the floor.
#[inline(always)]
fn pack_rgba<S: Level>(r: f32x8<S>, g: f32x8<S>, b: f32x8<S>) -> [u32; LANES] {
    let q = quantize_x8;
    let alpha = i32x8::splat(0xFF << 24);
    let packed = q(r) | (q(g) * i32x8::splat(1 << 8)) | (q(b) * i32x8::splat(1 << 16)) | alpha;
    bytemuck::cast(packed)
}

/// Eight pixels' channels through `tone` (SPEC §10), lane by lane with the
/// scalar operator; unchanged when it is the identity (the clamp follows in
/// the quantization).
#[inline(always)]
pub(crate) fn tone_x8<S: Level>(tone: &zline_shading::ToneMapping, rgb: [f32x8<S>; 3]) -> [f32x8<S>; 3] {
    if tone.is_identity() {
        return rgb;
    }
    tone_lanes(tone, rgb.map(|c| c.to_array())).map(f32x8::from)
}

/// [`tone_x8`]'s lanes: one compiled copy for every SIMD level.
#[inline(never)]
fn tone_lanes(tone: &zline_shading::ToneMapping, [r, g, b]: [[f32; LANES]; 3]) -> [[f32; LANES]; 3] {
    let mut out = [[0.0f32; LANES]; 3];
    for k in 0..LANES {
        let c = tone.apply(Vec3::new(r[k], g[k], b[k]));
        (out[0][k], out[1][k], out[2][k]) = (c.x, c.y, c.z);
    }
    out
}

/// SPEC §10 for one channel of eight pixels: clamped (NaN to 0), scaled,
/// rounded half up, as an integer in 0..=255 per lane.
#[inline(always)]
pub(crate) fn quantize_x8<S: Level>(c: f32x8<S>) -> i32x8<S> {
    // `clamp` turns NaN into its lower bound, 0.
    (c.clamp(f32x8::ZERO, f32x8::ONE) * f32x8::splat(255.0) + f32x8::splat(0.5)).fast_trunc_int()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::quantize;
    use zline_simd::lanes::Baseline;

    #[test]
    fn pack_matches_the_scalar_quantizer() {
        let r: [f32; 8] = [0.0, 1.0, 0.5, f32::NAN, -2.0, 7.0, 0.2, 100.0 / 255.0];
        let g = r.map(|v| v * 0.7);
        let b = r.map(|v| 1.0 - v);
        let got = pack_rgba(f32x8::<Baseline>::from(r), f32x8::from(g), f32x8::from(b));
        for k in 0..8 {
            let want = u32::from_le_bytes([quantize(r[k]), quantize(g[k]), quantize(b[k]), 255]);
            assert_eq!(got[k], want, "lane {k}");
        }
    }
}
