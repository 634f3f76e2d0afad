//! The output image: 8-bit RGB, top row first (SPEC §10).

use glam::Vec3;

/// An 8-bit RGB image, rows top to bottom, 3 bytes per pixel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Pixel data, `width · height · 3` bytes.
    pub rgb: Vec<u8>,
}

impl Image {
    /// The colour of pixel (x, y) as bytes.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = (y as usize * self.width as usize + x as usize) * 3;
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }
}

/// SPEC §10: floor(c·255 + 0.5) after clamping to [0, 1]; NaN becomes 0.
#[inline]
pub fn quantize(c: f32) -> u8 {
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    // In [0.5, 255.5]: the cast truncates, which is the floor here.
    (c * 255.0 + 0.5) as u8
}

/// [`quantize`] per channel.
#[inline]
pub fn quantize_rgb(c: Vec3) -> [u8; 3] {
    [quantize(c.x), quantize(c.y), quantize(c.z)]
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
        assert_eq!(quantize(1.0 / 255.0 * 0.49), 0);
    }
}
