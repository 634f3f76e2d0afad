//! Setup of eight triangles at a time, for callers that vectorize setup
//! across triangles: the edge table's order, orientation and bounds, the
//! plane basis and the plane gradients, computed lane by lane in plain
//! fixed-size arrays that the compiler turns into SIMD at the caller's
//! level.
//!
//! Every lane performs the scalar code's operations in its order — the
//! same integer tests, the same IEEE operations, no fused multiply-add —
//! so lane k gets the bits that [`EdgeTable::new`], [`PlaneBasis::new`](crate::PlaneBasis::new),
//! [`DepthPlane::new`] and [`AttributePlanes::new`] give triangle k (the
//! tests hold them to it). Everything is `#[inline(always)]`, and written
//! with loops rather than array `map`s or `from_fn`s (which a build may
//! leave out of line, a call each compiled for the baseline): it is meant
//! to be compiled inside the caller's SIMD job.

use crate::edge_table::EdgeTable;
use crate::fixed::{FixedPoint, Rect, SUBPIXEL_BITS, SUBPIXEL_ONE};
use crate::interpolate::{AttributePlanes, DepthPlane};

/// Triangles per [`SetupLanes`].
pub const SETUP_LANES: usize = 8;

/// One value per lane.
pub type Lanes<T> = [T; SETUP_LANES];

/// The snapped vertices of eight triangles: vertex j of lane k is
/// `(x[j][k], y[j][k])`, in the order the values will be given.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TriangleLanes {
    /// x in 1/256 pixels.
    pub x: [Lanes<i32>; 3],
    /// y in 1/256 pixels.
    pub y: [Lanes<i32>; 3],
}

impl TriangleLanes {
    /// Puts triangle `p` in lane `k`.
    #[inline(always)]
    pub fn set(&mut self, k: usize, p: [FixedPoint; 3]) {
        for (j, v) in p.iter().enumerate() {
            self.x[j][k] = v.x;
            self.y[j][k] = v.y;
        }
    }
}

/// The edge tables and plane bases of eight triangles ([`Self::new`]).
#[derive(Clone, Copy, Debug)]
pub struct SetupLanes {
    /// Vertices sorted by (y, x), as [`EdgeTable`] keeps them.
    sorted_x: [Lanes<i32>; 3],
    sorted_y: [Lanes<i32>; 3],
    long_is_left: Lanes<bool>,
    bounds: [Lanes<i32>; 4],
    /// Non-zero area, bounds holding a sample centre.
    drawn: Lanes<bool>,
    anchor: [Lanes<f64>; 2],
    cx: [Lanes<f64>; 3],
    cy: [Lanes<f64>; 3],
}

impl SetupLanes {
    /// The edge tables and plane bases of the triangles in `t`.
    #[inline(always)]
    pub fn new(t: &TriangleLanes) -> SetupLanes {
        // EdgeTable::new's three compare-exchanges on the key (y, x).
        let ([mut ax, mut bx, mut cx], [mut ay, mut by, mut cy]) = (t.x, t.y);
        let before = |px: i32, py: i32, qx: i32, qy: i32| py < qy || (py == qy && px < qx);
        for k in 0..SETUP_LANES {
            if before(bx[k], by[k], ax[k], ay[k]) {
                (ax[k], bx[k]) = (bx[k], ax[k]);
                (ay[k], by[k]) = (by[k], ay[k]);
            }
            if before(cx[k], cy[k], bx[k], by[k]) {
                (bx[k], cx[k]) = (cx[k], bx[k]);
                (by[k], cy[k]) = (cy[k], by[k]);
            }
            if before(bx[k], by[k], ax[k], ay[k]) {
                (ax[k], bx[k]) = (bx[k], ax[k]);
                (ay[k], by[k]) = (by[k], ay[k]);
            }
        }
        let mut cross = [0i64; SETUP_LANES];
        for k in 0..SETUP_LANES {
            let (a, b, c) =
                ((ax[k] as i64, ay[k] as i64), (bx[k] as i64, by[k] as i64), (cx[k] as i64, cy[k] as i64));
            cross[k] = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
        }
        // Bounds: |v| ≤ 2^29 (FixedPoint::snap), so the i32 form of
        // first_sample_at_or_after cannot overflow and equals the i64 one.
        const ROUND: i32 = (SUBPIXEL_ONE - 1 - SUBPIXEL_ONE / 2) as i32;
        let first = |v: i32| (v + ROUND) >> SUBPIXEL_BITS;
        let mut bounds = [[0; SETUP_LANES]; 4];
        for k in 0..SETUP_LANES {
            let (x0, x1, x2) = (t.x[0][k], t.x[1][k], t.x[2][k]);
            bounds[0][k] = first(x0.min(x1).min(x2));
            bounds[1][k] = first(ay[k]);
            bounds[2][k] = first(x0.max(x1).max(x2));
            bounds[3][k] = first(cy[k]);
        }
        // PlaneBasis::new on the vertices as given.
        let s = SUBPIXEL_ONE as f64;
        // Loops, not array `map`s: those were left out of line in some
        // builds (a call each, compiled for the baseline).
        let mut px = [[0.0; SETUP_LANES]; 3];
        let mut py = [[0.0; SETUP_LANES]; 3];
        for j in 0..3 {
            for k in 0..SETUP_LANES {
                px[j][k] = f64::from(t.x[j][k]) / s;
                py[j][k] = f64::from(t.y[j][k]) / s;
            }
        }
        let mut det = [0.0; SETUP_LANES];
        let mut basis_x = [[0.0; SETUP_LANES]; 3];
        let mut basis_y = [[0.0; SETUP_LANES]; 3];
        for k in 0..SETUP_LANES {
            let (x0, y0, x1, y1, x2, y2) = (px[0][k], py[0][k], px[1][k], py[1][k], px[2][k], py[2][k]);
            det[k] = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
            let inv = 1.0 / det[k];
            basis_x[0][k] = (y1 - y2) * inv;
            basis_x[1][k] = (y2 - y0) * inv;
            basis_x[2][k] = (y0 - y1) * inv;
            basis_y[0][k] = (x2 - x1) * inv;
            basis_y[1][k] = (x0 - x2) * inv;
            basis_y[2][k] = (x1 - x0) * inv;
        }
        let mut drawn = [false; SETUP_LANES];
        let mut long_is_left = [false; SETUP_LANES];
        for k in 0..SETUP_LANES {
            let empty = bounds[0][k] >= bounds[2][k] || bounds[1][k] >= bounds[3][k];
            drawn[k] = cross[k] != 0 && !empty && det[k] != 0.0;
            long_is_left[k] = cross[k] > 0;
        }
        SetupLanes {
            sorted_x: [ax, bx, cx],
            sorted_y: [ay, by, cy],
            long_is_left,
            bounds,
            drawn,
            anchor: [px[0], py[0]],
            cx: basis_x,
            cy: basis_y,
        }
    }

    /// Whether triangle `k` makes a primitive: [`EdgeTable::new`] and
    /// [`crate::PlaneBasis::new`] give `Some` and the bounds hold a sample
    /// centre.
    #[inline(always)]
    pub fn drawn(&self, k: usize) -> bool {
        self.drawn[k]
    }

    /// (∂v/∂x, ∂v/∂y) of every lane, for vertex values `v[j][k]`
    /// ([`crate::PlaneBasis::gradient`]).
    #[inline(always)]
    pub fn gradients(&self, v: &[Lanes<f64>; 3]) -> (Lanes<f64>, Lanes<f64>) {
        let mut dx = [0.0; SETUP_LANES];
        let mut dy = [0.0; SETUP_LANES];
        for k in 0..SETUP_LANES {
            dx[k] = self.cx[0][k] * v[0][k] + self.cx[1][k] * v[1][k] + self.cx[2][k] * v[2][k];
            dy[k] = self.cy[0][k] * v[0][k] + self.cy[1][k] * v[1][k] + self.cy[2][k] * v[2][k];
        }
        (dx, dy)
    }

    /// An attribute's gradients, as [`AttributePlanes::new`] rounds them to
    /// f32, for vertex values `v[j][k]`.
    #[inline(always)]
    pub fn attribute_gradients(&self, v: &[Lanes<f32>; 3]) -> (Lanes<f32>, Lanes<f32>) {
        let mut wide = [[0.0; SETUP_LANES]; 3];
        for j in 0..3 {
            for k in 0..SETUP_LANES {
                wide[j][k] = f64::from(v[j][k]);
            }
        }
        let (dx, dy) = self.gradients(&wide);
        let mut out = ([0.0; SETUP_LANES], [0.0; SETUP_LANES]);
        for k in 0..SETUP_LANES {
            (out.0[k], out.1[k]) = (dx[k] as f32, dy[k] as f32);
        }
        out
    }

    /// Triangle `k`'s edge table.
    #[inline(always)]
    pub fn edge_table(&self, k: usize) -> EdgeTable {
        let point = |j: usize| FixedPoint { x: self.sorted_x[j][k], y: self.sorted_y[j][k] };
        let b = &self.bounds;
        EdgeTable {
            sorted: [point(0), point(1), point(2)],
            long_is_left: self.long_is_left[k],
            bounds: Rect { x0: b[0][k], y0: b[1][k], x1: b[2][k], y1: b[3][k] },
        }
    }

    /// Triangle `k`'s depth plane, from its first vertex's depth `z0` and
    /// the gradients [`Self::gradients`] gave for lane `k`.
    #[inline(always)]
    pub fn depth_plane(&self, k: usize, z0: f64, (dzdx, dzdy): (f64, f64)) -> DepthPlane {
        DepthPlane { z0, dzdx, dzdy, anchor: (self.anchor[0][k], self.anchor[1][k]) }
    }

    /// Triangle `k`'s attribute planes, from its first vertex's values and
    /// the gradients [`Self::attribute_gradients`] gave for lane `k`.
    #[inline(always)]
    pub fn attribute_planes<const N: usize>(
        &self,
        k: usize,
        v0: [f32; N],
        (dx, dy): ([f32; N], [f32; N]),
    ) -> AttributePlanes<N> {
        AttributePlanes { v0, dx, dy, anchor: (self.anchor[0][k], self.anchor[1][k]) }
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::interpolate::PlaneBasis;

    /// Coordinates over the whole snap range, and small ones that make
    /// degenerate and sub-pixel triangles often.
    fn coordinate() -> impl Strategy<Value = i32> {
        prop_oneof![-(1 << 29)..=(1 << 29), -1024..1024, Just(0), Just(128), Just(383)]
    }

    fn point() -> impl Strategy<Value = FixedPoint> {
        (coordinate(), coordinate()).prop_map(|(x, y)| FixedPoint { x, y })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        #[test]
        fn lanes_equal_the_scalar_setup(
            tris in prop::array::uniform8(prop::array::uniform3(point())),
            z in prop::array::uniform3(-2.0f64..2.0),
            a in prop::array::uniform3(-1e3f32..1e3),
            shared in any::<bool>(),
        ) {
            let mut tris = tris;
            if shared {
                // Neighbours sharing an edge, and a triangle with a repeated vertex.
                tris[1] = [tris[0][1], tris[0][0], tris[1][2]];
                tris[2] = [tris[2][0], tris[2][0], tris[2][1]];
            }
            let mut lanes = TriangleLanes::default();
            for (k, p) in tris.iter().enumerate() {
                lanes.set(k, *p);
            }
            let setup = SetupLanes::new(&lanes);
            let zs = [z; SETUP_LANES];
            let z_lanes: [Lanes<f64>; 3] = std::array::from_fn(|j| std::array::from_fn(|k| zs[k][j]));
            let a_lanes: [Lanes<f32>; 3] = std::array::from_fn(|j| [a[j]; SETUP_LANES]);
            let (dzdx, dzdy) = setup.gradients(&z_lanes);
            let (dadx, dady) = setup.attribute_gradients(&a_lanes);
            for (k, p) in tris.iter().enumerate() {
                let edges = EdgeTable::new(*p);
                let basis = PlaneBasis::new(*p);
                let scalar = match (edges, basis) {
                    (Some(e), Some(b)) if !e.bounds().is_empty() => Some((e, b)),
                    _ => None,
                };
                prop_assert_eq!(setup.drawn(k), scalar.is_some(), "lane {}: {:?}", k, p);
                if let Some((e, b)) = scalar {
                    prop_assert_eq!(setup.edge_table(k), e);
                    let depth = DepthPlane::new(&b, z);
                    let lane = setup.depth_plane(k, z[0], (dzdx[k], dzdy[k]));
                    prop_assert_eq!(format!("{lane:?}"), format!("{depth:?}"));
                    let planes = AttributePlanes::new(&b, [[a[0]], [a[1]], [a[2]]]);
                    let lane = setup.attribute_planes(k, [a[0]], ([dadx[k]], [dady[k]]));
                    // Bit for bit, NaN and signed zeros included.
                    prop_assert_eq!(format!("{lane:?}"), format!("{planes:?}"));
                    prop_assert_eq!(lane.dx()[0].to_bits(), planes.dx()[0].to_bits());
                    prop_assert_eq!(lane.dy()[0].to_bits(), planes.dy()[0].to_bits());
                }
            }
        }
    }
}
