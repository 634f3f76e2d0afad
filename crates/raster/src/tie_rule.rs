//! Coverage of one sample by edge functions, under a chosen rule for the
//! samples that lie exactly on an edge: the top-left rule of SPEC §3 (the
//! same samples as [`EdgeTable::scan`](crate::EdgeTable::scan)), or the
//! rules a renderer without it would have — a closed triangle (every edge
//! sample in: an edge two triangles share is drawn twice) or an open one
//! (none in: the shared edge is drawn by neither). The classroom's "what
//! breaks without the top-left rule" counts coverage with these; the
//! renderer's kernels only ever use the edge table.

use crate::fixed::{FixedPoint, SUBPIXEL_HALF, SUBPIXEL_ONE};

/// Which samples on an edge a triangle covers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TieRule {
    /// Samples on a left edge or a top (horizontal) edge are in, those on
    /// right and bottom edges out (SPEC §3): each sample of a shared edge
    /// is drawn once.
    #[default]
    TopLeft,
    /// Every sample on an edge is in: a shared edge is drawn twice.
    Closed,
    /// No sample on an edge is in: a shared edge is drawn by neither.
    Open,
}

impl TieRule {
    /// Every rule, in the order the CLI lists them.
    pub const ALL: [TieRule; 3] = [TieRule::TopLeft, TieRule::Closed, TieRule::Open];

    /// The name the CLI uses: "top-left", "closed", "open".
    pub fn name(self) -> &'static str {
        match self {
            TieRule::TopLeft => "top-left",
            TieRule::Closed => "closed",
            TieRule::Open => "open",
        }
    }
}

/// Whether the triangle `vertices` (either winding; zero area covers
/// nothing) covers the sample of `column`, `row` — its centre at
/// (column + ½, row + ½) — under `rule`. Exact: integer edge functions on
/// the 1/256 grid (coordinates within ±2^29, products within 2^62).
pub fn covers(vertices: [FixedPoint; 3], column: i64, row: i64, rule: TieRule) -> bool {
    let [a, b, c] = vertices.map(|p| (i64::from(p.x), i64::from(p.y)));
    let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    if area == 0 {
        return false;
    }
    let sign = area.signum();
    let p = (column * SUBPIXEL_ONE + SUBPIXEL_HALF, row * SUBPIXEL_ONE + SUBPIXEL_HALF);
    [(a, b), (b, c), (c, a)].into_iter().all(|(from, to)| {
        let (dx, dy) = (to.0 - from.0, to.1 - from.1);
        // Positive inside (after the orientation's sign).
        let e = sign * (dx * (p.1 - from.1) - dy * (p.0 - from.0));
        if e != 0 {
            return e > 0;
        }
        match rule {
            TieRule::Closed => true,
            TieRule::Open => false,
            TieRule::TopLeft => {
                // The inward normal sign·(−dy, dx): a left edge has the
                // inside towards +x, a top edge (horizontal) towards +y
                // (y grows downwards).
                let (nx, ny) = (-sign * dy, sign * dx);
                nx > 0 || (nx == 0 && ny > 0)
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edge_table::EdgeTable;
    use crate::fixed::Rect;

    fn fp(x: i32, y: i32) -> FixedPoint {
        FixedPoint { x, y }
    }

    /// Deterministic pseudo-random numbers (a 64-bit LCG).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self, n: i32) -> i32 {
            self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((self.0 >> 33) % n as u64) as i32
        }
    }

    /// The top-left rule by edge functions covers exactly the edge table's
    /// samples, on triangles whose vertices sit on a quarter-pixel grid so
    /// that many samples fall on edges and vertices; closed ⊇ top-left ⊇
    /// open, differing only on edge samples.
    #[test]
    fn top_left_by_edge_functions_is_the_edge_tables_coverage() {
        let mut rng = Lcg(7);
        let clip = Rect { x0: -2, y0: -2, x1: 14, y1: 14 };
        let mut ties = 0;
        for _ in 0..3000 {
            let v = [0; 3].map(|_| fp(rng.next(48) * 64, rng.next(48) * 64));
            let mut table = std::collections::HashSet::new();
            if let Some(t) = EdgeTable::new(v) {
                t.scan(clip, |s| table.extend((s.x0..s.x1).map(|x| (x, s.y))));
            }
            for y in clip.y0..clip.y1 {
                for x in clip.x0..clip.x1 {
                    let (col, row) = (i64::from(x), i64::from(y));
                    let [tl, closed, open] = TieRule::ALL.map(|r| covers(v, col, row, r));
                    assert_eq!(tl, table.contains(&(x, y)), "{v:?} at ({x}, {y})");
                    assert!(closed >= tl && tl >= open, "{v:?} at ({x}, {y})");
                    ties += usize::from(closed != open);
                }
            }
        }
        assert!(ties > 1000, "too few samples on edges to test the rule: {ties}");
    }

    /// A square of two triangles sharing a diagonal through sample
    /// centres: every sample once under the top-left rule, the diagonal's
    /// twice when closed, never when open.
    #[test]
    fn a_shared_diagonal_is_drawn_once_twice_or_never() {
        // Corners at pixel corners 0 and 8: the diagonal x = y passes
        // through the centres (i + ½, i + ½).
        let (p0, p1, p2, p3) = (fp(0, 0), fp(2048, 0), fp(2048, 2048), fp(0, 2048));
        let halves = [[p0, p1, p2], [p0, p2, p3]];
        for rule in TieRule::ALL {
            for y in 0..8 {
                for x in 0..8 {
                    let count = halves.iter().filter(|t| covers(**t, x, y, rule)).count();
                    let want = match (rule, x == y) {
                        (TieRule::TopLeft, _) | (_, false) => 1,
                        (TieRule::Closed, true) => 2,
                        (TieRule::Open, true) => 0,
                    };
                    assert_eq!(count, want, "{rule:?} at ({x}, {y})");
                }
            }
        }
    }
}
