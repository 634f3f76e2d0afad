//! The output image: 8-bit RGB, top row first (SPEC §10).

use glam::Vec4;
use wide::{f32x4, CmpEq};
use zline_simd::lanes::{f32x8, Baseline};

/// An 8-bit image, rows top to bottom, one packed RGBA word per pixel
/// (bytes R, G, B, A in memory order via `u32::to_le_bytes`), so the
/// resolve step writes whole words. Alpha is 255 everywhere unless
/// [`Image::transparent`] (`RenderSettings::transparent_background`): then
/// it is each pixel's coverage and R, G, B are straight (not premultiplied)
/// colour, 0 where alpha is 0. PNG writers keep alpha only then.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Pixels, `width · height` words.
    pub pixels: Vec<u32>,
    /// True when the alpha bytes are coverage (a transparent background);
    /// false when they are all 255.
    pub transparent: bool,
}

/// The image rows one tile is resolved into: the rows of a band of the
/// image (a row of tiles), whole, or cut to a run of columns — a piece of
/// the band, which one thread draws while others draw the band's other
/// pieces (the rows of a band are shared, their columns are not). Index 0
/// of a row is image column [`ImageRows::first`].
#[derive(Debug)]
pub enum ImageRows<'r, 'a, T> {
    /// Whole rows, one after the other.
    Whole {
        /// The rows' values.
        values: &'a mut [T],
        /// Values per row: the image width.
        width: usize,
    },
    /// Row r is `rows[r]`, its first value at image column `first`.
    Cut {
        /// The rows, each cut to the piece's columns.
        rows: &'r mut [&'a mut [T]],
        /// The image column of each row's first value.
        first: usize,
    },
}

impl<'a, T> ImageRows<'a, 'a, T> {
    /// The whole rows of `values`, `width` values each.
    pub fn whole(values: &'a mut [T], width: usize) -> ImageRows<'a, 'a, T> {
        ImageRows::Whole { values, width }
    }
}

impl<T> ImageRows<'_, '_, T> {
    /// The image column of index 0 in every row.
    pub fn first(&self) -> usize {
        match self {
            ImageRows::Whole { .. } => 0,
            ImageRows::Cut { first, .. } => *first,
        }
    }

    /// Row `r` of these rows (panics past the last, like slice indexing).
    pub fn row(&mut self, r: usize) -> &mut [T] {
        match self {
            ImageRows::Whole { values, width } => &mut values[r * *width..][..*width],
            ImageRows::Cut { rows, .. } => rows[r],
        }
    }
}

impl Image {
    /// An image with no pixels, to be filled by a renderer.
    pub fn empty() -> Image {
        Image { width: 0, height: 0, pixels: Vec::new(), transparent: false }
    }

    /// The colour of pixel (x, y) as RGB bytes.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let [r, g, b, _] = self.pixels[y as usize * self.width as usize + x as usize].to_le_bytes();
        [r, g, b]
    }

    /// The alpha of pixel (x, y): 255 unless the image is
    /// [`Image::transparent`].
    pub fn alpha(&self, x: u32, y: u32) -> u8 {
        self.pixels[y as usize * self.width as usize + x as usize].to_le_bytes()[3]
    }

    /// The pixels as packed RGBA bytes (4 per pixel), for encoders.
    pub fn to_rgba(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|p| p.to_le_bytes()).collect()
    }

    /// The pixels as packed RGB bytes (3 per pixel), for encoders.
    pub fn to_rgb(&self) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|p| {
                let [r, g, b, _] = p.to_le_bytes();
                [r, g, b]
            })
            .collect()
    }
}

/// SPEC §10: floor(c·255 + 0.5) after clamping to [0, 1]; NaN becomes 0
/// (`f32::max` returns the non-NaN operand).
///
/// c·255 + 0.5 is exact in f32 (c·255 < 2^8 leaves room for the half), and
/// adding 2^23 to the integral floor puts it in the low mantissa bits. Every
/// step is an element-wise float operation, so loops over channels
/// vectorize; Rust's saturating `as u8` would not (it measured half of a
/// Gouraud frame).
#[inline]
#[expect(clippy::manual_clamp, reason = "max/min map NaN to 0; clamp would keep it")]
pub fn quantize(c: f32) -> u8 {
    const MANTISSA_SHIFT: f32 = (1u32 << 23) as f32;
    let scaled = (c.max(0.0).min(1.0) * 255.0 + 0.5).floor();
    (scaled + MANTISSA_SHIFT).to_bits() as u8
}

/// [`quantize`] for four channels at once: c·255 + 0.5 lies in
/// [0.5, 255.5] after the clamp, where truncation (one SIMD conversion) is
/// the floor. Same bytes as [`quantize`] per lane, packed as in [`Image`].
#[inline]
pub fn quantize_rgba(c: Vec4) -> u32 {
    // glam's `as_ivec4` converts lane by lane with Rust's saturating casts;
    // wide's truncation is one instruction, valid here because the clamp has
    // removed NaN and put every lane in [0.5, 255.5].
    let v = f32x4::from(c.to_array());
    let v = v.cmp_eq(v).blend(v, f32x4::ZERO);
    let v = v.fast_max(f32x4::ZERO).fast_min(f32x4::ONE) * f32x4::splat(255.0) + f32x4::splat(0.5);
    u32::from_le_bytes(v.fast_trunc_int().to_array().map(|x| x as u8))
}

/// [`quantize_rgba`] for two pixels in one 8-lane vector (the same
/// operations per lane, so the same bytes).
#[inline]
pub fn quantize_rgba_pair(a: Vec4, b: Vec4) -> [u32; 2] {
    let (a, b) = (a.to_array(), b.to_array());
    let v = f32x8::<Baseline>::from([a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]);
    // `clamp` turns NaN into its lower bound, 0.
    let v = v.clamp(f32x8::ZERO, f32x8::ONE) * f32x8::splat(255.0) + f32x8::splat(0.5);
    // Each lane holds a value in 0..=255: its low byte, picked by a shuffle.
    let q: [u8; 32] = bytemuck::cast(v.fast_trunc_int().to_array());
    [u32::from_le_bytes([q[0], q[4], q[8], q[12]]), u32::from_le_bytes([q[16], q[20], q[24], q[28]])]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantize_follows_spec() {
        assert_eq!(quantize(0.0), 0);
        assert_eq!(quantize(1.0), 255);
        assert_eq!(quantize(0.5), 128); // 127.5 + 0.5 = 128
        assert_eq!(quantize(-3.0), 0);
        assert_eq!(quantize(7.0), 255);
        assert_eq!(quantize(f32::NAN), 0);
        assert_eq!(
            quantize_rgba(Vec4::new(f32::NAN, -1.0, 2.0, f32::INFINITY)).to_le_bytes(),
            [0, 0, 255, 255]
        );
        assert_eq!(quantize(1.0 / 255.0 * 0.49), 0);
        for k in 0..=255u8 {
            let c = f32::from(k) / 255.0;
            assert_eq!(quantize(c), k);
            assert_eq!(quantize(c + 0.49 / 255.0), k);
            let q = quantize_rgba(Vec4::new(c, c + 0.49 / 255.0, c - 0.49 / 255.0, 1.0));
            assert_eq!(q.to_le_bytes(), [k, k, k, 255]);
            let c2 = Vec4::new(c - 0.49 / 255.0, f32::NAN, c, 0.5);
            assert_eq!(
                quantize_rgba_pair(c2, Vec4::splat(c)),
                [quantize_rgba(c2), quantize_rgba(Vec4::splat(c))]
            );
        }
    }
}
