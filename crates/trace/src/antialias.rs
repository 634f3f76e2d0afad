//! Anti-aliasing (SPEC §12): n × n camera rays a pixel on a regular grid,
//! or the course's adaptive supersampling.
//!
//! **Adaptive.** A pixel is a square whose four corners are traced (each
//! corner once for the whole image: neighbouring pixels share them) with a
//! ray through its centre, so a feature smaller than the pixel between the
//! corners is still seen. When the five samples agree — every channel,
//! tone-mapped to display values in [0, 1], within [`Adaptive::threshold`]
//! — the square's colour is ½·(mean of the corners) + ½·centre. Otherwise
//! the square is cut into four at its centre (four edge midpoints traced;
//! corners and centre reused) and each quarter is treated the same way,
//! to [`Adaptive::depth`] levels. A square's colour is the mean of its
//! quarters'.
//!
//! Every sample is a function of its image point alone, and the points are
//! dyadic fractions of the pixel (exact in f64), so the image and the ray
//! count do not depend on the thread count or on the order of the pixels.

use glam::Vec3;
use zline_shading::ToneMapping;

use crate::whitted::{Tracer, Work};

pub use zline_scene::trace_options::{Adaptive, MAX_ADAPTIVE_DEPTH};

/// A traced point: the linear colour and its display value.
#[derive(Clone, Copy)]
struct Sample {
    linear: Vec3,
    display: Vec3,
}

/// Traces image points for one row of pixels.
pub(crate) struct Sampler<'a> {
    pub(crate) tracer: &'a Tracer<'a>,
    pub(crate) tone: ToneMapping,
    pub(crate) work: Work,
    pub(crate) stack: Vec<(crate::ray::Ray, Vec3, u32)>,
}

impl Sampler<'_> {
    /// The tree sum of the camera ray through (x, y).
    pub(crate) fn trace(&mut self, x: f64, y: f64) -> Vec3 {
        self.tracer.trace(self.tracer.camera.ray(x, y), &mut self.work, &mut self.stack)
    }

    fn sample(&mut self, x: f64, y: f64) -> Sample {
        let linear = self.trace(x, y);
        Sample { linear, display: self.display(linear) }
    }

    fn display(&self, linear: Vec3) -> Vec3 {
        // NaN (a non-finite scene value) counts as 0: it neither spreads
        // nor hides a spread.
        let d = self.tone.apply(linear).clamp(Vec3::ZERO, Vec3::ONE);
        Vec3::select(d.cmpeq(d), d, Vec3::ZERO)
    }

    /// Pixel (x, y) of n × n regular samples, averaged.
    pub(crate) fn uniform(&mut self, x: u32, y: u32, n: u32) -> Vec3 {
        let mut sum = Vec3::ZERO;
        for j in 0..n {
            for i in 0..n {
                let sx = f64::from(x) + (f64::from(i) + 0.5) / f64::from(n);
                let sy = f64::from(y) + (f64::from(j) + 0.5) / f64::from(n);
                sum += self.trace(sx, sy);
            }
        }
        sum / (n * n) as f32
    }

    /// The colours at the corners of one row of pixels: (x, y) for x in
    /// 0..=width.
    pub(crate) fn corner_row(&mut self, y: u32, width: u32) -> Vec<Vec3> {
        (0..=width).map(|x| self.trace(f64::from(x), f64::from(y))).collect()
    }

    /// Pixel (x, y) by adaptive supersampling, given its corners' colours
    /// (top left, top right, bottom left, bottom right).
    pub(crate) fn adaptive(&mut self, x: u32, y: u32, corners: [Vec3; 4], a: Adaptive) -> Vec3 {
        let c = corners.map(|linear| Sample { linear, display: self.display(linear) });
        self.square(f64::from(x), f64::from(y), 1.0, c, a.depth, a.threshold)
    }

    /// The square at (x, y) of side `s` with corners `c`. The pixel's own
    /// square also compares its centre; a quarter compares its corners
    /// only, and traces its centre when it is cut.
    fn square(&mut self, x: f64, y: f64, s: f64, c: [Sample; 4], levels: u32, threshold: f32) -> Vec3 {
        let h = 0.5 * s;
        let pixel = s == 1.0;
        let centre = pixel.then(|| self.sample(x + h, y + h));
        let first = centre.unwrap_or(c[0]).display;
        let (lo, hi) = c.iter().fold((first, first), |(lo, hi), p| (lo.min(p.display), hi.max(p.display)));
        let corners = 0.25 * (c[0].linear + c[1].linear + c[2].linear + c[3].linear);
        if levels == 0 || (hi - lo).max_element() <= threshold {
            return centre.map_or(corners, |m| 0.5 * (corners + m.linear));
        }
        let centre = centre.unwrap_or_else(|| self.sample(x + h, y + h));
        let top = self.sample(x + h, y);
        let left = self.sample(x, y + h);
        let right = self.sample(x + s, y + h);
        let bottom = self.sample(x + h, y + s);
        let l = levels - 1;
        let quarters = self.square(x, y, h, [c[0], top, left, centre], l, threshold)
            + self.square(x + h, y, h, [top, c[1], centre, right], l, threshold)
            + self.square(x, y + h, h, [left, centre, c[2], bottom], l, threshold)
            + self.square(x + h, y + h, h, [centre, right, bottom, c[3]], l, threshold);
        0.25 * quarters
    }
}
