//! The geometry of the Whitted truth ([`crate::whitted`]) in f64: rays,
//! the ray–triangle test, and a bounding-volume hierarchy that answers as
//! brute force over every triangle.
//!
//! **The test.** Woop, Benthin and Wald's (2013) watertight test,
//! evaluated in f64: the triangle is moved into a frame where the ray
//! starts at the origin and runs along +z (axes permuted so that z is the
//! direction's largest component, then sheared), and the three 2D edge
//! functions decide. An edge function of a shared edge is computed from
//! the same two transformed corners by the two triangles, and IEEE
//! subtraction and multiplication make it exactly the negation of the
//! other: a ray through a shared edge or vertex hits at least one of the
//! triangles there, and a point exactly on an edge counts as inside
//! (both triangles hit). A triangle with a non-finite corner, zero
//! area, or seen edge-on (determinant 0) is never hit. The hit's
//! parameter t and barycentric coordinates come from the same edge
//! functions (relative error a few units of 2⁻⁵³).
//!
//! **The ray.** o + t·d for `t_min` < t < `t_max`, optionally skipping one
//! triangle by index (the one a secondary ray starts on).
//!
//! **The hierarchy.** The shared SAH tree (`zline_scene::sah`, the ray
//! tracer's too) over the triangles' boxes rounded outward to f32, every
//! box widened by 10⁻⁷ of the scene's extent so that the slab test's
//! rounding never rejects a triangle the exact test would hit; traversal
//! with a stack of its own. The closest
//! hit is the brute-force one: the smallest t, and at equal t the lower
//! triangle index (boxes are pruned only when they start strictly beyond
//! the best t).

use glam::DVec3;
use zline_scene::sah::{self, F64Node, SahTree};

/// A ray o + t·d over the open interval (`t_min`, `t_max`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ray {
    pub(crate) origin: DVec3,
    pub(crate) dir: DVec3,
    pub(crate) t_min: f64,
    pub(crate) t_max: f64,
    /// A triangle never hit: the one the ray leaves.
    pub(crate) skip: Option<u32>,
}

/// A hit: the ray parameter, the triangle's index, and the barycentric
/// coordinates of the point (of the triangle's corners 0, 1, 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Hit {
    pub(crate) t: f64,
    pub(crate) triangle: u32,
    pub(crate) b: [f64; 3],
}

impl Hit {
    /// The tie rule: the smaller t, at equal t the lower index.
    fn nearer_than(&self, other: &Hit) -> bool {
        self.t < other.t || (self.t == other.t && self.triangle < other.triangle)
    }
}

/// The per-ray part of the watertight test.
#[derive(Clone, Copy, Debug)]
struct Sheared {
    origin: DVec3,
    axes: [usize; 3],
    /// (−dx/dz, −dy/dz, 1/dz) in the permuted frame.
    shear: DVec3,
}

impl Sheared {
    /// `None` for a zero or non-finite direction or a non-finite origin.
    fn new(ray: &Ray) -> Option<Sheared> {
        let d = ray.dir;
        if !d.is_finite() || d == DVec3::ZERO || !ray.origin.is_finite() {
            return None;
        }
        let kz = d.abs().max_position();
        let kx = (kz + 1) % 3;
        let ky = (kx + 1) % 3;
        let shear = DVec3::new(-d[kx] / d[kz], -d[ky] / d[kz], 1.0 / d[kz]);
        Some(Sheared { origin: ray.origin, axes: [kx, ky, kz], shear })
    }

    /// The parameter and barycentrics where the line meets triangle `p`
    /// (edges and corners included), whatever the sign of t.
    fn intersect(&self, p: &[DVec3; 3]) -> Option<(f64, [f64; 3])> {
        let [kx, ky, kz] = self.axes;
        let s = self.shear;
        let moved = |v: DVec3| {
            let v = v - self.origin;
            DVec3::new(v[kx] + s.x * v[kz], v[ky] + s.y * v[kz], v[kz])
        };
        let (p0, p1, p2) = (moved(p[0]), moved(p[1]), moved(p[2]));
        let e0 = p1.x * p2.y - p1.y * p2.x;
        let e1 = p2.x * p0.y - p2.y * p0.x;
        let e2 = p0.x * p1.y - p0.y * p1.x;
        if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
            return None;
        }
        let det = e0 + e1 + e2;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let t = (e0 * p0.z + e1 * p1.z + e2 * p2.z) * s.z / det;
        t.is_finite().then(|| (t, [e0 / det, e1 / det, e2 / det]))
    }
}

/// The triangles in world space and their hierarchy.
#[derive(Debug, Default)]
pub(crate) struct Triangles {
    /// Corners by triangle index (the world's numbering).
    pub(crate) corners: Vec<[DVec3; 3]>,
    /// Indices of the triangles that can be hit, in leaf order.
    order: Vec<u32>,
    nodes: Vec<F64Node>,
}

impl Triangles {
    /// The hierarchy over `corners`; a triangle with a non-finite corner
    /// or zero area is left out (it is never hit).
    pub(crate) fn new(corners: Vec<[DVec3; 3]>) -> Triangles {
        let hittable = (0..corners.len() as u32).filter(|&i| {
            let p = &corners[i as usize];
            let n = (p[1] - p[0]).cross(p[2] - p[0]);
            p.iter().all(|c| c.is_finite()) && n.is_finite() && n != DVec3::ZERO
        });
        let tree = SahTree::build(hittable.map(|i| (i, sah::Bounds::enclosing(&corners[i as usize]))));
        let nodes = tree.f64_nodes();
        Triangles { corners, order: tree.order, nodes }
    }

    /// The nearest hit of `ray` by the tie rule.
    pub(crate) fn closest(&self, ray: &Ray) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        self.walk(ray, |hit| {
            if best.is_none_or(|b| hit.nearer_than(&b)) {
                best = Some(hit);
            }
            best.map_or(ray.t_max, |b| b.t)
        });
        best
    }

    /// Every hit of `ray`, in no particular order.
    pub(crate) fn all_hits(&self, ray: &Ray) -> Vec<Hit> {
        let mut hits = Vec::new();
        self.walk(ray, |hit| {
            hits.push(hit);
            ray.t_max
        });
        hits
    }

    /// Calls `found` for each hit in the ray's interval; `found` returns
    /// the parameter beyond which boxes need not be visited.
    fn walk(&self, ray: &Ray, mut found: impl FnMut(Hit) -> f64) {
        let Some(sheared) = Sheared::new(ray) else { return };
        if self.nodes.is_empty() || ray.t_min.is_nan() || ray.t_max.is_nan() {
            return;
        }
        let mut limit = ray.t_max;
        let mut stack = vec![0usize];
        while let Some(at) = stack.pop() {
            let node = &self.nodes[at];
            match node.entry(ray.origin, ray.dir, ray.t_min, ray.t_max) {
                Some(t) if t <= limit => {}
                _ => continue,
            }
            if node.count == 0 {
                stack.push(node.offset);
                stack.push(at + 1);
                continue;
            }
            for &triangle in &self.order[node.offset..node.offset + node.count] {
                if ray.skip == Some(triangle) {
                    continue;
                }
                let Some((t, b)) = sheared.intersect(&self.corners[triangle as usize]) else { continue };
                if t > ray.t_min && t < ray.t_max {
                    limit = found(Hit { t, triangle, b });
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(origin: DVec3, dir: DVec3) -> Ray {
        Ray { origin, dir, t_min: 0.0, t_max: f64::INFINITY, skip: None }
    }

    #[test]
    fn a_ray_through_the_middle_hits_at_the_plane() {
        let tri = [DVec3::new(-1.0, -1.0, -2.0), DVec3::new(1.0, -1.0, -2.0), DVec3::new(0.0, 1.0, -2.0)];
        let t = Triangles::new(vec![tri]);
        let hit = t.closest(&ray(DVec3::ZERO, DVec3::NEG_Z)).unwrap();
        assert_eq!((hit.t, hit.triangle), (2.0, 0));
        assert_eq!(hit.b, [0.25, 0.25, 0.5]);
        assert!(t.closest(&ray(DVec3::ZERO, DVec3::Z)).is_none(), "behind");
        assert!(t.closest(&Ray { t_max: 1.5, ..ray(DVec3::ZERO, DVec3::NEG_Z) }).is_none(), "beyond");
        assert!(t.closest(&Ray { skip: Some(0), ..ray(DVec3::ZERO, DVec3::NEG_Z) }).is_none(), "skipped");
        assert!(t.closest(&ray(DVec3::ZERO, DVec3::ZERO)).is_none());
        assert!(t.closest(&ray(DVec3::NAN, DVec3::Z)).is_none());
    }

    /// Rays through a shared edge hit one of its triangles, and at equal t
    /// the lower index wins.
    #[test]
    fn shared_edges_leave_no_crack_and_ties_go_to_the_lower_index() {
        let a = [DVec3::new(-1.0, -1.0, -3.0), DVec3::new(1.0, 1.0, -3.5), DVec3::new(-1.0, 1.0, -3.2)];
        let b = [DVec3::new(-1.0, -1.0, -3.0), DVec3::new(1.0, -1.0, -3.1), DVec3::new(1.0, 1.0, -3.5)];
        let t = Triangles::new(vec![a, b]);
        let eye = DVec3::new(0.013, -0.021, 0.7);
        // The edge's ends are corners of the square the two make: a ray
        // through them may pass just outside.
        for k in 1..2000 {
            let f = f64::from(k) / 2000.0;
            let on_edge = a[0].lerp(a[1], f);
            assert!(t.closest(&ray(eye, on_edge - eye)).is_some(), "slipped at {f}");
        }
        let flat = |z: f64| [DVec3::new(-1.0, -1.0, z), DVec3::new(1.0, -1.0, z), DVec3::new(0.0, 1.0, z)];
        let t = Triangles::new(vec![flat(-2.0), flat(-1.0), flat(-1.0)]);
        assert_eq!(t.closest(&ray(DVec3::ZERO, DVec3::NEG_Z)).unwrap().triangle, 1);
        assert_eq!(t.all_hits(&ray(DVec3::ZERO, DVec3::NEG_Z)).len(), 3);
    }

    /// The hierarchy answers as brute force.
    #[test]
    fn the_hierarchy_agrees_with_brute_force() {
        let mut tris = Vec::new();
        for i in 0..24 {
            for j in 0..24 {
                let (x, z) = (f64::from(i) * 0.37 - 4.0, f64::from(j) * 0.41 - 5.0);
                let y = 1.0 + 0.1 * f64::from((i * 7 + j * 3) % 5);
                tris.push([DVec3::new(x, y, z), DVec3::new(x + 0.5, y, z), DVec3::new(x, y + 0.3, z + 0.5)]);
            }
        }
        tris.push([DVec3::ZERO, DVec3::ZERO, DVec3::X]);
        tris.push([DVec3::NAN, DVec3::ZERO, DVec3::X]);
        let t = Triangles::new(tris.clone());
        let brute = |r: &Ray| {
            let s = Sheared::new(r).unwrap();
            let mut best: Option<Hit> = None;
            for (i, p) in tris.iter().enumerate() {
                if let Some((tt, b)) = s.intersect(p) {
                    let hit = Hit { t: tt, triangle: i as u32, b };
                    if tt > r.t_min && tt < r.t_max && best.is_none_or(|x| hit.nearer_than(&x)) {
                        best = Some(hit);
                    }
                }
            }
            best
        };
        let mut hits = 0;
        for i in 0..50 {
            for j in 0..50 {
                let o = DVec3::new(f64::from(i) * 0.2 - 5.0, 4.0, f64::from(j) * 0.2 - 6.0);
                let r = ray(o, DVec3::new(0.13, -1.0, 0.07));
                assert_eq!(t.closest(&r), brute(&r), "{o}");
                hits += usize::from(brute(&r).is_some());
            }
        }
        assert!(hits > 500, "{hits}");
    }
}
