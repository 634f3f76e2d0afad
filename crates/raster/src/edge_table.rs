//! Scan conversion with an edge table and an active edge list (SPEC §3).
//!
//! A triangle's three edges are put in an edge table sorted by their top y;
//! horizontal edges are dropped (they cover no sample row on their own). The
//! active edge list then holds exactly two edges for every sample row: the
//! long edge (top vertex to bottom vertex) on one side and, on the other,
//! the upper short edge until the middle vertex's row and the lower one
//! after it.
//!
//! ## Coverage rule
//! Sample rows are half-open per edge: an edge from y0 to y1 (y0 < y1) is
//! active on rows whose centre yc satisfies y0 ≤ yc < y1; each row's span is
//! the half-open range of columns whose centre xc satisfies
//! x_left(yc) ≤ xc < x_right(yc). This is exactly the top-left rule: samples
//! on left edges and on top (horizontal) edges are in, samples on right and
//! bottom edges are out.
//!
//! ## Exactness
//! The column where an edge crosses a row is computed with integers: the
//! first column `i` whose centre lies at or right of the edge is
//! ⌈num / (256·dy)⌉ for an integer `num`. Both triangles sharing an edge see
//! the same endpoints in the same order (upper first), compute the same
//! column, and one takes it as its first column while the other stops there:
//! no cracks and no double hits. Along the edge the column is stepped from row
//! to row with a quotient and a remainder (a DDA, the seed's incremental
//! x' = x + 1/m) that reproduces the exact division at every row, so starting
//! at any tile's first row gives the same columns as starting at the top.

use crate::fixed::{
    ceil_div, first_sample_at_or_after, floor_div, FixedPoint, Rect, SUBPIXEL_HALF, SUBPIXEL_ONE,
};

/// A run of covered samples on one row: columns `x0..x1` of row `y`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Span {
    /// The row.
    pub y: i32,
    /// First covered column.
    pub x0: i32,
    /// One past the last covered column.
    pub x1: i32,
}

/// A non-horizontal edge, upper endpoint first (fixed point, y0 < y1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Edge {
    x0: i64,
    y0: i64,
    x1: i64,
    y1: i64,
}

impl Edge {
    fn new(a: FixedPoint, b: FixedPoint) -> Edge {
        Edge { x0: a.x.into(), y0: a.y.into(), x1: b.x.into(), y1: b.y.into() }
    }
}

/// An edge's column on successive rows, stepped exactly: the column is
/// `x = ⌈num / d⌉` with `num = x·d − r`, `0 ≤ r < d`.
#[derive(Clone, Copy, Debug)]
struct EdgeWalker {
    x: i64,
    r: i64,
    d: i64,
    step_q: i64,
    step_r: i64,
}

impl EdgeWalker {
    /// The walker positioned on `row`, which must be one of the edge's rows.
    #[inline]
    fn at_row(e: &Edge, row: i64) -> EdgeWalker {
        let dy = e.y1 - e.y0;
        let dx = e.x1 - e.x0;
        let yc = row * SUBPIXEL_ONE + SUBPIXEL_HALF;
        // Column i is at or right of the edge when (i·256 + 128)·dy ≥ x0·dy + (yc − y0)·dx.
        let num = e.x0 * dy + (yc - e.y0) * dx - SUBPIXEL_HALF * dy;
        let d = SUBPIXEL_ONE * dy;
        let x = ceil_div(num, d);
        let step = SUBPIXEL_ONE * dx;
        let step_q = floor_div(step, d);
        EdgeWalker { x, r: x * d - num, d, step_q, step_r: step - step_q * d }
    }

    /// Moves to the next row: num grows by 256·dx.
    #[inline]
    fn step(&mut self) {
        self.x += self.step_q;
        self.r -= self.step_r;
        if self.r < 0 {
            self.r += self.d;
            self.x += 1;
        }
    }
}

/// The edge table of one triangle in window space, ready to scan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeTable {
    /// Vertices sorted by y (top first), as given after snapping.
    pub(crate) sorted: [FixedPoint; 3],
    /// True when the long edge (top to bottom) is the left boundary.
    pub(crate) long_is_left: bool,
    /// Rows and columns that may hold covered samples.
    pub(crate) bounds: Rect,
}

impl EdgeTable {
    /// Builds the table for a triangle in either winding. Returns `None` for
    /// a triangle of zero area, which covers no sample.
    #[inline]
    pub fn new(vertices: [FixedPoint; 3]) -> Option<EdgeTable> {
        // Sorted by (y, x) with three compare-exchanges (points with equal
        // keys are equal, so the order is the one a sort gives).
        let key = |p: FixedPoint| (i64::from(p.y) << 32) + i64::from(p.x);
        let [mut a, mut b, mut c] = vertices;
        if key(b) < key(a) {
            (a, b) = (b, a);
        }
        if key(c) < key(b) {
            (b, c) = (c, b);
        }
        if key(b) < key(a) {
            (a, b) = (b, a);
        }
        let s = [a, b, c];
        let [a, b, c] = s.map(|p| (i64::from(p.x), i64::from(p.y)));
        let cross = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
        if cross == 0 {
            return None;
        }
        let xs = vertices.map(|p| i64::from(p.x));
        let (min_x, max_x) = (xs.into_iter().min()?, xs.into_iter().max()?);
        let bounds = Rect {
            x0: clamp_i32(first_sample_at_or_after(min_x)),
            y0: clamp_i32(first_sample_at_or_after(a.1)),
            x1: clamp_i32(first_sample_at_or_after(max_x)),
            y1: clamp_i32(first_sample_at_or_after(c.1)),
        };
        // cross > 0 with y down: the middle vertex lies right of the long edge.
        Some(EdgeTable { sorted: s, long_is_left: cross > 0, bounds })
    }

    /// The pixels that may be covered: every emitted span lies inside.
    #[inline]
    pub fn bounds(&self) -> Rect {
        self.bounds
    }

    /// The vertices sorted top to bottom.
    #[inline]
    pub fn sorted_vertices(&self) -> [FixedPoint; 3] {
        self.sorted
    }

    /// True when the long edge (top vertex to bottom vertex) bounds the
    /// spans on the left.
    #[inline]
    pub fn long_edge_is_left(&self) -> bool {
        self.long_is_left
    }

    /// Calls `emit` for every non-empty span of covered samples inside
    /// `clip`, row by row from the top.
    #[inline(always)]
    pub fn scan(&self, clip: Rect, mut emit: impl FnMut(Span)) {
        let area = self.bounds.intersect(&clip);
        if area.is_empty() {
            return;
        }
        let [top, mid, bottom] = self.sorted;
        let long = Edge::new(top, bottom);
        let mid_row = first_sample_at_or_after(mid.y.into());
        let (first, end) = (i64::from(area.y0), i64::from(area.y1));
        let mut long_walk = EdgeWalker::at_row(&long, first);
        let parts = [
            (Edge::new(top, mid), first, mid_row.min(end)),
            (Edge::new(mid, bottom), mid_row.max(first), end),
        ];
        for (short, from, to) in parts {
            if from >= to {
                continue;
            }
            let mut short_walk = EdgeWalker::at_row(&short, from);
            for row in from..to {
                let (l, r) =
                    if self.long_is_left { (long_walk.x, short_walk.x) } else { (short_walk.x, long_walk.x) };
                let x0 = l.max(area.x0.into());
                let x1 = r.min(area.x1.into());
                if x0 < x1 {
                    emit(Span { y: clamp_i32(row), x0: clamp_i32(x0), x1: clamp_i32(x1) });
                }
                long_walk.step();
                short_walk.step();
            }
        }
    }
}

/// Rows and columns derived from coordinates within ±2^29 fit in i32.
#[inline]
fn clamp_i32(v: i64) -> i32 {
    v.clamp(i32::MIN.into(), i32::MAX.into()) as i32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(p: [(f32, f32); 3]) -> EdgeTable {
        EdgeTable::new(p.map(|(x, y)| FixedPoint::snap(x, y).unwrap())).unwrap()
    }

    fn spans(t: &EdgeTable, clip: Rect) -> Vec<Span> {
        let mut v = Vec::new();
        t.scan(clip, |s| v.push(s));
        v
    }

    #[test]
    fn axis_aligned_right_triangle_follows_top_left_rule() {
        // Legs on x = 0 (left edge: in) and y = 0 (top edge: in); hypotenuse x + y = 4.
        let t = tri([(0.0, 0.0), (0.0, 4.0), (4.0, 0.0)]);
        let got = spans(&t, Rect::from_size(0, 0, 8, 8));
        // Row y: centre y + 0.5; covered when xc < 4 − yc with xc = i + 0.5, i.e. i < 3 − y.
        let want: Vec<Span> = (0..3).map(|y| Span { y, x0: 0, x1: 3 - y }).collect();
        assert_eq!(got, want);
    }

    #[test]
    fn winding_does_not_matter() {
        let a = tri([(1.2, 0.3), (7.7, 2.9), (3.1, 6.6)]);
        let b = tri([(1.2, 0.3), (3.1, 6.6), (7.7, 2.9)]);
        let clip = Rect::from_size(0, 0, 16, 16);
        assert_eq!(spans(&a, clip), spans(&b, clip));
    }

    #[test]
    fn degenerate_triangle_is_rejected() {
        let p = [(0.0, 0.0), (1.0, 1.0), (2.0, 2.0)].map(|(x, y)| FixedPoint::snap(x, y).unwrap());
        assert!(EdgeTable::new(p).is_none());
    }

    #[test]
    fn clipping_to_a_tile_keeps_the_same_samples() {
        let t = tri([(-3.7, -1.2), (40.3, 9.9), (12.6, 37.1)]);
        let whole = spans(&t, Rect::from_size(-64, -64, 128, 128));
        let mut tiled = Vec::new();
        for ty in 0..8 {
            for tx in 0..8 {
                tiled.extend(spans(&t, Rect::from_size(tx * 7 - 8, ty * 7 - 8, 7, 7)));
            }
        }
        let count = |v: &[Span]| v.iter().map(|s| (s.x1 - s.x0) as usize).sum::<usize>();
        let clipped: Vec<Span> = whole
            .iter()
            .filter_map(|s| {
                let x0 = s.x0.max(-8);
                let x1 = s.x1.min(48);
                (s.y >= -8 && s.y < 48 && x0 < x1).then_some(Span { x0, x1, ..*s })
            })
            .collect();
        assert_eq!(count(&tiled), count(&clipped));
    }
}
