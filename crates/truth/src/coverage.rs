//! Coverage of a sample by a triangle in sample space: edge functions in f64
//! with the top-left rule (SPEC §3), and the triangle's screen-space
//! barycentric weights and depth at the sample.
//!
//! Each edge is evaluated in a canonical form — from its lexicographically
//! smaller endpoint to the larger one — and then signed so that the interior
//! is positive. Two triangles sharing an edge therefore compute bit-identical
//! values of opposite sign at every sample, and on the edge itself (value
//! exactly 0) the top-left rule gives the sample to exactly one of them: a
//! mesh covers each sample once, whatever the rounding of the coordinates.
//!
//! The top-left rule, in the fast renderer's terms (spans
//! x_left ≤ x < x_right on rows y_top ≤ y < y_bottom, y down): a sample on a
//! left edge (interior at larger x) or on a horizontal top edge (interior
//! at larger y) is covered; on a right or bottom edge it is not.

use glam::DVec2;

use crate::camera::Corner;

/// One edge: `sign · (delta.x·(p.y − origin.y) − delta.y·(p.x − origin.x))`.
#[derive(Clone, Copy, Debug)]
struct Edge {
    origin: DVec2,
    delta: DVec2,
    sign: f64,
    /// True for left and top edges: samples exactly on them are covered.
    inclusive: bool,
}

impl Edge {
    /// The edge from `p` to `q` of a triangle whose doubled signed area
    /// (x·y − y·x form) is `cross`.
    fn new(p: DVec2, q: DVec2, cross: f64) -> Edge {
        let forward = (p.x, p.y) < (q.x, q.y);
        let (origin, end) = if forward { (p, q) } else { (q, p) };
        let delta = end - origin;
        let sign = if forward == (cross > 0.0) { 1.0 } else { -1.0 };
        // ∂value/∂x = −sign·delta.y, ∂value/∂y = sign·delta.x.
        let inclusive = if delta.y != 0.0 { -sign * delta.y > 0.0 } else { sign * delta.x > 0.0 };
        Edge { origin, delta, sign, inclusive }
    }

    #[inline]
    fn value(&self, p: DVec2) -> f64 {
        self.sign * (self.delta.x * (p.y - self.origin.y) - self.delta.y * (p.x - self.origin.x))
    }
}

/// A triangle ready for coverage tests in sample space.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SampleTriangle {
    /// Edge i lies opposite corner i.
    edges: [Edge; 3],
    /// The corners, in the triangle's order.
    pub(crate) corners: [Corner; 3],
    /// |doubled area| in samples².
    area2: f64,
}

/// Edge values of one sample, interior positive (edge i opposite corner i).
pub(crate) type EdgeValues = [f64; 3];

impl SampleTriangle {
    /// The triangle through three projected corners; `None` when its area
    /// is zero or not finite (such a triangle covers nothing).
    pub(crate) fn new(corners: [Corner; 3]) -> Option<SampleTriangle> {
        let [a, b, c] = corners.map(|k| k.pos);
        let cross = signed_area2(a, b, c);
        if !(cross != 0.0 && cross.is_finite()) {
            return None;
        }
        let edges = [Edge::new(b, c, cross), Edge::new(c, a, cross), Edge::new(a, b, cross)];
        Some(SampleTriangle { edges, corners, area2: cross.abs() })
    }

    /// The edge values at `p`.
    #[inline]
    pub(crate) fn values(&self, p: DVec2) -> EdgeValues {
        self.edges.map(|e| e.value(p))
    }

    /// True when the sample with edge values `g` is covered: inside, or on
    /// a top or left edge.
    #[inline]
    pub(crate) fn covers(&self, g: &EdgeValues) -> bool {
        (0..3).all(|i| g[i] > 0.0 || (g[i] == 0.0 && self.edges[i].inclusive))
    }

    /// Screen-space barycentric weights of the corners at a sample with
    /// edge values `g` (which sum to the doubled area).
    #[inline]
    pub(crate) fn weights(&self, g: &EdgeValues) -> [f64; 3] {
        let sum = g[0] + g[1] + g[2];
        g.map(|v| v / sum)
    }

    /// d(weight_i)/dx and d(weight_i)/dy per sample step.
    pub(crate) fn weight_gradients(&self) -> [DVec2; 3] {
        self.edges.map(|e| DVec2::new(-e.sign * e.delta.y, e.sign * e.delta.x) / self.area2)
    }

    /// NC depth for screen weights `lambda` (depth is linear in window space).
    #[inline]
    pub(crate) fn depth(&self, lambda: &[f64; 3]) -> f64 {
        lambda[0] * self.corners[0].z + lambda[1] * self.corners[1].z + lambda[2] * self.corners[2].z
    }

    /// ∂z/∂x and ∂z/∂y per sample step.
    pub(crate) fn depth_gradient(&self) -> DVec2 {
        let grads = self.weight_gradients();
        (0..3).map(|i| grads[i] * self.corners[i].z).sum()
    }

    /// Distance in samples from the sample with edge values `g` to the
    /// triangle's boundary: exact inside; outside, the largest distance to
    /// an edge line it lies beyond, which never exceeds the true distance.
    pub(crate) fn boundary_distance(&self, g: &EdgeValues) -> f64 {
        let d = [0, 1, 2].map(|i| g[i] / self.edges[i].delta.length());
        if d.iter().all(|&v| v >= 0.0) {
            d[0].min(d[1]).min(d[2])
        } else {
            -d[0].min(d[1]).min(d[2])
        }
    }

    /// The sample rows and columns the triangle can cover, as half-open
    /// index ranges clamped to `limit` (columns, rows).
    pub(crate) fn sample_bounds(&self, limit: (i64, i64), margin: f64) -> SampleRect {
        corner_bounds(&self.corners, limit, margin)
    }
}

/// A half-open rectangle of sample indices.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct SampleRect {
    /// First column.
    pub(crate) x0: i64,
    /// First row.
    pub(crate) y0: i64,
    /// One past the last column.
    pub(crate) x1: i64,
    /// One past the last row.
    pub(crate) y1: i64,
}

impl SampleRect {
    /// The common part of two rectangles (possibly empty).
    pub(crate) fn intersect(&self, o: &SampleRect) -> SampleRect {
        SampleRect {
            x0: self.x0.max(o.x0),
            y0: self.y0.max(o.y0),
            x1: self.x1.min(o.x1),
            y1: self.y1.min(o.y1),
        }
    }

    /// True when no sample is inside.
    pub(crate) fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }
}

/// The samples whose centres lie within `margin` samples of the corners'
/// bounding box, clamped to [0, limit).
pub(crate) fn corner_bounds(corners: &[Corner; 3], limit: (i64, i64), margin: f64) -> SampleRect {
    let lo = corners[0].pos.min(corners[1].pos).min(corners[2].pos) - margin;
    let hi = corners[0].pos.max(corners[1].pos).max(corners[2].pos) + margin;
    // Centre i + ½ ≥ lo ⇔ i ≥ ⌈lo − ½⌉; centre ≤ hi ⇔ i ≤ ⌊hi − ½⌋. Clamping
    // in f64 first keeps the casts in range.
    let first = |v: f64, n: i64| (v - 0.5).ceil().clamp(0.0, n as f64) as i64;
    let end = |v: f64, n: i64| ((v - 0.5).floor() + 1.0).clamp(0.0, n as f64) as i64;
    SampleRect {
        x0: first(lo.x, limit.0),
        y0: first(lo.y, limit.1),
        x1: end(hi.x, limit.0),
        y1: end(hi.y, limit.1),
    }
}

/// (b − a) × (c − a), x·y − y·x: negative for a counter-clockwise triangle
/// as seen by the viewer (window y points down).
pub(crate) fn signed_area2(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(p: [(f64, f64); 3]) -> SampleTriangle {
        SampleTriangle::new(p.map(|(x, y)| Corner { pos: DVec2::new(x, y), z: 0.0, inv_w: 1.0 })).unwrap()
    }

    fn covers(t: &SampleTriangle, x: f64, y: f64) -> bool {
        t.covers(&t.values(DVec2::new(x, y)))
    }

    #[test]
    fn top_left_rule_on_an_axis_aligned_right_triangle() {
        // Corners (0,0), (4,0), (0,4): left edge x = 0, top edge y = 0, and
        // a diagonal right/bottom edge x + y = 4.
        for t in [tri([(0.0, 0.0), (4.0, 0.0), (0.0, 4.0)]), tri([(0.0, 0.0), (0.0, 4.0), (4.0, 0.0)])] {
            assert!(covers(&t, 0.0, 1.5), "left edge is in");
            assert!(covers(&t, 1.5, 0.0), "top edge is in");
            assert!(!covers(&t, 2.0, 2.0), "the diagonal is a right edge");
            assert!(covers(&t, 1.0, 1.0));
            assert!(!covers(&t, -0.1, 1.0));
        }
        // The mirrored triangle: right edge x = 4 and bottom edge y = 4 are out.
        let t = tri([(4.0, 4.0), (0.0, 4.0), (4.0, 0.0)]);
        assert!(!covers(&t, 4.0, 2.5) && !covers(&t, 2.5, 4.0));
        assert!(covers(&t, 2.0, 2.0), "the diagonal is its left edge");
    }

    #[test]
    fn shared_edges_cover_each_sample_once() {
        let (a, b, c, d) = ((0.3, 0.1), (7.7, 2.0), (6.1, 9.3), (0.2, 5.5));
        let t1 = tri([a, b, c]);
        let t2 = tri([a, c, d]);
        for j in -2..12 {
            for i in -2..10 {
                let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                let n = usize::from(covers(&t1, x, y)) + usize::from(covers(&t2, x, y));
                assert!(n <= 1, "sample ({x}, {y}) covered twice");
            }
        }
    }

    #[test]
    fn weights_and_distances() {
        let t = tri([(0.0, 0.0), (4.0, 0.0), (0.0, 4.0)]);
        let g = t.values(DVec2::new(1.0, 1.0));
        let w = t.weights(&g);
        assert!((w[0] - 0.5).abs() < 1e-15 && (w[1] - 0.25).abs() < 1e-15 && (w[2] - 0.25).abs() < 1e-15);
        assert!((t.boundary_distance(&g) - 1.0).abs() < 1e-15);
        let outside = t.values(DVec2::new(-2.0, 1.0));
        assert!((t.boundary_distance(&outside) - 2.0).abs() < 1e-15);
        let r = t.sample_bounds((100, 100), 0.0);
        assert_eq!(r, SampleRect { x0: 0, y0: 0, x1: 4, y1: 4 });
        assert!(SampleTriangle::new([Corner { pos: DVec2::ONE, z: 0.0, inv_w: 1.0 }; 3]).is_none());
    }
}
