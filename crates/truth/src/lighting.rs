//! The lighting models of SPEC §5 in f64, in eye space, with the viewer at
//! the eye-space origin (a local viewer; the fast renderer uses the origin
//! for orthographic cameras too, and so does the truth). A material lights
//! by one of two models (`Material::model`).
//!
//! The basic model (SPEC §5.1):
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
//! specular term at 0.
//!
//! The Cook–Torrance model (SPEC §5.2), with base colour `base` (kd, times
//! a texel and a vertex colour where the caller says so), metallic m,
//! roughness r and the GGX or Beckmann distribution
//! ([`crate::microfacet`]), E_i = f(d_i)·Il_i:
//!
//! ```text
//! I = ke + Ia·[c_diff·(1 − E_s) + E_s] + Σ_i E_i·(N·L_i)·[(1 − F_i)·c_diff/π + F_i·D_i·Vis_i]
//! ```
//!
//! with E_s = f0·A + B, (A, B) the split sum at (N·V, r)
//! ([`crate::split_sum`]: by default the truth's table of the integral)
//! and N·V clamped to [0, 1]. Its two parts, as SPEC §5.2 splits them:
//! ambient+diffuse = the terms with c_diff, Ia·c_diff·(1 − E_s) +
//! c_diff/π·Σ(1 − F)·E·N·L; specular = ke + the terms with f0,
//! Ia·E_s + Σ F·D·Vis·E·N·L.
//!
//! With an environment map (SPEC §5.3, [`crate::environment`]) the
//! uniform Ia becomes a function of direction: the basic model's ambient
//! term is ka·(Ia + k·E(N)/π); Cook–Torrance's Ia·[c_diff·(1 − E_s) + E_s]
//! becomes D·c_diff·(1 − E_s) + S·E_s with D = Ia + k·E(N)/π and S = Ia +
//! k·L_pre(R, r), R = 2(N·V)N − V (N·V not clamped, as the fast
//! renderer's `reflect`), the occlusion map multiplying both.
//!
//! Both: materials are `sanitized` first, as the fast renderer does; a
//! light with N·L ≤ 0 adds nothing. On a shadow receiver, a light hidden
//! from the surface point drops out of the sum, diffuse and specular
//! alike, in either model ([`crate::shadow`]); ambient (with Cook–Torrance,
//! the whole environment term) and emission stay.

use glam::{DMat4, DVec3};
use zline_shading::{Light, Material, Model};

use crate::environment::EnvironmentF64;
use crate::microfacet::MicrofacetF64;
use crate::shadow::{Occluders, TriangleId};
use crate::split_sum::SplitSum;

/// Where shadows are tested, when they are: (occluders, the exact
/// eye-space surface point P, the triangle P lies on).
pub(crate) type ShadowQuery<'o> = Option<(&'o Occluders, DVec3, TriangleId)>;

/// An error in N·H an f32 renderer may make near N·H = 1: a few ulps of 1
/// (the dot product of two vectors normalized in f32).
const F32_NH_ERROR: f64 = 3e-7;

/// A change of the colour (10⁻⁵, 0.0026 of an 8-bit step) beyond which a
/// sharp lobe counts as unresolved in f32 ([`Parts::switch_margin`]).
const UNRESOLVED: f64 = 1e-5;

/// A material's coefficients in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MaterialF64 {
    pub(crate) ke: DVec3,
    pub(crate) ka: DVec3,
    pub(crate) kd: DVec3,
    pub(crate) ks: DVec3,
    pub(crate) ns: f64,
    pub(crate) opacity: f64,
    /// The lighting model; Cook–Torrance's base colour is `kd` (ka, ks and
    /// ns unused).
    pub(crate) model: ModelF64,
}

/// The lighting model of a material, in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ModelF64 {
    /// SPEC §5.1.
    Basic,
    /// SPEC §5.2.
    CookTorrance(MicrofacetF64),
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
            model: match m.model {
                Model::Basic => ModelF64::Basic,
                Model::CookTorrance(microfacet) => ModelF64::CookTorrance(MicrofacetF64::new(microfacet)),
            },
        }
    }
}

/// A light in eye space.
#[derive(Clone, Copy, Debug, PartialEq)]
enum EyeLight {
    /// A point light, or a spot light with its cone.
    Point {
        position: DVec3,
        color: DVec3,
        a: [f64; 3],
        range: f64,
        spot: Option<SpotF64>,
    },
    Directional {
        to_light: DVec3,
        color: DVec3,
    },
}

/// A spot light's unit axis and the cosines of its cone's half-angles.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SpotF64 {
    axis: DVec3,
    cos_inner: f64,
    cos_outer: f64,
}

impl SpotF64 {
    /// The cone's falloff for the unit vector from the light to the
    /// surface (SPEC §5.1: KHR_lights_punctual's squared ramp between the
    /// cosines, its difference kept ≥ 0.001).
    fn factor(&self, from_light: DVec3) -> f64 {
        let t = (self.axis.dot(from_light) - self.cos_outer) / (self.cos_inner - self.cos_outer).max(0.001);
        t.clamp(0.0, 1.0).powi(2)
    }
}

/// What a Cook–Torrance sample reads from its material's occlusion and
/// emissive maps (SPEC §5.2; `zline_scene::SurfaceMaps`): the ambient
/// light Ia is multiplied by `occlusion` before the environment's terms
/// (lights are not), ke by `emission`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SampleMaps {
    /// 1 + strength·(R − 1) of the occlusion texel R; 1 without a map.
    pub(crate) occlusion: f64,
    /// The emissive texel's RGB; 1 without a map.
    pub(crate) emission: DVec3,
}

impl SampleMaps {
    /// No maps: Ia and ke as they are.
    pub(crate) const NONE: SampleMaps = SampleMaps { occlusion: 1.0, emission: DVec3::ONE };
}

/// Ambient light and the lights, in eye space, and where Cook–Torrance's
/// environment term takes its split sum from.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct EyeLights {
    ambient: DVec3,
    lights: Vec<EyeLight>,
    split_sum: SplitSum,
    /// The environment map in eye space (SPEC §5.3), when the scene has one.
    environment: Option<EnvironmentF64>,
}

/// The two parts of a lit colour (SPEC §7 keeps them apart), unclamped: a
/// texel or a vertex colour multiplies the first only.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Parts {
    /// Basic: ka·Ia + Σ f·Il·kd·max(0, N·L). Cook–Torrance: the terms
    /// with c_diff, Ia·c_diff·(1 − E_s) + c_diff/π·Σ(1 − F)·E·N·L.
    pub(crate) ambient_diffuse: DVec3,
    /// Basic: ke + Σ f·Il·ks·max(0, N·H)^ns, the emission and the specular
    /// term. Cook–Torrance: ke and the terms with f0, Ia·E_s + Σ F·D·Vis·E·N·L.
    pub(crate) specular: DVec3,
    /// How close the point is to a place where the model jumps, so that
    /// renderers may disagree near it; +∞ without one. The basic model:
    /// the smallest |N·L| over the lights whose specular term switches on
    /// or off at N·L = 0 (all of them when ks > 0, else none). Cook–Torrance:
    /// the smallest |N·L| over every light, whatever the material — its
    /// terms switch on at N·L = 0; they do so continuously (both tend to 0
    /// as N·L → 0⁺, except GGX's specular at N·V = 0) but with a kink, and
    /// next to a grazing viewer the lobe there can be steep, so every
    /// terminator counts, as conservative as ks > 0 is for the basic model;
    /// with Beckmann also |N·V| when there are lights (its Vis jumps at
    /// N·V = 0; see `MicrofacetF64::switches_at_grazing_view`). And 0 inside the
    /// highlight of a near-mirror (α² < 10⁻⁴, r < 0.1) wherever an error of
    /// 3·10⁻⁷ in N·H (a few f32 ulps) would change its specular term by
    /// more than 10⁻⁵ (to first order): there the 1 − N·H that D hangs on
    /// is a few thousand f32 ulps of 1 at most (at r = 0, α² = 10⁻⁷: one
    /// or two), so a renderer evaluating SPEC's formulas in f32 cannot get
    /// the highlight to a step — for it, the model jumps there.
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
    /// points, directions as vectors), with Cook–Torrance's split sum
    /// from `split_sum`.
    pub(crate) fn new(
        ambient: glam::Vec3,
        lights: &[Light],
        eye_from_world: &DMat4,
        split_sum: SplitSum,
    ) -> EyeLights {
        let lights = lights
            .iter()
            .map(|l| match *l {
                Light::Point { position, color, attenuation: at } => EyeLight::Point {
                    position: eye_from_world.transform_point3(position.as_dvec3()),
                    color: color.as_dvec3(),
                    a: [at.a0, at.a1, at.a2].map(f64::from),
                    range: f64::from(at.range),
                    spot: None,
                },
                Light::Spot { position, direction, color, attenuation: at, cone } => EyeLight::Point {
                    position: eye_from_world.transform_point3(position.as_dvec3()),
                    color: color.as_dvec3(),
                    a: [at.a0, at.a1, at.a2].map(f64::from),
                    range: f64::from(at.range),
                    spot: Some(SpotF64 {
                        axis: eye_from_world.transform_vector3(direction.as_dvec3()).normalize_or_zero(),
                        cos_inner: f64::from(cone.inner).cos(),
                        cos_outer: f64::from(cone.outer).cos(),
                    }),
                },
                Light::Directional { direction, color } => EyeLight::Directional {
                    to_light: -eye_from_world.transform_vector3(direction.as_dvec3()).normalize_or_zero(),
                    color: color.as_dvec3(),
                },
            })
            .collect();
        EyeLights { ambient: ambient.as_dvec3(), lights, split_sum, environment: None }
    }

    /// The same lights with an environment map (SPEC §5.3), prepared for
    /// this eye space: the ambient light becomes Ia + k·(what it gives).
    pub(crate) fn with_environment(self, environment: Option<EnvironmentF64>) -> EyeLights {
        EyeLights { environment, ..self }
    }

    /// The environment, when there is one.
    pub(crate) fn environment(&self) -> Option<&EnvironmentF64> {
        self.environment.as_ref()
    }

    /// The diffuse light D at unit (or zero) `normal`: Ia + k·E(N)/π with
    /// an environment, Ia without (SPEC §5.3).
    fn diffuse_light(&self, normal: DVec3) -> DVec3 {
        match &self.environment {
            Some(e) => self.ambient + e.diffuse(normal),
            None => self.ambient,
        }
    }

    /// The specular light S for the mirror direction `reflected` and GGX
    /// α² = `alpha2`: Ia + k·L_pre(R, r) with an environment, Ia without.
    fn specular_light(&self, reflected: DVec3, alpha2: f64) -> DVec3 {
        match &self.environment {
            Some(e) => self.ambient + e.specular(reflected, alpha2),
            None => self.ambient,
        }
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
    /// move `point` away from. A Cook–Torrance material's base colour is
    /// its kd here.
    pub(crate) fn shade_shadowed(
        &self,
        m: &MaterialF64,
        point: DVec3,
        normal: DVec3,
        shadow: ShadowQuery<'_>,
    ) -> Parts {
        match &m.model {
            ModelF64::Basic => self.shade_basic(m, point, normal, shadow),
            ModelF64::CookTorrance(microfacet) => {
                self.shade_microfacet(m, microfacet, (point, normal), shadow, (m.kd, SampleMaps::NONE))
            }
        }
    }

    /// Each light's unit direction from `point` and its intensity there
    /// (colour times attenuation), with the light; a point light at
    /// `point` itself is left out.
    fn incident(&self, point: DVec3) -> impl Iterator<Item = (&EyeLight, DVec3, DVec3)> + '_ {
        self.lights.iter().filter_map(move |light| match *light {
            EyeLight::Point { position, color, a, range, spot } => {
                let d = position - point;
                let dist = d.length();
                let cone = |l: DVec3| spot.map_or(1.0, |s| s.factor(-l));
                (dist != 0.0).then(|| {
                    let l = d / dist;
                    (light, l, color * (attenuation(a, dist) * window(range, dist) * cone(l)))
                })
            }
            EyeLight::Directional { to_light, color } => Some((light, to_light, color)),
        })
    }

    /// True when `shadow` says the occluders hide `light`.
    fn hidden(light: &EyeLight, shadow: ShadowQuery<'_>) -> bool {
        let Some((occluders, at, on)) = shadow else {
            return false;
        };
        match *light {
            EyeLight::Point { position, .. } => occluders.hides_point(at, on, position),
            EyeLight::Directional { to_light, .. } => occluders.hides_direction(at, on, to_light),
        }
    }

    /// SPEC §5.1.
    fn shade_basic(&self, m: &MaterialF64, point: DVec3, normal: DVec3, shadow: ShadowQuery<'_>) -> Parts {
        let view = (-point).normalize_or_zero();
        let specular_on = m.ks.max_element() > 0.0;
        let (mut diffuse, mut specular) = (DVec3::ZERO, DVec3::ZERO);
        let mut switch_margin = f64::INFINITY;
        for (light, to_light, intensity) in self.incident(point) {
            let n_dot_l = normal.dot(to_light);
            if specular_on {
                switch_margin = switch_margin.min(n_dot_l.abs());
            }
            if n_dot_l <= 0.0 || Self::hidden(light, shadow) {
                continue;
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
            ambient_diffuse: m.ka * self.diffuse_light(normal) + m.kd * diffuse,
            specular: m.ke + m.ks * specular,
            switch_margin,
        }
    }

    /// SPEC §5.2 at eye-space `point` with unit (or zero) `normal`, for a
    /// surface of `m`'s emission and `microfacet`'s parameters with base
    /// colour `base`: with Phong shading kd ⊙ texel ⊙ vertex colour, with
    /// flat and Gouraud shading kd (the texel and the vertex colour then
    /// multiply the returned ambient+diffuse part) — and the sample's
    /// occlusion and emission texels `maps` (with Phong shading; else
    /// [`SampleMaps::NONE`]). Shadows as in [`Self::shade_shadowed`].
    pub(crate) fn shade_microfacet(
        &self,
        m: &MaterialF64,
        microfacet: &MicrofacetF64,
        (point, normal): (DVec3, DVec3),
        shadow: ShadowQuery<'_>,
        (base, maps): (DVec3, SampleMaps),
    ) -> Parts {
        let view = (-point).normalize_or_zero();
        let n_dot_v = normal.dot(view);
        let nv = n_dot_v.clamp(0.0, 1.0);
        let (c_diff, f0) = microfacet.colors(base);
        let (mut diffuse, mut specular) = (DVec3::ZERO, DVec3::ZERO);
        let mut switch_margin = f64::INFINITY;
        for (light, to_light, intensity) in self.incident(point) {
            let n_dot_l = normal.dot(to_light);
            switch_margin = switch_margin.min(n_dot_l.abs());
            if n_dot_l <= 0.0 || Self::hidden(light, shadow) {
                continue;
            }
            let terms = microfacet.light_terms((normal, view, nv), f0, to_light, n_dot_l);
            diffuse += terms.diffuse * intensity;
            let term = terms.specular * intensity;
            specular += term;
            if term.max_element() * terms.steepness * F32_NH_ERROR > UNRESOLVED {
                switch_margin = 0.0;
            }
        }
        if microfacet.switches_at_grazing_view() && !self.lights.is_empty() {
            switch_margin = switch_margin.min(n_dot_v.abs());
        }
        let [a, b] = self.split_sum.eval(microfacet.distribution, nv, microfacet.roughness);
        let e_s = f0 * a + b;
        // SPEC §5.3: D = Ia + k·E(N)/π and S = Ia + k·L_pre(R, r), R =
        // 2(N·V)N − V (N·V unclamped), both times the occlusion.
        let reflected = normal * (2.0 * n_dot_v) - view;
        let diffuse_light = self.diffuse_light(normal) * maps.occlusion;
        let specular_light = self.specular_light(reflected, microfacet.alpha2) * maps.occlusion;
        Parts {
            ambient_diffuse: diffuse_light * c_diff * (DVec3::ONE - e_s)
                + c_diff * diffuse / std::f64::consts::PI,
            specular: m.ke * maps.emission + specular_light * e_s + specular,
            switch_margin,
        }
    }
}

/// f(d) = min(1, 1/(a0 + a1·d + a2·d²)); 1 where the denominator is ≤ 1.
/// KHR_lights_punctual's range window clamp(1 − (d/range)⁴, 0, 1) (SPEC
/// §5.1); 1 for a range that is not a finite number > 0.
fn window(range: f64, d: f64) -> f64 {
    if !(range > 0.0 && range.is_finite()) {
        1.0
    } else {
        (1.0 - (d / range).powi(4)).clamp(0.0, 1.0)
    }
}

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
    use zline_shading::{Attenuation, Distribution, Microfacet};

    #[test]
    fn head_on_point_light_and_attenuation() {
        let m = MaterialF64 {
            ke: DVec3::ZERO,
            ka: DVec3::ZERO,
            kd: DVec3::splat(0.5),
            ks: DVec3::splat(0.25),
            ns: 10.0,
            opacity: 1.0,
            model: ModelF64::Basic,
        };
        let at = Attenuation::new(1.0, 0.5, 0.25);
        let light = Light::Point { position: Vec3::new(0.0, 0.0, -3.0), color: Vec3::ONE, attenuation: at };
        let lights = EyeLights::new(Vec3::ZERO, &[light], &DMat4::IDENTITY, SplitSum::Integral);
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
        let lights = EyeLights::new(Vec3::splat(0.25), &[light], &DMat4::IDENTITY, SplitSum::Integral);
        let p = lights.shade(&m, DVec3::new(0.0, 0.0, -5.0), DVec3::Z);
        assert_eq!((p.ambient_diffuse, p.specular), (DVec3::splat(0.25), DVec3::ZERO));
    }

    #[test]
    fn emission_joins_the_specular_part_even_unlit() {
        let m = MaterialF64 { ke: DVec3::new(0.1, 0.2, 0.3), ..MaterialF64::new(&Material::DEFAULT) };
        let light = Light::Directional { direction: Vec3::Z, color: Vec3::ONE };
        let lights = EyeLights::new(Vec3::ZERO, &[light], &DMat4::IDENTITY, SplitSum::Integral);
        let p = lights.shade(&m, DVec3::new(0.0, 0.0, -5.0), DVec3::Z);
        assert_eq!((p.ambient_diffuse, p.specular), (DVec3::ZERO, m.ke));
    }

    fn cook_torrance(kd: Vec3, metallic: f32, roughness: f32, distribution: Distribution) -> MaterialF64 {
        let microfacet = Microfacet { metallic, roughness, distribution };
        MaterialF64::new(&Material {
            kd,
            ke: Vec3::new(0.01, 0.02, 0.03),
            model: Model::CookTorrance(microfacet),
            ..Material::DEFAULT
        })
    }

    #[test]
    fn cook_torrance_parts_split_as_spec_says() {
        // Head-on (N = L = V = H) under ambient Ia and a point light at
        // distance 2 with f = 1/3: F = f0, D·Vis = 1/(4π α²), and the
        // environment term with E_s = f0·A + B at N·V = 1.
        let m = cook_torrance(Vec3::new(0.8, 0.4, 0.2), 0.5, 0.5, Distribution::Ggx);
        let ModelF64::CookTorrance(microfacet) = m.model else { unreachable!() };
        let at = Attenuation::new(1.0, 0.5, 0.25);
        let light = Light::Point { position: Vec3::new(0.0, 0.0, -3.0), color: Vec3::ONE, attenuation: at };
        let ambient = Vec3::new(0.2, 0.3, 0.4);
        let lights = EyeLights::new(ambient, &[light], &DMat4::IDENTITY, SplitSum::Integral);
        let p = lights.shade(&m, DVec3::new(0.0, 0.0, -5.0), DVec3::Z);
        let (c_diff, f0) = microfacet.colors(m.kd);
        let [a, b] = crate::split_sum::lookup(Distribution::Ggx, 1.0, 0.5);
        let e_s = f0 * a + b;
        let ia = ambient.as_dvec3();
        let e = 1.0 / 3.0;
        let pi = std::f64::consts::PI;
        let want_ad = ia * c_diff * (DVec3::ONE - e_s) + c_diff * (DVec3::ONE - f0) * e / pi;
        let want_sp = m.ke + ia * e_s + f0 * e / (4.0 * pi * 0.0625);
        assert!(
            (p.ambient_diffuse - want_ad).abs().max_element() < 1e-15,
            "{} vs {want_ad}",
            p.ambient_diffuse
        );
        assert!((p.specular - want_sp).abs().max_element() < 1e-15, "{} vs {want_sp}", p.specular);
        assert_eq!(p.switch_margin, 1.0);
        // The base colour is the caller's (kd ⊙ texel per sample): it
        // forms c_diff and f0, so it reaches both parts.
        let base = m.kd * DVec3::new(0.5, 1.0, 0.25);
        let q = lights.shade_microfacet(
            &m,
            &microfacet,
            (DVec3::new(0.0, 0.0, -5.0), DVec3::Z),
            None,
            (base, SampleMaps::NONE),
        );
        let (c_diff, f0) = microfacet.colors(base);
        let e_s = f0 * a + b;
        let want_ad = ia * c_diff * (DVec3::ONE - e_s) + c_diff * (DVec3::ONE - f0) * e / pi;
        let want_sp = m.ke + ia * e_s + f0 * e / (4.0 * pi * 0.0625);
        assert!(
            (q.ambient_diffuse - want_ad).abs().max_element() < 1e-15,
            "{} vs {want_ad}",
            q.ambient_diffuse
        );
        assert!((q.specular - want_sp).abs().max_element() < 1e-15, "{} vs {want_sp}", q.specular);
    }

    #[test]
    fn cook_torrance_switch_margins() {
        // A directional light at 60° from N, the viewer at 80° from N.
        let light = Light::Directional { direction: -Vec3::new(0.75f32.sqrt(), 0.0, 0.5), color: Vec3::ONE };
        let lights = EyeLights::new(Vec3::ZERO, &[light], &DMat4::IDENTITY, SplitSum::Integral);
        let view = DVec3::new(-(80.0f64.to_radians().sin()), 0.0, 80.0f64.to_radians().cos());
        let point = -view * 4.0;
        // Every light counts (N·L = 0.5), Beckmann's N·V (0.17) too.
        let ggx = lights.shade(&cook_torrance(Vec3::ONE, 0.0, 0.5, Distribution::Ggx), point, DVec3::Z);
        assert!((ggx.switch_margin - 0.5).abs() < 1e-7, "{}", ggx.switch_margin);
        let beckmann =
            lights.shade(&cook_torrance(Vec3::ONE, 0.0, 0.5, Distribution::Beckmann), point, DVec3::Z);
        assert!(
            (beckmann.switch_margin - 80.0f64.to_radians().cos()).abs() < 1e-7,
            "{}",
            beckmann.switch_margin
        );
        // Even with ks = 0 (unused by Cook–Torrance), unlike the basic model.
        let basic = MaterialF64 { ks: DVec3::ZERO, ..MaterialF64::new(&Material::DEFAULT) };
        assert_eq!(lights.shade(&basic, point, DVec3::Z).switch_margin, f64::INFINITY);
        let m = MaterialF64 { ks: DVec3::ZERO, ..cook_torrance(Vec3::ONE, 0.0, 0.5, Distribution::Ggx) };
        assert!((lights.shade(&m, point, DVec3::Z).switch_margin - 0.5).abs() < 1e-7);
    }

    #[test]
    fn a_near_mirror_highlight_counts_as_a_switch() {
        // The viewer on the mirror direction of a directional light: H = N.
        let light = Light::Directional { direction: -Vec3::new(0.6, 0.0, 0.8), color: Vec3::ONE };
        let lights = EyeLights::new(Vec3::ZERO, &[light], &DMat4::IDENTITY, SplitSum::Integral);
        let point = -DVec3::new(-0.6, 0.0, 0.8) * 4.0;
        for distribution in [Distribution::Ggx, Distribution::Beckmann] {
            let sharp = lights.shade(&cook_torrance(Vec3::ONE, 1.0, 0.0, distribution), point, DVec3::Z);
            assert_eq!(sharp.switch_margin, 0.0, "{distribution:?}");
            let rough = lights.shade(&cook_torrance(Vec3::ONE, 1.0, 0.5, distribution), point, DVec3::Z);
            assert!((rough.switch_margin - 0.8).abs() < 1e-7, "{distribution:?}: {}", rough.switch_margin);
            // Far from the highlight, the sharp lobe is 0 and resolved.
            let away = lights.shade(
                &cook_torrance(Vec3::ONE, 1.0, 0.0, distribution),
                DVec3::new(0.0, 0.0, -4.0),
                DVec3::Z,
            );
            assert!(away.switch_margin > 0.5, "{distribution:?}: {}", away.switch_margin);
        }
    }
}
