//! The world of the Whitted truth ([`crate::whitted`]) in f64: every
//! object's triangles in world space with their shading attributes and
//! surfaces, numbered object by object in mesh order; what a hit reads
//! from its texture (colour and alpha); and shadow rays.

use glam::{DMat3, DVec2, DVec3, DVec4};
use zline_scene::trace_options::ShadowRays;
use zline_scene::{Scene, TextureMap};
use zline_shading::{Filter, Light, ShadingMode};

use crate::lighting::MaterialF64;
use crate::texture::{self, UvDerivatives};
use crate::whitted_hit::{Ray, Triangles};
use crate::whitted_record::LightPath;

/// Hits of one surface along a shadow ray within this of each other (in
/// the ray's parameter, relative beyond 1) are one crossing (SPEC §12).
pub const SAME_CROSSING: f64 = 1e-5;

/// A point light's shadow segment stops this share of its length short
/// of the light (SPEC §12).
pub const SHADOW_SEGMENT_END: f64 = 1e-4;

/// Hits closer than this times max(1, |p|∞) to a secondary ray's start p
/// are ignored.
const SELF_DISTANCE: f64 = 1e-9;

/// An object's shading, as the tree reads it.
#[derive(Clone, Debug)]
pub(crate) struct Surface {
    /// The material, sanitized.
    pub(crate) material: MaterialF64,
    /// The mirror coefficient kr.
    pub(crate) kr: DVec3,
    /// The index of refraction of its inside.
    pub(crate) ior: f64,
    /// The diffuse map (the scene's filter override applied), when the
    /// mesh has texture coordinates for every vertex.
    pub(crate) texture: Option<TextureMap>,
    /// Flat shading: the face normal.
    pub(crate) flat: bool,
}

/// A triangle's shading attributes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Attributes {
    /// Its object's index (and its surface's).
    pub(crate) object: u32,
    /// Unit vertex normals in world space (zero where the normal matrix
    /// is singular).
    pub(crate) normals: [DVec3; 3],
    /// Texture coordinates (zero without a texture).
    pub(crate) uvs: [DVec2; 3],
}

/// The triangles, their hierarchy and what shades them.
#[derive(Debug)]
pub(crate) struct World {
    /// Corners by triangle index, in a hierarchy.
    pub(crate) triangles: Triangles,
    /// Shading attributes by triangle index.
    pub(crate) attributes: Vec<Attributes>,
    /// One per object.
    pub(crate) surfaces: Vec<Surface>,
}

impl World {
    /// Every object of `scene` in world space: corners by the f64 model
    /// matrix, normals by the inverse transpose of its linear part. An
    /// index out of range reads a NaN corner (never hit).
    pub(crate) fn new(scene: &Scene) -> World {
        let s = &scene.settings;
        let mut corners = Vec::new();
        let mut attributes = Vec::new();
        let mut surfaces = Vec::with_capacity(scene.objects.len());
        for (index, object) in scene.objects.iter().enumerate() {
            let mesh = &object.mesh;
            let m = object.world_from_object.as_dmat4();
            let normal_matrix = DMat3::from_mat4(m).inverse().transpose();
            let textured = mesh.diffuse_map.is_some() && mesh.uvs.len() == mesh.positions.len();
            let material = object.material().sanitized();
            let texture = mesh.diffuse_map.clone().filter(|_| textured).map(|mut map| {
                if let Some(filter) = s.texture_filter {
                    map.sampler.filter = filter;
                }
                map
            });
            surfaces.push(Surface {
                material: MaterialF64::new(&material),
                kr: material.kr.as_dvec3(),
                ior: f64::from(material.ior),
                texture,
                flat: object.shading.unwrap_or(s.shading) == ShadingMode::Flat,
            });
            for tri in &mesh.triangles {
                let at = |i: u32| mesh.positions.get(i as usize).map_or(DVec3::NAN, |p| p.as_dvec3());
                corners.push(tri.map(|i| m.transform_point3(at(i))));
                let normal = |i: u32| {
                    let n = mesh.normals.get(i as usize).map_or(DVec3::ZERO, |n| n.as_dvec3());
                    (normal_matrix * n).normalize_or_zero()
                };
                let uv = |i: u32| {
                    mesh.uvs.get(i as usize).filter(|_| textured).map_or(DVec2::ZERO, |u| u.as_dvec2())
                };
                attributes.push(Attributes {
                    object: index as u32,
                    normals: tri.map(normal),
                    uvs: tri.map(uv),
                });
            }
        }
        World { triangles: Triangles::new(corners), attributes, surfaces }
    }

    /// The share of `light` that reaches `p` (on triangle `on`) and the
    /// path its shadow ray found, with `mode`'s shadow rays.
    pub(crate) fn shadow(&self, p: DVec3, on: u32, light: &Light, mode: ShadowRays) -> (f64, LightPath) {
        let near = self_distance(p);
        let ray = match *light {
            Light::Point { position, .. } | Light::Spot { position, .. } => {
                let dir = position.as_dvec3() - p;
                Ray {
                    origin: p,
                    dir,
                    t_min: near / dir.length(),
                    t_max: 1.0 - SHADOW_SEGMENT_END,
                    skip: Some(on),
                }
            }
            Light::Directional { direction, .. } => Ray {
                origin: p,
                dir: -direction.as_dvec3().normalize_or_zero(),
                t_min: near,
                t_max: f64::INFINITY,
                skip: Some(on),
            },
        };
        let mut hits = self.triangles.all_hits(&ray);
        // A mask's cut-out texels are no surface.
        hits.retain(|h| self.alpha(h.triangle, self.texel(h.triangle, h.b)) != Alpha::CutOut);
        if hits.is_empty() {
            return (1.0, LightPath::Clear);
        }
        if mode == ShadowRays::Opaque {
            return (0.0, LightPath::Blocked);
        }
        hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.triangle.cmp(&b.triangle)));
        let (mut passed, mut crossings) = (1.0, 0u32);
        let mut current: Option<(f64, u32)> = None;
        for hit in hits {
            let object = self.attributes[hit.triangle as usize].object;
            let same = current.is_some_and(|(t, o)| o == object && hit.t - t <= SAME_CROSSING * t.max(1.0));
            if same {
                continue;
            }
            current = Some((hit.t, object));
            let kt = 1.0 - self.opacity(hit.triangle, self.texel(hit.triangle, hit.b));
            if kt <= 0.0 {
                return (0.0, LightPath::Blocked);
            }
            passed *= kt;
            crossings += 1;
        }
        (passed, LightPath::Filtered(crossings))
    }

    /// The point at barycentrics `b` of `triangle`.
    pub(crate) fn point(&self, triangle: u32, [b0, b1, b2]: [f64; 3]) -> DVec3 {
        let c = &self.triangles.corners[triangle as usize];
        c[0] * b0 + c[1] * b1 + c[2] * b2
    }

    /// The diffuse texture's RGBA at barycentrics `b` of `triangle`, read
    /// at level 0; `None` without a texture.
    pub(crate) fn texel(&self, triangle: u32, [b0, b1, b2]: [f64; 3]) -> Option<DVec4> {
        let attributes = &self.attributes[triangle as usize];
        let map = self.surfaces[attributes.object as usize].texture.as_ref()?;
        let [u0, u1, u2] = attributes.uvs;
        let uv = u0 * b0 + u1 * b1 + u2 * b2;
        Some(texture::sample(&map.texture, &map.sampler, uv, &UvDerivatives::default()))
    }

    /// The level-0 texel a nearest-filtered texture reads at barycentrics
    /// `b` of `triangle` (unwrapped indices), for the mask.
    pub(crate) fn texel_index(&self, triangle: u32, [b0, b1, b2]: [f64; 3]) -> Option<[i64; 2]> {
        let attributes = &self.attributes[triangle as usize];
        let map = self.surfaces[attributes.object as usize].texture.as_ref()?;
        if map.sampler.filter != Filter::Nearest {
            return None;
        }
        let [u0, u1, u2] = attributes.uvs;
        let uv = u0 * b0 + u1 * b1 + u2 * b2;
        let (w, h) = map.texture.level_size(0);
        let index = |c: f64, size: u32| {
            let u = (c * f64::from(size)).floor();
            if u.is_finite() {
                u as i64
            } else {
                0
            }
        };
        Some([index(uv.x, w), index(uv.y, h)])
    }

    /// What the diffuse map's alpha (in `texel`) does on `triangle`: a
    /// mask's cutoff takes precedence over blending, as in the rasterizer.
    pub(crate) fn alpha(&self, triangle: u32, texel: Option<DVec4>) -> Alpha {
        let object = self.attributes[triangle as usize].object;
        let (Some(map), Some(texel)) = (self.surfaces[object as usize].texture.as_ref(), texel) else {
            return Alpha::Opaque;
        };
        match map.alpha_cutoff {
            Some(cutoff) if texel.w < f64::from(cutoff) => Alpha::CutOut,
            Some(_) => Alpha::Opaque,
            None if map.alpha_blend => Alpha::Blend(texel.w),
            None => Alpha::Opaque,
        }
    }

    /// The opacity d on `triangle` where the texture reads `texel`: the
    /// material's, times a blending map's alpha; 0 where a mask cuts out.
    pub(crate) fn opacity(&self, triangle: u32, texel: Option<DVec4>) -> f64 {
        let d = self.surfaces[self.attributes[triangle as usize].object as usize].material.opacity;
        match self.alpha(triangle, texel) {
            Alpha::Opaque => d,
            Alpha::Blend(a) => d * a,
            Alpha::CutOut => 0.0,
        }
    }
}

/// A diffuse map's alpha at a hit (SPEC §12).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Alpha {
    /// No alpha, or a mask's alpha at or above its cutoff.
    Opaque,
    /// A blending map's alpha: it multiplies the opacity.
    Blend(f64),
    /// A mask's alpha below its cutoff: no surface.
    CutOut,
}

/// The distance from a secondary ray's start `p` within which its hits
/// are ignored: [`SELF_DISTANCE`]·max(1, |p|∞).
pub(crate) fn self_distance(p: DVec3) -> f64 {
    SELF_DISTANCE * p.abs().max_element().max(1.0)
}
