//! Render checks (`zline check`): a rendered image against a reference,
//! exact by default, with tolerances as options, and what a failed check
//! leaves behind to look at.
//!
//! - **Exact**: every channel of every pixel equal. zline's images are the
//!   same bit for bit on any machine, thread count or SIMD level, so this
//!   is a usable default, not a wish.
//! - **Per-pixel tolerance**: a pixel *fails* when its largest channel
//!   difference (R, G, B or alpha) exceeds `max_difference`; the check passes while the share
//!   of failing pixels is at most `max_share` (Blender's `idiff -fail
//!   -failpercent`).
//! - **SSIM** (Wang, Bovik, Sheikh and Simoncelli 2004): the mean
//!   structural similarity of the two images' luma (Rec. 601 weights),
//!   with the paper's 11 × 11 Gaussian window of σ = 1.5, K1 = 0.01, K2 =
//!   0.03, L = 255, over the windows that fit inside the image (the
//!   reference implementation's "valid" region). The check passes while it
//!   is at least `min_ssim`.
//! - The **heat map** shows each pixel's largest channel difference:
//!   black for none, then blue, red, yellow and white as it grows to 255.

use serde::Serialize;
use zline_pipeline::Image;

/// What a check allows.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Tolerance {
    /// A pixel fails when a channel differs by more than this (0..=255).
    pub max_difference: u8,
    /// The check passes while at most this share of pixels fails (0..=1).
    pub max_share: f64,
    /// The check also needs a mean SSIM at least this, when set.
    pub min_ssim: Option<f64>,
}

impl Tolerance {
    /// Every pixel equal.
    pub const EXACT: Tolerance = Tolerance { max_difference: 0, max_share: 0.0, min_ssim: None };
}

/// How two images compare.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comparison {
    /// Whether the check passes.
    pub passed: bool,
    /// Both images' size (width, height), or why they cannot be compared.
    pub size: (u32, u32),
    /// Pixels whose channels are not all equal.
    pub differing_pixels: u64,
    /// Pixels past the tolerance's `max_difference`.
    pub failing_pixels: u64,
    /// `failing_pixels` over all pixels.
    pub failing_share: f64,
    /// The largest channel difference.
    pub max_difference: u8,
    /// The root mean square channel difference (R, G, B and A), in 8-bit
    /// levels.
    pub rms: f64,
    /// The mean SSIM of the luma, when the tolerance asks for it and the
    /// images hold at least one window (module doc).
    pub ssim: Option<f64>,
    /// The tolerance judged against.
    pub tolerance: Tolerance,
}

/// Compares `actual` with `reference` under `tolerance`; `None` when
/// their sizes differ.
pub fn compare(actual: &Image, reference: &Image, tolerance: Tolerance) -> Option<Comparison> {
    if (actual.width, actual.height) != (reference.width, reference.height) {
        return None;
    }
    let (mut differing, mut failing, mut max, mut squares) = (0u64, 0u64, 0u8, 0u64);
    for (a, r) in actual.pixels.iter().zip(&reference.pixels) {
        let d = channel_difference(*a, *r);
        differing += u64::from(d > 0);
        failing += u64::from(d > tolerance.max_difference);
        max = max.max(d);
        let (a, r) = (a.to_le_bytes(), r.to_le_bytes());
        squares += (0..4).map(|c| u64::from(a[c].abs_diff(r[c])).pow(2)).sum::<u64>();
    }
    let n = actual.pixels.len().max(1) as f64;
    let share = failing as f64 / n;
    let ssim = tolerance.min_ssim.and(ssim(actual, reference));
    let ssim_ok = match (tolerance.min_ssim, ssim) {
        (Some(min), Some(s)) => s >= min,
        (Some(_), None) => false,
        (None, _) => true,
    };
    Some(Comparison {
        passed: share <= tolerance.max_share && ssim_ok,
        size: (actual.width, actual.height),
        differing_pixels: differing,
        failing_pixels: failing,
        failing_share: share,
        max_difference: max,
        rms: (squares as f64 / (4.0 * n)).sqrt(),
        ssim,
        tolerance,
    })
}

/// The largest of the four channels' (R, G, B, A) differences of two
/// pixels.
fn channel_difference(a: u32, b: u32) -> u8 {
    let (a, b) = (a.to_le_bytes(), b.to_le_bytes());
    (0..4).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0)
}

/// The heat map of the two images' largest channel difference per pixel
/// (module doc); both of one size.
pub fn heat_map(actual: &Image, reference: &Image) -> Image {
    let pixels = actual
        .pixels
        .iter()
        .zip(&reference.pixels)
        .map(|(a, r)| {
            let [r, g, b] = heat(channel_difference(*a, *r));
            u32::from_le_bytes([r, g, b, 255])
        })
        .collect();
    Image { width: actual.width, height: actual.height, pixels, transparent: false }
}

/// The heat map's colour for a difference `d`: black at 0, then blue (1),
/// red (64), yellow (128) and white (255), linear between.
pub fn heat(d: u8) -> [u8; 3] {
    const STOPS: [(f32, [f32; 3]); 5] = [
        (0.0, [0.0, 0.0, 0.0]),
        (1.0, [40.0, 40.0, 255.0]),
        (64.0, [255.0, 0.0, 0.0]),
        (128.0, [255.0, 255.0, 0.0]),
        (255.0, [255.0, 255.0, 255.0]),
    ];
    let d = f32::from(d);
    let k = STOPS.iter().rposition(|(at, _)| *at <= d).unwrap_or(0).min(STOPS.len() - 2);
    let ((a, ca), (b, cb)) = (STOPS[k], STOPS[k + 1]);
    let t = ((d - a) / (b - a)).clamp(0.0, 1.0);
    [0, 1, 2].map(|c| (ca[c] + (cb[c] - ca[c]) * t).round() as u8)
}

/// The SSIM window's side and Gaussian σ (Wang et al. 2004).
const WINDOW: usize = 11;
const SIGMA: f64 = 1.5;

/// Rec. 601 luma of a pixel, 0..=255.
fn luma(p: u32) -> f64 {
    let [r, g, b, _] = p.to_le_bytes();
    0.299 * f64::from(r) + 0.587 * f64::from(g) + 0.114 * f64::from(b)
}

/// The mean SSIM of two images' luma (module doc); `None` when either side
/// is smaller than the window or the sizes differ.
pub fn ssim(a: &Image, b: &Image) -> Option<f64> {
    let (w, h) = (a.width as usize, a.height as usize);
    if (a.width, a.height) != (b.width, b.height) || w < WINDOW || h < WINDOW {
        return None;
    }
    let x: Vec<f64> = a.pixels.iter().map(|p| luma(*p)).collect();
    let y: Vec<f64> = b.pixels.iter().map(|p| luma(*p)).collect();
    ssim_luma(&x, &y, w, h)
}

/// [`ssim`] on luma planes of `w` × `h` values in 0..=255.
pub fn ssim_luma(x: &[f64], y: &[f64], w: usize, h: usize) -> Option<f64> {
    if w < WINDOW || h < WINDOW || x.len() != w * h || y.len() != w * h {
        return None;
    }
    let half = (WINDOW / 2) as f64;
    let g: Vec<f64> =
        (0..WINDOW).map(|i| (-((i as f64 - half).powi(2)) / (2.0 * SIGMA * SIGMA)).exp()).collect();
    let total: f64 = g.iter().sum();
    let g: Vec<f64> = g.iter().map(|v| v / total).collect();
    // Separable weighted means of x, y, x², y², xy over each valid window.
    let (ow, oh) = (w - WINDOW + 1, h - WINDOW + 1);
    let filter = |f: &dyn Fn(usize) -> f64| -> Vec<f64> {
        let mut rows = vec![0.0; ow * h];
        for r in 0..h {
            for c in 0..ow {
                rows[r * ow + c] = (0..WINDOW).map(|k| g[k] * f(r * w + c + k)).sum();
            }
        }
        let mut out = vec![0.0; ow * oh];
        for r in 0..oh {
            for c in 0..ow {
                out[r * ow + c] = (0..WINDOW).map(|k| g[k] * rows[(r + k) * ow + c]).sum();
            }
        }
        out
    };
    let mx = filter(&|i| x[i]);
    let my = filter(&|i| y[i]);
    let mxx = filter(&|i| x[i] * x[i]);
    let myy = filter(&|i| y[i] * y[i]);
    let mxy = filter(&|i| x[i] * y[i]);
    let (c1, c2) = ((0.01f64 * 255.0).powi(2), (0.03f64 * 255.0).powi(2));
    let sum: f64 = (0..ow * oh)
        .map(|i| {
            let (vx, vy, cxy) = (mxx[i] - mx[i] * mx[i], myy[i] - my[i] * my[i], mxy[i] - mx[i] * my[i]);
            ((2.0 * mx[i] * my[i] + c1) * (2.0 * cxy + c2))
                / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2))
        })
        .sum();
    Some(sum / (ow * oh) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(w: u32, h: u32, f: impl Fn(u32, u32) -> [u8; 3]) -> Image {
        let pixels = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                let [r, g, b] = f(x, y);
                u32::from_le_bytes([r, g, b, 255])
            })
            .collect();
        Image { width: w, height: h, pixels, transparent: false }
    }

    #[test]
    fn exact_is_exact_and_tolerances_count_the_pixels_past_them() {
        let a = image(16, 16, |x, y| [(x * 16) as u8, (y * 16) as u8, 7]);
        let same = compare(&a, &a.clone(), Tolerance::EXACT).unwrap();
        assert!(same.passed && same.differing_pixels == 0 && same.rms == 0.0);
        // One pixel off by 3, one by 1.
        let mut b = a.clone();
        b.pixels[5] ^= 3;
        b.pixels[9] ^= 1 << 8;
        let exact = compare(&b, &a, Tolerance::EXACT).unwrap();
        assert!(!exact.passed);
        assert_eq!((exact.differing_pixels, exact.failing_pixels, exact.max_difference), (2, 2, 3));
        let loose = Tolerance { max_difference: 1, ..Tolerance::EXACT };
        let c = compare(&b, &a, loose).unwrap();
        assert_eq!(c.failing_pixels, 1);
        assert!(!c.passed);
        let share = Tolerance { max_difference: 1, max_share: 1.0 / 256.0, min_ssim: None };
        assert!(compare(&b, &a, share).unwrap().passed);
        assert!(compare(&image(8, 8, |_, _| [0; 3]), &a, Tolerance::EXACT).is_none());
    }

    #[test]
    fn the_heat_map_ramps_from_black_through_blue_red_and_yellow_to_white() {
        assert_eq!(heat(0), [0, 0, 0]);
        assert_eq!(heat(1), [40, 40, 255]);
        assert_eq!(heat(64), [255, 0, 0]);
        assert_eq!(heat(128), [255, 255, 0]);
        assert_eq!(heat(255), [255, 255, 255]);
        let a = image(2, 1, |x, _| [x as u8 * 64, 0, 0]);
        let b = image(2, 1, |_, _| [0, 0, 0]);
        let map = heat_map(&a, &b);
        assert_eq!((map.pixel(0, 0), map.pixel(1, 0)), ([0, 0, 0], [255, 0, 0]));
    }

    #[test]
    fn ssim_matches_the_reference_implementation() {
        // scikit-image 0.2x `structural_similarity(x, y, gaussian_weights=True,
        // sigma=1.5, use_sample_covariance=False, data_range=255)`, the
        // settings that reproduce Wang et al.'s published MATLAB code, on
        // these two pairs of 32 × 24 planes (`skimage` printed the values).
        let (w, h) = (32, 24);
        let plane = |f: &dyn Fn(usize, usize) -> f64| -> Vec<f64> {
            (0..h).flat_map(|j| (0..w).map(move |i| (i, j))).map(|(i, j)| f(i, j)).collect()
        };
        let x = plane(&|i, j| ((i * 37 + j * 11) % 256) as f64);
        let y = plane(&|i, j| {
            let bump = if (i as f64 - 16.0).powi(2) + (j as f64 - 12.0).powi(2) < 30.0 { 20.0 } else { 0.0 };
            (((i * 37 + j * 11) % 256) as f64 * 0.8 + 40.0 + bump).min(255.0)
        });
        let s = ssim_luma(&x, &y, w, h).unwrap();
        assert!((s - 0.952_939_167_120_813_8).abs() < 1e-9, "{s}");
        let z = plane(&|i, j| 128.0 + 100.0 * (i as f64 * 0.3).sin() * (j as f64 * 0.2).cos());
        let noisy = plane(&|i, j| {
            128.0
                + 100.0 * (i as f64 * 0.3).sin() * (j as f64 * 0.2).cos()
                + ((i * 7919 + j * 104_729) % 17) as f64
                - 8.0
        });
        let s = ssim_luma(&z, &noisy, w, h).unwrap();
        assert!((s - 0.977_192_025_965_934_2).abs() < 1e-9, "{s}");
    }

    #[test]
    fn ssim_is_one_for_equal_images_and_falls_with_noise_and_shift() {
        let a = image(32, 32, |x, y| [((x * 7 + y * 3) % 256) as u8; 3]);
        assert!((ssim(&a, &a).unwrap() - 1.0).abs() < 1e-12);
        let shifted = image(32, 32, |x, y| [((x * 7 + y * 3) % 256) as u8 / 2 + 60; 3]);
        let s = ssim(&a, &shifted).unwrap();
        assert!(s < 0.99 && s > 0.0, "{s}");
        assert!(ssim(&image(8, 32, |_, _| [0; 3]), &image(8, 32, |_, _| [0; 3])).is_none());
    }
}
