//! L_pre(R, r) by direct integration over the panorama (SPEC §5.3):
//!
//! ```text
//! L_pre = ∫ L(l)·w(l) dω / ∫ w(l) dω,   w(l) = D_GGX(N·H)/4 · (N·l),  N = V = R,  H = normalize(l + R)
//! ```
//!
//! over N·l > 0, L the bilinear panorama, α² = max(r⁴, 10⁻⁷), GGX for
//! either distribution (SPEC: the Beckmann distribution reads the same
//! levels). ((N·H)² = (1 + R·l)/2, so no half vector is formed.)
//!
//! The domain: the panorama's dual cells, each the patch between four
//! neighbouring texel centres (half a row at each pole), inside which the
//! bilinear L is one bilinear polynomial in (u, v): the integrand is then
//! smooth within a cell, and a 2 × 2 Gauss–Legendre rule in (u, v), with
//! the Jacobian (2π)(π/H)·sin θ, is of fourth order. Its relative error on
//! a cell of angular size h is about 10⁻³·(h/ℓ)⁴, where ℓ = max(α, δ/4) is
//! (a lower bound of) the distance over which GGX's weight changes by a
//! factor e at angle δ from R (its log-slope in l is δ/(α² + δ²/4)). A cell
//! with h > [`KAPPA`]·ℓ at its nearest angle to R is split into s × s
//! equal (u, v) parts, s ≤ [`MAX_SPLIT`], each with its own 2 × 2 rule: far
//! from R every cell counts with four points; the peak is split down to
//! its width; for a wide lobe, cells across R's horizon (where the factor
//! N·l has a kink) are split in 4 × 4.
//!
//! Narrower lobes than the split allows: below α = Θ/4, Θ = 4·h_max /
//! (KAPPA·MAX_SPLIT) (h_max the largest cell: Θ = h_max/8, 0.7° for a
//! 64 × 32 panorama), the directions within Θ of R form a cap whose weight
//! ∫_cap w dω is integrated in GGX's own variable u₁, where the weight is
//! N·l (within 10⁻⁴ of 1 in so small a cap: a 256-node midpoint rule is
//! exact to rounding), and whose radiance is L(R), the bilinear read
//! along R (the lobe's first-order term cancels by symmetry; what is left
//! is Θ²-small next to a texel); outside it, as above, Gauss points inside
//! the cap left out. The same sum for every roughness, no blending.
//!
//! Measured (unit tests): for a linear radiance a + b·(d·e) on 128 × 64
//! texels, within 1.6·10⁻⁴ of the closed form a + b·(R·e)·⟨cos θ_l⟩ at
//! every r (the bilinear reading's own error; r = 0 is that reading); on
//! the 64 × 32 procedural sky (sun included), within 7·10⁻⁵ (relative) of
//! the same sum with cells four times smaller (KAPPA/4, 4·MAX_SPLIT, the
//! cap four times narrower), r from 0 to 1. (A one-off check against 2·10⁶
//! GGX-sampled directions near the sun agreed to the sampling noise,
//! 0.3 %.)

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::DVec3;

/// A cell spans at most this share of ℓ before it is split.
pub(crate) const KAPPA: f64 = 0.5;

/// A cell is split into at most this many parts along each side.
pub(crate) const MAX_SPLIT: u32 = 64;

/// A cell across R's horizon, where the weight's factor N·l has a kink
/// (the rule is of second order there), is split into at least this many
/// parts a side, for a lobe whose D at the horizon is more than
/// [`HORIZON_WEIGHT`] of its peak (r ≳ 0.4; the kink's error, 3·10⁻⁴ of
/// L_pre unsplit at r = 0.7, scales with that ratio).
const HORIZON_SPLIT: f64 = 4.0;

/// See [`HORIZON_SPLIT`].
const HORIZON_WEIGHT: f64 = 1e-3;

/// Nodes of the midpoint rule for the cap's weight (in u₁, where the
/// integrand N·l is a smooth rational function).
const CAP_NODES: u32 = 256;

/// Gauss–Legendre nodes on [0, 1] (each of weight ½).
const GAUSS: [f64; 2] = [0.5 - 0.288_675_134_594_812_9, 0.5 + 0.288_675_134_594_812_9];

/// A row of dual cells: between texel rows `top` and `bottom` (the same
/// row at a pole).
#[derive(Clone, Copy, Debug, PartialEq)]
struct DualRow {
    top: usize,
    bottom: usize,
    /// The row's range of v, in texels (0 to H).
    v0: f64,
    v1: f64,
    /// Per Gauss node: (sin θ, cos θ, the fraction between `top` and
    /// `bottom`, the node's solid angle in an unsplit cell).
    nodes: [(f64, f64, f64, f64); 2],
    /// The cell's angular size: max(Δθ, Δφ·max sin θ).
    extent: f64,
    /// A cell whose centre has R·c at or below this is never split.
    cos_unsplit: f64,
    /// A cell whose centre has R·c below this lies under R's horizon.
    cos_below: f64,
    /// A cell whose centre has R·c below this (and not below `cos_below`)
    /// may straddle R's horizon.
    cos_above: f64,
}

/// The panorama's dual cells, prepared once per frame.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct DualGrid {
    width: usize,
    height: usize,
    /// Per dual column i and Gauss node a (index 2i + a): (sin φ, cos φ).
    columns: Vec<(f64, f64)>,
    rows: Vec<DualRow>,
    /// Cell centres, rows of `width`.
    centres: Vec<DVec3>,
    /// Θ, the cap radius.
    cap: f64,
}

impl DualGrid {
    /// The dual cells of a `width × height` panorama.
    pub(super) fn new(width: usize, height: usize) -> DualGrid {
        let (w, h) = (width as f64, height as f64);
        let columns = (0..2 * width)
            .map(|k| {
                let u = (k as f64 / 2.0).floor() + 0.5 + GAUSS[k % 2];
                (TAU * (u / w - 0.5)).sin_cos()
            })
            .collect();
        let rows: Vec<DualRow> = (0..=height).map(|j| dual_row(j, width, height)).collect();
        let mut centres = Vec::with_capacity(rows.len() * width);
        for row in &rows {
            for i in 0..width {
                centres.push(direction((i as f64 + 1.0) / w, 0.5 * (row.v0 + row.v1) / h));
            }
        }
        let largest = rows.iter().map(|r| r.extent).fold(0.0, f64::max);
        let cap = 4.0 * largest / (KAPPA * f64::from(MAX_SPLIT));
        DualGrid { width, height, columns, rows, centres, cap }
    }

    /// L_pre around unit `r` for GGX α² = `alpha2` over the panorama
    /// `texels`, cells split beyond `kappa`·ℓ into at most `max_split`
    /// parts a side (the cap radius scaled to match).
    pub(super) fn lobe_average(
        &self,
        texels: &[DVec3],
        r: DVec3,
        alpha2: f64,
        (kappa, max_split): (f64, u32),
    ) -> Option<DVec3> {
        let alpha = alpha2.sqrt();
        let radius = self.cap * (KAPPA * f64::from(MAX_SPLIT)) / (kappa * f64::from(max_split));
        let cap = if alpha < radius / 4.0 { radius } else { 0.0 };
        // D at the horizon (θ_h = 45°) over D at the peak: 4α⁴/(1 + α²)².
        let wide = 4.0 * alpha2 * alpha2 / (1.0 + alpha2).powi(2) > HORIZON_WEIGHT;
        let lobe = Lobe { alpha2, alpha, cap, wide };
        let cos_cap = if lobe.cap > 0.0 { lobe.cap.cos() } else { 1.0 };
        let mut sums = Sums { lobe: &lobe, cos_cap, sum: DVec3::ZERO, weight: 0.0 };
        for (j, row) in self.rows.iter().enumerate() {
            let (top, bottom) = (&texels[row.top * self.width..], &texels[row.bottom * self.width..]);
            for i in 0..self.width {
                let cos = r.dot(self.centres[j * self.width + i]);
                if cos < row.cos_below {
                    continue;
                }
                let next = (i + 1) % self.width;
                let corners = [top[i], top[next], bottom[i], bottom[next]];
                let mut s = if kappa >= KAPPA && cos <= row.cos_unsplit {
                    1
                } else {
                    lobe.split(row.extent, cos, (kappa, max_split))
                };
                if cos < row.cos_above && lobe.wide {
                    // Across R's horizon, where N·l has its kink.
                    s = s.max((HORIZON_SPLIT * KAPPA / kappa).ceil() as u32);
                }
                if s == 1 {
                    for &(sin_t, cos_t, fy, solid_angle) in &row.nodes {
                        for (a, &fx) in GAUSS.iter().enumerate() {
                            let (sin_p, cos_p) = self.columns[2 * i + a];
                            let d = DVec3::new(sin_t * sin_p, cos_t, -sin_t * cos_p);
                            sums.add(r.dot(d), solid_angle, || bilerp(&corners, fx, fy));
                        }
                    }
                } else {
                    self.split_cell((i, row), (r, s), &corners, &mut sums);
                }
            }
        }
        let (mut sum, mut weight) = (sums.sum, sums.weight);
        if lobe.cap > 0.0 {
            let w = lobe.cap_weight();
            sum += self.bilinear_along(texels, r) * w;
            weight += w;
        }
        (weight > 0.0).then(|| sum / weight)
    }

    /// Adds to `sums` the Gauss points of dual cell (i, `row`) split into
    /// `s × s` parts, for the lobe around `r`.
    fn split_cell(
        &self,
        (i, row): (usize, &DualRow),
        (r, s): (DVec3, u32),
        corners: &[DVec3; 4],
        sums: &mut Sums<'_>,
    ) {
        let (w, h, sf) = (self.width as f64, self.height as f64, f64::from(s));
        let pole = row.top == row.bottom;
        let (du, dv) = (1.0 / sf, (row.v1 - row.v0) / sf);
        let columns: Vec<(f64, f64, f64)> = (0..s)
            .flat_map(|p| GAUSS.map(|g| (f64::from(p) + g) / sf))
            .map(|fx| {
                let (sin_p, cos_p) = (TAU * ((i as f64 + 0.5 + fx) / w - 0.5)).sin_cos();
                (fx, sin_p, cos_p)
            })
            .collect();
        for q in 0..s {
            for &gy in &GAUSS {
                let fy = (f64::from(q) + gy) / sf;
                let theta = PI * (row.v0 + (row.v1 - row.v0) * fy) / h;
                let (sin_t, cos_t) = theta.sin_cos();
                let solid_angle = (TAU / w * du * 0.5) * (PI / h * dv * 0.5) * sin_t;
                let fy = if pole { 0.0 } else { fy };
                for &(fx, sin_p, cos_p) in &columns {
                    let d = DVec3::new(sin_t * sin_p, cos_t, -sin_t * cos_p);
                    sums.add(r.dot(d), solid_angle, || bilerp(corners, fx, fy));
                }
            }
        }
    }

    /// The bilinear panorama along unit `d` (SPEC §5.3: u wraps, v clamps).
    pub(super) fn bilinear_along(&self, texels: &[DVec3], d: DVec3) -> DVec3 {
        let u = 0.5 + d.x.atan2(-d.z) / TAU;
        let v = d.y.clamp(-1.0, 1.0).acos() / PI;
        bilinear(texels, (self.width, self.height), u, v)
    }
}

/// The bilinear panorama of `w × h` texels at image position (u, v).
pub(super) fn bilinear(texels: &[DVec3], (w, h): (usize, usize), u: f64, v: f64) -> DVec3 {
    let (w, h) = (w as i64, h as i64);
    let x = u * w as f64 - 0.5;
    let y = (v * h as f64 - 0.5).clamp(0.0, (h - 1) as f64);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (i, j) = (x0 as i64, y0 as i64);
    let at = |i: i64, j: i64| texels[(j.min(h - 1) * w + i.rem_euclid(w)) as usize];
    let top = at(i, j).lerp(at(i + 1, j), fx);
    let bottom = at(i, j + 1).lerp(at(i + 1, j + 1), fx);
    top.lerp(bottom, fy)
}

/// The bilinear patch of `corners` (top left, top right, bottom left,
/// bottom right) at (fx, fy) ∈ [0, 1]².
fn bilerp(corners: &[DVec3; 4], fx: f64, fy: f64) -> DVec3 {
    corners[0].lerp(corners[1], fx).lerp(corners[2].lerp(corners[3], fx), fy)
}

/// Dual row `j` of a `width × height` panorama: between texel rows j − 1
/// and j (row 0 above, row H − 1 below, at the poles).
fn dual_row(j: usize, width: usize, height: usize) -> DualRow {
    let (w, h) = (width as f64, height as f64);
    let v0 = if j == 0 { 0.0 } else { j as f64 - 0.5 };
    let v1 = if j == height { h } else { j as f64 + 0.5 };
    let nodes = GAUSS.map(|g| {
        let theta = PI * (v0 + (v1 - v0) * g) / h;
        let (sin_t, cos_t) = theta.sin_cos();
        (sin_t, cos_t, g, (TAU / w * 0.5) * (PI * (v1 - v0) / h * 0.5) * sin_t)
    });
    let (top, bottom) = (PI * v0 / h, PI * v1 / h);
    let max_sin = if top <= FRAC_PI_2 && bottom >= FRAC_PI_2 { 1.0 } else { top.sin().max(bottom.sin()) };
    let extent = (bottom - top).max(TAU / w * max_sin);
    DualRow {
        top: j.saturating_sub(1),
        bottom: j.min(height - 1),
        v0,
        v1,
        nodes,
        extent,
        // Unsplit once extent ≤ KAPPA·δ/4, δ = angle − extent.
        cos_unsplit: (extent * (1.0 + 4.0 / KAPPA)).min(PI).cos(),
        cos_below: (FRAC_PI_2 + extent).min(PI).cos(),
        cos_above: (FRAC_PI_2 - extent).max(0.0).cos(),
    }
}

/// The two sums of the lobe average.
struct Sums<'l> {
    lobe: &'l Lobe,
    /// Directions with R·l above this lie in the cap (1 without one).
    cos_cap: f64,
    /// Σ L·w·dω and Σ w·dω.
    sum: DVec3,
    weight: f64,
}

impl Sums<'_> {
    /// Adds a point with R·l = `cos`, of solid angle `solid_angle` and
    /// radiance `radiance()`, unless it lies under R's horizon or in the cap.
    #[inline]
    fn add(&mut self, cos: f64, solid_angle: f64, radiance: impl FnOnce() -> DVec3) {
        if cos > 0.0 && cos <= self.cos_cap {
            let w = self.lobe.weight(cos) * solid_angle;
            self.sum += radiance() * w;
            self.weight += w;
        }
    }
}

/// GGX's lobe with N = V = R.
struct Lobe {
    alpha2: f64,
    alpha: f64,
    /// The cap radius Θ, or 0 without a cap.
    cap: f64,
    /// Weighs R's horizon enough for its cells to be split.
    wide: bool,
}

impl Lobe {
    /// D_GGX(N·H)/4·(N·l) for a direction l with R·l = `cos` > 0.
    fn weight(&self, cos: f64) -> f64 {
        let nh2 = 0.5 * (1.0 + cos);
        let q = nh2 * (self.alpha2 - 1.0) + 1.0;
        self.alpha2 / (PI * q * q) / 4.0 * cos
    }

    /// Parts a side for a cell of angular size `extent` whose centre has
    /// R·c = `cos`.
    fn split(&self, extent: f64, cos: f64, (kappa, max_split): (f64, u32)) -> u32 {
        let nearest = (cos.clamp(-1.0, 1.0).acos() - extent).max(0.0);
        let scale = self.alpha.max(0.25 * nearest).max(0.25 * self.cap);
        ((extent / (kappa * scale)).ceil() as u32).clamp(1, max_split)
    }

    /// ∫ w dω within Θ of R: with GGX's u₁ (tan²θ_h = α²u₁/(1 − u₁)),
    /// D/4·dω_l = du₁·dφ/2π, so it is ∫₀^U (N·l) du₁, N·l = 2cos²θ_h − 1,
    /// cos²θ_h = (1 − u₁)/(1 + (α² − 1)u₁), U = t/(α² + t), t = tan²(Θ/2).
    fn cap_weight(&self) -> f64 {
        let t2 = (0.5 * self.cap).tan().powi(2);
        let end = t2 / (self.alpha2 + t2);
        let du = end / f64::from(CAP_NODES);
        (0..CAP_NODES)
            .map(|k| {
                let u = (f64::from(k) + 0.5) * du;
                let cos2 = (1.0 - u) / (1.0 + (self.alpha2 - 1.0) * u);
                (2.0 * cos2 - 1.0) * du
            })
            .sum()
    }
}

/// The unit direction through image position (u, v).
pub(super) fn direction(u: f64, v: f64) -> DVec3 {
    let (phi, theta) = (TAU * (u - 0.5), PI * v);
    let (sin_t, cos_t) = theta.sin_cos();
    DVec3::new(sin_t * phi.sin(), cos_t, -sin_t * phi.cos())
}
