//! Hierarchical depth: the tile's coarse depth, tested before a
//! primitive's spans are walked.
//!
//! A tile keeps a value at least as far as every depth its buffer holds
//! (`CoarseDepth::most`), found again after each tile's worth of samples
//! the opaque pass writes (one pass of vector maxima over the buffer). Until
//! every sample is drawn it is the far plane, and nothing is tested. Then a
//! primitive whose stored depths are all at least that far
//! ([`DepthPlane::least_over`] its bounds within the tile: the plane's
//! least value there, less twice the bound on the stored depth's error)
//! would fail the depth test at every sample, `z < stored`, so it is
//! skipped whole — in the opaque and the transparency passes alike, as both
//! test against the opaque depth — and the image is the same bits.
//!
//! A test that fails costs a few f64 operations per primitive and tile, as
//! much as a small triangle's walk in a tile that is all foreground (a
//! million-triangle sphere): after each failure the next 2^k − 1 primitives
//! (k the failures in a row, at most [`MAX_BACKOFF`]) go untested, and a
//! success tests every primitive again.

use zline_raster::{DepthPlane, Rect, LANES};
use zline_simd::lanes::f32x8;

use super::target::TileTarget;

/// The most failures in a row that lengthen the wait: at most 63
/// primitives go untested after a failure.
const MAX_BACKOFF: u32 = 6;

impl TileTarget {
    /// Whether every sample of a primitive within `bounds`, of depth plane
    /// `depth`, would fail the depth test in this tile (see the module).
    #[inline(always)]
    pub(super) fn hidden(&mut self, bounds: Rect, depth: &DepthPlane) -> bool {
        let c = &mut self.coarse;
        if c.most >= self.far {
            return false;
        }
        if c.wait > 0 {
            c.wait -= 1;
            return false;
        }
        let b = bounds.intersect(&self.rect);
        let corners = (f64::from(b.x0), f64::from(b.y0), f64::from(b.x1), f64::from(b.y1));
        if depth.least_over(corners) >= f64::from(c.most) {
            c.misses = 0;
            self.hidden += 1;
            return true;
        }
        c.misses = (c.misses + 1).min(MAX_BACKOFF);
        c.wait = (1 << c.misses) - 1;
        false
    }

    /// Counts `n` samples the opaque pass wrote; after a tile's worth, finds
    /// the coarse depth again.
    #[inline]
    pub(super) fn wrote(&mut self, n: u64) {
        self.coarse.written += n;
        if self.coarse.written >= (self.depth.len() * LANES) as u64 {
            self.coarse.written = 0;
            self.coarse.most = most(&self.depth, self.far);
        }
    }
}

/// The greatest of `depth`, or `far` when it is empty. A padding lane
/// beside a tile narrower than its vectors stays at `far`, so such a tile
/// is never tested: only less useful, never wrong.
fn most(depth: &[f32x8], far: f32) -> f32 {
    let Some(&first) = depth.first() else { return far };
    let lanes = depth.iter().fold(first, |m, &v| m.fast_max(v));
    lanes.to_array().into_iter().fold(f32::NEG_INFINITY, f32::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use zline_raster::{FixedPoint, PlaneBasis};

    /// A triangle over the 16 × 16 tile at depths `z`, and its bounds.
    fn plane(z: [f64; 3]) -> (Rect, DepthPlane) {
        let p = [(-4.0, -4.0), (40.0, -4.0), (-4.0, 40.0)].map(|(x, y)| FixedPoint::snap(x, y).unwrap());
        let basis = PlaneBasis::new(p).unwrap();
        (Rect { x0: -4, y0: -4, x1: 40, y1: 40 }, DepthPlane::new(&basis, z))
    }

    /// A tile whose every sample holds `z` but those in `undrawn` (far).
    fn tile(z: f32, undrawn: usize) -> TileTarget {
        let mut t = TileTarget::default();
        t.clear(Rect { x0: 0, y0: 0, x1: 16, y1: 16 }, Vec3::ZERO, 1.0);
        let drawn = t.depth.len() - undrawn;
        t.depth[..drawn].fill(f32x8::splat(z));
        t.wrote((drawn * LANES) as u64);
        t
    }

    #[test]
    fn a_primitive_behind_every_sample_is_hidden_and_one_in_front_is_not() {
        let mut t = tile(0.25, 0);
        assert!(t.hidden(plane([0.5; 3]).0, &plane([0.5; 3]).1));
        // Behind at every sample of the tile, though nearer outside it.
        let (b, slope) = plane([0.26, 0.9, 0.9]);
        assert!(t.hidden(b, &slope));
        // Equal depths pass no sample either, but the bound keeps it drawn.
        assert!(!t.hidden(b, &plane([0.25; 3]).1));
    }

    #[test]
    fn a_tile_not_yet_covered_tests_nothing() {
        let mut t = tile(0.25, 1);
        assert_eq!(t.coarse.most, 1.0);
        assert!(!t.hidden(plane([0.5; 3]).0, &plane([0.5; 3]).1));
        // Cleared: nothing drawn.
        t.clear(Rect { x0: 0, y0: 0, x1: 16, y1: 16 }, Vec3::ZERO, 1.0);
        assert!(!t.hidden(plane([0.5; 3]).0, &plane([0.5; 3]).1));
    }

    #[test]
    fn failures_in_a_row_wait_longer_and_a_success_tests_every_primitive() {
        let mut t = tile(0.25, 0);
        let (b, near) = plane([0.1; 3]);
        let far = plane([0.5; 3]).1;
        // k failures in a row: the next 2^k − 1 primitives go untested.
        for k in 1..=3 {
            assert!(!t.hidden(b, &near));
            for _ in 0..(1 << k) - 1 {
                assert!(!t.hidden(b, &far), "untested after {k} failures");
            }
        }
        assert!(t.hidden(b, &far));
        assert!(t.hidden(b, &far));
        assert!(!t.hidden(b, &near));
        assert!(!t.hidden(b, &far), "one failure: one untested");
        assert!(t.hidden(b, &far));
    }

    #[test]
    fn the_coarse_depth_is_found_again_after_a_tiles_worth_of_writes() {
        let mut t = tile(0.25, 0);
        t.depth.fill(f32x8::splat(0.125));
        t.wrote(255);
        assert_eq!(t.coarse.most, 0.25, "not yet");
        t.wrote(1);
        assert_eq!(t.coarse.most, 0.125);
    }
}
