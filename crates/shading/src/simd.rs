//! The lighting model for eight samples at once (SoA, `wide::f32x8`).
//!
//! Per-sample Phong shading is a chain of square roots and divisions whose
//! latency a single sample cannot hide; eight independent lanes keep the
//! units busy (on x86-64-v3 one AVX instruction per step). Each lane performs
//! exactly the operations of [`PreparedLights::shade_parts`] in the same
//! order — IEEE square root and division are correctly rounded in vector
//! form too — so a lane's result does not depend on its neighbours or on
//! which lane it occupies. A unit test checks lane results against the
//! scalar path bit for bit.

use std::ops::{Add, Mul};

use zline_simd::lanes::{f32x8, i32x8, Baseline, Level};

use crate::prepared::{pow_by_squaring, Point, PreparedLights, PreparedMaterial, Shininess};
use crate::simd_pbr::{MapTexels, MicrofacetX8};
use crate::vec3x8::all_lanes;
pub use crate::vec3x8::Vec3x8;

impl Shininess {
    /// [`Shininess::pow`] per lane.
    #[inline(always)]
    fn pow_x8<L: Level>(self, x: f32x8<L>) -> f32x8<L> {
        match self {
            Shininess::Whole(n) => pow_by_squaring(x, f32x8::ONE, n),
            Shininess::Real(ns) => f32x8::from(x.to_array().map(
                #[inline(always)]
                |v| v.powf(ns),
            )),
        }
    }
}

impl PreparedLights {
    /// [`PreparedLights::shade`] for eight samples: clamped colours at
    /// `point` with unit `normal`, the eye at the origin.
    #[inline(always)]
    pub fn shade_x8<L: Level>(&self, m: &PreparedMaterial, point: Vec3x8<L>, normal: Vec3x8<L>) -> Vec3x8<L> {
        let (ambient_diffuse, specular) = self.shade_parts_x8(m, point, normal);
        ambient_diffuse.add(specular).clamp_to(self.ceiling())
    }

    /// [`PreparedLights::shade_parts`] for eight samples: the unclamped
    /// ambient+diffuse and specular parts, for texturing (SPEC §7).
    #[inline(always)]
    pub fn shade_parts_x8<L: Level>(
        &self,
        m: &PreparedMaterial,
        point: Vec3x8<L>,
        normal: Vec3x8<L>,
    ) -> (Vec3x8<L>, Vec3x8<L>) {
        self.parts_x8(
            m,
            point,
            normal,
            #[inline(always)]
            |_| all_lanes(),
            #[inline(always)]
            |_| None,
        )
    }

    /// The kernels' one lighting entry: the unclamped colour of eight
    /// samples, where `modulate` multiplies the material's colour (a
    /// texel, a vertex colour; the identity for none): for the basic
    /// model `modulate(ambient+diffuse) + specular` (SPEC §7), for
    /// Cook–Torrance the model with the base colour `modulate(kd)` per
    /// lane (SPEC §5.2). Light k (its index in the scene's list) reaches
    /// each lane with the share `share(k, point, normal)` of its intensity
    /// when `share` is given (shadow maps); else, when `mask` is given
    /// (planar shadows), it contributes nothing to a lane whose mask has
    /// bit `m.shadow_bits + k` set (bits past 31, and every bit for a
    /// material without `shadow_bits`, leave it lit). A Cook–Torrance
    /// material reads its maps' texels from `maps` (see [`MapTexels`]).
    /// Bit for bit [`PreparedLights::shade_modulated`] with
    /// the same hidden lights,
    /// with one copy of the light loop per model: the choices are
    /// branches, the same way for a whole primitive, and fold away where
    /// the caller's arguments are constants.
    #[inline(always)]
    pub fn shade_x8_with<L: Level>(
        &self,
        m: &PreparedMaterial,
        (point, normal): (Vec3x8<L>, Vec3x8<L>),
        mask: Option<i32x8<L>>,
        share: Option<impl Fn(u32, Vec3x8<L>, Vec3x8<L>) -> f32x8<L>>,
        modulate: impl Fn(Vec3x8<L>) -> Vec3x8<L>,
        maps: MapTexels<L>,
    ) -> Vec3x8<L> {
        let (visible, shared) = hidden_lights(m, (point, normal), mask, &share);
        match m.microfacet {
            None => {
                let (ambient_diffuse, specular) =
                    self.basic_parts_x8(m, (point, normal, true), visible, shared);
                modulate(ambient_diffuse) + specular
            }
            Some(microfacet) => {
                let base = modulate(Vec3x8::splat(m.material.kd));
                let lanes = MicrofacetX8::new(microfacet, maps.metallic_roughness);
                let (ambient_diffuse, specular) =
                    self.microfacet_parts_x8(m, (lanes, maps), (point, normal, base), visible, shared);
                ambient_diffuse + specular
            }
        }
    }

    /// [`Self::shade_x8_with`] for the basic model only (a material known
    /// not to be Cook–Torrance): the kernels' copy for the common case,
    /// without the microfacet model's code; `environment` false promises
    /// there is no environment map (see [`Self::uniform_ambient`]), so a
    /// copy compiled with it false has no environment code either.
    #[inline(always)]
    pub fn shade_x8_basic<L: Level>(
        &self,
        m: &PreparedMaterial,
        (point, normal): (Vec3x8<L>, Vec3x8<L>),
        (mask, environment): (Option<i32x8<L>>, bool),
        share: Option<impl Fn(u32, Vec3x8<L>, Vec3x8<L>) -> f32x8<L>>,
        modulate: impl Fn(Vec3x8<L>) -> Vec3x8<L>,
    ) -> Vec3x8<L> {
        let (visible, shared) = hidden_lights(m, (point, normal), mask, &share);
        let (ambient_diffuse, specular) =
            self.basic_parts_x8(m, (point, normal, environment), visible, shared);
        modulate(ambient_diffuse) + specular
    }

    /// Folds `add(sums, to_light, intensity, active)` over the lights at
    /// eight samples at `point`, in the order of the scalar path
    /// (directional lights, then point lights), light k counting in the
    /// lanes `visible(k)` sets, with its intensity scaled by `share(k)`
    /// when that is given. The sums travel by value, so they stay in
    /// registers (a closure holding them by `&mut` kept them in memory:
    /// 3 % more instructions on the Phong sphere).
    #[inline(always)]
    pub(crate) fn fold_lights_x8<L: Level, T>(
        &self,
        point: Vec3x8<L>,
        (visible, share): (impl Fn(u32) -> f32x8<L>, impl Fn(u32) -> Option<f32x8<L>>),
        mut sums: T,
        add: impl Fn(T, Vec3x8<L>, Vec3x8<L>, f32x8<L>) -> T,
    ) -> T {
        for (to_light, color, k) in self.directional_lights() {
            // The direction and the lanes first: after the share's branch,
            // the compiler loaded the direction before it and broadcast it
            // after (three more instructions a light).
            let (to_light, active) = (Vec3x8::splat(to_light), visible(k));
            let mut intensity = Vec3x8::splat(color);
            if let Some(f) = share(k) {
                intensity = intensity.scale(f);
            }
            sums = add(sums, to_light, intensity, active);
        }
        for &Point { position, color, attenuation, ref shape, index: k } in self.point_lights() {
            let v = Vec3x8::splat(position).sub(point);
            let dist = v.dot(v).sqrt();
            let present = dist.cmp_gt(f32x8::ZERO) & visible(k);
            let to_light = v.div(dist);
            let mut intensity = Vec3x8::splat(color);
            if let Some(a) = attenuation {
                let denom = f32x8::splat(a.a0) + dist * (f32x8::splat(a.a1) + dist * f32x8::splat(a.a2));
                let f = denom.cmp_gt(f32x8::ONE).blend(f32x8::ONE / denom, f32x8::ONE);
                intensity = intensity.scale(f);
            }
            if let Some(shape) = shape {
                // Shape::factor's operations, in its order.
                let x = dist * f32x8::splat(shape.inv_range);
                let x2 = x * x;
                let window = (f32x8::ONE - x2 * x2).clamp(f32x8::ZERO, f32x8::ONE);
                let along = to_light.dot(Vec3x8::splat(shape.axis)) * f32x8::splat(shape.scale);
                let c = (f32x8::splat(shape.offset) - along).clamp(f32x8::ZERO, f32x8::ONE);
                intensity = intensity.scale(window * (c * c));
            }
            if let Some(f) = share(k) {
                intensity = intensity.scale(f);
            }
            sums = add(sums, to_light, intensity, present);
        }
        sums
    }

    /// The parts for `m`: its model's sums over the lights, a
    /// Cook–Torrance material with its kd as the base colour.
    #[inline(always)]
    fn parts_x8<L: Level>(
        &self,
        m: &PreparedMaterial,
        point: Vec3x8<L>,
        normal: Vec3x8<L>,
        visible: impl Fn(u32) -> f32x8<L>,
        share: impl Fn(u32) -> Option<f32x8<L>>,
    ) -> (Vec3x8<L>, Vec3x8<L>) {
        match m.microfacet {
            None => self.basic_parts_x8(m, (point, normal, true), visible, share),
            Some(microfacet) => {
                let base = Vec3x8::splat(m.material.kd);
                let lanes = MicrofacetX8::new(microfacet, None);
                self.microfacet_parts_x8(m, (lanes, MapTexels::NONE), (point, normal, base), visible, share)
            }
        }
    }

    /// The basic model's sums over the lights, light k counting in the
    /// lanes `visible(k)` sets, with its intensity scaled by `share(k)`
    /// when that is given.
    #[inline(always)]
    fn basic_parts_x8<L: Level>(
        &self,
        m: &PreparedMaterial,
        (point, normal, environment): (Vec3x8<L>, Vec3x8<L>, bool),
        visible: impl Fn(u32) -> f32x8<L>,
        share: impl Fn(u32) -> Option<f32x8<L>>,
    ) -> (Vec3x8<L>, Vec3x8<L>) {
        let view = Vec3x8::default().sub(point).normalize_or_zero();
        let sum = self.fold_lights_x8(
            point,
            (visible, share),
            SumsX8::default(),
            #[inline(always)]
            |mut sum: SumsX8<L>, to_light, intensity, active| {
                sum.add(m, normal, view, to_light, intensity, active);
                sum
            },
        );
        let mat = &m.material;
        // `environment` false says there is none (the kernels' common copy
        // knows it where it is compiled).
        let ambient = match self.environment().filter(|_| environment) {
            None => Vec3x8::splat(mat.ka * self.ambient()),
            Some(e) => {
                let [x, y, z] = crate::environment::ambient_lanes(e, mat.ka, normal.to_lanes());
                Vec3x8::from_arrays([x, y, z])
            }
        };
        let ambient_diffuse = ambient.add(Vec3x8::splat(mat.kd).mul(sum.diffuse));
        let specular = Vec3x8::splat(mat.ke).add(Vec3x8::splat(mat.ks).mul(sum.specular));
        (ambient_diffuse, specular)
    }
}

/// The two ways a light is hidden from eight samples at (`point`,
/// `normal`), as closures over the light's index k: the lanes where it
/// counts (the planar `mask`'s bit `m.shadow_bits + k` clear, when there is
/// a mask and no `share`), and its share from the shadow maps (`share`,
/// when given).
#[inline(always)]
#[allow(clippy::type_complexity, reason = "two closures, named by what they return")]
fn hidden_lights<'s, L: Level, F: Fn(u32, Vec3x8<L>, Vec3x8<L>) -> f32x8<L>>(
    m: &PreparedMaterial,
    (point, normal): (Vec3x8<L>, Vec3x8<L>),
    mask: Option<i32x8<L>>,
    share: &'s Option<F>,
) -> (impl Fn(u32) -> f32x8<L> + 's, impl Fn(u32) -> Option<f32x8<L>> + 's) {
    let first = m.shadow_bits.unwrap_or(u32::MAX);
    let visible = move |k: u32| match (share.is_none(), mask) {
        (true, Some(mask)) => match first.checked_add(k).filter(
            #[inline(always)]
            |&b| b < 32,
        ) {
            Some(b) => {
                let bit = i32x8::splat(1 << b);
                bytemuck::cast::<i32x8<L>, f32x8<L>>((mask & bit).cmp_eq(i32x8::ZERO))
            }
            None => all_lanes(),
        },
        _ => all_lanes(),
    };
    let shared = zline_simd::inlined(
        #[inline(always)]
        #[allow(
            clippy::manual_map,
            reason = "`Option::map` may stay out of line, and the shadow-map lookup with it"
        )]
        move |k| match share {
            Some(f) => Some(f(k, point, normal)),
            None => None,
        },
    );
    (zline_simd::inlined(visible), shared)
}

/// Running sums over the lights, per lane (see `prepared::Sums`).
#[derive(Default)]
struct SumsX8<L: Level = Baseline> {
    diffuse: Vec3x8<L>,
    specular: Vec3x8<L>,
}

impl<L: Level> SumsX8<L> {
    #[inline(always)]
    fn add(
        &mut self,
        m: &PreparedMaterial,
        normal: Vec3x8<L>,
        view: Vec3x8<L>,
        to_light: Vec3x8<L>,
        intensity: Vec3x8<L>,
        active: f32x8<L>,
    ) {
        let n_dot_l = normal.dot(to_light);
        // The scalar path skips a light when N·L ≤ 0 (so NaN stays lit).
        let lit = active & (n_dot_l.cmp_le(f32x8::ZERO) ^ all_lanes());
        if lit.none() {
            return;
        }
        self.diffuse = self.diffuse.add(intensity.scale(n_dot_l).keep(lit));
        if m.specular {
            let n_dot_h = normal.dot(to_light.add(view).normalize_or_zero());
            let shiny = lit & n_dot_h.cmp_gt(f32x8::splat(m.specular_threshold));
            if shiny.any() {
                let power = m.shininess.pow_x8(shiny.blend(n_dot_h, f32x8::ONE));
                self.specular = self.specular.add(intensity.scale(power).keep(shiny));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::{Mat4, Vec3};

    use super::*;
    use crate::light::{Attenuation, Light};
    use crate::material::Material;
    use crate::model::LightingModel;

    /// No environment map, and the procedural sky turned 30°.
    fn environments() -> [Option<crate::environment::Environment>; 2] {
        use crate::environment::{Environment, EnvironmentLight, Panorama};
        let light = std::sync::Arc::new(EnvironmentLight::new(Panorama::sky(64, 32)));
        let mut sky = Environment::new(light);
        (sky.intensity, sky.rotation_degrees) = (0.7, 30.0);
        [None, Some(sky)]
    }

    #[test]
    fn every_lane_matches_the_scalar_path_bit_for_bit() {
        for environment in environments() {
            every_lane_matches_with(environment);
        }
    }

    /// A spot light with a range whose cone's edge and range cross the
    /// test points: lanes fall inside the cone, within its falloff and
    /// outside it, within and past the range.
    fn spot_light() -> Light {
        Light::Spot {
            position: Vec3::new(0.0, 1.5, -1.0),
            direction: Vec3::new(0.1, -1.0, -0.6),
            color: Vec3::new(0.7, 0.9, 0.4),
            attenuation: Attenuation::new(1.0, 0.0, 0.2).with_range(3.0),
            cone: crate::light::Cone { inner: 0.15, outer: 0.4 },
        }
    }

    fn every_lane_matches_with(environment: Option<crate::environment::Environment>) {
        let model = LightingModel {
            ambient: Vec3::new(0.1, 0.15, 0.2),
            lights: vec![
                Light::Point {
                    position: Vec3::new(1.0, 2.0, 0.5),
                    color: Vec3::new(1.0, 0.8, 0.6),
                    attenuation: Attenuation::new(1.0, 0.3, 0.1),
                },
                Light::Point {
                    position: Vec3::new(-2.0, 0.0, -1.0),
                    color: Vec3::ONE,
                    attenuation: Attenuation::NONE,
                },
                Light::Directional { direction: Vec3::new(0.2, -1.0, -0.5), color: Vec3::new(0.3, 0.3, 0.5) },
                spot_light(),
            ],
            environment,
        };
        let lights = PreparedLights::new(&model, &Mat4::from_rotation_x(0.4));
        for ns in [1.0, 20.0, 64.0, 7.5] {
            let plastic = Material::plastic(Vec3::new(0.7, 0.4, 0.2), 0.6, ns);
            let m = PreparedMaterial::new(Material { ke: Vec3::new(0.05, 0.1, 0.3), ..plastic });
            let mut points = [Vec3::ZERO; 8];
            let mut normals = [Vec3::ZERO; 8];
            for k in 0..8 {
                let t = k as f32 * 0.37 + ns;
                points[k] = Vec3::new(t.sin(), (1.3 * t).cos(), -2.0 - 0.3 * t.cos());
                normals[k] = Vec3::new((2.1 * t).cos(), 0.5 * t.sin(), 1.0).normalize();
            }
            normals[7] = Vec3::ZERO; // a degenerate normal
            points[6] = Vec3::new(1.0, 2.0, 0.5); // on a point light
            let gather = |v: &[Vec3; 8]| Vec3x8::<Baseline> {
                x: f32x8::from(v.map(|p| p.x)),
                y: f32x8::from(v.map(|p| p.y)),
                z: f32x8::from(v.map(|p| p.z)),
            };
            let got = lights.shade_x8(&m, gather(&points), gather(&normals));
            for k in 0..8 {
                let want = lights.shade(&m, points[k], normals[k], Vec3::ZERO);
                let lane = got.lane(k);
                assert_eq!(
                    lane.to_array().map(f32::to_bits),
                    want.to_array().map(f32::to_bits),
                    "ns {ns} lane {k}: {lane} vs {want}"
                );
            }
        }
    }

    #[test]
    fn cook_torrance_lanes_match_the_scalar_path_bit_for_bit() {
        for environment in environments() {
            cook_torrance_lanes_match_with(environment);
        }
    }

    fn cook_torrance_lanes_match_with(environment: Option<crate::environment::Environment>) {
        use crate::material::Model;
        use crate::pbr::{Distribution, Microfacet};
        use crate::prepared::Surface;
        let model = LightingModel {
            ambient: Vec3::new(0.2, 0.25, 0.3),
            lights: vec![
                Light::Point {
                    position: Vec3::new(1.0, 2.0, 0.5),
                    color: Vec3::new(1.0, 0.8, 0.6),
                    attenuation: Attenuation::new(1.0, 0.3, 0.1),
                },
                Light::Directional { direction: Vec3::new(0.2, -1.0, -0.5), color: Vec3::new(0.9, 0.9, 1.5) },
                spot_light(),
            ],
            environment,
        };
        let lights = PreparedLights::new(&model, &Mat4::from_rotation_x(0.4));
        for distribution in [Distribution::Ggx, Distribution::Beckmann] {
            for (metallic, roughness) in [(0.0, 0.0), (0.0, 0.3), (1.0, 0.6), (0.5, 1.0), (0.98, 0.05)] {
                let microfacet = Microfacet { metallic, roughness, distribution };
                let material = Material {
                    ke: Vec3::new(0.05, 0.0, 0.1),
                    kd: Vec3::new(0.9, 0.6, 0.2),
                    model: Model::CookTorrance(microfacet),
                    ..Material::default()
                };
                let m = PreparedMaterial::new(material);
                let mut points = [Vec3::ZERO; 8];
                let mut normals = [Vec3::ZERO; 8];
                let mut tints = [Vec3::ZERO; 8];
                for k in 0..8 {
                    let t = k as f32 * 0.41 + roughness * 3.0 + metallic;
                    points[k] = Vec3::new(t.sin(), (1.3 * t).cos(), -2.0 - 0.3 * t.cos());
                    normals[k] = Vec3::new((2.1 * t).cos(), 0.5 * t.sin(), 1.0).normalize();
                    tints[k] = Vec3::new(0.5 + 0.5 * t.sin(), 0.8, (0.3 * t).cos().abs());
                }
                normals[7] = Vec3::ZERO; // a degenerate normal
                normals[5] = -normals[5]; // facing away from the viewer
                let gather = |v: &[Vec3; 8]| Vec3x8::<Baseline> {
                    x: f32x8::from(v.map(|p| p.x)),
                    y: f32x8::from(v.map(|p| p.y)),
                    z: f32x8::from(v.map(|p| p.z)),
                };
                let tint = gather(&tints);
                let unshared = None::<fn(u32, Vec3x8, Vec3x8) -> f32x8>;
                let (b, g) = (
                    f32x8::from([1.0, 0.5, 0.0, 0.25, 1.0, 0.9, 0.3, 0.7]),
                    f32x8::from([1.0, 0.1, 0.6, 0.0, 0.8, 1.0, 0.3, 0.5]),
                );
                let occlusion = f32x8::from([1.0, 0.0, 0.5, 0.25, 0.9, 0.3, 1.0, 0.6]);
                let maps = MapTexels {
                    metallic_roughness: Some((b, g)),
                    occlusion: Some(occlusion),
                    emission: Some(tint),
                };
                let got = lights.shade_x8_with(
                    &m,
                    (gather(&points), gather(&normals)),
                    None,
                    unshared,
                    |c| tint * c,
                    maps,
                );
                let plain = lights.shade_x8(&m, gather(&points), gather(&normals));
                for k in 0..8 {
                    let texels = Surface {
                        metallic_roughness: Some((b.as_array_ref()[k], g.as_array_ref()[k])),
                        occlusion: Some(occlusion.as_array_ref()[k]),
                        emission: Some(tints[k]),
                    };
                    let want = lights.shade_modulated(
                        &m,
                        (points[k], normals[k], Vec3::ZERO),
                        |c| tints[k] * c,
                        texels,
                    );
                    let label = format!("{distribution:?} m {metallic} r {roughness} lane {k}");
                    assert_eq!(
                        got.lane(k).to_array().map(f32::to_bits),
                        want.to_array().map(f32::to_bits),
                        "{label}"
                    );
                    let want = lights.shade(&m, points[k], normals[k], Vec3::ZERO);
                    assert_eq!(
                        plain.lane(k).to_array().map(f32::to_bits),
                        want.to_array().map(f32::to_bits),
                        "{label}"
                    );
                }
            }
        }
    }

    /// Light k is hidden from a lane exactly where the planar mask has bit
    /// `shadow_bits + k` set (no bit past 31: visible), and only when no
    /// shadow-map share is given.
    #[test]
    fn planar_mask_bits_hide_the_lights_they_name() {
        let lanes: [i32; 8] = [0, -1, 1, i32::MIN, 0x5555_5555, 0x2AAA_AAAA, 1 << 30, 0x7FFF_FFFF];
        let mask = i32x8::<Baseline>::from(lanes);
        let none: Option<fn(u32, Vec3x8, Vec3x8) -> f32x8> = None;
        let share: Option<fn(u32, Vec3x8, Vec3x8) -> f32x8> = Some(|_, _, _| f32x8::ONE);
        let at = (Vec3x8::default(), Vec3x8::default());
        for first in [None, Some(0), Some(1), Some(5), Some(30), Some(31), Some(32), Some(u32::MAX - 2)] {
            let mut m = PreparedMaterial::new(Material::default());
            m.shadow_bits = first;
            let (visible, _) = hidden_lights(&m, at, Some(mask), &none);
            let (with_share, _) = hidden_lights(&m, at, Some(mask), &share);
            let (without_mask, _) = hidden_lights(&m, at, None, &none);
            for k in 0..40u32 {
                let got = visible(k).to_array().map(|v| v.to_bits() != 0);
                let want = lanes.map(|bits| {
                    let bit = first.and_then(|f| f.checked_add(k)).filter(|&b| b < 32);
                    bit.is_none_or(|b| bits & (1 << b) == 0)
                });
                assert_eq!(got, want, "first {first:?} light {k}");
                assert!(with_share(k).all() && without_mask(k).all(), "first {first:?} light {k}");
            }
        }
    }
}
