//! Triangle generators shared by the tests, and small helpers around the
//! crate's scan converter.
//!
//! Coordinates are generated either directly in fixed point (so they can be
//! put exactly on sample positions: see [`Lattice`]) or as f32 pixels that go
//! through [`FixedPoint::snap`], as the pipeline's do.

use proptest::prelude::*;
use std::f64::consts::TAU;
use zline_raster::{EdgeTable, FixedPoint, Rect, Span, SUBPIXEL_ONE};

/// A triangle in window space, snapped.
pub(crate) type Tri = [FixedPoint; 3];

/// One pixel in fixed-point units.
pub(crate) const ONE: i64 = SUBPIXEL_ONE;
/// Half a pixel: the offset of a sample from its pixel's corner.
pub(crate) const HALF: i64 = ONE / 2;

/// A point from fixed-point coordinates.
pub(crate) fn fixed(x: i64, y: i64) -> FixedPoint {
    FixedPoint { x: i32::try_from(x).expect("x fits in i32"), y: i32::try_from(y).expect("y fits in i32") }
}

/// A point from pixel coordinates, rounded to f32 then snapped like the
/// pipeline's vertices.
pub(crate) fn snapped(x: f64, y: f64) -> FixedPoint {
    FixedPoint::snap(x as f32, y as f32).expect("test coordinates are in range")
}

/// `v` rounded to the nearest multiple of `q` plus `offset`.
fn round_to(v: i64, q: i64, offset: i64) -> i64 {
    (v - offset + q / 2).div_euclid(q) * q + offset
}

/// Where generated vertices may lie, to stress the tie cases of the
/// top-left rule: vertices on samples, edges through samples, horizontal
/// edges on sample rows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Lattice {
    /// Anywhere on the 1/256 px grid.
    Free,
    /// Multiples of half a pixel: pixel corners and pixel centres (samples).
    HalfPixel,
    /// y on a sample row, x anywhere.
    SampleRow,
    /// Exactly on samples.
    SampleCentre,
}

impl Lattice {
    /// Moves a fixed-point point onto the lattice (by at most half a pixel).
    pub(crate) fn put(self, x: i64, y: i64) -> FixedPoint {
        let (x, y) = match self {
            Lattice::Free => (x, y),
            Lattice::HalfPixel => (round_to(x, HALF, 0), round_to(y, HALF, 0)),
            Lattice::SampleRow => (x, round_to(y, ONE, HALF)),
            Lattice::SampleCentre => (round_to(x, ONE, HALF), round_to(y, ONE, HALF)),
        };
        fixed(x, y)
    }

    /// Moves a point given in pixels onto the lattice.
    pub(crate) fn put_px(self, x: f64, y: f64) -> FixedPoint {
        let s = ONE as f64;
        self.put((x * s).round() as i64, (y * s).round() as i64)
    }
}

/// Any lattice, the free one half the time.
pub(crate) fn lattice() -> impl Strategy<Value = Lattice> {
    prop_oneof![
        3 => Just(Lattice::Free),
        1 => Just(Lattice::HalfPixel),
        1 => Just(Lattice::SampleRow),
        1 => Just(Lattice::SampleCentre),
    ]
}

/// A fixed-point coordinate in `lo..hi` pixels.
fn coord(lo: i64, hi: i64) -> impl Strategy<Value = i64> {
    lo * ONE..hi * ONE
}

/// Triangles with vertices in `lo..hi` pixels on a random lattice.
pub(crate) fn lattice_tri(lo: i64, hi: i64) -> impl Strategy<Value = Tri> {
    (
        lattice(),
        [(coord(lo, hi), coord(lo, hi)), (coord(lo, hi), coord(lo, hi)), (coord(lo, hi), coord(lo, hi))],
    )
        .prop_map(|(l, p)| p.map(|(x, y)| l.put(x, y)))
}

/// Triangles from f32 pixel coordinates in `lo..hi`, snapped.
pub(crate) fn f32_tri(lo: f32, hi: f32) -> impl Strategy<Value = Tri> {
    [(lo..hi, lo..hi), (lo..hi, lo..hi), (lo..hi, lo..hi)]
        .prop_map(|p| p.map(|(x, y)| FixedPoint::snap(x, y).expect("in range")))
}

/// Triangles at most a few pixels across, near the origin.
pub(crate) fn subpixel_tri() -> impl Strategy<Value = Tri> {
    let offset = || (-3 * ONE..=3 * ONE, -3 * ONE..=3 * ONE);
    (lattice(), coord(-8, 8), coord(-8, 8), [offset(), offset(), offset()])
        .prop_map(|(l, bx, by, p)| p.map(|(x, y)| l.put(bx + x / 4, by + y / 4)))
}

/// Long thin triangles at random angles: up to 2000 px long and between
/// 1/256 and 1 px wide (log-uniform: as many below 1/16 px as above), the
/// third vertex anywhere along the long side.
pub(crate) fn sliver(centre: f64) -> impl Strategy<Value = Tri> {
    (lattice(), -centre..centre, -centre..centre, 0.0..TAU, 4.0..2000.0f64, 0.0..8.0f64, 0.0..1.0f64)
        .prop_map(|(l, cx, cy, angle, len, thin, t)| {
            let width = (-thin).exp2();
            let (d, n) = ((angle.cos(), angle.sin()), (-angle.sin(), angle.cos()));
            let along = |s: f64| (cx + s * len * d.0, cy + s * len * d.1);
            let (a, b, c) = (along(-0.5), along(0.5), along(t - 0.5));
            [l.put_px(a.0, a.1), l.put_px(b.0, b.1), l.put_px(c.0 + width * n.0, c.1 + width * n.1)]
        })
}

/// Slivers whose long edge runs through samples: from a sample, n steps of a
/// small integer vector (p, q) px, so the edge passes through n + 1 samples;
/// the third vertex 1/256 to 1 px off the edge (log-uniform). Samples lie
/// exactly on the edge, and values change steeply across it.
pub(crate) fn sample_edge_sliver() -> impl Strategy<Value = Tri> {
    let direction = (-20i64..=20, -20i64..=20).prop_filter("a direction", |&(p, q)| p != 0 || q != 0);
    (coord(-300, 300), coord(-300, 300), direction, 1i64..=100, 0.0..1.0f64, 0.0..8.0f64, any::<bool>())
        .prop_map(|(x, y, (p, q), n, t, thin, left)| {
            let a = (round_to(x, ONE, HALF), round_to(y, ONE, HALF));
            let b = (a.0 + n * p * ONE, a.1 + n * q * ONE);
            let len = ((p * p + q * q) as f64).sqrt();
            let w = (-thin).exp2() * ONE as f64 * if left { -1.0 } else { 1.0 };
            let along = |u: i64, v: i64| u as f64 + t * (v - u) as f64;
            let c = (along(a.0, b.0) - w * q as f64 / len, along(a.1, b.1) + w * p as f64 / len);
            [fixed(a.0, a.1), fixed(b.0, b.1), fixed(c.0.round() as i64, c.1.round() as i64)]
        })
}

/// Triangles up to 300 px across far from the origin: up to ±1e5 px, and
/// sometimes near the largest accepted coordinate (±2^21 px), from f32.
pub(crate) fn far_tri() -> impl Strategy<Value = Tri> {
    let base = prop_oneof![4 => -1.0e5..1.0e5f64, 1 => prop_oneof![-2.09e6..-2.0e6f64, 2.0e6..2.09e6f64]];
    let offset = || (-300.0..300.0f64, -300.0..300.0f64);
    (base.clone(), base, [offset(), offset(), offset()], 0.0..1.0f64).prop_map(|(bx, by, p, scale)| {
        // Scale some triangles down to a few pixels.
        let s = scale * scale;
        p.map(|(x, y)| snapped(bx + s * x, by + s * y))
    })
}

/// Slivers far from the origin.
pub(crate) fn far_sliver() -> impl Strategy<Value = Tri> {
    (-1.0e5..1.0e5f64, -1.0e5..1.0e5f64, sliver(10.0)).prop_map(|(bx, by, t)| {
        t.map(|p| fixed(i64::from(p.x) + (bx as i64) * ONE, i64::from(p.y) + (by as i64) * ONE))
    })
}

/// Triangles up to 8192 px wide and at most 8 px tall, anywhere in
/// −9000..9192 px. A quarter of them have a top edge 8192 px long just above
/// a sample row and a height of 1 to 8 px, so their first span holds at
/// least 8192·(1 − 1/256) = 8160 samples.
pub(crate) fn wide_tri() -> impl Strategy<Value = Tri> {
    let any =
        (lattice(), -9000i64..1000, 1i64..=8192, coord(-50, 50), 0..=8 * ONE, 1..=8 * ONE, 0.0..=1.0f64)
            .prop_map(|(l, x0, w, y0, h1, h2, t)| {
                let (x0, w) = (x0 * ONE, w * ONE);
                [l.put(x0, y0), l.put(x0 + w, y0 + h1), l.put(x0 + (t * w as f64) as i64, y0 + h2)]
            });
    let full = (coord(-9000, 1000), -50i64..50, ONE..=8 * ONE, 0.0..=1.0f64).prop_map(|(x0, row, h, t)| {
        // The top edge is 1/256 px above the samples of `row`.
        let (y0, w) = (row * ONE + HALF - 1, 8192 * ONE);
        [fixed(x0, y0), fixed(x0 + w, y0), fixed(x0 + (t * w as f64) as i64, y0 + h)]
    });
    prop_oneof![3 => any, 1 => full]
}

/// The kinds of triangle the interpolation tests run on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Shape {
    /// Up to 300 px across, near the origin.
    General,
    /// Up to 8192 px wide, a few rows.
    Wide,
    /// Up to 2000 px long, at most 1 px wide.
    Sliver,
    /// Far from the origin.
    Far,
}

impl Shape {
    /// Every shape, for reports.
    pub(crate) const ALL: [Shape; 4] = [Shape::General, Shape::Wide, Shape::Sliver, Shape::Far];

    /// Triangles of this shape.
    pub(crate) fn triangles(self) -> BoxedStrategy<Tri> {
        match self {
            Shape::General => prop_oneof![f32_tri(-150.0, 150.0), lattice_tri(-150, 150)].boxed(),
            Shape::Wide => wide_tri().boxed(),
            Shape::Sliver => prop_oneof![sliver(300.0), sample_edge_sliver()].boxed(),
            Shape::Far => prop_oneof![far_tri(), far_sliver()].boxed(),
        }
    }
}

/// A triangle of any shape, with its shape.
pub(crate) fn any_shape() -> impl Strategy<Value = (Shape, Tri)> {
    prop::sample::select(Shape::ALL.to_vec()).prop_flat_map(|s| (Just(s), s.triangles()))
}

/// The crate's spans for `t` inside `clip` (none for zero area).
pub(crate) fn spans(t: Tri, clip: Rect) -> Vec<Span> {
    let mut out = Vec::new();
    if let Some(table) = EdgeTable::new(t) {
        table.scan(clip, |s| out.push(s));
    }
    out
}

/// Every span of `t`, scanned with its own bounds as the clip.
pub(crate) fn all_spans(t: Tri) -> Vec<Span> {
    EdgeTable::new(t).map_or_else(Vec::new, |table| spans(t, table.bounds()))
}

/// The pixels within `margin` of the triangle's bounding box (in pixels).
pub(crate) fn window(t: Tri, margin: i32) -> Rect {
    let px = |v: i32| i32::try_from(i64::from(v).div_euclid(ONE)).expect("fits");
    let (xs, ys) = (t.map(|p| px(p.x)), t.map(|p| px(p.y)));
    let (min, max) =
        (|a: [i32; 3]| a.into_iter().min().unwrap_or(0), |a: [i32; 3]| a.into_iter().max().unwrap_or(0));
    Rect { x0: min(xs) - margin, y0: min(ys) - margin, x1: max(xs) + 1 + margin, y1: max(ys) + 1 + margin }
}

/// The rectangles of a tiling with `size`×`size` tiles whose corners sit at
/// `origin` modulo `size`, that meet `area`.
pub(crate) fn tiles(area: Rect, size: i32, origin: (i32, i32)) -> Vec<Rect> {
    let start = |a: i32, o: i32| a - (a - o).rem_euclid(size);
    let mut out = Vec::new();
    let mut y = start(area.y0, origin.1);
    while y < area.y1 {
        let mut x = start(area.x0, origin.0);
        while x < area.x1 {
            out.push(Rect::from_size(x, y, size, size));
            x += size;
        }
        y += size;
    }
    out
}
