//! Occluders: triangles in a bounding-volume hierarchy, and the f64
//! segment and ray test that decides whether a light is seen from a
//! point. The truth's shadows (zline-truth) and the adaptive choice of an
//! area light's samples ([`crate::choose_area_samples`]) both ask it.
//!
//! The rule: light k is hidden from P when a triangle crosses the open
//! segment from P to the light's position (a point light), or the ray from
//! P towards the light (a directional light). With the segment P + t·D,
//! D = position − P, t ∈ (1e-9, 1 − 1e-9); with the ray, D the unit vector
//! towards the light, t > 1e-9. A hit on a triangle's edge or corner
//! counts (so a ray through a shared edge cannot slip between two
//! triangles); a segment lying in a triangle's plane does not hit it. The
//! triangle the point lies on is skipped by identity ([`TriangleId`]),
//! not by an offset of the ray's start.
//!
//! The hierarchy is the shared SAH tree ([`crate::sah`]) over the
//! triangles' boxes rounded outward to f32, and its boxes are widened a
//! little more, so that it rejects only triangles the segment–triangle
//! test would miss too: the answer is the brute-force answer over all
//! triangles.

use glam::DVec3;

use crate::sah::{self, F64Node, SahTree};

/// Hits at a segment or ray parameter t ≤ this (relative to the segment
/// for a point light) are ignored, and for point lights those at
/// t ≥ 1 − this too.
const T_EPSILON: f64 = 1e-9;

/// Which mesh triangle a caster is, or which one a receiver sample lies
/// on: the object's index in the scene and the triangle's in its mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TriangleId {
    /// The object's index in the scene.
    pub object: u32,
    /// The triangle's index in the object's mesh.
    pub triangle: u32,
}

/// A caster triangle in eye space: a corner and the two edges from it,
/// and which mesh triangle it is.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Triangle {
    a: DVec3,
    e1: DVec3,
    e2: DVec3,
    id: TriangleId,
}

impl Triangle {
    /// The triangle a, b, c; `None` with a non-finite corner or zero area.
    fn new(id: TriangleId, a: DVec3, b: DVec3, c: DVec3) -> Option<Triangle> {
        let (e1, e2) = (b - a, c - a);
        let n = e1.cross(e2);
        (a.is_finite() && b.is_finite() && c.is_finite() && n.is_finite() && n != DVec3::ZERO)
            .then_some(Triangle { a, e1, e2, id })
    }

    /// The box of the corners the test reads, in f32 rounded outward.
    fn bounds(&self) -> sah::Bounds {
        sah::Bounds::enclosing(&[self.a, self.a + self.e1, self.a + self.e2])
    }

    /// Möller–Trumbore: the parameter t where o + t·d meets the triangle
    /// (edges included), `None` when it misses or d is parallel to it.
    fn hit(&self, o: DVec3, d: DVec3) -> Option<f64> {
        let p = d.cross(self.e2);
        let det = self.e1.dot(p);
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let inv = 1.0 / det;
        let s = o - self.a;
        let u = s.dot(p) * inv;
        if !(0.0..=1.0).contains(&u) {
            return None;
        }
        let q = s.cross(self.e1);
        let v = d.dot(q) * inv;
        if v < 0.0 || u + v > 1.0 {
            return None;
        }
        Some(self.e2.dot(q) * inv)
    }
}

/// Every caster triangle of a frame in eye space, in a bounding-volume
/// hierarchy, and the segment test of the shadow rule.
#[derive(Debug, Default)]
pub struct Occluders {
    triangles: Vec<Triangle>,
    nodes: Vec<F64Node>,
}

impl Occluders {
    /// The occluders formed by `triangles` (identity and eye-space
    /// corners); degenerate and non-finite ones are dropped.
    pub fn new(triangles: impl IntoIterator<Item = (TriangleId, [DVec3; 3])>) -> Occluders {
        let triangles: Vec<Triangle> =
            triangles.into_iter().filter_map(|(id, [a, b, c])| Triangle::new(id, a, b, c)).collect();
        let tree = SahTree::build((0..).zip(triangles.iter().map(Triangle::bounds)));
        // Boxes widened by a hair of the scene's size: the slab test's
        // rounding must never reject a triangle the exact test hits.
        let nodes = tree.f64_nodes();
        Occluders { triangles: tree.order.iter().map(|&i| triangles[i as usize]).collect(), nodes }
    }

    /// True without any caster triangle.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// True when a caster triangle other than `on` (the one `point` lies
    /// on) crosses the segment from `point` to a point light at `light`.
    pub fn hides_point(&self, point: DVec3, on: TriangleId, light: DVec3) -> bool {
        self.crossed(point, light - point, 1.0 - T_EPSILON, on)
    }

    /// True when a caster triangle other than `on` (the one `point` lies
    /// on) crosses the ray from `point` along the unit vector `to_light`
    /// (a directional light).
    pub fn hides_direction(&self, point: DVec3, on: TriangleId, to_light: DVec3) -> bool {
        self.crossed(point, to_light, f64::INFINITY, on)
    }

    /// True when some triangle other than `skip` meets o + t·d for
    /// T_EPSILON < t < t_max.
    fn crossed(&self, o: DVec3, d: DVec3, t_max: f64, skip: TriangleId) -> bool {
        if self.nodes.is_empty() || !o.is_finite() || !d.is_finite() || d == DVec3::ZERO {
            return false;
        }
        // The tree has at most 63 levels (crate::sah), so the stack holds
        // at most one node a level plus one.
        let mut stack = [0usize; 64];
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let at = stack[len];
            let node = &self.nodes[at];
            if node.entry(o, d, 0.0, t_max).is_none() {
                continue;
            }
            if node.count == 0 {
                stack[len] = node.offset;
                stack[len + 1] = at + 1;
                len += 2;
                continue;
            }
            let hit = self.triangles[node.offset..node.offset + node.count]
                .iter()
                .filter(|t| t.id != skip)
                .filter_map(|t| t.hit(o, d))
                .any(|t| t > T_EPSILON && t < t_max);
            if hit {
                return true;
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Triangle `triangle` of object 0.
    fn id(triangle: u32) -> TriangleId {
        TriangleId { object: 0, triangle }
    }

    /// A receiver triangle that is no caster.
    const ELSEWHERE: TriangleId = TriangleId { object: 9, triangle: 0 };

    /// The unit square at y = 1, x and z in [0, 1], as two triangles.
    fn roof() -> Occluders {
        let p = |x: f64, z: f64| DVec3::new(x, 1.0, z);
        Occluders::new([
            (id(0), [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]),
            (id(1), [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)]),
        ])
    }

    #[test]
    fn a_point_light_above_the_roof_is_hidden_below_it_only() {
        let o = roof();
        let light = DVec3::new(0.5, 3.0, 0.5);
        assert!(o.hides_point(DVec3::new(0.5, 0.0, 0.5), ELSEWHERE, light));
        // Through the shared diagonal: still hidden.
        assert!(o.hides_point(DVec3::new(0.25, 0.0, 0.25), ELSEWHERE, DVec3::new(0.25, 3.0, 0.25)));
        // Beside the roof's shadow (the shadow of x ∈ [0, 1] from x = 0.5,
        // height 3, reaches x ∈ [−0.25, 1.25] at y = 0).
        assert!(!o.hides_point(DVec3::new(1.3, 0.0, 0.5), ELSEWHERE, light));
        assert!(o.hides_point(DVec3::new(1.2, 0.0, 0.5), ELSEWHERE, light));
        // A point between the roof and the light, and a light below the roof.
        assert!(!o.hides_point(DVec3::new(0.5, 2.0, 0.5), ELSEWHERE, light));
        assert!(!o.hides_point(DVec3::new(0.5, 0.0, 0.5), ELSEWHERE, DVec3::new(0.5, 0.5, 0.5)));
        // Hits at the segment's ends do not count.
        assert!(!o.hides_point(DVec3::new(0.5, 1.0, 0.5), ELSEWHERE, light));
        assert!(!o.hides_point(DVec3::new(0.5, 0.0, 0.5), ELSEWHERE, DVec3::new(0.5, 1.0, 0.5)));
    }

    #[test]
    fn a_directional_light_is_hidden_along_its_ray() {
        let o = roof();
        assert!(o.hides_direction(DVec3::new(0.5, -5.0, 0.5), ELSEWHERE, DVec3::Y));
        assert!(!o.hides_direction(DVec3::new(0.5, -5.0, 0.5), ELSEWHERE, -DVec3::Y));
        assert!(!o.hides_direction(DVec3::new(1.5, -5.0, 0.5), ELSEWHERE, DVec3::Y));
        let slant = DVec3::new(1.0, 1.0, 0.0).normalize();
        assert!(o.hides_direction(DVec3::new(-0.5, 0.0, 0.5), ELSEWHERE, slant));
    }

    #[test]
    fn degenerate_triangles_cast_nothing() {
        let a = DVec3::new(0.0, 1.0, 0.0);
        let o = Occluders::new([
            (id(0), [a, a, DVec3::new(1.0, 1.0, 1.0)]),
            (id(1), [a, DVec3::NAN, a]),
            (id(2), [a; 3]),
        ]);
        assert!(o.is_empty());
        assert!(!o.hides_point(DVec3::ZERO, ELSEWHERE, DVec3::new(0.0, 3.0, 0.0)));
    }

    /// The hierarchy answers as brute force over a grid of many triangles.
    #[test]
    fn the_hierarchy_agrees_with_brute_force() {
        let mut tris = Vec::new();
        for i in 0..20 {
            for j in 0..20 {
                let (x, z) = (f64::from(i) * 0.37 - 3.0, f64::from(j) * 0.41 - 4.0);
                let y = 1.0 + 0.1 * f64::from((i * 7 + j * 3) % 5);
                tris.push([DVec3::new(x, y, z), DVec3::new(x + 0.3, y, z), DVec3::new(x, y + 0.2, z + 0.3)]);
            }
        }
        let o = Occluders::new((0..).map(id).zip(tris.iter().copied()));
        let flat: Vec<Triangle> =
            tris.iter().filter_map(|&[a, b, c]| Triangle::new(id(0), a, b, c)).collect();
        let light = DVec3::new(0.3, 6.0, -0.2);
        let mut hidden = 0;
        for i in 0..60 {
            for j in 0..60 {
                let p = DVec3::new(f64::from(i) * 0.15 - 4.5, 0.0, f64::from(j) * 0.15 - 5.0);
                let brute = flat
                    .iter()
                    .filter_map(|t| t.hit(p, light - p))
                    .any(|t| t > T_EPSILON && t < 1.0 - T_EPSILON);
                assert_eq!(o.hides_point(p, ELSEWHERE, light), brute, "{p}");
                hidden += usize::from(brute);
            }
        }
        assert!(hidden > 100 && hidden < 3500, "{hidden}");
    }

    /// The triangle a point lies on is skipped by identity; every other
    /// triangle of the same object still hides.
    #[test]
    fn the_sample_s_own_triangle_is_skipped() {
        let o = roof();
        // A point on triangle 0 (z < x), slightly below the roof's plane so
        // that its own triangle would hit at t ≈ 1e-6 > 1e-9.
        let p = DVec3::new(0.75, 1.0 - 1e-6, 0.25);
        assert!(o.hides_direction(p, ELSEWHERE, DVec3::Y));
        assert!(!o.hides_direction(p, id(0), DVec3::Y));
        assert!(o.hides_direction(p, id(1), DVec3::Y));
        // Under triangle 1 (z > x): only skipping triangle 1 itself lets
        // the light through.
        let q = DVec3::new(0.25, 0.5, 0.75);
        assert!(o.hides_point(q, id(0), DVec3::new(0.25, 3.0, 0.75)));
        assert!(!o.hides_point(q, id(1), DVec3::new(0.25, 3.0, 0.75)));
        // The identity is the pair: triangle 1 of another object is not it.
        assert!(o.hides_point(q, TriangleId { object: 1, triangle: 1 }, DVec3::new(0.25, 3.0, 0.75)));
    }
}
