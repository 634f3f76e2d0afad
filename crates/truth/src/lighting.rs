//! The lighting model of SPEC §5 in f64, in eye space, with the viewer at
//! the eye-space origin (a local viewer; the fast renderer uses the origin
//! for orthographic cameras too, and so does the truth):
//!
//! ```text
//! I = ke + ka·Ia + Σ_i f(d_i) · Il_i · [ kd·max(0, N·L_i) + ks·max(0, N·H_i)^ns ]
//! ```
//!
//! with ke the material's emission (`Material::ke`, 0 by default), kept
//! with the specular term because no texel or vertex colour modulates it
//! (as the fast renderer's `LitParts` keep it);
//! f(d) = min(1, 1/(a0 + a1·d + a2·d²)) (1 where the denominator is ≤ 1, as
//! `Attenuation::factor` states), f = 1 and a constant L for directional
//! lights, and no specular term where N·L ≤ 0 or N·H ≤ 0. A point light at
//! the surface point itself contributes nothing; a zero L + V leaves the
//! specular term at 0. Materials are `sanitized` first, as the fast
//! renderer does. On a shadow receiver, a light hidden from the surface
//! point drops out of the sum ([`crate::shadow`]).

use glam::{DMat4, DVec3};
use zline_shading::{Light, Material};

use crate::shadow::{Occluders, TriangleId};

/// A material's coefficients in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MaterialF64 {
    pub(crate) ke: DVec3,
    pub(crate) ka: DVec3,
    pub(crate) kd: DVec3,
    pub(crate) ks: DVec3,
    pub(crate) ns: f64,
    pub(crate) opacity: f64,
}

impl MaterialF64 {
    /// The sanitized material in f64.
    pub(crate) fn new(m: &Material) -> MaterialF64 {
        let m = m.sanitized();
        MaterialF64 {
            ke: m.ke.as_dvec3(),
            ka: m.ka.as_dvec3(),
            kd: m.kd.as_dvec3(),
            ks: m.ks.as_dvec3(),
            ns: f64::from(m.ns),
            opacity: f64::from(m.opacity),
        }
    }
}

/// A light in eye space.
#[derive(Clone, Copy, Debug, PartialEq)]
enum EyeLight {
    Point { position: DVec3, color: DVec3, a: [f64; 3] },
    Directional { to_light: DVec3, color: DVec3 },
}

/// Ambient light and the lights, in eye space.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct EyeLights {
    ambient: DVec3,
    lights: Vec<EyeLight>,
}

/// The two parts of a lit colour (SPEC §7 keeps them apart), unclamped: a
/// texel or a vertex colour multiplies the first only.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Parts {
    /// ka·Ia + Σ f·Il·kd·max(0, N·L).
    pub(crate) ambient_diffuse: DVec3,
    /// ke + Σ f·Il·ks·max(0, N·H)^ns: the emission and the specular term.
    pub(crate) specular: DVec3,
    /// The smallest |N·L| over the lights whose specular term can switch
    /// on or off there (ks > 0); +∞ without such lights. The model is
    /// discontinuous at N·L = 0, so renderers may disagree near it.
    pub(crate) switch_margin: f64,
}

impl Parts {
    /// The lit colour, clamped to [0, 1] per channel.
    pub(crate) fn color(&self) -> DVec3 {
        (self.ambient_diffuse + self.specular).clamp(DVec3::ZERO, DVec3::ONE)
    }

    /// Weighted sum of three parts (interpolation); margins take the minimum.
    pub(crate) fn blend(parts: &[Parts; 3], w: &[f64; 3]) -> Parts {
        Parts {
            ambient_diffuse: (0..3).map(|k| parts[k].ambient_diffuse * w[k]).sum(),
            specular: (0..3).map(|k| parts[k].specular * w[k]).sum(),
            switch_margin: parts.iter().map(|p| p.switch_margin).fold(f64::INFINITY, f64::min),
        }
    }
}

impl EyeLights {
    /// The scene's lights transformed by eye_from_world (positions as
    /// points, directions as vectors).
    pub(crate) fn new(ambient: glam::Vec3, lights: &[Light], eye_from_world: &DMat4) -> EyeLights {
        let lights = lights
            .iter()
            .map(|l| match *l {
                Light::Point { position, color, attenuation: at } => EyeLight::Point {
                    position: eye_from_world.transform_point3(position.as_dvec3()),
                    color: color.as_dvec3(),
                    a: [at.a0, at.a1, at.a2].map(f64::from),
                },
                Light::Directional { direction, color } => EyeLight::Directional {
                    to_light: -eye_from_world.transform_vector3(direction.as_dvec3()).normalize_or_zero(),
                    color: color.as_dvec3(),
                },
            })
            .collect();
        EyeLights { ambient: ambient.as_dvec3(), lights }
    }

    /// The lighting model at eye-space `point` with unit (or zero) `normal`.
    pub(crate) fn shade(&self, m: &MaterialF64, point: DVec3, normal: DVec3) -> Parts {
        self.shade_shadowed(m, point, normal, None)
    }

    /// The lighting model with shadows: with `shadow` = (occluders, P, on),
    /// a light that would light the point (N·L > 0) but that the occluders
    /// other than triangle `on` (the one P lies on) hide from the eye-space
    /// point P adds neither diffuse nor specular (see [`crate::shadow`]).
    /// P is the exact surface point, which screen-linear interpolation may
    /// move `point` away from.
    pub(crate) fn shade_shadowed(
        &self,
        m: &MaterialF64,
        point: DVec3,
        normal: DVec3,
        shadow: Option<(&Occluders, DVec3, TriangleId)>,
    ) -> Parts {
        let view = (-point).normalize_or_zero();
        let specular_on = m.ks.max_element() > 0.0;
        let (mut diffuse, mut specular) = (DVec3::ZERO, DVec3::ZERO);
        let mut switch_margin = f64::INFINITY;
        for light in &self.lights {
            let (to_light, intensity) = match *light {
                EyeLight::Point { position, color, a } => {
                    let d = position - point;
                    let dist = d.length();
                    if dist == 0.0 {
                        continue;
                    }
                    (d / dist, color * attenuation(a, dist))
                }
                EyeLight::Directional { to_light, color } => (to_light, color),
            };
            let n_dot_l = normal.dot(to_light);
            if specular_on {
                switch_margin = switch_margin.min(n_dot_l.abs());
            }
            if n_dot_l <= 0.0 {
                continue;
            }
            if let Some((occluders, at, on)) = shadow {
                let hidden = match *light {
                    EyeLight::Point { position, .. } => occluders.hides_point(at, on, position),
                    EyeLight::Directional { to_light, .. } => occluders.hides_direction(at, on, to_light),
                };
                if hidden {
                    continue;
                }
            }
            diffuse += intensity * n_dot_l;
            if specular_on {
                let n_dot_h = normal.dot((to_light + view).normalize_or_zero());
                if n_dot_h > 0.0 {
                    specular += intensity * n_dot_h.powf(m.ns);
                }
            }
        }
        Parts {
            ambient_diffuse: m.ka * self.ambient + m.kd * diffuse,
            specular: m.ke + m.ks * specular,
            switch_margin,
        }
    }
}

/// f(d) = min(1, 1/(a0 + a1·d + a2·d²)); 1 where the denominator is ≤ 1.
fn attenuation(a: [f64; 3], d: f64) -> f64 {
    let denom = a[0] + d * (a[1] + d * a[2]);
    if denom > 1.0 {
        1.0 / denom
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use zline_shading::Attenuation;

    #[test]
    fn head_on_point_light_and_attenuation() {
        let m = MaterialF64 {
            ke: DVec3::ZERO,
            ka: DVec3::ZERO,
            kd: DVec3::splat(0.5),
            ks: DVec3::splat(0.25),
            ns: 10.0,
            opacity: 1.0,
        };
        let at = Attenuation { a0: 1.0, a1: 0.5, a2: 0.25 };
        let light = Light::Point { position: Vec3::new(0.0, 0.0, -3.0), color: Vec3::ONE, attenuation: at };
        let lights = EyeLights::new(Vec3::ZERO, &[light], &DMat4::IDENTITY);
        // Surface at z = −5 facing the eye: N = L = V = H = +z, d = 2, f = 1/3.
        let p = lights.shade(&m, DVec3::new(0.0, 0.0, -5.0), DVec3::Z);
        assert!((p.ambient_diffuse - DVec3::splat(0.5 / 3.0)).length() < 1e-15);
        assert!((p.specular - DVec3::splat(0.25 / 3.0)).length() < 1e-15);
        assert_eq!(p.switch_margin, 1.0);
    }

    #[test]
    fn no_specular_behind_the_surface() {
        let m = MaterialF64::new(&Material::plastic(Vec3::ONE, 1.0, 1.0));
        let light = Light::Directional { direction: Vec3::Z, color: Vec3::ONE };
        let lights = EyeLights::new(Vec3::splat(0.25), &[light], &DMat4::IDENTITY);
        let p = lights.shade(&m, DVec3::new(0.0, 0.0, -5.0), DVec3::Z);
        assert_eq!((p.ambient_diffuse, p.specular), (DVec3::splat(0.25), DVec3::ZERO));
    }

    #[test]
    fn emission_joins_the_specular_part_even_unlit() {
        let m = MaterialF64 { ke: DVec3::new(0.1, 0.2, 0.3), ..MaterialF64::new(&Material::DEFAULT) };
        let light = Light::Directional { direction: Vec3::Z, color: Vec3::ONE };
        let lights = EyeLights::new(Vec3::ZERO, &[light], &DMat4::IDENTITY);
        let p = lights.shade(&m, DVec3::new(0.0, 0.0, -5.0), DVec3::Z);
        assert_eq!((p.ambient_diffuse, p.specular), (DVec3::ZERO, m.ke));
    }
}
