//! The microfacet models (SPEC §5.2): Cook–Torrance with the
//! Trowbridge–Reitz (GGX) distribution and the height-correlated Smith
//! visibility, as glTF 2.0 Appendix B and the Khronos glTF Sample Viewer
//! evaluate the metallic–roughness material, and with the Beckmann
//! distribution and Cook–Torrance's V-groove geometric attenuation, as
//! the course presents the Torrance–Sparrow/Cook–Torrance model. For one
//! light of intensity E at unit direction L, with unit normal N and unit
//! view vector V (H = normalize(L + V), dots clamped to [0, 1]):
//!
//! ```text
//! c_diff = base·(1 − metallic)          f0 = 0.04 + (base − 0.04)·metallic
//! F = f0 + (1 − f0)·(1 − V·H)^5         α = roughness²
//! diffuse  = (1 − F) · c_diff / π · E · N·L
//! specular = F · Vis · D · E · N·L
//! ```
//!
//! and a uniform environment of radiance Ia (the scene's ambient) in the
//! split-sum form: E_s = f0·A + B with (A, B) the directional albedo of
//! the specular lobe at (N·V, roughness) ([`split_sum`]), ambient =
//! Ia·[c_diff·(1 − E_s) + E_s].
//!
//! Everything here is plain scalar arithmetic in a fixed order (+, −, ×,
//! ÷, square roots, `max`/`min`, and `exp` for Beckmann): the eight-lane
//! version in `simd.rs` performs the same operations per lane, so the two
//! agree bit for bit.

use std::f32::consts::PI;

use glam::Vec3;

/// The microfacet distribution of a Cook–Torrance material.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Distribution {
    /// Trowbridge–Reitz (GGX) with the height-correlated Smith visibility:
    /// glTF's metallic–roughness material.
    #[default]
    Ggx,
    /// Beckmann with Cook–Torrance's geometric attenuation
    /// G = min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H)): the course's
    /// Torrance–Sparrow/Cook–Torrance model.
    Beckmann,
}

impl Distribution {
    /// The lower-case name the CLI and scene files use.
    pub fn name(self) -> &'static str {
        match self {
            Distribution::Ggx => "ggx",
            Distribution::Beckmann => "beckmann",
        }
    }
}

/// The parameters of a Cook–Torrance material besides its base colour
/// (which is the material's kd).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    /// Metallic factor in [0, 1]: 0 a dielectric (f0 = 0.04, a diffuse
    /// lobe of the base colour), 1 a conductor (f0 = the base colour, no
    /// diffuse lobe).
    pub metallic: f32,
    /// Perceptual roughness in [0, 1]; α = roughness².
    pub roughness: f32,
    /// The distribution of microfacet normals.
    pub distribution: Distribution,
}

impl Default for Microfacet {
    /// glTF's defaults: metallic 1, roughness 1, GGX.
    fn default() -> Self {
        Microfacet { metallic: 1.0, roughness: 1.0, distribution: Distribution::Ggx }
    }
}

/// The smallest α² the distribution uses: α = 0 (a perfect mirror) would
/// make D a 0/0 where N = H; 1e-7 keeps it finite (D ≤ 1/(π·1e-7)), and a
/// highlight that narrow covers no sample in practice.
pub const MIN_ALPHA2: f32 = 1e-7;

/// F0 of a dielectric: ((ior − 1)/(ior + 1))² with glTF's ior of 1.5.
pub const DIELECTRIC_F0: f32 = 0.04;

impl Microfacet {
    /// The parameters with NaN replaced by the default and each clamped
    /// to [0, 1].
    pub fn sanitized(self) -> Microfacet {
        let c = |v: f32, default: f32| if v.is_nan() { default } else { v.clamp(0.0, 1.0) };
        Microfacet { metallic: c(self.metallic, 1.0), roughness: c(self.roughness, 1.0), ..self }
    }

    /// α² (never below [`MIN_ALPHA2`]).
    #[inline]
    pub fn alpha2(self) -> f32 {
        let alpha = self.roughness * self.roughness;
        (alpha * alpha).max(MIN_ALPHA2)
    }

    /// (c_diff, f0) of a surface of this material with base colour `base`.
    #[inline]
    pub fn colors(self, base: Vec3) -> (Vec3, Vec3) {
        let m = self.metallic;
        let c_diff = base * (1.0 - m);
        let f0 = Vec3::splat(DIELECTRIC_F0) + (base - Vec3::splat(DIELECTRIC_F0)) * m;
        (c_diff, f0)
    }
}

/// `x` clamped to [0, 1] with NaN taken to 0, as the eight-lane `max`
/// then `min` do (`f32::clamp` would keep a NaN).
#[inline]
#[allow(clippy::manual_clamp, reason = "NaN becomes 0, as in the lanes")]
pub(crate) fn clamp01(x: f32) -> f32 {
    x.max(0.0).min(1.0)
}

/// Schlick's weight (1 − x)^5 for x in [0, 1], as four multiplications.
#[inline]
pub(crate) fn schlick_weight(x: f32) -> f32 {
    let y = 1.0 - x;
    let y2 = y * y;
    y2 * y2 * y
}

/// The distribution D at clamped N·H `nh` and α².
#[inline]
pub(crate) fn distribution_d(distribution: Distribution, alpha2: f32, nh: f32) -> f32 {
    match distribution {
        Distribution::Ggx => {
            let f = nh * nh * (alpha2 - 1.0) + 1.0;
            alpha2 / (PI * f * f)
        }
        Distribution::Beckmann => {
            let c2 = nh * nh;
            if c2.is_nan() || c2 <= 0.0 {
                return 0.0;
            }
            let tan2 = (1.0 - c2) / c2;
            (-tan2 / alpha2).exp() / (PI * alpha2 * c2 * c2)
        }
    }
}

/// The visibility Vis = G/(4·N·L·N·V) at clamped dots `nl` > 0, `nv`,
/// `nh`, `vh` and α²: the height-correlated Smith form for GGX,
/// Cook–Torrance's V-groove G for Beckmann; 0 where the denominator is 0.
#[inline]
pub(crate) fn visibility(distribution: Distribution, alpha2: f32, nl: f32, nv: f32, nh: f32, vh: f32) -> f32 {
    match distribution {
        Distribution::Ggx => {
            let gv = nl * (nv * nv * (1.0 - alpha2) + alpha2).sqrt();
            let gl = nv * (nl * nl * (1.0 - alpha2) + alpha2).sqrt();
            let g = gv + gl;
            if g > 0.0 {
                0.5 / g
            } else {
                0.0
            }
        }
        Distribution::Beckmann => {
            if !(nv > 0.0 && vh > 0.0) {
                return 0.0;
            }
            let g = (2.0 * nh * nv / vh).min(2.0 * nh * nl / vh).min(1.0);
            g / (4.0 * nl * nv)
        }
    }
}

/// The specular lobe's D·Vis at one light (without F).
#[inline]
pub(crate) fn d_vis(distribution: Distribution, alpha2: f32, (nl, nv, nh, vh): (f32, f32, f32, f32)) -> f32 {
    if distribution == Distribution::Beckmann && !(nh * nh > 0.0 && nv > 0.0 && vh > 0.0) {
        return 0.0;
    }
    distribution_d(distribution, alpha2, nh) * visibility(distribution, alpha2, nl, nv, nh, vh)
}

/// Sums of one Cook–Torrance surface over the lights (the per-light
/// terms without c_diff and F folded in: `diffuse` holds
/// Σ (1 − F)·E·N·L, `specular` Σ F·D·Vis·E·N·L).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct MicrofacetSums {
    pub(crate) diffuse: Vec3,
    pub(crate) specular: Vec3,
}

impl MicrofacetSums {
    /// Adds one light: unit `to_light`, `intensity` E, at a sample with
    /// unit `normal` and `view`, clamped N·V `nv`.
    #[inline]
    #[allow(clippy::too_many_arguments, reason = "the per-light inputs, as the eight-lane twin takes them")]
    pub(crate) fn add(
        &mut self,
        (m, alpha2, f0): (&Microfacet, f32, Vec3),
        normal: Vec3,
        view: Vec3,
        nv: f32,
        to_light: Vec3,
        intensity: Vec3,
    ) {
        let nl = normal.dot(to_light);
        if nl <= 0.0 {
            return;
        }
        let nl = nl.min(1.0);
        let half = (to_light + view).normalize_or_zero();
        let nh = clamp01(normal.dot(half));
        let vh = clamp01(view.dot(half));
        let s = schlick_weight(vh);
        let fresnel = f0 + (Vec3::ONE - f0) * s;
        let e = intensity * nl;
        self.diffuse += (Vec3::ONE - fresnel) * e;
        self.specular += fresnel * (d_vis(m.distribution, alpha2, (nl, nv, nh, vh)) * e);
    }

    /// (ambient+diffuse, emission+specular) of the surface: `ke` its
    /// emission, `base` its base colour, the environment's radiance for the
    /// diffuse and the specular lobe (Ia for both when it is uniform).
    #[inline]
    pub(crate) fn parts(
        self,
        m: &Microfacet,
        base: Vec3,
        ke: Vec3,
        (diffuse_light, specular_light): (Vec3, Vec3),
        nv: f32,
    ) -> (Vec3, Vec3) {
        let (c_diff, f0) = m.colors(base);
        let [a, b] = split_sum(m.distribution, nv, m.roughness);
        let e_s = f0 * a + Vec3::splat(b);
        let ambient_diffuse =
            diffuse_light * (c_diff * (Vec3::ONE - e_s)) + c_diff * (self.diffuse * (1.0 / PI));
        let specular = ke + specular_light * e_s + self.specular;
        (ambient_diffuse, specular)
    }
}

/// The mirror direction of unit `view` about unit `normal`, 2(N·V)N − V:
/// where the environment's specular lobe is centred.
#[inline]
pub(crate) fn reflect(view: Vec3, normal: Vec3) -> Vec3 {
    normal * (2.0 * normal.dot(view)) - view
}

/// Side of the split-sum table: √(N·V) and roughness at i/(SIZE − 1) (the
/// square root crowds the nodes near grazing N·V, where A and B change
/// over ΔN·V ≈ α).
pub const SPLIT_SUM_SIZE: usize = 32;

/// Samples per table entry (a Hammersley set, importance-sampled).
const SPLIT_SUM_SAMPLES: u32 = 1 << 16;

/// (A, B) with ∫ f_spec·N·L dω = f0·A + B (f90 = 1) for a viewer at
/// N·V = `nv` on a surface of `roughness`: the directional albedo of the
/// specular lobe, split by Schlick's Fresnel. Bilinear in a
/// [`SPLIT_SUM_SIZE`]² table computed once per distribution (entries whose
/// estimate passes A + B = 1, by sampling noise at grazing N·V, scaled to 1).
#[inline]
pub fn split_sum(distribution: Distribution, nv: f32, roughness: f32) -> [f32; 2] {
    let table = split_sum_table(distribution);
    let n = (SPLIT_SUM_SIZE - 1) as f32;
    let (x, y) = (clamp01(nv).sqrt() * n, clamp01(roughness) * n);
    let (x0, y0) = (x.floor().min(n - 1.0), y.floor().min(n - 1.0));
    let (fx, fy) = (x - x0, y - y0);
    let (i, j) = (x0 as usize, y0 as usize);
    let at = |i: usize, j: usize| table[j * SPLIT_SUM_SIZE + i];
    let lerp = |a: [f32; 2], b: [f32; 2], t: f32| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
    let top = lerp(at(i, j), at(i + 1, j), fx);
    let bottom = lerp(at(i, j + 1), at(i + 1, j + 1), fx);
    lerp(top, bottom, fy)
}

/// The table of [`split_sum`] for `distribution` ([`SPLIT_SUM_SIZE`]²
/// entries, N·V along rows): [`split_sum_entries`], computed once and kept
/// as source in `split_sum_data.rs` (a test recomputes it and compares bit
/// for bit), so no render pays for the quadrature.
pub fn split_sum_table(distribution: Distribution) -> &'static [[f32; 2]] {
    match distribution {
        Distribution::Ggx => &crate::split_sum_data::GGX,
        Distribution::Beckmann => &crate::split_sum_data::BECKMANN,
    }
}

/// The entries of [`split_sum_table`], computed: (A, B) by
/// [`directional_albedo`] with 65,536 directions at N·V, roughness =
/// (i/(SIZE − 1))², j/(SIZE − 1). An estimate past A + B = 1 (sampling noise
/// at grazing N·V, up to 1 %) is scaled to 1: single scattering keeps
/// A + B ≤ 1.
pub fn split_sum_entries(distribution: Distribution) -> Vec<[f32; 2]> {
    (0..SPLIT_SUM_SIZE * SPLIT_SUM_SIZE).map(|k| split_sum_entry(distribution, k)).collect()
}

/// Entry `k` of [`split_sum_entries`] (N·V index k mod SIZE, roughness
/// index k / SIZE).
pub fn split_sum_entry(distribution: Distribution, k: usize) -> [f32; 2] {
    let n = SPLIT_SUM_SIZE;
    let u = (k % n) as f64 / (n - 1) as f64;
    let (nv, roughness) = (u * u, (k / n) as f64 / (n - 1) as f64);
    let [a, b] = directional_albedo(distribution, nv, roughness, SPLIT_SUM_SAMPLES);
    let scale = 1.0 / (a + b).max(1.0);
    [(a * scale) as f32, (b * scale) as f32]
}

/// (A, B) at one (N·V, roughness), in f64, by importance sampling the
/// distribution of half vectors with `samples` points of a Hammersley set
/// (deterministic). N·V = 0 is taken as 1e-4 (a grazing viewer).
pub fn directional_albedo(distribution: Distribution, nv: f64, roughness: f64, samples: u32) -> [f64; 2] {
    let nv = nv.max(1e-4);
    let view = [(1.0 - nv * nv).max(0.0).sqrt(), 0.0, nv];
    let alpha = roughness * roughness;
    let alpha2 = (alpha * alpha).max(f64::from(MIN_ALPHA2));
    let (mut a, mut b) = (0.0, 0.0);
    for k in 0..samples {
        let u1 = (f64::from(k) + 0.5) / f64::from(samples);
        let u2 = f64::from(k.reverse_bits()) / 4_294_967_296.0;
        // tan²θ_h from the distribution's inverse CDF.
        let tan2 = match distribution {
            Distribution::Ggx => alpha2 * u1 / (1.0 - u1),
            Distribution::Beckmann => -alpha2 * (1.0 - u1).ln(),
        };
        let cos_h = 1.0 / (1.0 + tan2).sqrt();
        let sin_h = (1.0 - cos_h * cos_h).max(0.0).sqrt();
        let phi = 2.0 * std::f64::consts::PI * u2;
        let h = [sin_h * phi.cos(), sin_h * phi.sin(), cos_h];
        let vh = view[0] * h[0] + view[1] * h[1] + view[2] * h[2];
        let l = [2.0 * vh * h[0] - view[0], 2.0 * vh * h[1] - view[1], 2.0 * vh * h[2] - view[2]];
        let (nl, nh) = (l[2], h[2]);
        if nl <= 0.0 || vh <= 0.0 {
            continue;
        }
        // f·N·L / pdf(L) with pdf(L) = D·N·H / (4·V·H): D cancels.
        let vis = match distribution {
            Distribution::Ggx => {
                let gv = nl * (nv * nv * (1.0 - alpha2) + alpha2).sqrt();
                let gl = nv * (nl * nl * (1.0 - alpha2) + alpha2).sqrt();
                0.5 / (gv + gl)
            }
            Distribution::Beckmann => {
                let g = (2.0 * nh * nv / vh).min(2.0 * nh * nl / vh).min(1.0);
                g / (4.0 * nl * nv)
            }
        };
        let weight = vis * nl * 4.0 * vh / nh;
        let s = (1.0 - vh).powi(5);
        a += (1.0 - s) * weight;
        b += s * weight;
    }
    [a / f64::from(samples), b / f64::from(samples)]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫₀¹ f(μ) dμ by the midpoint rule on `n` pieces, in f64.
    fn integrate(n: usize, f: impl Fn(f64) -> f64) -> f64 {
        (0..n).map(|k| f((k as f64 + 0.5) / n as f64)).sum::<f64>() / n as f64
    }

    const DISTRIBUTIONS: [Distribution; 2] = [Distribution::Ggx, Distribution::Beckmann];

    #[test]
    fn the_distributions_integrate_to_one_projected() {
        // ∫ D(h)·(N·H) dω_h = 2π ∫₀¹ D(μ)·μ dμ = 1 (μ = cos θ_h).
        for distribution in DISTRIBUTIONS {
            for alpha in [0.3f32, 0.5, 0.8, 1.0] {
                let alpha2 = alpha * alpha;
                let total = 2.0
                    * std::f64::consts::PI
                    * integrate(400_000, |mu| {
                        f64::from(distribution_d(distribution, alpha2, mu as f32)) * mu
                    });
                assert!((total - 1.0).abs() < 2e-4, "{distribution:?} α {alpha}: ∫ D·cos = {total}");
            }
        }
    }

    #[test]
    fn ggx_passes_the_weak_white_furnace_test() {
        // ∫ G1(V)·D(H)·max(0, V·H) / (N·V) dω_h = 1 (Heitz 2014, the weak
        // white furnace), with G1(V) = 4·N·V·Vis(N·L = 1, N·V): the
        // height-correlated form reduces to Smith's G1 when L = N.
        let (n_theta, n_phi) = (4000, 256);
        for alpha in [0.2f32, 0.5, 1.0] {
            let alpha2 = alpha * alpha;
            for theta_v in [0.0f64, 0.6, 1.2] {
                let view = [theta_v.sin(), 0.0, theta_v.cos()];
                let nv = view[2];
                let g1 =
                    4.0 * nv * f64::from(visibility(Distribution::Ggx, alpha2, 1.0, nv as f32, 1.0, 1.0));
                let mut total = 0.0;
                for i in 0..n_theta {
                    let mu = (i as f64 + 0.5) / n_theta as f64;
                    let sin = (1.0 - mu * mu).sqrt();
                    let d = f64::from(distribution_d(Distribution::Ggx, alpha2, mu as f32));
                    for j in 0..n_phi {
                        let phi = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / n_phi as f64;
                        let vh = view[0] * sin * phi.cos() + view[2] * mu;
                        total += d * vh.max(0.0);
                    }
                }
                let total = g1 * total * 2.0 * std::f64::consts::PI / (n_theta * n_phi) as f64 / nv;
                assert!((total - 1.0).abs() < 2e-3, "α {alpha}, θ_v {theta_v}: {total}");
            }
        }
    }

    #[test]
    fn ggx_albedo_at_alpha_one_head_on_is_one_minus_ln_2() {
        // α = 1, V = N, F = 1: ∫ D·Vis·(N·L) dω_l = 1 − ln 2 (D = 1/π and
        // Vis = 0.5/(N·L + 1) there). By quadrature over θ_l with the
        // implementation's D·Vis, and by the split-sum table's sampler.
        let want = 1.0 - std::f64::consts::LN_2;
        let quadrature = 2.0
            * std::f64::consts::PI
            * integrate(200_000, |nl| {
                let half = ((1.0 + nl) / 2.0).sqrt(); // N·H = V·H = cos(θ_l / 2)
                let h = half as f32;
                f64::from(d_vis(Distribution::Ggx, 1.0, (nl as f32, 1.0, h, h))) * nl
            });
        assert!((quadrature - want).abs() < 1e-3, "quadrature {quadrature} vs {want}");
        let [a, b] = directional_albedo(Distribution::Ggx, 1.0, 1.0, 4096);
        assert!((a + b - want).abs() < 1e-3, "sampled {} vs {want}", a + b);
        let [a, b] = split_sum(Distribution::Ggx, 1.0, 1.0);
        assert!((f64::from(a + b) - want).abs() < 1e-3, "table {} vs {want}", a + b);
    }

    #[test]
    fn a_mirror_reflects_everything_and_the_table_stays_within_zero_and_one() {
        // Roughness 0: A + B = 1 at every angle (a sampled half vector at
        // N weighs V·H/N·V = 1). α² is kept at 1e-7, not 0, so the half
        // vectors spread by ~3e-4 rad: 2.3e-4 off at N·V = 0.1.
        for distribution in DISTRIBUTIONS {
            for nv in [0.1, 0.5, 1.0] {
                let [a, b] = directional_albedo(distribution, nv, 0.0, 64);
                assert!((a + b - 1.0).abs() < 1e-3, "{distribution:?} N·V {nv}: {}", a + b);
            }
            for (k, &[a, b]) in split_sum_table(distribution).iter().enumerate() {
                assert!(a >= 0.0 && b >= 0.0 && a + b <= 1.0 + 1e-6, "{distribution:?} entry {k}: {a} {b}");
            }
        }
    }

    #[test]
    fn a_white_dielectric_in_a_white_furnace_stays_white() {
        // Ia = 1, base 1, metallic 0, no lights: c_diff·(1 − E_s) + E_s = 1.
        for distribution in DISTRIBUTIONS {
            for roughness in [0.0, 0.3, 1.0] {
                let m = Microfacet { metallic: 0.0, roughness, distribution };
                for nv in [0.05, 0.5, 1.0] {
                    let (ad, sp) = MicrofacetSums::default().parts(
                        &m,
                        Vec3::ONE,
                        Vec3::ZERO,
                        (Vec3::ONE, Vec3::ONE),
                        nv,
                    );
                    let total = ad + sp;
                    assert!((total - Vec3::ONE).abs().max_element() < 1e-6, "{total}");
                }
            }
        }
    }

    #[test]
    fn head_on_light_gives_the_formula_by_hand() {
        // N = L = V = H: F = f0, GGX D = 1/(π α²), Vis = 1/(4 α)·… with
        // N·L = N·V = 1: Vis = 0.5/(2·√1) = 1/4; so the specular sum is
        // f0·E/(4π α²) and the diffuse sum (1 − f0)·E.
        let m = Microfacet { metallic: 0.0, roughness: 0.5, distribution: Distribution::Ggx };
        let (alpha2, f0) = (m.alpha2(), Vec3::splat(DIELECTRIC_F0));
        let mut sums = MicrofacetSums::default();
        sums.add((&m, alpha2, f0), Vec3::Z, Vec3::Z, 1.0, Vec3::Z, Vec3::ONE);
        let alpha2 = 0.0625f32;
        let want = 0.04 / (4.0 * PI * alpha2);
        assert!((sums.specular.x - want).abs() < 1e-6 * want, "{} vs {want}", sums.specular.x);
        assert!((sums.diffuse.x - 0.96).abs() < 1e-7);
    }

    #[test]
    fn the_stored_split_sum_tables_are_their_definition() {
        // `ZLINE_WRITE_SPLIT_SUM=1 cargo test -p zline-shading --release
        // stored_split_sum` rewrites src/split_sum_data.rs (65,536
        // directions per entry: seconds in a release build); otherwise
        // every 29th entry and the corners are recomputed and compared.
        if std::env::var_os("ZLINE_WRITE_SPLIT_SUM").is_some() {
            let tables = DISTRIBUTIONS.map(split_sum_entries);
            let mut out = String::from(
                "//! The split-sum tables of `pbr::split_sum` (SPEC §5.2), written by\n\
                 //! `pbr::split_sum_entries` (see the test that checks them).\n\n",
            );
            for (name, table) in ["GGX", "BECKMANN"].iter().zip(&tables) {
                out += &format!("/// (A, B) for {name}, N·V along rows.\n#[rustfmt::skip]\npub(crate) const {name}: [[f32; 2]; {}] = [\n", table.len());
                for row in table.chunks(4) {
                    out += "   ";
                    for [a, b] in row {
                        out += &format!(" [{a:?}, {b:?}],");
                    }
                    out += "\n";
                }
                out += "];\n\n";
            }
            let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/split_sum_data.rs");
            std::fs::write(path, out.trim_end().to_owned() + "\n").unwrap();
            return;
        }
        let last = SPLIT_SUM_SIZE * SPLIT_SUM_SIZE - 1;
        for distribution in DISTRIBUTIONS {
            let stored = split_sum_table(distribution);
            assert_eq!(stored.len(), last + 1);
            for k in (0..=last).step_by(29).chain([SPLIT_SUM_SIZE - 1, last - SPLIT_SUM_SIZE + 1, last]) {
                let (s, c) = (stored[k], split_sum_entry(distribution, k));
                assert_eq!(
                    s.map(f32::to_bits),
                    c.map(f32::to_bits),
                    "{distribution:?} entry {k}: {s:?} vs {c:?}"
                );
            }
        }
    }
}
