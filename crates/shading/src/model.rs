//! The basic lighting model, evaluated at one point (SPEC §5):
//!
//! ```text
//! I = ke + ka·Ia + Σ_i f(d_i) · Il_i · [ kd·max(0, N·L_i) + ks·max(0, N·H_i)^ns ]
//! ```
//!
//! ke is the material's emission (glTF `emissiveFactor`, MTL `Ke`; 0 by
//! default). A texture modulates ka and kd only (SPEC §7), so ke travels
//! with the specular term in the part a texel does not multiply.
//!
//! with a local viewer, the Blinn half-way vector, and no specular term where
//! N·L ≤ 0. The result is clamped to [0, 1] per channel.

use glam::Vec3;

use crate::environment::Environment;
use crate::light::Light;
use crate::material::{Material, Model};
use crate::pbr::MicrofacetSums;

/// Ambient light plus a list of lights, all in one coordinate frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LightingModel {
    /// Ambient light Ia (RGB).
    pub ambient: Vec3,
    /// The light sources.
    pub lights: Vec<Light>,
    /// Light from an environment map (SPEC §5.3), added to the ambient
    /// light: Ia + E(N)/π in the basic model's ambient term, the
    /// irradiance and prefiltered radiance in Cook–Torrance's.
    pub environment: Option<Environment>,
}

/// The two parts of the lit colour, kept apart so a texture can modulate the
/// first and not the second (SPEC §7). Neither part is clamped. Emission,
/// which no texture modulates, is in the second.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LitParts {
    /// ka·Ia + Σ f·Il·kd·max(0, N·L).
    pub ambient_diffuse: Vec3,
    /// ke + Σ f·Il·ks·max(0, N·H)^ns: the emission and the specular term.
    pub specular: Vec3,
}

impl LitParts {
    /// The lit colour, clamped to [0, 1] per channel.
    #[inline]
    pub fn color(&self) -> Vec3 {
        self.color_below(1.0)
    }

    /// The lit colour clamped to [0, `ceiling`] per channel (see
    /// `PreparedLights::ceiling`).
    #[inline]
    pub fn color_below(&self, ceiling: f32) -> Vec3 {
        (self.ambient_diffuse + self.specular).clamp(Vec3::ZERO, Vec3::splat(ceiling))
    }
}

impl LightingModel {
    /// The same lights expressed in another frame (see [`Light::transformed`]).
    pub fn transformed(&self, to: &glam::Mat4) -> LightingModel {
        LightingModel {
            ambient: self.ambient,
            lights: self.lights.iter().map(|l| l.transformed(to)).collect(),
            environment: self.environment.as_ref().map(|e| e.transformed(to)),
        }
    }

    /// The clamped colour at `point` with unit normal `normal`, seen from
    /// `eye`.
    #[inline]
    pub fn shade(&self, material: &Material, point: Vec3, normal: Vec3, eye: Vec3) -> Vec3 {
        self.shade_parts(material, point, normal, eye).color()
    }

    /// The ambient+diffuse and specular parts at `point`, unclamped.
    ///
    /// `normal` must be unit length. A zero view vector (the eye on the
    /// surface) or a zero L + V leaves the specular term at 0.
    #[inline]
    pub fn shade_parts(&self, material: &Material, point: Vec3, normal: Vec3, eye: Vec3) -> LitParts {
        self.shade_parts_seen(material, (point, normal, eye), |_, _| None)
    }

    /// [`Self::shade_parts`] with each light's intensity multiplied by
    /// what `seen(k, to_light)` says reaches `point` from light k (the
    /// fraction per channel: a ray tracer's shadow ray), `None` for all of
    /// it (no multiplication, so `shade_parts`' results are these with
    /// every light seen whole). It is asked only for lights in front of
    /// the surface (N·L > 0) under the basic model.
    #[inline]
    pub fn shade_parts_seen(
        &self,
        material: &Material,
        (point, normal, eye): (Vec3, Vec3, Vec3),
        mut seen: impl FnMut(usize, Vec3) -> Option<Vec3>,
    ) -> LitParts {
        let view = (eye - point).normalize_or_zero();
        if let Model::CookTorrance(m) = material.model {
            // SPEC §5.2, the lights in the scene's order.
            let nv = crate::pbr::clamp01(normal.dot(view));
            let (alpha2, (_, f0)) = (m.alpha2(), m.colors(material.kd));
            let mut sums = MicrofacetSums::default();
            for (k, light) in self.lights.iter().enumerate() {
                let Some((to_light, mut intensity)) = light.incident(point) else { continue };
                if let Some(f) = seen(k, to_light) {
                    intensity *= f;
                }
                sums.add((&m, alpha2, f0), normal, view, nv, to_light, intensity);
            }
            let environment = match &self.environment {
                None => (self.ambient, self.ambient),
                Some(e) => {
                    let e = e.prepare(self.ambient);
                    (e.diffuse(normal), e.specular(crate::pbr::reflect(view, normal), m.roughness))
                }
            };
            let (ambient_diffuse, specular) = sums.parts(&m, material.kd, material.ke, environment, nv);
            return LitParts { ambient_diffuse, specular };
        }
        let mut diffuse = Vec3::ZERO;
        let mut specular = Vec3::ZERO;
        let specular_on = material.has_specular();
        for (k, light) in self.lights.iter().enumerate() {
            let Some((to_light, mut intensity)) = light.incident(point) else { continue };
            let n_dot_l = normal.dot(to_light);
            if n_dot_l <= 0.0 {
                continue;
            }
            if let Some(f) = seen(k, to_light) {
                intensity *= f;
            }
            diffuse += intensity * n_dot_l;
            if specular_on {
                let half = (to_light + view).normalize_or_zero();
                let n_dot_h = normal.dot(half);
                if n_dot_h > 0.0 {
                    specular += intensity * n_dot_h.powf(material.ns);
                }
            }
        }
        let ambient =
            self.environment.as_ref().map_or(self.ambient, |e| e.prepare(self.ambient).diffuse(normal));
        LitParts {
            ambient_diffuse: material.ka * ambient + material.kd * diffuse,
            specular: material.ke + material.ks * specular,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::Attenuation;

    #[track_caller]
    fn check_close(got: Vec3, want: Vec3) {
        assert!((got - want).abs().max_element() < 1e-6, "got {got}, want {want}");
    }

    fn white_point(at: Vec3, attenuation: Attenuation) -> LightingModel {
        LightingModel {
            ambient: Vec3::ZERO,
            lights: vec![Light::Point { position: at, color: Vec3::ONE, attenuation }],
            environment: None,
        }
    }

    #[test]
    fn head_on_point_light_gives_kd_plus_ks() {
        // N = L = V = H = +z: N·L = N·H = 1, so I = kd + ks (before clamping).
        let m = Material {
            ka: Vec3::ZERO,
            kd: Vec3::splat(0.5),
            ks: Vec3::splat(0.25),
            ns: 10.0,
            opacity: 1.0,
            ..Material::default()
        };
        let model = white_point(Vec3::new(0.0, 0.0, 2.0), Attenuation::NONE);
        let parts = model.shade_parts(&m, Vec3::ZERO, Vec3::Z, Vec3::new(0.0, 0.0, 5.0));
        check_close(parts.ambient_diffuse, Vec3::splat(0.5));
        check_close(parts.specular, Vec3::splat(0.25));
    }

    #[test]
    fn attenuation_follows_the_formula_and_clamps_at_one() {
        let a = Attenuation::new(1.0, 0.5, 0.25);
        assert_eq!(a.factor(2.0), 1.0 / (1.0 + 1.0 + 1.0));
        let strong = Attenuation::new(0.1, 0.0, 0.0);
        assert_eq!(strong.factor(3.0), 1.0);
    }

    #[test]
    fn light_behind_surface_gives_no_diffuse_or_specular() {
        let m = Material::plastic(Vec3::ONE, 1.0, 1.0);
        let model = white_point(Vec3::new(0.0, 0.0, -1.0), Attenuation::NONE);
        let parts = model.shade_parts(&m, Vec3::ZERO, Vec3::Z, Vec3::new(0.0, 0.0, 1.0));
        assert_eq!(parts, LitParts::default());
    }

    #[test]
    fn directional_light_uses_minus_direction() {
        let m = Material {
            ka: Vec3::ZERO,
            kd: Vec3::ONE,
            ks: Vec3::ZERO,
            ns: 1.0,
            opacity: 1.0,
            ..Material::default()
        };
        let model = LightingModel {
            ambient: Vec3::splat(0.1),
            lights: vec![Light::Directional { direction: Vec3::new(0.0, -1.0, -1.0), color: Vec3::ONE }],
            environment: None,
        };
        let c = model.shade(&m, Vec3::ZERO, Vec3::Z, Vec3::Z);
        check_close(c, Vec3::splat(std::f32::consts::FRAC_1_SQRT_2));
    }
}
