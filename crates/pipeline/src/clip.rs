//! Clipping in clip space, before the divide (SPEC §2).
//!
//! Setup drops a triangle entirely outside one plane of the view volume
//! (the vertex stage's outcodes, [`crate::volume`]). A triangle that
//! crosses the near or far plane, or leaves the guard band (x, y within
//! ±`guard`·w, far outside the window), is clipped here with
//! Sutherland–Hodgman, which keeps w > 0 for every vertex that will be
//! divided.
//!
//! New vertices interpolate every attribute linearly in clip space, always
//! from the inside vertex towards the outside one, so two triangles sharing a
//! clipped edge get bit-identical new vertices and stay watertight.

use crate::vertex::{ClipVertex, NEEDS_SETUP};
use crate::volume::ClipVolume;

/// Most vertices a triangle can have after clipping by the six planes.
pub const MAX_CLIPPED: usize = 9;

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
    let code = code & !NEEDS_SETUP;
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
    use glam::{Vec3, Vec4};

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
}
