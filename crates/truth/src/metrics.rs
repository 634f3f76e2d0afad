//! Error statistics between an 8-bit image and the truth, in 8-bit units.

use crate::image::TruthImage;

/// How far an image is from a reference, in 8-bit units (1 = one step of
/// 1/255). Per-pixel shares count a pixel by its largest channel error.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ErrorStats {
    /// Pixels compared.
    pub pixels: usize,
    /// Root mean square of the channel errors.
    pub rmse: f64,
    /// Mean absolute channel error.
    pub mean_abs: f64,
    /// Largest absolute channel error.
    pub max_abs: f64,
    /// Share of pixels with every channel equal.
    pub share_exact: f64,
    /// Share of pixels with a channel off by more than 1.
    pub share_over_1: f64,
}

impl ErrorStats {
    /// Statistics of an 8-bit RGB image (3 bytes per pixel, rows top first,
    /// as `zline_pipeline::Image::to_rgb` returns) against the quantized
    /// truth. Panics when the sizes differ.
    pub fn of_rgb8(image: &[u8], truth: &TruthImage) -> ErrorStats {
        let reference = truth.quantized_rgb8();
        assert_eq!(image.len(), reference.len(), "image and truth differ in size");
        Self::from_channels(image.iter().zip(&reference).map(|(&a, &b)| f64::from(a) - f64::from(b)))
    }

    /// Statistics between two unquantized truth images (each channel
    /// clamped to [0, 1] and scaled by 255; "exact" means a difference
    /// below 10⁻⁹ units). Panics when the sizes differ.
    pub fn between(a: &TruthImage, b: &TruthImage) -> ErrorStats {
        assert_eq!((a.width, a.height), (b.width, b.height), "images differ in size");
        let unit = |c: f64| c.clamp(0.0, 1.0) * 255.0;
        let diffs = a.rgb.iter().zip(&b.rgb).flat_map(|(p, q)| {
            let (p, q) = (p.to_array(), q.to_array());
            [0, 1, 2].map(|i| {
                let d = unit(p[i]) - unit(q[i]);
                if d.abs() < 1e-9 {
                    0.0
                } else {
                    d
                }
            })
        });
        Self::from_channels(diffs)
    }

    /// Statistics of channel differences given pixel by pixel (R, G, B).
    fn from_channels(diffs: impl Iterator<Item = f64>) -> ErrorStats {
        let diffs: Vec<f64> = diffs.collect();
        let pixels = diffs.len() / 3;
        if pixels == 0 {
            return ErrorStats::default();
        }
        let (mut sq, mut abs, mut max, mut exact, mut over) = (0.0, 0.0, 0.0f64, 0usize, 0usize);
        for px in diffs.chunks_exact(3) {
            let worst = px.iter().fold(0.0f64, |m, d| m.max(d.abs()));
            exact += usize::from(worst == 0.0);
            over += usize::from(worst > 1.0);
            max = max.max(worst);
            sq += px.iter().map(|d| d * d).sum::<f64>();
            abs += px.iter().map(|d| d.abs()).sum::<f64>();
        }
        let channels = (pixels * 3) as f64;
        ErrorStats {
            pixels,
            rmse: (sq / channels).sqrt(),
            mean_abs: abs / channels,
            max_abs: max,
            share_exact: exact as f64 / pixels as f64,
            share_over_1: over as f64 / pixels as f64,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn statistics_of_a_known_difference() {
        let truth = TruthImage { width: 2, height: 1, rgb: vec![DVec3::ZERO, DVec3::ONE], diagnostics: None };
        let stats = ErrorStats::of_rgb8(&[0, 0, 0, 255, 252, 255], &truth);
        assert_eq!((stats.pixels, stats.max_abs, stats.share_exact, stats.share_over_1), (2, 3.0, 0.5, 0.5));
        assert!((stats.rmse - (9.0f64 / 6.0).sqrt()).abs() < 1e-12);
        assert_eq!(ErrorStats::between(&truth, &truth).share_exact, 1.0);
    }
}
