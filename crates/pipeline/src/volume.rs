//! The view volume and the clipping planes in clip space (SPEC §2), shared
//! by the vertex stage (which classifies every vertex) and the clipper
//! (which cuts triangles against the planes a triangle's vertices leave).
//!
//! Two sets of planes: the view volume −w ≤ x, y, z ≤ w decides what is
//! dropped; the clipping planes — near, far and a guard band far outside the
//! window — decide what is clipped. x and y are not clipped to the window:
//! the scan converter clips spans to tiles, so the guard band only bounds
//! coordinates for exact fixed-point arithmetic.

use glam::Vec4;
use zline_simd::lanes::{f32x8, Level};

/// Pixels of guard band beyond each side of the window.
pub const GUARD_BAND_PIXELS: f32 = 8192.0;

/// The planes a frame clips against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipVolume {
    /// |x| ≤ guard_x·w keeps window x within the guard band.
    pub guard_x: f32,
    /// |y| ≤ guard_y·w keeps window y within the guard band.
    pub guard_y: f32,
}

impl ClipVolume {
    /// The guard band for a window size.
    pub fn new(width: u32, height: u32) -> ClipVolume {
        let g = |size: u32| 1.0 + 2.0 * GUARD_BAND_PIXELS / size.max(1) as f32;
        ClipVolume { guard_x: g(width), guard_y: g(height) }
    }

    /// Signed distances to the clipping planes (inside ≥ 0): near, far,
    /// left, right, bottom, top of the guard band.
    #[inline]
    pub fn distances(&self, p: Vec4) -> [f32; 6] {
        let (gx, gy) = (self.guard_x * p.w, self.guard_y * p.w);
        [p.z + p.w, p.w - p.z, p.x + gx, gx - p.x, p.y + gy, gy - p.y]
    }

    /// [`ClipVolume::clip_code`] of eight points (x, y, z, w in lanes).
    #[inline(always)]
    pub fn clip_codes_x8<S: Level>(&self, [x, y, z, w]: [f32x8<S>; 4]) -> [u8; 8] {
        let (gx, gy) = (f32x8::splat(self.guard_x) * w, f32x8::splat(self.guard_y) * w);
        outcodes([z + w, w - z, x + gx, gx - x, y + gy, gy - y])
    }

    /// Bit i set when `p` is outside clipping plane i (NaN counts as outside).
    #[inline]
    pub fn clip_code(&self, p: Vec4) -> u8 {
        let mut code = 0;
        for (i, d) in self.distances(p).into_iter().enumerate() {
            code |= u8::from(d.is_nan() || d < 0.0) << i;
        }
        code
    }
}

/// Bit i set when `p` is outside view-volume plane i (x, y, z in ±w):
/// left, right, bottom, top, near, far.
#[inline]
pub fn view_code(p: Vec4) -> u8 {
    let d = [p.x + p.w, p.w - p.x, p.y + p.w, p.w - p.y, p.z + p.w, p.w - p.z];
    let mut code = 0;
    for (i, d) in d.into_iter().enumerate() {
        code |= u8::from(d.is_nan() || d < 0.0) << i;
    }
    code
}

/// [`view_code`] of eight points (x, y, z, w in lanes).
#[inline(always)]
pub fn view_codes_x8<S: Level>([x, y, z, w]: [f32x8<S>; 4]) -> [u8; 8] {
    outcodes([x + w, w - x, y + w, w - y, z + w, w - z])
}

/// Per lane, bit i set when distance i is negative or NaN (not ≥ 0). The
/// bits are summed as floats in lanes (powers of two: exact), which keeps
/// the eight codes apart without moving masks between registers.
#[inline(always)]
fn outcodes<S: Level>(d: [f32x8<S>; 6]) -> [u8; 8] {
    let zero = f32x8::splat(0.0);
    let mut code = zero;
    let mut bit = 1.0;
    for d in d {
        code += (!d.cmp_ge(zero)).blend(f32x8::splat(bit), zero);
        bit *= 2.0;
    }
    let code = code.to_array();
    let mut codes = [0; 8];
    for (c, v) in codes.iter_mut().zip(code) {
        *c = v as u8;
    }
    codes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_vertices_are_outside() {
        let vol = ClipVolume::new(10, 10);
        assert_ne!(vol.clip_code(Vec4::new(f32::NAN, 0.0, 0.0, 1.0)), 0);
        assert_ne!(view_code(Vec4::splat(f32::NAN)), 0);
    }
}
