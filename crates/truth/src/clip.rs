//! Clipping against the near and far planes in homogeneous clip space, in
//! f64, before any divide (SPEC §2).
//!
//! Sutherland–Hodgman over the planes z + w ≥ 0 (near) then w − z ≥ 0
//! (far), each only when a vertex lies outside it — the order and the fan
//! triangulation (0, i, i + 1) the fast renderer uses, so that screen-linear
//! interpolation over a clipped triangle, which depends on the fan, is the
//! same piecewise-linear function. Every polygon vertex carries its
//! barycentric weights `beta` with respect to the original triangle; the
//! attributes of a new vertex are those weights applied to the original
//! vertices' attributes, which is SPEC §2's "interpolated linearly in clip
//! space". New vertices are interpolated from the inside vertex towards the
//! outside one, so two triangles sharing a clipped edge get the same vertex.
//!
//! x and y are not clipped: samples are only taken inside the image, and
//! f64 holds any window coordinate a vertex with w ≥ near can reach. (The
//! fast renderer also clips a guard band 8192 pixels around the window;
//! with screen-linear interpolation that changes its fan for triangles
//! reaching that far, a case the truth does not imitate.)

use glam::{DVec3, DVec4};

/// Most vertices a triangle has after clipping by two planes.
pub(crate) const MAX_CLIPPED: usize = 5;

/// A polygon vertex: clip position and weights of the original vertices.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct ClipCorner {
    /// Clip-space position.
    pub(crate) clip: DVec4,
    /// Barycentric weights with respect to the original triangle.
    pub(crate) beta: DVec3,
}

impl ClipCorner {
    fn lerp(&self, other: &ClipCorner, t: f64) -> ClipCorner {
        ClipCorner { clip: self.clip.lerp(other.clip, t), beta: self.beta.lerp(other.beta, t) }
    }
}

/// Signed distance to clipping plane `plane` (0 near, 1 far), inside ≥ 0.
fn distance(p: DVec4, plane: usize) -> f64 {
    if plane == 0 {
        p.z + p.w
    } else {
        p.w - p.z
    }
}

/// Clips the triangle (finite clip positions) against near and far; returns
/// the polygon and its vertex count (0 when nothing is left).
pub(crate) fn clip_triangle(clip: [DVec4; 3]) -> ([ClipCorner; MAX_CLIPPED], usize) {
    let mut poly = [ClipCorner::default(); MAX_CLIPPED];
    for (k, (p, c)) in poly.iter_mut().zip(clip).enumerate() {
        *p = ClipCorner { clip: c, beta: DVec3::AXES[k] };
    }
    let mut n = 3;
    for plane in 0..2 {
        if clip.iter().all(|&p| distance(p, plane) >= 0.0) {
            continue;
        }
        let mut out = [ClipCorner::default(); MAX_CLIPPED];
        let mut m = 0;
        for i in 0..n {
            let (p, q) = (&poly[i], &poly[(i + 1) % n]);
            let (dp, dq) = (distance(p.clip, plane), distance(q.clip, plane));
            if dp >= 0.0 {
                out[m] = *p;
                m += 1;
            }
            if (dp >= 0.0) != (dq >= 0.0) && m < MAX_CLIPPED {
                out[m] = if dp >= 0.0 { p.lerp(q, dp / (dp - dq)) } else { q.lerp(p, dq / (dq - dp)) };
                m += 1;
            }
        }
        if m < 3 {
            return (poly, 0);
        }
        (poly, n) = (out, m);
    }
    (poly, n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_clip_keeps_w_positive_and_weights_consistent() {
        let tri = [
            DVec4::new(0.0, 0.0, -3.0, -1.0),
            DVec4::new(0.5, 0.0, 0.5, 2.0),
            DVec4::new(0.0, 0.5, 0.5, 2.0),
        ];
        let (poly, n) = clip_triangle(tri);
        assert_eq!(n, 4);
        for p in &poly[..n] {
            assert!(p.clip.w > 0.0 && p.clip.z + p.clip.w >= -1e-12, "{p:?}");
            let from_beta = tri[0] * p.beta.x + tri[1] * p.beta.y + tri[2] * p.beta.z;
            assert!((from_beta - p.clip).abs().max_element() < 1e-12);
            assert!((p.beta.element_sum() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn triangles_inside_or_outside_pass_or_vanish() {
        let inside =
            [DVec4::new(0.0, 0.0, 0.0, 1.0), DVec4::new(1.0, 0.0, 0.0, 1.0), DVec4::new(0.0, 1.0, 0.0, 1.0)];
        let (poly, n) = clip_triangle(inside);
        assert_eq!(n, 3);
        assert_eq!(poly[1].clip, inside[1]);
        let behind = inside.map(|p| DVec4::new(p.x, p.y, -2.0, 1.0));
        assert_eq!(clip_triangle(behind).1, 0);
    }
}
