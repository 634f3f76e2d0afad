//! The resolve of a frame with a transparent background
//! (`RenderSettings::transparent_background`): RGBA pixels whose alpha is
//! the coverage.
//!
//! The frame is drawn on a black background, and everything in the colour
//! path is linear in the background (undrawn samples take it, the
//! transparency pass blends C = o·c + (1 − o)·C_behind, the box filter
//! averages), so the colour planes hold premultiplied colour P. The alpha
//! plane follows the same blends with c = 1: α = 1 for a drawn opaque
//! sample, 0 for an undrawn one, α = o + (1 − o)·α_behind through the
//! transparency pass (see `TileTarget::blocks`), 1 under a line. Over n×n
//! samples P and α are averaged first; the pixel is then the straight
//! colour P/α (0 where α = 0), and α, each quantized as SPEC §10 says.
//! Compositing it over a background B gives P + (1 − α)·B: the frame drawn
//! on B, up to the two quantizations.

use zline_raster::LANES;
use zline_simd::lanes::{f32x8, i32x8, Baseline, Level};

use crate::image::ImageRows;
use crate::resolve::{quantize_x8, store_block};
use crate::tile::{load, sample, TileTarget};

impl TileTarget {
    /// [`TileTarget::resolve`] with alpha: eight pixels at a time, straight
    /// colour and coverage (one sample per pixel).
    pub fn resolve_coverage(&self, out: &mut ImageRows<'_, '_, u32>) {
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
                let (empty, alpha) = if self.colors_valid {
                    (f32x8::<Baseline>::ZERO, load(&self.alpha, i))
                } else {
                    let empty = load(&self.depth, i).cmp_eq(f32x8::splat(self.far));
                    (empty, empty.blend(f32x8::ZERO, f32x8::ONE))
                };
                let p = zline_simd::inlined(
                    #[inline(always)]
                    |plane: &[f32x8]| empty.blend(f32x8::ZERO, load(plane, i)),
                );
                let px = pack_straight([p(red), p(green), p(blue)], alpha, &self.tone);
                store_block(out, first, x, &self.rect, &px);
            }
        }
    }

    /// [`TileTarget::resolve_supersampled`] with alpha: the mean of the n²
    /// samples' premultiplied colours and alphas (a fixed order), then the
    /// straight colour.
    pub fn resolve_coverage_supersampled(&self, out: &mut ImageRows<'_, '_, u32>, n: u32) {
        let n = n as i32;
        let scale = 1.0 / (n * n) as f32;
        let [red, green, blue] = &self.rgb;
        let (py0, px0, first) = (self.rect.y0 / n, self.rect.x0 / n, out.first());
        for py in py0..self.rect.y1 / n {
            let out = out.row((py - py0) as usize);
            for px in px0..self.rect.x1 / n {
                let mut sum = [0.0f32; 4];
                for sy in py * n..(py + 1) * n {
                    for sx in px * n..(px + 1) * n {
                        let i = self.index(sx, sy);
                        let (drawn, alpha) = if self.colors_valid {
                            (true, sample(&self.alpha, i))
                        } else {
                            let drawn = sample(&self.depth, i) != self.far;
                            (drawn, if drawn { 1.0 } else { 0.0 })
                        };
                        if drawn {
                            sum[0] += sample(red, i);
                            sum[1] += sample(green, i);
                            sum[2] += sample(blue, i);
                        }
                        sum[3] += alpha;
                    }
                }
                let mean = sum.map(|v| f32x8::<Baseline>::splat(v * scale));
                out[px as usize - first] = pack_straight([mean[0], mean[1], mean[2]], mean[3], &self.tone)[0];
            }
        }
    }
}

/// Eight pixels of premultiplied colour `p` and alpha `alpha` as packed
/// RGBA words: straight colour p/α (0 where α is not above 0) through
/// `tone`, and α, each quantized by SPEC §10.
#[inline(always)]
pub(crate) fn pack_straight<S: Level>(
    p: [f32x8<S>; 3],
    alpha: f32x8<S>,
    tone: &zline_shading::ToneMapping,
) -> [u32; LANES] {
    let covered = alpha.cmp_gt(f32x8::ZERO);
    let safe = covered.blend(alpha, f32x8::ONE);
    let straight = zline_simd::inlined(
        #[inline(always)]
        |c: f32x8<S>| covered.blend(c / safe, f32x8::ZERO),
    );
    let [r, g, b] = crate::resolve::tone_x8(tone, [straight(p[0]), straight(p[1]), straight(p[2])]);
    let packed: i32x8<S> =
        quantize_x8(r) | (quantize_x8(g) << 8) | (quantize_x8(b) << 16) | (quantize_x8(alpha) << 24);
    bytemuck::cast(packed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::quantize;

    #[test]
    fn straight_colour_is_premultiplied_over_alpha() {
        let a: [f32; 8] = [1.0, 0.75, 0.5, 0.0, 0.25, 1.0, 0.1, f32::NAN];
        let c: [f32; 8] = [0.2, 0.6, 0.9, 0.0, 0.5, 0.0, 0.7, 0.3];
        let p = f32x8::<Baseline>::from(std::array::from_fn::<f32, 8, _>(|k| c[k] * a[k]));
        let got = pack_straight([p, p, p], f32x8::from(a), &Default::default());
        for k in 0..7 {
            let s = if a[k] > 0.0 { quantize(c[k] * a[k] / a[k]) } else { 0 };
            assert_eq!(got[k].to_le_bytes(), [s, s, s, quantize(a[k])], "lane {k}");
        }
        // NaN alpha: not covered, alpha 0 (SPEC §10 maps NaN to 0).
        assert_eq!(got[7].to_le_bytes(), [0, 0, 0, 0]);
    }
}
