//! The truth's output: unquantized colours, SPEC §10's quantization, and
//! the optional diagnostics.

use glam::DVec3;

/// An image from [`crate::render_truth`]: colours before quantization, rows
/// top first.
#[derive(Clone, Debug, PartialEq)]
pub struct TruthImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width · height` colours: the mean of each pixel's sample colours
    /// (each lit, clamped, fogged and blended), not clamped again.
    pub rgb: Vec<DVec3>,
    /// Where a renderer that rounds coordinates and colours differently may
    /// legitimately differ; with [`crate::TruthOptions::diagnostics`] only.
    pub diagnostics: Option<Diagnostics>,
}

/// Per-pixel measures of how sensitive the truth is to small shifts of the
/// geometry: what a comparison with a fast renderer must allow for.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Diagnostics {
    /// The distance in pixels from the pixel's nearest sample to the nearest
    /// place where the image may change abruptly — an edge of any triangle
    /// (hidden or not), or a swap of depth order between the visible
    /// fragment and another one covering the sample — capped at 2 pixels;
    /// 0 where a light's N·L is within 10⁻⁴ of 0, where its specular term
    /// switches on. Nearest filtering and alpha cutoffs are not covered.
    pub boundary_distance: Vec<f32>,
    /// The largest change, in 8-bit steps, of a sample's colour when the
    /// sample moves 1/256 pixel along x or y — twice the largest shift of a
    /// vertex snapped to the 1/256-pixel grid, so a bound (to first order)
    /// on what such snapping does to the colour away from boundaries.
    pub sensitivity: Vec<f32>,
}

impl TruthImage {
    /// The unquantized colour of pixel (x, y).
    pub fn pixel(&self, x: u32, y: u32) -> DVec3 {
        self.rgb[y as usize * self.width as usize + x as usize]
    }

    /// The image as 8-bit RGB, 3 bytes per pixel, rows top first, quantized
    /// as SPEC §10 says (the layout of `zline_pipeline::Image::to_rgb`).
    pub fn quantized_rgb8(&self) -> Vec<u8> {
        self.rgb.iter().flat_map(|c| c.to_array().map(quantize)).collect()
    }
}

/// SPEC §10: floor(c·255 + 0.5) after clamping to [0, 1]; NaN gives 0.
pub fn quantize(c: f64) -> u8 {
    if c.is_nan() {
        return 0;
    }
    (c.clamp(0.0, 1.0) * 255.0 + 0.5).floor() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantize_follows_spec() {
        assert_eq!([0.0, 1.0, 0.5, -3.0, 7.0, f64::NAN].map(quantize), [0, 255, 128, 0, 255, 0]);
        for k in 0..=255u8 {
            let c = f64::from(k) / 255.0;
            assert_eq!((quantize(c), quantize(c + 0.49 / 255.0), quantize(c - 0.49 / 255.0)), (k, k, k));
        }
    }
}
