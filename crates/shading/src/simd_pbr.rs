//! SPEC §5.2, the Cook–Torrance model, for eight samples: the lanes of
//! `PreparedLights::microfacet_parts` and `pbr::MicrofacetSums`, bit for
//! bit (the same operations in the same order per lane).

use std::ops::{Add, Mul};

use zline_simd::lanes::{f32x8, Baseline, Level};

use crate::pbr::{split_sum, Distribution, Microfacet, DIELECTRIC_F0, MIN_ALPHA2};
use crate::prepared::{PreparedLights, PreparedMaterial};
use crate::vec3x8::{all_lanes, Vec3x8};

/// The texels of a Cook–Torrance material's maps at eight samples (each
/// `None` where the material has no such map): what SPEC §5.2 multiplies
/// by them.
#[derive(Clone, Copy, Debug)]
pub struct MapTexels<L: Level = Baseline> {
    /// glTF's metallic–roughness texture: (B, G), multiplying the metallic
    /// and roughness factors.
    pub metallic_roughness: Option<(f32x8<L>, f32x8<L>)>,
    /// The occlusion 1 + strength·(R − 1), multiplying the environment's
    /// light (the ambient term), not the lights'.
    pub occlusion: Option<f32x8<L>>,
    /// The emissive texture's RGB, multiplying ke.
    pub emission: Option<Vec3x8<L>>,
}

impl<L: Level> MapTexels<L> {
    /// No maps.
    pub const NONE: MapTexels<L> = MapTexels { metallic_roughness: None, occlusion: None, emission: None };
}

/// A Cook–Torrance material's parameters per lane: its factors, times
/// the metallic–roughness texture's B and G where it has one.
#[derive(Clone, Copy)]
pub(crate) struct MicrofacetX8<L: Level> {
    metallic: f32x8<L>,
    roughness: f32x8<L>,
    /// max(roughness⁴, [`MIN_ALPHA2`]), as `Microfacet::alpha2`.
    alpha2: f32x8<L>,
    distribution: Distribution,
}

impl<L: Level> MicrofacetX8<L> {
    #[inline(always)]
    pub(crate) fn new((m, alpha2): (Microfacet, f32), maps: Option<(f32x8<L>, f32x8<L>)>) -> MicrofacetX8<L> {
        let (metallic, roughness) = (f32x8::splat(m.metallic), f32x8::splat(m.roughness));
        let distribution = m.distribution;
        match maps {
            None => MicrofacetX8 { metallic, roughness, alpha2: f32x8::splat(alpha2), distribution },
            Some((b, g)) => {
                let (metallic, roughness) = (metallic * b, roughness * g);
                let alpha = roughness * roughness;
                let alpha2 = (alpha * alpha).max(f32x8::splat(MIN_ALPHA2));
                MicrofacetX8 { metallic, roughness, alpha2, distribution }
            }
        }
    }
}

/// Running sums of the Cook–Torrance terms over the lights, per lane
/// (see `pbr::MicrofacetSums`).
#[derive(Default)]
struct MicrofacetSumsX8<L: Level = Baseline> {
    diffuse: Vec3x8<L>,
    specular: Vec3x8<L>,
}

impl<L: Level> MicrofacetSumsX8<L> {
    #[inline(always)]
    fn add(
        &mut self,
        (distribution, alpha2, f0): (Distribution, f32x8<L>, Vec3x8<L>),
        (normal, view, nv): (Vec3x8<L>, Vec3x8<L>, f32x8<L>),
        to_light: Vec3x8<L>,
        intensity: Vec3x8<L>,
        active: f32x8<L>,
    ) {
        let nl = normal.dot(to_light);
        // The scalar path skips a light when N·L ≤ 0 (so NaN stays lit).
        let lit = active & (nl.cmp_le(f32x8::ZERO) ^ all_lanes());
        if lit.none() {
            return;
        }
        let (zero, one) = (f32x8::ZERO, f32x8::ONE);
        let nl = nl.min(one);
        let half = to_light.add(view).normalize_or_zero();
        let nh = normal.dot(half).clamp(zero, one);
        let vh = view.dot(half).clamp(zero, one);
        let y = one - vh;
        let y2 = y * y;
        let s = y2 * y2 * y;
        let ones = Vec3x8 { x: one, y: one, z: one };
        let fresnel = f0.add(ones.sub(f0).scale(s));
        let e = intensity.scale(nl);
        self.diffuse = self.diffuse.add(ones.sub(fresnel).mul(e).keep(lit));
        let dv = d_vis_x8(distribution, alpha2, (nl, nv, nh, vh));
        self.specular = self.specular.add(fresnel.mul(e.scale(dv)).keep(lit));
    }
}

/// `pbr::d_vis` per lane, bit for bit (D times Vis, each as
/// `pbr::distribution_d` and `pbr::visibility` compute it).
#[inline(always)]
fn d_vis_x8<L: Level>(
    distribution: Distribution,
    a2: f32x8<L>,
    (nl, nv, nh, vh): (f32x8<L>, f32x8<L>, f32x8<L>, f32x8<L>),
) -> f32x8<L> {
    let pi = std::f32::consts::PI;
    let zero = f32x8::ZERO;
    match distribution {
        Distribution::Ggx => {
            let one_minus = f32x8::ONE - a2;
            let f = nh * nh * (a2 - f32x8::ONE) + f32x8::ONE;
            let d = a2 / (f32x8::splat(pi) * f * f);
            let gv = nl * (nv * nv * one_minus + a2).sqrt();
            let gl = nv * (nl * nl * one_minus + a2).sqrt();
            let g = gv + gl;
            let vis = g.cmp_gt(zero).blend(f32x8::splat(0.5) / g, zero);
            d * vis
        }
        Distribution::Beckmann => {
            let c2 = nh * nh;
            let ok = c2.cmp_gt(zero) & nv.cmp_gt(zero) & vh.cmp_gt(zero);
            let tan2 = (f32x8::ONE - c2) / c2;
            let exponent = -tan2 / a2;
            let e = f32x8::from(exponent.to_array().map(
                #[inline(always)]
                |v| v.exp(),
            ));
            let d = e / (f32x8::splat(pi) * a2 * c2 * c2);
            let two = f32x8::splat(2.0);
            let g = (two * nh * nv / vh).min(two * nh * nl / vh).min(f32x8::ONE);
            ok.blend(d * (g / (f32x8::splat(4.0) * nl * nv)), zero)
        }
    }
}

impl PreparedLights {
    /// SPEC §5.2 for eight samples of base colour `base`: the lanes of
    /// `PreparedLights::microfacet_parts`, bit for bit.
    #[inline(always)]
    pub(crate) fn microfacet_parts_x8<L: Level>(
        &self,
        m: &PreparedMaterial,
        (microfacet, maps): (MicrofacetX8<L>, MapTexels<L>),
        (point, normal, base): (Vec3x8<L>, Vec3x8<L>, Vec3x8<L>),
        visible: impl Fn(u32) -> f32x8<L>,
        share: impl Fn(u32) -> Option<f32x8<L>>,
    ) -> (Vec3x8<L>, Vec3x8<L>) {
        let view = Vec3x8::default().sub(point).normalize_or_zero();
        let nv = normal.dot(view).clamp(f32x8::ZERO, f32x8::ONE);
        let metallic = microfacet.metallic;
        let dielectric = Vec3x8::splat(glam::Vec3::splat(DIELECTRIC_F0));
        let f0 = dielectric.add(base.sub(dielectric).scale(metallic));
        let c_diff = base.scale(f32x8::ONE - metallic);
        let (distribution, alpha2) = (microfacet.distribution, microfacet.alpha2);
        let sum = self.fold_lights_x8(
            point,
            (visible, share),
            MicrofacetSumsX8::default(),
            #[inline(always)]
            |mut sum: MicrofacetSumsX8<L>, to_light, intensity, active| {
                sum.add((distribution, alpha2, f0), (normal, view, nv), to_light, intensity, active);
                sum
            },
        );
        // The environment's split sum, looked up per lane.
        let (mut a, mut b) = ([0.0f32; 8], [0.0f32; 8]);
        let roughness = microfacet.roughness.as_array_ref();
        for (k, &v) in nv.as_array_ref().iter().enumerate() {
            [a[k], b[k]] = split_sum(distribution, v, roughness[k]);
        }
        let (a, b) = (f32x8::from(a), f32x8::from(b));
        let e_s = f0.scale(a).add(Vec3x8 { x: b, y: b, z: b });
        let (mut diffuse_light, mut specular_light) = match self.environment() {
            None => (Vec3x8::splat(self.ambient()), Vec3x8::splat(self.ambient())),
            Some(e) => {
                let (d, s) = crate::environment::environment_lanes(
                    e,
                    (normal.to_lanes(), view.to_lanes()),
                    microfacet.roughness.to_array(),
                );
                (Vec3x8::from_arrays(d), Vec3x8::from_arrays(s))
            }
        };
        if let Some(occlusion) = maps.occlusion {
            diffuse_light = diffuse_light.scale(occlusion);
            specular_light = specular_light.scale(occlusion);
        }
        let mut ke = Vec3x8::splat(m.material.ke);
        if let Some(emission) = maps.emission {
            ke = ke.mul(emission);
        }
        let one = Vec3x8::splat(glam::Vec3::ONE);
        let ambient_diffuse = diffuse_light
            .mul(c_diff.mul(one.sub(e_s)))
            .add(c_diff.mul(sum.diffuse.scale(f32x8::splat(1.0 / std::f32::consts::PI))));
        let specular = ke.add(specular_light.mul(e_s)).add(sum.specular);
        (ambient_diffuse, specular)
    }
}
