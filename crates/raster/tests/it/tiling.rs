//! The values a pixel gets do not depend on how the screen is tiled
//! (SPEC §10): scanning a triangle with its whole bounds as the clip, or tile
//! by tile with tiles of 1, 5, 16 or 64 px at any origin, gives the same
//! pixels with bit-identical depth and attributes — from the per-sample
//! walker and from the eight-lane block walker alike.

use crate::depth::depths;
use crate::exact::DEPTH_SCALE;
use crate::shapes::{all_spans, spans, tiles, Shape, Tri};
use proptest::array::{uniform2, uniform3};
use proptest::prelude::*;
use std::collections::BTreeSet;
use zline_raster::{
    for_each_block, for_each_sample, AttributePlanes, DepthPlane, EdgeTable, PlaneBasis, Rect,
};

/// What a pixel gets: (row, col, depth bits, attribute bits).
type Bits = (i32, i32, u32, [u32; 2]);

struct Planes {
    depth: DepthPlane,
    attrs: AttributePlanes<2>,
}

/// The values of every sample the clips cover, sorted.
fn values(t: Tri, p: &Planes, clips: &[Rect]) -> Vec<Bits> {
    let mut out = Vec::new();
    for &clip in clips {
        for span in spans(t, clip) {
            for_each_sample(&p.depth, &p.attrs, span, |x, z, a| {
                out.push((span.y, x, z.to_bits(), a.map(f32::to_bits)));
            });
        }
    }
    out.sort_unstable();
    out
}

/// The same as [`values`], from the eight-lane walker: the lanes in each
/// block's mask.
fn block_values(t: Tri, p: &Planes, clips: &[Rect]) -> Vec<Bits> {
    let mut out = Vec::new();
    for &clip in clips {
        for span in spans(t, clip) {
            for_each_block(&p.depth, &p.attrs, span, |b| {
                assert_eq!(b.x % 8, 0, "blocks start on multiples of 8");
                for k in 0..8 {
                    let x = b.x + k as i32;
                    assert_eq!(b.mask & (1 << k) != 0, (span.x0..span.x1).contains(&x), "mask of lane {k}");
                    if b.mask & (1 << k) != 0 {
                        out.push((
                            span.y,
                            x,
                            b.z[k].to_bits(),
                            [b.attr(0, k).to_bits(), b.attr(1, k).to_bits()],
                        ));
                    }
                }
            });
        }
    }
    out.sort_unstable();
    out
}

/// The tiles of `size` px at `origin` that meet the covered samples of `t`
/// (grown by a pixel) — the others would be empty, and skipping them keeps
/// 1 px tiles affordable on long slivers.
fn tiles_near(t: Tri, size: i32, origin: (i32, i32)) -> Vec<Rect> {
    let mut keep = BTreeSet::new();
    for s in all_spans(t) {
        let around = Rect { x0: s.x0 - 1, y0: s.y - 1, x1: s.x1 + 1, y1: s.y + 2 };
        keep.extend(tiles(around, size, origin).into_iter().map(|r| (r.y0, r.x0)));
    }
    keep.into_iter().map(|(y, x)| Rect::from_size(x, y, size, size)).collect()
}

/// Every tiling gives the same bits as the whole scan.
#[track_caller]
fn check_tiling_invariant(t: Tri, p: &Planes, origins: [(i32, i32); 4]) {
    let Some(table) = EdgeTable::new(t) else { return };
    let whole = values(t, p, &[table.bounds()]);
    assert!(
        block_values(t, p, &[table.bounds()]) == whole,
        "the block walker differs from the sample walker for {t:?}"
    );
    for (size, origin) in [1, 5, 16, 64].into_iter().zip(origins) {
        let origin = (origin.0 % size, origin.1 % size);
        let tiled = values(t, p, &tiles_near(t, size, origin));
        assert!(
            block_values(t, p, &tiles_near(t, size, origin)) == tiled,
            "block walker, {size} px tiles, {t:?}"
        );
        if tiled != whole {
            let first = whole.iter().zip(&tiled).find(|(a, b)| a != b);
            panic!(
                "{size} px tiles at {origin:?} give {} samples, the whole scan {}; first difference \
                 (row, col, z bits, attribute bits) {first:?} for {t:?}",
                tiled.len(),
                whole.len()
            );
        }
    }
}

fn planes(t: Tri, k: [i64; 3], v: [[f32; 2]; 3]) -> Option<Planes> {
    let basis = PlaneBasis::new(t)?;
    let depth = DepthPlane::new(&basis, k.map(|k| k as f64 / DEPTH_SCALE));
    Some(Planes { depth, attrs: AttributePlanes::new(&basis, v) })
}

/// General triangles (up to 300 px), spans up to 2048 px wide, slivers.
fn triangles() -> impl Strategy<Value = Tri> {
    let wide = Shape::Wide.triangles().prop_map(|t| {
        // Narrow to 2048 px around the first vertex: the 1 px tiling of a
        // full 8192 px triangle costs too much for what it adds.
        t.map(|p| zline_raster::FixedPoint { x: t[0].x + (p.x - t[0].x) / 4, ..p })
    });
    prop_oneof![Shape::General.triangles(), wide, Shape::Sliver.triangles()]
}

proptest! {
    #![proptest_config(crate::config())]

    #[test]
    fn values_do_not_depend_on_the_tiling(
        t in triangles(),
        k in depths(),
        v in uniform3(uniform2(-1e3..1e3f32)),
        origins in [(0i32..64, 0i32..64), (0..64, 0..64), (0..64, 0..64), (0..64, 0..64)],
    ) {
        if let Some(p) = planes(t, k, v) {
            check_tiling_invariant(t, &p, origins);
        }
    }
}
