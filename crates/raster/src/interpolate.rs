//! Plane equations for depth and attributes, evaluated incrementally along
//! spans (SPEC §4, §6).
//!
//! A value that is linear in window space (NC depth; 1/w and a/w for
//! perspective-correct interpolation; a itself for screen-linear mode) is a
//! plane v(x, y) = v0 + ∂v/∂x·(x − ax) + ∂v/∂y·(y − ay), anchored at the
//! triangle's first vertex — not at the window origin, where steep gradients
//! would cost fractional bits (STYLE habit 4). Gradients are set up in f64.
//!
//! ## Incremental evaluation without drift
//! Along a span the seed steps v(x+1) = v(x) + ∂v/∂x. Each step rounds, so
//! error grows with the span's length. zline evaluates the plane directly
//! at anchors on a fixed global grid — every column that is a multiple of
//! [`REANCHOR_BLOCK`] — and reaches the k-th column after an anchor (k < 16)
//! in one step of k increments: v = v(anchor) + k·∂v/∂x. That is the seed's
//! recurrence unrolled: one rounding per sample instead of k, and the eight
//! samples of a [`SampleBlock`] are independent, so they fill SIMD lanes.
//! (Accumulating the steps was measured first; it chains one add per sample
//! and cost about 4 cycles per pixel of latency in the depth loop alone.)
//! The anchors and blocks depend only on the pixel, never on where a span or
//! tile starts, so the same pixel gets the same bits in any tiling, and
//! [`for_each_sample`] and [`for_each_block`] give the same bits.
//!
//! Bounds (checked by the property tests, for spans up to 8192 pixels):
//! - depth is evaluated in f64 and rounded once to f32: |z − z_exact| ≤
//!   2^-24·|z| + 64·2^-52·M, where M is the largest magnitude met on the way
//!   — |z0| plus the gradients times the offsets from the anchor (see
//!   [`DepthPlane::error_bound`]). The f64 part matters only on steep
//!   slivers, where an anchor may lie far outside the triangle; elsewhere the
//!   bound is the single f32 rounding.
//! - attributes are evaluated in f32: |v − v_exact| ≤ 32·2^-24·M, with M the
//!   largest magnitude among v0, the anchor value and k·∂v/∂x (see
//!   [`AttributePlanes::error_bound`]).
//!
//! The seed also interpolates down the edges (x' = x − 1/m, z' = z + …); the
//! direct evaluation at each anchor replaces that walk, which is the same
//! plane without the drift down tall edges.

use crate::edge_table::Span;
use crate::fixed::FixedPoint;

/// Columns between direct evaluations of a plane (a power of two).
pub const REANCHOR_BLOCK: i32 = 16;

/// What turns three vertex values into a plane's gradients, for one
/// triangle: ∂v/∂x = Σ `cx[k]·v[k]`, ∂v/∂y = Σ `cy[k]·v[k]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneBasis {
    anchor: (f64, f64),
    cx: [f64; 3],
    cy: [f64; 3],
}

impl PlaneBasis {
    /// The basis for a triangle with snapped vertices `p` (in the order the
    /// values will be given). `None` for zero area.
    #[inline]
    pub fn new(p: [FixedPoint; 3]) -> Option<PlaneBasis> {
        let [(x0, y0), (x1, y1), (x2, y2)] = p.map(FixedPoint::to_f64);
        let det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
        if det == 0.0 {
            return None;
        }
        let inv = 1.0 / det;
        Some(PlaneBasis {
            anchor: (x0, y0),
            cx: [(y1 - y2) * inv, (y2 - y0) * inv, (y0 - y1) * inv],
            cy: [(x2 - x1) * inv, (x0 - x2) * inv, (x1 - x0) * inv],
        })
    }

    /// The anchor: the first vertex, in pixels.
    #[inline]
    pub fn anchor(&self) -> (f64, f64) {
        self.anchor
    }

    /// (∂v/∂x, ∂v/∂y) for vertex values `v`.
    #[inline]
    pub fn gradient(&self, v: [f64; 3]) -> (f64, f64) {
        let dot = |c: [f64; 3]| c[0] * v[0] + c[1] * v[1] + c[2] * v[2];
        (dot(self.cx), dot(self.cy))
    }
}

/// NC depth over a triangle, kept in f64 (SPEC §4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthPlane {
    pub(crate) z0: f64,
    pub(crate) dzdx: f64,
    pub(crate) dzdy: f64,
    pub(crate) anchor: (f64, f64),
}

impl DepthPlane {
    /// Relative part of the error bound: one f32 rounding.
    pub const RELATIVE_ERROR: f64 = 1.0 / (1u64 << 24) as f64;

    /// The depth plane through the vertices' NC depths.
    #[inline]
    pub fn new(basis: &PlaneBasis, z: [f64; 3]) -> DepthPlane {
        let (dzdx, dzdy) = basis.gradient(z);
        DepthPlane { z0: z[0], dzdx, dzdy, anchor: basis.anchor }
    }

    /// Direct evaluation at a point in pixels (f64).
    #[inline]
    pub fn at(&self, x: f64, y: f64) -> f64 {
        self.z0 + self.dzdx * (x - self.anchor.0) + self.dzdy * (y - self.anchor.1)
    }

    /// The bound on |z − z_exact| for the stored depth of the sample at
    /// (x, y) whose exact depth is `z` (see the module doc): the anchor's
    /// evaluation rounds terms as large as the gradients times the offsets,
    /// the step of k ≤ 15 columns rounds twice, and the f32 conversion once.
    pub fn error_bound(&self, x: f64, y: f64, z: f64) -> f64 {
        let (ox, oy) = ((x - self.anchor.0).abs(), (y - self.anchor.1).abs());
        let block = f64::from(REANCHOR_BLOCK);
        let m = self.z0.abs() + self.dzdx.abs() * (ox + block) + self.dzdy.abs() * oy;
        Self::RELATIVE_ERROR * z.abs() + 64.0 * f64::EPSILON * m + f64::MIN_POSITIVE
    }

    /// A lower bound on the stored depth of every sample inside the
    /// rectangle `[x0, x1] × [y0, y1]` (pixels): the plane's least value
    /// there (at a corner), less twice the error bound at the rectangle's
    /// greatest offsets from the anchor and greatest |z| (the bound grows
    /// with each). Minus infinity when any of it is not finite, so that no
    /// test against it holds.
    pub fn least_over(&self, (x0, y0, x1, y1): (f64, f64, f64, f64)) -> f64 {
        let (ax, ay) = self.anchor;
        let (tx, ty) =
            ([self.dzdx * (x0 - ax), self.dzdx * (x1 - ax)], [self.dzdy * (y0 - ay), self.dzdy * (y1 - ay)]);
        let least = self.z0 + tx[0].min(tx[1]) + ty[0].min(ty[1]);
        let most = self.z0 + tx[0].max(tx[1]) + ty[0].max(ty[1]);
        let (ox, oy) = ((x0 - ax).abs().max((x1 - ax).abs()), (y0 - ay).abs().max((y1 - ay).abs()));
        let bound = self.error_bound(ax + ox, ay + oy, least.abs().max(most.abs()));
        let all = [self.z0, self.dzdx, self.dzdy, least, most, bound];
        if all.iter().all(|v| v.is_finite()) {
            least - 2.0 * bound
        } else {
            f64::NEG_INFINITY
        }
    }

    /// ∂z/∂x.
    #[inline]
    pub fn dzdx(&self) -> f64 {
        self.dzdx
    }
}

/// N attributes linear in window space, kept in f32.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AttributePlanes<const N: usize> {
    pub(crate) v0: [f32; N],
    pub(crate) dx: [f32; N],
    pub(crate) dy: [f32; N],
    pub(crate) anchor: (f64, f64),
}

impl AttributePlanes<0> {
    /// No attributes: for spans that need depth only.
    pub const NONE: AttributePlanes<0> = AttributePlanes { v0: [], dx: [], dy: [], anchor: (0.0, 0.0) };
}

impl<const N: usize> AttributePlanes<N> {
    /// Planes through the vertex values `v[k][i]` (vertex k, attribute i).
    #[inline]
    pub fn new(basis: &PlaneBasis, v: [[f32; N]; 3]) -> AttributePlanes<N> {
        let mut dx = [0.0; N];
        let mut dy = [0.0; N];
        for i in 0..N {
            let (gx, gy) = basis.gradient([v[0][i], v[1][i], v[2][i]].map(f64::from));
            dx[i] = gx as f32;
            dy[i] = gy as f32;
        }
        AttributePlanes { v0: v[0], dx, dy, anchor: basis.anchor }
    }

    /// Direct evaluation at a point in pixels.
    #[inline]
    pub fn at(&self, x: f64, y: f64) -> [f32; N] {
        let ox = (x - self.anchor.0) as f32;
        let oy = (y - self.anchor.1) as f32;
        std::array::from_fn(|i| self.v0[i] + (self.dx[i] * ox + self.dy[i] * oy))
    }

    /// ∂v/∂x per attribute.
    #[inline]
    pub fn dx(&self) -> [f32; N] {
        self.dx
    }

    /// ∂v/∂y per attribute.
    #[inline]
    pub fn dy(&self) -> [f32; N] {
        self.dy
    }

    /// The bound on |v − v_exact| for attribute `i` of the sample at (x, y)
    /// (see the module doc): the anchor's evaluation rounds terms as large as
    /// the offsets times the gradients, and the step of k ≤ 15 columns
    /// rounds its product and its sum.
    pub fn error_bound(&self, i: usize, x: f64, y: f64) -> f32 {
        let ox = (x - self.anchor.0).abs() as f32;
        let oy = (y - self.anchor.1).abs() as f32;
        let m = self.v0[i].abs() + self.dx[i].abs() * ox + self.dy[i].abs() * oy;
        let steps = REANCHOR_BLOCK as f32 * self.dx[i].abs();
        32.0 * f32::EPSILON * (m + steps) + f32::MIN_POSITIVE
    }
}

/// Samples per [`SampleBlock`].
pub const LANES: usize = 8;

/// Column offsets 0, 1, …, 15 as floats (exact).
const BLOCK_OFFSETS: [f32; 16] =
    [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0, 13.0, 14.0, 15.0];

/// Eight consecutive samples of one row, starting at a column that is a
/// multiple of [`LANES`]; lanes outside the span are evaluated too but not
/// in `mask`.
///
/// Attributes are handed over as their anchor: lane k of attribute i is
/// `anchor[i] + dx[i] * offsets[k]` in f32 ([`Self::attr`]),
/// which a SIMD caller evaluates as one vector operation per attribute
/// with the same bits. (Building the 8 × N lanes here in scalar code cost
/// the span kernels a round trip through memory, and left LLVM to choose
/// how to vectorize it: out-of-line `array::from_fn` for wide layouts, or
/// scatters at the AVX-512 level.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleBlock<'a, const N: usize> {
    /// Column of lane 0 (a multiple of [`LANES`]).
    pub x: i32,
    /// Bit k set when column `x + k` is in the span.
    pub mask: u8,
    /// NC depth per lane.
    pub z: [f32; LANES],
    /// The attributes at the anchor column of the block's 16-column group.
    pub anchor: &'a [f32; N],
    /// ∂v/∂x per attribute.
    pub dx: &'a [f32; N],
    /// Each lane's column offset from the anchor column: 0–7 or 8–15.
    pub offsets: [f32; LANES],
}

impl<const N: usize> SampleBlock<'_, N> {
    /// Attribute `i` at lane `k`.
    #[inline(always)]
    pub fn attr(&self, i: usize, k: usize) -> f32 {
        self.anchor[i] + self.dx[i] * self.offsets[k]
    }
}

/// The values at one anchor column of a row.
struct Anchor<const N: usize> {
    column: i32,
    z: f64,
    attrs: [f32; N],
}

impl<const N: usize> Anchor<N> {
    #[inline(always)]
    fn new(depth: &DepthPlane, attrs: &AttributePlanes<N>, column: i32, yc: f64) -> Anchor<N> {
        let xc = f64::from(column) + 0.5;
        Anchor { column, z: depth.at(xc, yc), attrs: attrs.at(xc, yc) }
    }

    /// Depth `k` columns after the anchor.
    #[inline(always)]
    fn z(&self, depth: &DepthPlane, k: usize) -> f32 {
        (self.z + depth.dzdx * f64::from(BLOCK_OFFSETS[k])) as f32
    }

    /// Attribute `i`, `k` columns after the anchor.
    #[inline(always)]
    fn attr(&self, attrs: &AttributePlanes<N>, i: usize, k: usize) -> f32 {
        self.attrs[i] + attrs.dx[i] * BLOCK_OFFSETS[k]
    }
}

/// Walks one span, calling `f(x, z, attributes)` for each sample in order
/// (see the module doc for how values are evaluated).
#[inline(always)]
pub fn for_each_sample<const N: usize>(
    depth: &DepthPlane,
    attrs: &AttributePlanes<N>,
    span: Span,
    mut f: impl FnMut(i32, f32, &[f32; N]),
) {
    let yc = f64::from(span.y) + 0.5;
    let mut x = span.x0;
    while x < span.x1 {
        let anchor = Anchor::new(depth, attrs, x & !(REANCHOR_BLOCK - 1), yc);
        let end = (anchor.column + REANCHOR_BLOCK).min(span.x1);
        for xi in x..end {
            let k = (xi - anchor.column) as usize;
            f(xi, anchor.z(depth, k), &std::array::from_fn(|i| anchor.attr(attrs, i, k)));
        }
        x = end;
    }
}

/// Column offsets of the first and of the second block after an anchor.
const LOW_OFFSETS: [f32; LANES] = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];
const HIGH_OFFSETS: [f32; LANES] = [8.0, 9.0, 10.0, 11.0, 12.0, 13.0, 14.0, 15.0];

/// `[f(0), …, f(7)]`, written out.
#[inline(always)]
fn lanes8(f: impl Fn(usize) -> f32) -> [f32; LANES] {
    [f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7)]
}

/// Walks one span in [`SampleBlock`]s of eight lanes, left to right. Lane
/// values are bit-identical to [`for_each_sample`]'s.
#[inline(always)]
pub fn for_each_block<const N: usize>(
    depth: &DepthPlane,
    attrs: &AttributePlanes<N>,
    span: Span,
    mut f: impl FnMut(&SampleBlock<'_, N>),
) {
    let yc = f64::from(span.y) + 0.5;
    let lanes = LANES as i32;
    let mut anchor = Anchor::new(depth, attrs, span.x0 & !(REANCHOR_BLOCK - 1), yc);
    let mut x = span.x0 & !(lanes - 1);
    while x < span.x1 {
        if x >= anchor.column + REANCHOR_BLOCK {
            anchor = Anchor::new(depth, attrs, x & !(REANCHOR_BLOCK - 1), yc);
        }
        // Lanes 0–7 or 8–15 of the anchor's 16 columns, as constants (an
        // index into them is checked per lane and keeps the depths scalar).
        let offsets = if x - anchor.column < lanes { LOW_OFFSETS } else { HIGH_OFFSETS };
        let lo = (span.x0 - x).clamp(0, lanes);
        let hi = (span.x1 - x).clamp(0, lanes);
        let mask = ((0xFFu32 << lo) & (0xFFu32 >> (lanes - hi))) as u8;
        let block = SampleBlock {
            x,
            mask,
            z: lanes8(|k| (anchor.z + depth.dzdx * f64::from(offsets[k])) as f32),
            anchor: &anchor.attrs,
            dx: &attrs.dx,
            offsets,
        };
        f(&block);
        x += lanes;
    }
}
