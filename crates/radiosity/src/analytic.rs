//! The analytic form factor from a point to a polygon (Lambert's contour
//! integral, as Baum, Rushmeier and Winget 1989 use it for patches too
//! close for the hemicube): with r_k the polygon's corners seen from the
//! point p of normal n,
//! F = 1/(2π) · |Σ_k θ_k · n·(r_k × r_k+1)/|r_k × r_k+1||,
//! θ_k the angle between r_k and r_k+1. The polygon is first clipped to
//! the half-space in front of p; nothing hides any of it (the caller
//! knows whether something does).

use glam::{DVec3, Vec3};

use crate::patch::Patch;

/// The form factor from the point `p` of unit normal `n` to the triangle
/// `corners`, as if nothing stood between them.
pub fn point_to_triangle(p: Vec3, n: Vec3, corners: &[Vec3; 3]) -> f64 {
    let (p, n) = (p.as_dvec3(), n.as_dvec3());
    let rel: Vec<DVec3> = corners.iter().map(|c| c.as_dvec3() - p).collect();
    // Clipped to n·r ≥ 0 (Sutherland–Hodgman, one plane).
    let mut poly = Vec::with_capacity(4);
    for k in 0..3 {
        let (a, b) = (rel[k], rel[(k + 1) % 3]);
        let (da, db) = (n.dot(a), n.dot(b));
        if da >= 0.0 {
            poly.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            poly.push(a + (b - a) * (da / (da - db)));
        }
    }
    if poly.len() < 3 {
        return 0.0;
    }
    let mut sum = 0.0;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        let cross = a.cross(b);
        let length = cross.length();
        if length == 0.0 || a.length() == 0.0 || b.length() == 0.0 {
            continue;
        }
        let theta = (a.dot(b) / (a.length() * b.length())).clamp(-1.0, 1.0).acos();
        sum += theta * n.dot(cross) / length;
    }
    (sum / (2.0 * std::f64::consts::PI)).abs()
}

/// Near patches are those whose centres lie closer than this many times
/// the longer of the two patches' longest edges.
pub const NEAR_REACH: f32 = 2.0;

/// Replaces, in the hemicube's row of patch `from`, the form factor of
/// every near patch ([`NEAR_REACH`]) the hemicube saw by the analytic one
/// from `from`'s centre ([`point_to_triangle`]): the hemicube decides
/// what is seen, the contour integral how much. A patch the hemicube did
/// not see stays 0. Returns how many entries it replaced.
pub fn refine_near(patches: &[Patch], from: usize, row: &mut [f32]) -> usize {
    let p = &patches[from];
    let edge = |q: &Patch| {
        let [a, b, c] = q.corners;
        (b - a).length_squared().max((c - b).length_squared()).max((a - c).length_squared()).sqrt()
    };
    let own = edge(p);
    let mut replaced = 0;
    for (j, q) in patches.iter().enumerate() {
        if row[j] <= 0.0 || j == from {
            continue;
        }
        let reach = NEAR_REACH * own.max(edge(q));
        if (q.centre - p.centre).length_squared() < reach * reach {
            row[j] = point_to_triangle(p.centre, p.normal, &q.corners) as f32;
            replaced += 1;
        }
    }
    replaced
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_under_the_centre_of_a_square_sees_its_closed_form() {
        // Howell's catalogue B-3: from a point under the corner of an a × b
        // rectangle at distance c, F = 1/(2π)·(A/√(1+A²)·atan(B/√(1+A²)) +
        // B/√(1+B²)·atan(A/√(1+B²))), A = a/c, B = b/c. Under the centre
        // of a 2a × 2a square: four such corners.
        let (a, h) = (0.5f32, 1.0f32);
        let c = |x: f32, y: f32| Vec3::new(x, y, h);
        let tris = [[c(-a, -a), c(a, -a), c(a, a)], [c(-a, -a), c(a, a), c(-a, a)]];
        let f: f64 = tris.iter().map(|t| point_to_triangle(Vec3::ZERO, Vec3::Z, t)).sum();
        let x = f64::from(a / h);
        let root = (1.0 + x * x).sqrt();
        let corner = (2.0 * x / root * (x / root).atan()) / (2.0 * std::f64::consts::PI);
        assert!((f - 4.0 * corner).abs() < 1e-9, "{f} against {}", 4.0 * corner);
        // Behind the point: nothing; half in front: clipped.
        assert_eq!(point_to_triangle(Vec3::ZERO, -Vec3::Z, &tris[0]), 0.0);
        let tilted = point_to_triangle(Vec3::ZERO, Vec3::X, &tris[0]);
        assert!(tilted > 0.0 && tilted < f, "{tilted}");
    }
}
