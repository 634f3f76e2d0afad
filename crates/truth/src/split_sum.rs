//! The environment term of the Cook–Torrance model (SPEC §5.2) in f64:
//! the specular lobe's directional albedo split by Schlick's Fresnel,
//!
//! ```text
//! ∫ f_spec(L, V)·(N·L) dω_L = f0·A + B,   f_spec = F·D·Vis,  F = f0 + (1 − f0)·(1 − V·H)^5
//! ```
//!
//! so that E_s = f0·A + B at (N·V, roughness).
//!
//! [`directional_albedo`] evaluates (A, B) by deterministic quadrature —
//! written here, sharing nothing with zline's Monte-Carlo tabulation. The
//! integral is taken over half vectors: with H at polar angle θ_h and
//! azimuth φ about N (V in the xz plane), dω_L = 4·(V·H)·dω_H, and θ_h is
//! reached through the distribution's inverse CDF u ↦ θ_h (GGX
//! tan²θ_h = α²u/(1 − u), Beckmann tan²θ_h = −α²·ln(1 − u)), so that
//! D·(N·H)·dω_H = du·dφ/(2π) and the integrand is
//! Vis·(N·L)·4·(V·H)/(N·H), bounded and smooth except where L crosses the
//! horizon. That crossing is found exactly: N·L > 0 ⟺ cos φ > c*(θ_h)
//! with c* = (N·V/(2 cos θ_h) − N·V·cos θ_h)/(sin θ_V·sin θ_h), increasing
//! in θ_h; so each φ integral runs over [0, φ*] (symmetric in φ), and the
//! outer integral is split where φ* reaches π and 0 (found by bisection).
//! Beckmann's V-groove G changes branch at three values of V·H, which
//! split the φ intervals too. Each piece is integrated by 8-point
//! Gauss–Legendre panels, u = 1 − (1 − x)² removes the integrable
//! 1/(N·H) growth at θ_h → 90°, and the piece where φ* falls from π to 0
//! clusters its nodes at both ends (square-root behaviour there).
//! Checked against a brute-force integral over light directions and
//! against `zline_shading::directional_albedo` with 2²² samples (agreement
//! to 10⁻⁶ away from grazing); [`directional_albedo`] is within 10⁻⁶ of
//! the same quadrature with four times the nodes away from grazing N·V,
//! 3·10⁻⁶ at grazing N·V.
//!
//! N·V below 10⁻⁹ is taken as 10⁻⁹: the integrand divides by N·V
//! (Beckmann) and the value there is the limit N·V → 0⁺.
//!
//! Per sample the truth reads a table ([`SplitSum::Integral`], the
//! default): 128 × 128 nodes with N·V = t³ and r = r_c + (1 − r_c)·s² for
//! t, s uniform in [0, 1], r_c = 10^(−7/4) (below it α² is held at 10⁻⁷,
//! so the integral does not change), filled with a coarser quadrature
//! (≈ 10⁻⁵), bilinear in (t, s). Compared with [`directional_albedo`] at
//! random points its (A, B) are within 1.0·10⁻³ (|ΔA| + |ΔB|) everywhere
//! and within 2.5·10⁻⁴ for N·V ≥ 0.1 (the unit tests hold it to that);
//! the error is largest at grazing N·V with low roughness, where A and B
//! change over ΔN·V ≈ α. [`SplitSum::ZlineTable`] instead reads zline's
//! own 32 × 32 table (its data, `zline_shading::split_sum_table`,
//! interpolated bilinearly here in f64), for comparisons that separate the
//! rest of the model from that table's resolution and sampling noise.

use std::f64::consts::PI;
use std::sync::OnceLock;

use rayon::prelude::*;
use zline_shading::Distribution;

/// Where the truth's lighting takes the environment's split sum (A, B)
/// from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SplitSum {
    /// The integral, from the truth's own 128 × 128 table of its
    /// quadrature ([`lookup`]): within 10⁻³ of [`directional_albedo`].
    #[default]
    Integral,
    /// zline's 32 × 32 table as data (`zline_shading::split_sum_table`,
    /// uniform over N·V, r ∈ [0, 1] as SPEC §5.2 states), interpolated
    /// bilinearly in f64: the truth of the model with the fast renderer's
    /// table in place of the integral, for tests that hold the rest of the
    /// model to f32 rounding.
    ZlineTable,
}

impl SplitSum {
    /// (A, B) at clamped `nv` and `roughness` for `distribution`.
    pub fn eval(self, distribution: Distribution, nv: f64, roughness: f64) -> [f64; 2] {
        match self {
            SplitSum::Integral => lookup(distribution, nv, roughness),
            SplitSum::ZlineTable => zline_table(distribution, nv, roughness),
        }
    }
}

/// The smallest α² (SPEC §5.2: α² kept ≥ 10⁻⁷).
pub(crate) const MIN_ALPHA2: f64 = 1e-7;

/// N·V below this is taken as this in the quadrature.
const MIN_NV: f64 = 1e-9;

/// 8-point Gauss–Legendre nodes and weights on [−1, 1].
const GAUSS_LEGENDRE_8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
];

/// ∫ₐᵇ f by `panels` equal panels of 8-point Gauss–Legendre (0 when b ≤ a).
fn gauss(a: f64, b: f64, panels: usize, mut f: impl FnMut(f64) -> [f64; 2]) -> [f64; 2] {
    let mut sum = [0.0; 2];
    if b <= a {
        return sum;
    }
    let h = (b - a) / panels as f64;
    for p in 0..panels {
        let centre = a + (p as f64 + 0.5) * h;
        for (x, w) in GAUSS_LEGENDRE_8 {
            let v = f(centre + 0.5 * h * x);
            sum[0] += w * v[0];
            sum[1] += w * v[1];
        }
    }
    [sum[0] * 0.5 * h, sum[1] * 0.5 * h]
}

/// ∫ₐᵇ f with the nodes clustered at both ends: x = a + (b − a)(1 − cos πs)/2.
fn gauss_clustered(a: f64, b: f64, panels: usize, mut f: impl FnMut(f64) -> [f64; 2]) -> [f64; 2] {
    if b <= a {
        return [0.0; 2];
    }
    gauss(0.0, 1.0, panels, |s| {
        let x = a + (b - a) * 0.5 * (1.0 - (PI * s).cos());
        let jacobian = (b - a) * 0.5 * PI * (PI * s).sin();
        let v = f(x);
        [v[0] * jacobian, v[1] * jacobian]
    })
}

/// Quadrature resolution: Gauss–Legendre panels over θ_h (per piece) and
/// over φ (per piece).
#[derive(Clone, Copy, Debug)]
struct Resolution {
    outer: usize,
    inner: usize,
}

/// The table's quadrature: about 10⁻⁵ (|ΔA| + |ΔB|), 8·10⁻⁵ at worst.
const TABLE_RESOLUTION: Resolution = Resolution { outer: 4, inner: 1 };

/// [`directional_albedo`]'s: about 10⁻⁶ (3·10⁻⁶ at grazing N·V).
const FINE_RESOLUTION: Resolution = Resolution { outer: 16, inner: 4 };

/// (A, B) at (`nv`, `roughness`) for `distribution` by quadrature (see the
/// module documentation): within about 10⁻⁶ of the integral (3·10⁻⁶ at
/// grazing N·V). Slow (a millisecond); the lighting reads [`lookup`].
pub fn directional_albedo(distribution: Distribution, nv: f64, roughness: f64) -> [f64; 2] {
    albedo(distribution, nv, roughness, FINE_RESOLUTION)
}

/// The half-vector polar angle as tan²θ_h at the outer variable x ∈ [0, 1)
/// (u = 1 − (1 − x)², then the inverse CDF); +∞ at x = 1.
fn tan2_at(distribution: Distribution, alpha2: f64, x: f64) -> f64 {
    let rest = (1.0 - x) * (1.0 - x); // 1 − u
    match distribution {
        Distribution::Ggx => alpha2 * (1.0 - rest) / rest,
        Distribution::Beckmann => -alpha2 * rest.ln(),
    }
}

/// (cos θ_h, sin θ_h) from tan²θ_h (finite).
fn cos_sin(tan2: f64) -> (f64, f64) {
    (1.0 / (1.0 + tan2).sqrt(), (tan2 / (1.0 + tan2)).sqrt())
}

fn albedo(distribution: Distribution, nv: f64, roughness: f64, res: Resolution) -> [f64; 2] {
    let nv = nv.clamp(MIN_NV, 1.0);
    let sv = (1.0 - nv * nv).max(0.0).sqrt();
    let r = roughness.clamp(0.0, 1.0);
    let alpha2 = (r * r * r * r).max(MIN_ALPHA2);
    // c*(θ_h): N·L > 0 exactly where cos φ > c* (±∞ where sin θ_V·sin θ_h = 0).
    let threshold = |tan2: f64| {
        if !tan2.is_finite() {
            return f64::INFINITY;
        }
        let (ch, sh) = cos_sin(tan2);
        let num = nv / (2.0 * ch) - nv * ch;
        let den = sv * sh;
        if den > 0.0 {
            num / den
        } else if num < 0.0 {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        }
    };
    // The x where c* reaches `target` (c* increases with θ_h, so with x).
    let crossing = |target: f64| {
        if threshold(tan2_at(distribution, alpha2, 0.0)) >= target {
            return 0.0;
        }
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if threshold(tan2_at(distribution, alpha2, mid)) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    let (all_phi, no_phi) = (crossing(-1.0), crossing(1.0));
    let outer = |x: f64| -> [f64; 2] {
        let tan2 = tan2_at(distribution, alpha2, x);
        if !tan2.is_finite() {
            return [0.0; 2];
        }
        let (ch, sh) = cos_sin(tan2);
        let phi_max = threshold(tan2).clamp(-1.0, 1.0).acos();
        if phi_max <= 0.0 {
            return [0.0; 2];
        }
        let inner = |phi: f64| -> [f64; 2] {
            let vh = sv * sh * phi.cos() + nv * ch;
            let nl = 2.0 * vh * ch - nv;
            if nl <= 0.0 || vh <= 0.0 {
                return [0.0; 2];
            }
            let vis = match distribution {
                Distribution::Ggx => {
                    0.5 / (nl * (nv * nv * (1.0 - alpha2) + alpha2).sqrt()
                        + nv * (nl * nl * (1.0 - alpha2) + alpha2).sqrt())
                }
                Distribution::Beckmann => {
                    let g = (2.0 * ch * nv / vh).min(2.0 * ch * nl / vh).min(1.0);
                    g / (4.0 * nl * nv)
                }
            };
            let weight = vis * nl * 4.0 * vh / ch;
            let s = (1.0 - vh).powi(5);
            [(1.0 - s) * weight, s * weight]
        };
        // Beckmann's G = min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H)) changes
        // branch at V·H = 2(N·H)(N·V), N·V/N·H and 2(N·H)(N·V)/(4(N·H)² − 1).
        let mut cuts = vec![0.0, phi_max];
        if distribution == Distribution::Beckmann && sv * sh > 0.0 {
            let mut vhs = vec![2.0 * ch * nv, nv / ch];
            if 4.0 * ch * ch > 1.0 {
                vhs.push(2.0 * ch * nv / (4.0 * ch * ch - 1.0));
            }
            for vh in vhs {
                let c = (vh - nv * ch) / (sv * sh);
                if c > -1.0 && c < 1.0 {
                    let phi = c.acos();
                    if phi > 0.0 && phi < phi_max {
                        cuts.push(phi);
                    }
                }
            }
            cuts.sort_by(f64::total_cmp);
        }
        let mut sum = [0.0; 2];
        for w in cuts.windows(2) {
            let v = gauss(w[0], w[1], res.inner, inner);
            sum[0] += v[0];
            sum[1] += v[1];
        }
        let jacobian = 2.0 * (1.0 - x); // du/dx
        [sum[0] * jacobian, sum[1] * jacobian]
    };
    let full = gauss(0.0, all_phi, res.outer, outer);
    let partial = gauss_clustered(all_phi, no_phi, res.outer, outer);
    // (1/2π)·∫du ∫dφ over φ ∈ (−π, π], the half range counted twice.
    [(full[0] + partial[0]) / PI, (full[1] + partial[1]) / PI]
}

/// Nodes of the truth's table along each axis.
const NODES: usize = 128;

/// The roughness at or below which α² = 10⁻⁷: 10^(−7/4).
fn roughness_floor() -> f64 {
    MIN_ALPHA2.sqrt().sqrt()
}

/// The table of `distribution`, computed on first use (in parallel):
/// entry (i, j) at N·V = (i/127)³, r = r_c + (1 − r_c)·(j/127)².
fn table(distribution: Distribution) -> &'static [[f64; 2]] {
    static GGX: OnceLock<Vec<[f64; 2]>> = OnceLock::new();
    static BECKMANN: OnceLock<Vec<[f64; 2]>> = OnceLock::new();
    let cell = match distribution {
        Distribution::Ggx => &GGX,
        Distribution::Beckmann => &BECKMANN,
    };
    cell.get_or_init(|| {
        let step = 1.0 / (NODES - 1) as f64;
        let rc = roughness_floor();
        (0..NODES * NODES)
            .into_par_iter()
            .map(|k| {
                let (i, j) = (k % NODES, k / NODES);
                let t = i as f64 * step;
                let s = j as f64 * step;
                albedo(distribution, t * t * t, rc + (1.0 - rc) * s * s, TABLE_RESOLUTION)
            })
            .collect()
    })
}

/// Bilinear interpolation in a `size` × `size` table (row j = second
/// coordinate) at continuous indices (x, y) ∈ [0, size − 1]².
fn bilinear(table: &[[f64; 2]], size: usize, x: f64, y: f64) -> [f64; 2] {
    let last = (size - 2) as f64;
    let (x0, y0) = (x.floor().clamp(0.0, last), y.floor().clamp(0.0, last));
    let (fx, fy) = (x - x0, y - y0);
    let (i, j) = (x0 as usize, y0 as usize);
    let at = |i: usize, j: usize| table[j * size + i];
    let lerp = |a: [f64; 2], b: [f64; 2], t: f64| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
    let top = lerp(at(i, j), at(i + 1, j), fx);
    let bottom = lerp(at(i, j + 1), at(i + 1, j + 1), fx);
    lerp(top, bottom, fy)
}

/// (A, B) at `nv`, `roughness` (each clamped to [0, 1]) from the truth's
/// table: within 10⁻³ of [`directional_albedo`], 2.5·10⁻⁴ for N·V ≥ 0.1.
pub fn lookup(distribution: Distribution, nv: f64, roughness: f64) -> [f64; 2] {
    let rc = roughness_floor();
    let t = nv.clamp(0.0, 1.0).cbrt();
    let s = ((roughness.clamp(0.0, 1.0) - rc).max(0.0) / (1.0 - rc)).sqrt();
    let n = (NODES - 1) as f64;
    bilinear(table(distribution), NODES, t * n, s * n)
}

/// (A, B) from zline's table as data, bilinear in f64 over its grid
/// (√(N·V) and roughness uniform; [`SplitSum::ZlineTable`]).
fn zline_table(distribution: Distribution, nv: f64, roughness: f64) -> [f64; 2] {
    static TABLES: OnceLock<[Vec<[f64; 2]>; 2]> = OnceLock::new();
    let size = zline_shading::SPLIT_SUM_SIZE;
    let tables = TABLES.get_or_init(|| {
        [Distribution::Ggx, Distribution::Beckmann].map(|d| {
            let table = zline_shading::split_sum_table(d);
            assert_eq!(table.len(), size * size, "zline's split-sum table is SPLIT_SUM_SIZE² entries");
            table.iter().map(|&[a, b]| [f64::from(a), f64::from(b)]).collect()
        })
    });
    let table = match distribution {
        Distribution::Ggx => &tables[0],
        Distribution::Beckmann => &tables[1],
    };
    let n = (size - 1) as f64;
    bilinear(table, size, nv.clamp(0.0, 1.0).sqrt() * n, roughness.clamp(0.0, 1.0) * n)
}

#[cfg(test)]
mod tests {
    use super::*;

    const DISTRIBUTIONS: [Distribution; 2] = [Distribution::Ggx, Distribution::Beckmann];

    fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
        (a[0] - b[0]).abs() + (a[1] - b[1]).abs()
    }

    /// ∫ f_spec·(N·L) dω over light directions on a (μ = N·L, φ) midpoint
    /// grid, straight from SPEC's formulas: an independent check.
    fn brute_force(distribution: Distribution, nv: f64, roughness: f64, n: usize) -> [f64; 2] {
        let view = glam::DVec3::new((1.0 - nv * nv).sqrt(), 0.0, nv);
        let alpha2 = (roughness.powi(4)).max(MIN_ALPHA2);
        let mut sum = [0.0; 2];
        for i in 0..n {
            let nl = (i as f64 + 0.5) / n as f64;
            let sin = (1.0 - nl * nl).sqrt();
            for k in 0..n {
                let phi = PI * (k as f64 + 0.5) / n as f64;
                let light = glam::DVec3::new(sin * phi.cos(), sin * phi.sin(), nl);
                let h = (light + view).normalize();
                let (nh, vh) = (h.z, view.dot(h));
                let dvis = match distribution {
                    Distribution::Ggx => {
                        let f = nh * nh * (alpha2 - 1.0) + 1.0;
                        let vis = 0.5
                            / (nl * (nv * nv * (1.0 - alpha2) + alpha2).sqrt()
                                + nv * (nl * nl * (1.0 - alpha2) + alpha2).sqrt());
                        alpha2 / (PI * f * f) * vis
                    }
                    Distribution::Beckmann => {
                        let tan2 = (1.0 - nh * nh) / (nh * nh);
                        let d = (-tan2 / alpha2).exp() / (PI * alpha2 * nh.powi(4));
                        let g = (2.0 * nh * nv / vh).min(2.0 * nh * nl / vh).min(1.0);
                        d * g / (4.0 * nl * nv)
                    }
                };
                let s = (1.0 - vh).powi(5);
                sum[0] += (1.0 - s) * dvis * nl;
                sum[1] += s * dvis * nl;
            }
        }
        let cell = 2.0 * PI / (n * n) as f64; // dμ·dφ, φ over (0, π) counted twice
        [sum[0] * cell, sum[1] * cell]
    }

    #[test]
    fn the_quadrature_agrees_with_a_brute_force_integral() {
        // Rough enough lobes for a 1500² grid over light directions.
        for distribution in DISTRIBUTIONS {
            for (nv, r) in [(0.13, 0.36), (0.5, 0.5), (0.9, 0.7), (0.3, 1.0), (1.0, 0.45)] {
                let q = directional_albedo(distribution, nv, r);
                let b = brute_force(distribution, nv, r, 1500);
                assert!(distance(q, b) < 2e-5, "{distribution:?} ({nv}, {r}): {q:?} vs {b:?}");
            }
        }
    }

    #[test]
    fn the_quadrature_converges() {
        for distribution in DISTRIBUTIONS {
            for (nv, r) in [(1e-3, 0.3), (1e-4, 0.02), (0.02, 1.0), (0.7, 0.9), (0.05, 0.1), (0.0, 0.0)] {
                let q = directional_albedo(distribution, nv, r);
                let finer = albedo(distribution, nv, r, Resolution { outer: 64, inner: 8 });
                let table = albedo(distribution, nv, r, TABLE_RESOLUTION);
                assert!(distance(q, finer) < 5e-6, "{distribution:?} ({nv}, {r}): {q:?} vs {finer:?}");
                assert!(
                    distance(table, finer) < 1e-4,
                    "{distribution:?} ({nv}, {r}): {table:?} vs {finer:?}"
                );
            }
        }
    }

    #[test]
    fn ggx_at_alpha_one_head_on_is_one_minus_ln_2() {
        // α = 1, V = N: D = 1/π, Vis = 0.5/(N·L + 1), so with F = 1
        // ∫ D·Vis·(N·L) dω = 2π·∫₀¹ μ/(2π(μ + 1)) dμ = 1 − ln 2.
        let [a, b] = directional_albedo(Distribution::Ggx, 1.0, 1.0);
        assert!((a + b - (1.0 - std::f64::consts::LN_2)).abs() < 1e-9, "{}", a + b);
    }

    #[test]
    fn a_mirror_reflects_everything_away_from_grazing() {
        // α² = 10⁻⁷: A + B = 1 up to the lobe's spread (~3·10⁻⁴ rad).
        for distribution in DISTRIBUTIONS {
            for nv in [0.1, 0.5, 1.0] {
                let [a, b] = directional_albedo(distribution, nv, 0.0);
                assert!((a + b - 1.0).abs() < 1e-3, "{distribution:?} N·V {nv}: {}", a + b);
                // ... and B is Schlick's weight at V·H = N·V.
                assert!((b - (1.0 - nv).powi(5)).abs() < 1e-3, "{distribution:?} N·V {nv}: B {b}");
            }
        }
    }

    #[test]
    fn the_table_is_within_its_stated_bound() {
        // A fixed pseudo-random set of points, a third of them at grazing N·V.
        let mut seed = 0x5eed_u64;
        let mut next = || {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for distribution in DISTRIBUTIONS {
            let (mut worst, mut worst_away) = (0.0f64, 0.0f64);
            for k in 0..300 {
                let (u, r) = (next(), next());
                let nv = if k % 3 == 0 { u.powi(4) } else { u };
                let e = distance(lookup(distribution, nv, r), directional_albedo(distribution, nv, r));
                worst = worst.max(e);
                if nv >= 0.1 {
                    worst_away = worst_away.max(e);
                }
            }
            assert!(
                worst < 1e-3 && worst_away < 2.5e-4,
                "{distribution:?}: {worst} overall, {worst_away} for N·V ≥ 0.1"
            );
        }
        // At the nodes the table holds the quadrature itself.
        let node = lookup(Distribution::Ggx, (5.0f64 / 127.0).powi(3), roughness_floor());
        let exact = albedo(Distribution::Ggx, (5.0f64 / 127.0).powi(3), roughness_floor(), TABLE_RESOLUTION);
        assert!(distance(node, exact) < 1e-12, "{node:?} vs {exact:?}");
    }

    #[test]
    fn zline_table_mode_reads_zline_at_its_nodes() {
        let size = zline_shading::SPLIT_SUM_SIZE;
        for distribution in DISTRIBUTIONS {
            let table = zline_shading::split_sum_table(distribution);
            for (i, j) in [(0, 0), (3, 7), (size - 1, size - 1), (size / 2, 1)] {
                let n = (size - 1) as f64;
                let u = i as f64 / n;
                let got = SplitSum::ZlineTable.eval(distribution, u * u, j as f64 / n);
                let want = table[j * size + i].map(f64::from);
                assert!(distance(got, want) < 1e-12, "{distribution:?} ({i}, {j}): {got:?} vs {want:?}");
            }
        }
    }
}
