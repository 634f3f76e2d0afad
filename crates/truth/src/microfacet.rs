//! The Cook–Torrance (microfacet) model of SPEC §5.2 in f64, for one light
//! at a time: the per-light terms that [`crate::lighting::EyeLights`] sums.
//!
//! ```text
//! c_diff = base·(1 − m)            f0 = 0.04 + (base − 0.04)·m
//! F = f0 + (1 − f0)·(1 − V·H)^5     α = r², α² ≥ 10⁻⁷
//! GGX:      D = α² / (π·((N·H)²(α² − 1) + 1)²)
//!           Vis = 0.5 / (N·L·√((N·V)²(1 − α²) + α²) + N·V·√((N·L)²(1 − α²) + α²))
//! Beckmann: D = exp(−tan²θ_h/α²) / (π·α²·(N·H)⁴),  tan²θ_h = (1 − (N·H)²)/(N·H)²
//!           Vis = G / (4·N·L·N·V),  G = min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H))
//! per light of intensity E:  diffuse (1 − F)·c_diff/π·E·N·L,  specular F·D·Vis·E·N·L
//! ```
//!
//! Dot products are clamped to [0, 1]; Vis = 0 where its denominator is 0
//! (Beckmann at N·V = 0); Beckmann's D = 0 at N·H = 0 (its limit) and
//! wherever its exponential underflows; a zero L + V gives H = 0, so
//! N·H = V·H = 0. Written from SPEC alone: the f32 code of `zline_shading`
//! is not called.

use glam::DVec3;
use zline_shading::{Distribution, Microfacet};

use crate::split_sum::MIN_ALPHA2;

/// F0 of a dielectric (ior 1.5).
const DIELECTRIC_F0: f64 = 0.04;

/// α² below which a lobe counts as sharp: its 1 − N·H spans ≲ 10⁻⁴,
/// within a few thousand f32 ulps of 1 (r < 0.1).
const SHARP_ALPHA2: f64 = 1e-4;

/// One light's Cook–Torrance terms per unit intensity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LightTerms {
    /// (1 − F)·N·L (times c_diff/π and the intensity: the diffuse term).
    pub(crate) diffuse: DVec3,
    /// F·D·Vis·N·L (times the intensity: the specular term).
    pub(crate) specular: DVec3,
    /// For a sharp lobe (α² < 10⁻⁴), |dD/d(N·H)|/D: the specular term's
    /// relative change per unit error in N·H; 0 otherwise.
    pub(crate) steepness: f64,
}

/// A Cook–Torrance material's parameters in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MicrofacetF64 {
    /// Metallic m ∈ [0, 1].
    pub(crate) metallic: f64,
    /// Perceptual roughness r ∈ [0, 1].
    pub(crate) roughness: f64,
    /// α² = max(r⁴, 10⁻⁷).
    pub(crate) alpha2: f64,
    /// The distribution of microfacet normals.
    pub(crate) distribution: Distribution,
}

impl MicrofacetF64 {
    /// The parameters (already sanitized: in [0, 1], no NaN) in f64.
    pub(crate) fn new(m: Microfacet) -> MicrofacetF64 {
        let (metallic, roughness) = (f64::from(m.metallic), f64::from(m.roughness));
        let alpha = roughness * roughness;
        MicrofacetF64 {
            metallic,
            roughness,
            alpha2: (alpha * alpha).max(MIN_ALPHA2),
            distribution: m.distribution,
        }
    }

    /// The parameters with a metallic–roughness texel's factors (SPEC
    /// §5.2, glTF): metallic times `b` (the texel's blue channel),
    /// roughness times `g` (its green), α² recomputed from the product.
    pub(crate) fn mapped(&self, b: f64, g: f64) -> MicrofacetF64 {
        let (metallic, roughness) = (self.metallic * b, self.roughness * g);
        let alpha = roughness * roughness;
        MicrofacetF64 { metallic, roughness, alpha2: (alpha * alpha).max(MIN_ALPHA2), ..*self }
    }

    /// (c_diff, f0) for the base colour `base`.
    pub(crate) fn colors(&self, base: DVec3) -> (DVec3, DVec3) {
        let m = self.metallic;
        (base * (1.0 - m), DVec3::splat(DIELECTRIC_F0) + (base - DIELECTRIC_F0) * m)
    }

    /// The distribution D at clamped N·H.
    fn d(&self, nh: f64) -> f64 {
        let a2 = self.alpha2;
        match self.distribution {
            Distribution::Ggx => {
                let f = nh * nh * (a2 - 1.0) + 1.0;
                a2 / (std::f64::consts::PI * f * f)
            }
            Distribution::Beckmann => {
                if nh <= 0.0 {
                    return 0.0;
                }
                let c2 = nh * nh;
                let tan2 = (1.0 - c2) / c2;
                let e = (-tan2 / a2).exp();
                if e == 0.0 {
                    // Also where (N·H)⁴ underflows: not 0/0.
                    return 0.0;
                }
                e / (std::f64::consts::PI * a2 * c2 * c2)
            }
        }
    }

    /// The visibility Vis at clamped dots, 0 where its denominator is 0.
    fn vis(&self, nl: f64, nv: f64, nh: f64, vh: f64) -> f64 {
        let a2 = self.alpha2;
        let (numerator, denominator) = match self.distribution {
            Distribution::Ggx => {
                (0.5, nl * (nv * nv * (1.0 - a2) + a2).sqrt() + nv * (nl * nl * (1.0 - a2) + a2).sqrt())
            }
            Distribution::Beckmann => {
                if vh <= 0.0 {
                    // H ⟂ V only where L = −V: then N·H = 0 and D = 0 anyway.
                    return 0.0;
                }
                let g = (2.0 * nh * nv / vh).min(2.0 * nh * nl / vh).min(1.0);
                (g, 4.0 * nl * nv)
            }
        };
        if denominator > 0.0 {
            numerator / denominator
        } else {
            0.0
        }
    }

    /// One light's terms per unit intensity, without c_diff/π: (1 − F)·N·L
    /// and F·D·Vis·N·L, for unit `normal`, `view` and `to_light` with N·L =
    /// `n_dot_l` > 0, clamped N·V `nv` and Fresnel f0 `f0`.
    pub(crate) fn light_terms(
        &self,
        (normal, view, nv): (DVec3, DVec3, f64),
        f0: DVec3,
        to_light: DVec3,
        n_dot_l: f64,
    ) -> LightTerms {
        let nl = n_dot_l.min(1.0);
        let half = (to_light + view).normalize_or_zero();
        let nh = normal.dot(half).clamp(0.0, 1.0);
        let vh = view.dot(half).clamp(0.0, 1.0);
        let fresnel = f0 + (DVec3::ONE - f0) * (1.0 - vh).powi(5);
        let d = self.d(nh);
        let dvis = d * self.vis(nl, nv, nh, vh);
        let specular = fresnel * (dvis * nl);
        // |dD/d(N·H)|/D, for the lobe's conditioning in f32.
        let steepness = if self.alpha2 < SHARP_ALPHA2 && d > 0.0 {
            match self.distribution {
                Distribution::Ggx => 4.0 * nh * (1.0 - self.alpha2) / (nh * nh * (self.alpha2 - 1.0) + 1.0),
                Distribution::Beckmann => (2.0 / (nh * nh * nh * self.alpha2) - 4.0 / nh).abs(),
            }
        } else {
            0.0
        };
        LightTerms { diffuse: (DVec3::ONE - fresnel) * nl, specular, steepness }
    }

    /// True when the model jumps where N·V crosses 0 (for switch margins):
    /// Beckmann's, whose G → 2(N·H)(N·V)/(V·H) as N·V → 0⁺, so that
    /// Vis·N·L → (N·H)/(2·V·H) ≠ 0, while Vis = 0 at N·V = 0. GGX's
    /// height-correlated Vis·N·L tends to its value at N·V = 0.
    pub(crate) fn switches_at_grazing_view(&self) -> bool {
        self.distribution == Distribution::Beckmann
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn material(metallic: f32, roughness: f32, distribution: Distribution) -> MicrofacetF64 {
        MicrofacetF64::new(Microfacet { metallic, roughness, distribution })
    }

    #[test]
    fn head_on_terms_by_hand() {
        // N = L = V = H: F = f0, D = 1/(π α²) (both), GGX Vis = 0.5/(2·1) = 1/4,
        // Beckmann G = 1, Vis = 1/4.
        for distribution in [Distribution::Ggx, Distribution::Beckmann] {
            let m = material(0.0, 0.5, distribution);
            let f0 = DVec3::splat(0.04);
            let LightTerms { diffuse, specular, .. } =
                m.light_terms((DVec3::Z, DVec3::Z, 1.0), f0, DVec3::Z, 1.0);
            let alpha2 = 0.0625; // (0.5²)²
            let want = 0.04 / (4.0 * PI * alpha2);
            assert!((specular - DVec3::splat(want)).abs().max_element() < 1e-14 * want, "{specular}");
            assert!((diffuse - DVec3::splat(0.96)).abs().max_element() < 1e-15, "{diffuse}");
        }
    }

    #[test]
    fn colors_mix_dielectric_and_metal() {
        let base = DVec3::new(0.2, 0.5, 1.0);
        let (c_diff, f0) = material(0.25, 1.0, Distribution::Ggx).colors(base);
        assert!((c_diff - base * 0.75).abs().max_element() < 1e-15);
        assert!((f0 - (DVec3::splat(0.04) * 0.75 + base * 0.25)).abs().max_element() < 1e-15);
        let (c_diff, f0) = material(1.0, 1.0, Distribution::Ggx).colors(base);
        assert_eq!((c_diff, f0), (DVec3::ZERO, base));
    }

    #[test]
    fn roughness_zero_keeps_alpha2_at_its_floor() {
        assert_eq!(material(0.0, 0.0, Distribution::Beckmann).alpha2, 1e-7);
        assert_eq!(material(0.0, 1.0, Distribution::Ggx).alpha2, 1.0);
    }

    #[test]
    fn beckmann_grazing_view_and_horizon_half_vector_give_zero() {
        let m = material(0.0, 0.5, Distribution::Beckmann);
        let f0 = DVec3::splat(0.04);
        // N·V = 0: Vis's denominator is 0.
        let specular = m.light_terms((DVec3::Z, DVec3::X, 0.0), f0, DVec3::Z, 1.0).specular;
        assert_eq!(specular, DVec3::ZERO);
        // L = −V (V below the surface, clamped N·V = 0): H = 0.
        let v = DVec3::new(0.0, 0.6, -0.8);
        let LightTerms { diffuse, specular, .. } = m.light_terms((DVec3::Z, v, 0.0), f0, -v, 0.8);
        assert_eq!(specular, DVec3::ZERO);
        assert!((diffuse - DVec3::splat(0.0)).abs().max_element() < 1e-15, "F = 1 at V·H = 0: {diffuse}");
    }
}
