//! The scan converter against the oracle: the same samples, exactly, for
//! every triangle (SPEC §3).

use crate::oracle;
use crate::shapes::{fixed, lattice_tri, spans, subpixel_tri, window, Tri, ONE};
use proptest::prelude::*;
use zline_raster::{EdgeTable, Rect};

/// The crate's covered samples of `t` inside `clip` as (row, col), in the
/// order emitted, after checking the span contract: non-empty, inside the
/// clip and the table's bounds, rows increasing.
#[track_caller]
fn scanned(t: Tri, clip: Rect) -> Vec<(i32, i32)> {
    let bounds = EdgeTable::new(t).map(|e| e.bounds());
    let mut out = Vec::new();
    let mut last_row = None;
    for s in spans(t, clip) {
        let inside = |r: Rect| r.x0 <= s.x0 && s.x1 <= r.x1 && r.y0 <= s.y && s.y < r.y1;
        assert!(s.x0 < s.x1, "empty span {s:?} for {t:?}");
        assert!(inside(clip), "span {s:?} outside the clip {clip:?} for {t:?}");
        assert!(bounds.is_some_and(inside), "span {s:?} outside the bounds {bounds:?} for {t:?}");
        assert!(last_row < Some(s.y), "span {s:?} after row {last_row:?} for {t:?}");
        last_row = Some(s.y);
        out.extend((s.x0..s.x1).map(|x| (s.y, x)));
    }
    out
}

/// The crate covers exactly the oracle's samples of `t` in `clip`.
#[track_caller]
fn check_matches_oracle(t: Tri, clip: Rect) {
    let got = scanned(t, clip);
    let want = oracle::covered(t, clip);
    if got != want {
        let only = |a: &[(i32, i32)], b: &[(i32, i32)]| -> Vec<(i32, i32)> {
            a.iter().filter(|p| !b.contains(p)).take(8).copied().collect()
        };
        panic!(
            "coverage differs from the oracle for {t:?} in {clip:?}\n\
             (row, col) covered only by the crate: {:?}\n\
             (row, col) covered only by the oracle: {:?}\n\
             counts: crate {}, oracle {}",
            only(&got, &want),
            only(&want, &got),
            got.len(),
            want.len()
        );
    }
}

/// [`check_matches_oracle`] on a window around the triangle, in both
/// windings and all vertex orders.
#[track_caller]
fn check_all_orders(t: Tri) {
    let clip = window(t, 2);
    for [i, j, k] in [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]] {
        check_matches_oracle([t[i], t[j], t[k]], clip);
    }
}

/// Every triangle with vertices on the lattice of quarter pixels in
/// [0, 2]² px, in all six vertex orders, on the 4×4 samples around it. The
/// lattice holds samples (at 0.5 and 1.5), pixel corners and points between,
/// so it has every tie the top-left rule decides: vertices on samples,
/// horizontal edges on sample rows, edges of many slopes through samples.
/// 85 320 triangles × 6 orders; about a second with the test profile.
#[test]
fn every_triangle_on_a_quarter_pixel_lattice_matches_the_oracle() {
    let q = ONE / 4;
    let points: Vec<_> = (0..=8).flat_map(|y| (0..=8).map(move |x| fixed(x * q, y * q))).collect();
    let clip = Rect::from_size(-1, -1, 4, 4);
    let mut covered = 0;
    for (i, &a) in points.iter().enumerate() {
        for (j, &b) in points.iter().enumerate().skip(i + 1) {
            for &c in &points[j + 1..] {
                for t in [[a, b, c], [b, c, a], [c, a, b], [a, c, b], [c, b, a], [b, a, c]] {
                    check_matches_oracle(t, clip);
                }
                covered += oracle::covered_grid([a, b, c], clip).len();
            }
        }
    }
    // The test ran on something: many triangles cover samples.
    assert!(covered > 10_000, "only {covered} covered samples");
}

proptest! {
    #![proptest_config(crate::config())]

    /// Triangles from random f32 coordinates, snapped.
    #[test]
    fn random_triangles_match_the_oracle(t in crate::shapes::f32_tri(-40.0, 120.0)) {
        check_all_orders(t);
    }

    /// Triangles whose vertices are often on samples, on sample rows or on
    /// pixel corners.
    #[test]
    fn triangles_on_sample_lattices_match_the_oracle(t in lattice_tri(-20, 60)) {
        check_all_orders(t);
    }

    /// Triangles a few pixels across or smaller, down to a few 1/256 px.
    #[test]
    fn subpixel_triangles_match_the_oracle(t in subpixel_tri()) {
        check_all_orders(t);
    }

    /// Up to 2000 px long, 1/256 to 1 px wide, at any angle, some with an
    /// edge through many samples.
    #[test]
    fn slivers_match_the_oracle(t in crate::shapes::Shape::Sliver.triangles()) {
        check_matches_oracle(t, window(t, 2));
        check_matches_oracle([t[0], t[2], t[1]], window(t, 2));
    }

    /// Up to ±1e5 px, and near ±2^21 px (the largest accepted coordinate),
    /// including slivers: the grid is a window around the triangle.
    #[test]
    fn far_triangles_match_the_oracle(
        t in prop_oneof![crate::shapes::far_tri(), crate::shapes::far_sliver()]
    ) {
        check_matches_oracle(t, window(t, 2));
        check_matches_oracle([t[0], t[2], t[1]], window(t, 2));
    }

    /// A clip rectangle that cuts the triangle anywhere keeps exactly the
    /// oracle's samples inside it.
    #[test]
    fn clipped_triangles_match_the_oracle(
        t in lattice_tri(-20, 60),
        (x, y, w, h) in (-25i32..65, -25i32..65, 0i32..40, 0i32..40),
    ) {
        check_matches_oracle(t, Rect::from_size(x, y, w, h));
    }
}
