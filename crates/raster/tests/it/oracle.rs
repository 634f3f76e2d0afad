//! The oracle: a brute-force rasteriser that tests samples one by one with
//! exact integer edge functions (i128: no product of fixed-point coordinates
//! can overflow). It shares no code with the crate's edge table, only the
//! conventions of SPEC §3 and of the fixed-point format:
//! - the sample of pixel (i, j) is at (i + 0.5, j + 0.5) px, in fixed point
//!   (i·256 + 128, j·256 + 128);
//! - a sample strictly inside the triangle is covered; a sample on an edge is
//!   covered iff the edge is a top edge (horizontal, with the triangle below
//!   it in y-down window space) or a left edge (not horizontal, with the
//!   triangle to its right). On a vertex both edges through it must qualify.
//!
//! "Inside" is "on the same side of every edge as the third vertex", so the
//! test does not depend on the winding.

use crate::shapes::{Tri, HALF, ONE};
use zline_raster::Rect;

/// A point in fixed-point units.
pub(crate) type P = (i128, i128);

/// Which side of the line a→b the point p is on: (b − a) × (p − a).
pub(crate) fn side(a: P, b: P, p: P) -> i128 {
    (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
}

/// The sample position of pixel (col, row) in fixed point.
pub(crate) fn sample(col: i64, row: i64) -> P {
    (
        i128::from(col) * i128::from(ONE) + i128::from(HALF),
        i128::from(row) * i128::from(ONE) + i128::from(HALF),
    )
}

/// The vertices widened to i128.
pub(crate) fn points(t: Tri) -> [P; 3] {
    t.map(|v| (i128::from(v.x), i128::from(v.y)))
}

/// True when the edge a→b of a triangle whose third vertex is r owns the
/// samples lying on it.
fn is_top_or_left(a: P, b: P, r: P) -> bool {
    if a.1 == b.1 {
        // Horizontal: a top edge when the triangle (r) is below it, y down.
        return r.1 > a.1;
    }
    // Left edge: r lies right of the edge's line at r's height, i.e.
    // r.x > a.x + (r.y − a.y)·(b.x − a.x)/(b.y − a.y); multiplied out by
    // (b.y − a.y), whose sign decides the direction of the inequality.
    let lhs = (r.0 - a.0) * (b.1 - a.1) - (r.1 - a.1) * (b.0 - a.0);
    (lhs > 0) == (b.1 > a.1)
}

#[derive(Clone, Copy, Debug)]
struct OracleEdge {
    a: P,
    b: P,
    /// The sign of `side(a, b, ·)` inside the triangle.
    inside: i128,
    /// Whether samples on the edge are covered.
    owns_ties: bool,
}

/// One triangle, ready for sample tests.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Oracle {
    edges: [OracleEdge; 3],
}

impl Oracle {
    /// `None` for a triangle of zero area (it covers nothing).
    pub(crate) fn new(t: Tri) -> Option<Oracle> {
        let p = points(t);
        if side(p[0], p[1], p[2]) == 0 {
            return None;
        }
        let edges = [0, 1, 2].map(|k| {
            let (a, b, r) = (p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
            OracleEdge { a, b, inside: side(a, b, r).signum(), owns_ties: is_top_or_left(a, b, r) }
        });
        Some(Oracle { edges })
    }

    /// True when the sample of pixel (col, row) is covered.
    pub(crate) fn covers(&self, col: i64, row: i64) -> bool {
        let s = sample(col, row);
        self.edges.iter().all(|e| match side(e.a, e.b, s) {
            0 => e.owns_ties,
            d => d.signum() == e.inside,
        })
    }
}

/// The covered samples of `rect` as (row, col), row-major, testing every
/// sample of the rectangle.
pub(crate) fn covered_grid(t: Tri, rect: Rect) -> Vec<(i32, i32)> {
    let Some(o) = Oracle::new(t) else { return Vec::new() };
    let mut out = Vec::new();
    for row in rect.y0..rect.y1 {
        for col in rect.x0..rect.x1 {
            if o.covers(col.into(), row.into()) {
                out.push((row, col));
            }
        }
    }
    out
}

/// Like [`covered_grid`], for rectangles too large to test every sample:
/// each row tests only the columns within 2 px of where the triangle meets
/// the band 1 px above and below the row's sample line (computed in f64,
/// whose error is far below a pixel). Samples outside that window cannot be
/// inside the triangle.
pub(crate) fn covered_windowed(t: Tri, rect: Rect) -> Vec<(i32, i32)> {
    let Some(o) = Oracle::new(t) else { return Vec::new() };
    let mut out = Vec::new();
    for row in rect.y0..rect.y1 {
        let Some((lo, hi)) = row_window(t, row) else { continue };
        let (lo, hi) = (lo.max(rect.x0.into()), hi.min(rect.x1.into()));
        for col in lo..hi {
            if o.covers(col, row.into()) {
                out.push((row, i32::try_from(col).expect("inside rect")));
            }
        }
    }
    out
}

/// The covered samples of `rect`: every sample for small rectangles, row
/// windows for large ones.
pub(crate) fn covered(t: Tri, rect: Rect) -> Vec<(i32, i32)> {
    let area = i64::from(rect.width()) * i64::from(rect.height());
    if area <= 1 << 16 {
        covered_grid(t, rect)
    } else {
        covered_windowed(t, rect)
    }
}

/// Columns `lo..hi` that may hold covered samples on `row`, or `None` when
/// the triangle does not reach within 1 px of the row.
fn row_window(t: Tri, row: i32) -> Option<(i64, i64)> {
    let yc = f64::from(row) + 0.5;
    let (lo, hi) = (yc - 1.0, yc + 1.0);
    let p = t.map(|v| (f64::from(v.x) / ONE as f64, f64::from(v.y) / ONE as f64));
    // The triangle clipped to the band lo ≤ y ≤ hi is a convex polygon whose
    // corners are vertices inside the band and edge crossings of its borders.
    let mut xs = Vec::with_capacity(9);
    for k in 0..3 {
        let (a, b) = (p[k], p[(k + 1) % 3]);
        if (lo..=hi).contains(&a.1) {
            xs.push(a.0);
        }
        for h in [lo, hi] {
            if a.1 != b.1 && a.1.min(b.1) <= h && h <= a.1.max(b.1) {
                xs.push(a.0 + (h - a.1) * (b.0 - a.0) / (b.1 - a.1));
            }
        }
    }
    let min = xs.iter().copied().reduce(f64::min)?;
    let max = xs.iter().copied().reduce(f64::max)?;
    // Saturating casts; the caller clamps to its rectangle.
    Some(((min - 2.0).floor() as i64, (max + 2.0).ceil() as i64 + 1))
}

/// Hand-computed cases: the oracle itself must be right before anything is
/// compared with it.
mod tests {
    use super::*;
    use crate::shapes::fixed;

    /// A triangle with vertices given in half pixels (so on sample rows and
    /// columns when odd).
    fn halves(p: [(i64, i64); 3]) -> Tri {
        p.map(|(x, y)| fixed(x * HALF, y * HALF))
    }

    #[track_caller]
    fn check_oracle(t: Tri, rect: Rect, want: &[(i32, i32)]) {
        assert_eq!(covered_grid(t, rect), want, "oracle on {t:?}");
        assert_eq!(covered_windowed(t, rect), want, "windowed oracle on {t:?}");
        let mut reversed = t;
        reversed.swap(1, 2);
        assert_eq!(covered_grid(reversed, rect), want, "oracle on the other winding {reversed:?}");
    }

    #[test]
    fn oracle_applies_the_top_left_rule_to_a_square_with_edges_through_samples() {
        // The square with corners on the samples of pixels (0, 0) and (2, 2):
        // its top and left sides own their samples, bottom and right do not.
        let rect = Rect::from_size(-2, -2, 8, 8);
        let upper = halves([(1, 1), (5, 1), (5, 5)]); // top edge, right edge, diagonal (left)
        let lower = halves([(1, 1), (5, 5), (1, 5)]); // diagonal (right), bottom edge, left edge
        check_oracle(upper, rect, &[(0, 0), (0, 1), (1, 1)]);
        check_oracle(lower, rect, &[(1, 0)]);
    }

    #[test]
    fn oracle_gives_a_shared_vertex_to_one_triangle_only() {
        // Four triangles around the sample of pixel (1, 1): it belongs to
        // exactly one of them, the one right of and below it.
        let c = (3, 3);
        let rim = [(3, 1), (5, 3), (3, 5), (1, 3)];
        let owners: Vec<usize> = (0..4)
            .filter(|&k| {
                let t = halves([c, rim[k], rim[(k + 1) % 4]]);
                Oracle::new(t).is_some_and(|o| o.covers(1, 1))
            })
            .collect();
        // Triangle 1 is (centre, right, bottom).
        assert_eq!(owners, [1]);
    }

    #[test]
    fn oracle_covers_nothing_for_zero_area() {
        let rect = Rect::from_size(-2, -2, 8, 8);
        let line = halves([(1, 1), (3, 3), (5, 5)]);
        assert!(Oracle::new(line).is_none());
        check_oracle(line, rect, &[]);
    }

    #[test]
    fn oracle_matches_the_hand_computed_right_triangle() {
        // Legs on x = 0 and y = 0, hypotenuse x + y = 4 through samples:
        // row y covers columns 0..3−y (the hypotenuse is a right edge).
        let t = [fixed(0, 0), fixed(0, 4 * ONE), fixed(4 * ONE, 0)];
        let want: Vec<(i32, i32)> = (0..3).flat_map(|y| (0..3 - y).map(move |x| (y, x))).collect();
        check_oracle(t, Rect::from_size(-1, -1, 6, 6), &want);
    }
}
