//! Clipping in clip space, before the divide (SPEC §2).
//!
//! Every triangle is classified by outcodes against the view volume
//! (−w ≤ x, y, z ≤ w): entirely outside one plane → dropped. A triangle that
//! crosses the near or far plane, or leaves the guard band (x, y within
//! ±`guard`·w, far outside the window), is clipped with Sutherland–Hodgman,
//! which keeps w > 0 for every vertex that will be divided. x and y are not
//! clipped to the window itself: the scan converter clips spans to tiles, so
//! the guard band only bounds coordinates for exact fixed-point arithmetic.
//!
//! New vertices interpolate every attribute linearly in clip space, always
//! from the inside vertex towards the outside one, so two triangles sharing a
//! clipped edge get bit-identical new vertices and stay watertight.

use glam::Vec4;

use crate::vertex::ClipVertex;

/// Most vertices a triangle can have after clipping by the six planes.
pub const MAX_CLIPPED: usize = 9;

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
    fn distances(&self, p: Vec4) -> [f32; 6] {
        let (gx, gy) = (self.guard_x * p.w, self.guard_y * p.w);
        [p.z + p.w, p.w - p.z, p.x + gx, gx - p.x, p.y + gy, gy - p.y]
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

/// Clips a triangle against the planes in `code` (the OR of its vertices'
/// [`ClipVolume::clip_code`]s). Writes the polygon into `out` and returns its
/// vertex count (0 when nothing is left; a fan of n − 2 triangles otherwise).
pub fn clip_polygon(
    volume: &ClipVolume,
    tri: [ClipVertex; 3],
    code: u8,
    out: &mut [ClipVertex; MAX_CLIPPED],
) -> usize {
    let mut a = [ClipVertex::default(); MAX_CLIPPED];
    let code = code & !crate::vertex::NEEDS_SETUP;
    a[..3].copy_from_slice(&tri);
    let mut n = 3;
    for plane in 0..6 {
        if code & (1 << plane) == 0 {
            continue;
        }
        let mut m = 0;
        for i in 0..n {
            let (p, q) = (&a[i], &a[(i + 1) % n]);
            let (dp, dq) = (volume.distances(p.clip)[plane], volume.distances(q.clip)[plane]);
            let (p_in, q_in) = (dp >= 0.0, dq >= 0.0);
            if p_in {
                out[m] = *p;
                m += 1;
            }
            if p_in != q_in && m < MAX_CLIPPED {
                out[m] = if p_in { p.lerp(q, dp / (dp - dq)) } else { q.lerp(p, dq / (dq - dp)) };
                m += 1;
            }
        }
        n = m;
        if n < 3 {
            return 0;
        }
        a[..n].copy_from_slice(&out[..n]);
    }
    out[..n].copy_from_slice(&a[..n]);
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn v(x: f32, y: f32, z: f32, w: f32) -> ClipVertex {
        ClipVertex { clip: Vec4::new(x, y, z, w), normal: Vec3::Z, ..ClipVertex::default() }
    }

    #[test]
    fn near_plane_clip_keeps_w_positive() {
        let vol = ClipVolume::new(100, 100);
        // One vertex behind the eye (w < 0), two in front.
        let tri = [v(0.0, 0.0, -3.0, -1.0), v(0.5, 0.0, 0.5, 2.0), v(0.0, 0.5, 0.5, 2.0)];
        let code = tri.iter().fold(0, |c, p| c | vol.clip_code(p.clip));
        let mut out = [ClipVertex::default(); MAX_CLIPPED];
        let n = clip_polygon(&vol, tri, code, &mut out);
        assert_eq!(n, 4);
        for p in &out[..n] {
            assert!(p.clip.w > 0.0 && p.clip.z + p.clip.w >= -1e-6, "{p:?}");
        }
    }

    #[test]
    fn nan_vertices_are_outside() {
        let vol = ClipVolume::new(10, 10);
        assert_ne!(vol.clip_code(Vec4::new(f32::NAN, 0.0, 0.0, 1.0)), 0);
        assert_ne!(view_code(Vec4::splat(f32::NAN)), 0);
    }
}
