//! Meshes whose triangles share edges cover every sample inside them exactly
//! once and nothing outside, in any tile layout (SPEC §3).
//!
//! Two kinds of mesh: fans (a centre and k ≥ 3 rim vertices in angular
//! order, a star-shaped polygon) and jittered n×m vertex grids with each
//! cell split along a random diagonal. Each triangle's vertex order is
//! random, so both windings meet along shared edges. Generated meshes whose
//! snapping to a lattice would fold a triangle over are discarded, so the
//! triangles never overlap.
//!
//! Expected counts come from two independent sources: the oracle (the sum of
//! its per-triangle coverage) and an exact point-in-polygon test against the
//! mesh's outline: a sample strictly inside the outline is covered exactly
//! once, one strictly outside never, one on the outline at most once.

use crate::oracle::{self, side, Oracle, P};
use crate::shapes::{lattice, tiles, window, Lattice, Tri};
use proptest::prelude::*;
use std::f64::consts::TAU;
use zline_raster::{EdgeTable, FixedPoint, Rect};

/// Triangles sharing edges, and the outline of their union.
#[derive(Clone, Debug)]
struct Mesh {
    triangles: Vec<Tri>,
    outline: Vec<FixedPoint>,
    /// False when snapping folded a triangle (the generators discard it).
    valid: bool,
}

/// Twice the signed area of a triangle, in fixed-point units.
fn cross(t: Tri) -> i128 {
    let p = oracle::points(t);
    side(p[0], p[1], p[2])
}

/// `t` with its vertices in one of the six orders.
fn reorder(t: Tri, order: usize) -> Tri {
    let [i, j, k] = [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]][order % 6];
    [t[i], t[j], t[k]]
}

/// A fan around a centre: rim vertices at increasing angles, each gap below
/// half a turn (gap weights 60..=100 out of k of them), radii 6..40 px.
fn fan() -> impl Strategy<Value = Mesh> {
    (lattice(), 20.0..60.0f64, 20.0..60.0f64, 3usize..=12).prop_flat_map(|(l, cx, cy, k)| {
        let rim = prop::collection::vec((60u32..=100, 6.0..40.0f64, 0usize..6), k);
        (Just(l), Just((cx, cy)), rim, 0.0..TAU)
            .prop_map(|(l, centre, rim, turn)| build_fan(l, centre, &rim, turn))
    })
}

fn build_fan(l: Lattice, (cx, cy): (f64, f64), rim: &[(u32, f64, usize)], turn: f64) -> Mesh {
    let total: u32 = rim.iter().map(|r| r.0).sum();
    let mut angle = turn;
    let mut outline = Vec::new();
    for &(gap, radius, _) in rim {
        outline.push(l.put_px(cx + radius * angle.cos(), cy + radius * angle.sin()));
        angle += TAU * f64::from(gap) / f64::from(total);
    }
    let c = l.put_px(cx, cy);
    let k = outline.len();
    let canonical: Vec<Tri> = (0..k).map(|i| [c, outline[i], outline[(i + 1) % k]]).collect();
    // Star-shaped after snapping: every triangle turns the same way, and the
    // rim goes round the centre once (angles in (0, π) summing to 2π).
    let same_turn = canonical.iter().all(|&t| cross(t) > 0) || canonical.iter().all(|&t| cross(t) < 0);
    let sweep: f64 = canonical.iter().map(|t| angle_at(t[0], t[1], t[2])).sum();
    let valid = same_turn && (sweep - TAU).abs() < 1e-6;
    let triangles = canonical.iter().zip(rim).map(|(&t, r)| reorder(t, r.2)).collect();
    Mesh { triangles, outline, valid }
}

/// The unsigned angle at `c` between `a` and `b`.
fn angle_at(c: FixedPoint, a: FixedPoint, b: FixedPoint) -> f64 {
    let v = |p: FixedPoint| (f64::from(p.x - c.x), f64::from(p.y - c.y));
    let (u, w) = (v(a), v(b));
    (u.0 * w.1 - u.1 * w.0).abs().atan2(u.0 * w.0 + u.1 * w.1)
}

/// A grid of (n+1)×(m+1) vertices spaced 3..16 px, each moved by up to a
/// quarter of the spacing, each cell split along a random diagonal.
fn grid() -> impl Strategy<Value = Mesh> {
    (lattice(), 1usize..=6, 1usize..=6, 3.0..16.0f64, 3.0..16.0f64).prop_flat_map(|(l, n, m, sx, sy)| {
        let jitter = prop::collection::vec((-0.25..0.25f64, -0.25..0.25f64), (n + 1) * (m + 1));
        let cells = prop::collection::vec((any::<bool>(), 0usize..6, 0usize..6), n * m);
        (Just((l, n, m, sx, sy)), -10.0..10.0f64, -10.0..10.0f64, jitter, cells)
            .prop_map(|(g, ox, oy, jitter, cells)| build_grid(g, (ox, oy), &jitter, &cells))
    })
}

type GridSize = (Lattice, usize, usize, f64, f64);

fn build_grid(
    (l, n, m, sx, sy): GridSize,
    (ox, oy): (f64, f64),
    jitter: &[(f64, f64)],
    cells: &[(bool, usize, usize)],
) -> Mesh {
    let at = |i: usize, j: usize| {
        let (jx, jy) = jitter[j * (n + 1) + i];
        l.put_px(ox + (i as f64 + jx) * sx, oy + (j as f64 + jy) * sy)
    };
    let mut canonical = Vec::new();
    let mut triangles = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let (p00, p10, p01, p11) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
            let (diagonal, o1, o2) = cells[j * n + i];
            let pair = if diagonal {
                [[p00, p10, p11], [p00, p11, p01]]
            } else {
                [[p00, p10, p01], [p10, p11, p01]]
            };
            canonical.extend(pair);
            triangles.extend([reorder(pair[0], o1), reorder(pair[1], o2)]);
        }
    }
    // Same turn everywhere: with a simple outline, no triangle overlaps another.
    let valid = canonical.iter().all(|&t| cross(t) > 0);
    let mut outline: Vec<FixedPoint> = (0..n).map(|i| at(i, 0)).collect();
    outline.extend((0..m).map(|j| at(n, j)));
    outline.extend((1..=n).rev().map(|i| at(i, m)));
    outline.extend((1..=m).rev().map(|j| at(0, j)));
    Mesh { triangles, outline, valid }
}

/// Where a sample lies relative to a polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Place {
    Inside,
    Outside,
    OnOutline,
}

/// Exact winding-number test of sample `s` against `polygon`.
fn place(polygon: &[P], s: P) -> Place {
    let mut winding = 0;
    for (k, &a) in polygon.iter().enumerate() {
        let b = polygon[(k + 1) % polygon.len()];
        let d = side(a, b, s);
        let between = |u: i128, v: i128, w: i128| u.min(v) <= w && w <= u.max(v);
        if d == 0 && between(a.0, b.0, s.0) && between(a.1, b.1, s.1) {
            return Place::OnOutline;
        }
        if a.1 <= s.1 && s.1 < b.1 && d > 0 {
            winding += 1;
        } else if b.1 <= s.1 && s.1 < a.1 && d < 0 {
            winding -= 1;
        }
    }
    if winding == 0 {
        Place::Outside
    } else {
        Place::Inside
    }
}

/// Hits per sample of `area` when every tile of the given size scans every
/// triangle whose bounds meet it, with the tile as the clip.
#[track_caller]
fn count_tiled(mesh: &Mesh, area: Rect, tile: Option<(i32, (i32, i32))>) -> Vec<u32> {
    let tables: Vec<EdgeTable> = mesh.triangles.iter().filter_map(|&t| EdgeTable::new(t)).collect();
    let clips = match tile {
        Some((size, origin)) => tiles(area, size, origin),
        None => vec![area],
    };
    let width = area.width() as usize;
    let mut hits = vec![0u32; width * area.height() as usize];
    for clip in clips {
        for table in tables.iter().filter(|t| !t.bounds().intersect(&clip).is_empty()) {
            table.scan(clip, |s| {
                let ok = |r: Rect| r.x0 <= s.x0 && s.x1 <= r.x1 && r.y0 <= s.y && s.y < r.y1;
                assert!(ok(clip) && ok(area), "span {s:?} outside the clip {clip:?} or the area {area:?}");
                let row = (s.y - area.y0) as usize * width;
                for x in s.x0..s.x1 {
                    hits[row + (x - area.x0) as usize] += 1;
                }
            });
        }
    }
    hits
}

/// Every sample of the mesh's surroundings is hit as often as the oracle
/// says, and that is once inside the outline, never outside it, at most
/// once on it — for every tiling given.
#[track_caller]
fn check_watertight(mesh: &Mesh, tilings: &[Option<(i32, (i32, i32))>]) {
    let area = mesh.triangles.iter().map(|&t| window(t, 2)).reduce(|a, b| Rect {
        x0: a.x0.min(b.x0),
        y0: a.y0.min(b.y0),
        x1: a.x1.max(b.x1),
        y1: a.y1.max(b.y1),
    });
    let Some(area) = area else { return };
    let outline: Vec<P> = mesh.outline.iter().map(|p| (i128::from(p.x), i128::from(p.y))).collect();
    let oracles: Vec<Oracle> = mesh.triangles.iter().filter_map(|&t| Oracle::new(t)).collect();
    let mut expected = Vec::new();
    for row in area.y0..area.y1 {
        for col in area.x0..area.x1 {
            let by_oracle = oracles.iter().filter(|o| o.covers(col.into(), row.into())).count() as u32;
            let where_ = place(&outline, oracle::sample(col.into(), row.into()));
            let fine = match where_ {
                Place::Inside => by_oracle == 1,
                Place::Outside => by_oracle == 0,
                Place::OnOutline => by_oracle <= 1,
            };
            assert!(fine, "the oracle covers ({col}, {row}) {by_oracle} times, {where_:?} of {mesh:?}");
            expected.push(by_oracle);
        }
    }
    let inside = expected.iter().filter(|&&c| c == 1).count();
    for &tiling in tilings {
        let hits = count_tiled(mesh, area, tiling);
        let wrong: Vec<_> = (0..hits.len())
            .filter(|&i| hits[i] != expected[i])
            .take(8)
            .map(|i| {
                let (col, row) = (
                    area.x0 + (i % area.width() as usize) as i32,
                    area.y0 + (i / area.width() as usize) as i32,
                );
                format!("({col}, {row}): {} hits, want {}", hits[i], expected[i])
            })
            .collect();
        assert!(wrong.is_empty(), "tiling {tiling:?} of {mesh:?} ({inside} samples inside): {wrong:?}");
    }
}

/// The tilings tried: 1, 7, 16 and 64 px tiles with a random origin, and
/// the whole area as one tile.
fn tilings() -> impl Strategy<Value = Vec<Option<(i32, (i32, i32))>>> {
    [(0i32..64, 0i32..64), (0..64, 0..64), (0..64, 0..64), (0..64, 0..64)].prop_map(|origins| {
        let mut out: Vec<_> = [1, 7, 16, 64]
            .into_iter()
            .zip(origins)
            .map(|(size, (x, y))| Some((size, (x % size, y % size))))
            .collect();
        out.push(None);
        out
    })
}

proptest! {
    #![proptest_config(crate::config())]

    /// Fans, up to 12 triangles around a shared centre.
    #[test]
    fn fans_cover_every_sample_once(mesh in fan().prop_filter("folded by snapping", |m| m.valid), t in tilings()) {
        check_watertight(&mesh, &t);
    }

    /// Jittered grids, up to 6×6 cells of two triangles.
    #[test]
    fn grids_cover_every_sample_once(mesh in grid().prop_filter("folded by snapping", |m| m.valid), t in tilings()) {
        check_watertight(&mesh, &t);
    }
}

/// A regular grid with every vertex on a sample and every edge through
/// samples: the ties everywhere, the same answer for any tile size.
#[test]
fn a_grid_on_samples_covers_every_sample_once() {
    let cells = vec![(true, 0, 0); 36];
    let jitter = vec![(0.0, 0.0); 49];
    let mesh = build_grid((Lattice::SampleCentre, 6, 6, 4.0, 4.0), (0.5, 0.5), &jitter, &cells);
    assert!(mesh.valid);
    let all: Vec<_> = (1..=24).map(|size| Some((size, (0, 0)))).chain([None]).collect();
    check_watertight(&mesh, &all);
    // 24×24 samples inside or on the outline, of which the top and left
    // sides are kept: 24 rows of 24.
    let area = Rect::from_size(-4, -4, 32, 32);
    assert_eq!(count_tiled(&mesh, area, None).iter().sum::<u32>(), 24 * 24);
}
