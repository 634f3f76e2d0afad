//! The output image: 8-bit RGB, top row first (SPEC §10).

use glam::Vec4;

/// An 8-bit image, rows top to bottom, stored RGBA (4 bytes per pixel,
/// alpha always 255) so the resolve step writes whole words; the PNG writer
/// drops alpha.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Pixel data, `width · height · 4` bytes.
    pub rgba: Vec<u8>,
}

impl Image {
    /// An image with no pixels, to be filled by a renderer.
    pub fn empty() -> Image {
        Image { width: 0, height: 0, rgba: Vec::new() }
    }

    /// The colour of pixel (x, y) as RGB bytes.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = (y as usize * self.width as usize + x as usize) * 4;
        [self.rgba[i], self.rgba[i + 1], self.rgba[i + 2]]
    }

    /// The pixels as packed RGB bytes (3 per pixel), for encoders.
    pub fn to_rgb(&self) -> Vec<u8> {
        self.rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect()
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
/// the floor. Same bytes as [`quantize`] per lane.
#[inline]
pub fn quantize_rgba(c: Vec4) -> [u8; 4] {
    // Vec4::max/min return the second operand for NaN lanes: NaN becomes 0.
    let v = (c.max(Vec4::ZERO).min(Vec4::ONE) * 255.0 + 0.5).as_ivec4();
    v.to_array().map(|x| x as u8)
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
        assert_eq!(quantize_rgba(Vec4::new(f32::NAN, -1.0, 2.0, f32::INFINITY)), [0, 0, 255, 255]);
        assert_eq!(quantize(1.0 / 255.0 * 0.49), 0);
        for k in 0..=255u8 {
            let c = f32::from(k) / 255.0;
            assert_eq!(quantize(c), k);
            assert_eq!(quantize(c + 0.49 / 255.0), k);
            assert_eq!(quantize_rgba(Vec4::new(c, c + 0.49 / 255.0, c - 0.49 / 255.0, 1.0)), [k, k, k, 255]);
        }
    }
}
