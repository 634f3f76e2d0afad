//! Shading one fragment (SPEC §5–8): the prim's attributes at the sample,
//! the texture, the shading mode, the lighting model and fog, all in f64.
//!
//! Interpolation. The sample's screen weights λ over the prim (its corners
//! in sample space) become weights over the original triangle's vertices,
//! through the corners' clip weights β: perspective-correct weights
//! μ_i = (λ_i/w_i) / Σ_j (λ_j/w_j), or screen-linear weights λ_i
//! (`Interpolation::ScreenLinear`: linear over each clipped piece, as the
//! fast renderer's planes are). The exact surface point — for fog and the
//! depth-independent eye position — always uses μ.
//!
//! Shading modes (SPEC §6), per-object override first:
//! - Flat: the lighting model at the original triangle's eye-space centroid
//!   with its face normal (p1 − p0) × (p2 − p0), normalized.
//! - Gouraud: the lighting model at the three original vertices, colours
//!   interpolated: untextured, the clamped vertex colours
//!   (`GouraudClamp::PerVertex`, the default) or the unclamped ones,
//!   clamped per sample (`GouraudClamp::PerSample`); textured, whatever the
//!   clamp setting, the ambient+diffuse and specular parts separately (SPEC
//!   §7). A clipped piece's new vertices carry interpolated colours, not
//!   relit ones.
//! - Phong: eye position and normal interpolated, the normal renormalized
//!   (a zero normal stays zero) and perturbed by a bump or normal map when
//!   the mesh has one ([`crate::normal_map`]), the lighting model per
//!   sample. A shadow
//!   receiver is always shaded so, and a light the occluders hide from the
//!   exact surface point is left out ([`crate::shadow`]).
//!
//! Vertex colours (`Mesh::colors`), like a texel, multiply the
//! ambient+diffuse part (ka and kd), never the emission or the specular
//! term: flat shading by the mean of the original triangle's three corner
//! colours (the colour at its centroid), Gouraud shading by each vertex's
//! colour before that vertex's part is clamped or interpolated, Phong
//! shading by the colour interpolated to the sample with the same weights
//! as every other attribute. A mesh whose colour list is shorter than its
//! positions gives the missing vertices white.
//!
//! With a texture, c = clamp(texel ⊙ (ambient+diffuse) + specular); the
//! texture coordinates' derivatives for the level of detail are exact
//! (quotient rule for perspective-correct s = S/Q) in sample space.
//!
//! Cook–Torrance materials (SPEC §5.2) follow the same rules with flat and
//! Gouraud shading: the model is evaluated with the base colour kd, and
//! the texel and the vertex colour multiply its ambient+diffuse part (the
//! terms with c_diff), not its specular part (ke and the terms with f0).
//! Per sample (Phong shading, shadow receivers) they multiply the base
//! colour instead, before c_diff and f0 are formed: base = kd ⊙ texel ⊙
//! vertex colour, c = clamp(ambient+diffuse + specular) of that surface.

use glam::{DVec2, DVec3, DVec4};
use zline_scene::{GouraudClamp, TextureMap};
use zline_shading::ShadingMode;

use crate::coverage::SampleTriangle;
use crate::fog::apply_fog;
use crate::frame::Shader;
use crate::frame::{face_cross, Frame, ObjectFrame, Prim};
use crate::lighting::{ModelF64, Parts, SampleMaps};
use crate::microfacet::MicrofacetF64;
use crate::sample::SampleShading;
use crate::shadow::TriangleId;
use crate::texture::{self, UvDerivatives};

/// A shaded fragment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Shaded {
    /// Lit, clamped and fogged colour.
    pub(crate) color: DVec3,
    /// The texel's alpha (1 without a texture).
    pub(crate) alpha: f64,
    /// See [`Parts::switch_margin`].
    pub(crate) switch_margin: f64,
}

/// A prim's attributes at one sample.
struct Surface<'f> {
    prim: &'f Prim,
    object: &'f ObjectFrame,
    /// The original triangle's vertex indices.
    vertices: [usize; 3],
    /// Attribute weights of the original vertices.
    attr: [f64; 3],
    /// Perspective-correct weights: the exact surface point.
    exact: [f64; 3],
    /// Derivatives of `attr` along x and y (sample space).
    d_attr: [DVec2; 3],
}

impl Frame<'_> {
    /// The prim's attributes at sample position `p`; `None` for a prim that
    /// has no area (never drawn).
    fn surface(&self, id: u32, p: DVec2) -> Option<Surface<'_>> {
        let prim = &self.prims[id as usize];
        let object = &self.objects[prim.object as usize];
        let geometry = self.geometry(prim);
        let tri = SampleTriangle::new(geometry.corners)?;
        let lambda = tri.weights(&tri.values(p));
        let inv_w = geometry.corners.map(|c| c.inv_w);
        let q: f64 = (0..3).map(|i| lambda[i] * inv_w[i]).sum();
        let mu = [0, 1, 2].map(|i| lambda[i] * inv_w[i] / q);
        let grads = tri.weight_gradients();
        let d_sub = if self.perspective {
            let dq: DVec2 = (0..3).map(|i| grads[i] * inv_w[i]).sum();
            [0, 1, 2].map(|i| (grads[i] * inv_w[i] - dq * mu[i]) / q)
        } else {
            grads
        };
        let sub = if self.perspective { mu } else { lambda };
        let beta = geometry.beta;
        let to_original = |w: [f64; 3]| -> [f64; 3] {
            let v: DVec3 = (0..3).map(|i| beta[i] * w[i]).sum();
            v.to_array()
        };
        let d_attr = [0, 1, 2].map(|k| (0..3).map(|i| d_sub[i] * beta[i][k]).sum());
        let tri_indices = object.mesh.triangles[prim.triangle as usize];
        Some(Surface {
            prim,
            object,
            vertices: tri_indices.map(|i| i as usize),
            attr: to_original(sub),
            exact: to_original(mu),
            d_attr,
        })
    }

    /// The texel alpha of prim `id` at `p` (1 without a texture): what an
    /// alpha cutoff tests before the depth buffer is written.
    pub(crate) fn alpha(&self, id: u32, p: DVec2) -> f64 {
        self.surface(id, p).and_then(|s| self.texel(&s)).map_or(1.0, |t| t.w)
    }

    /// Shades prim `id` at sample position `p`.
    pub(crate) fn shade(&self, id: u32, p: DVec2) -> Shaded {
        let Some(s) = self.surface(id, p) else {
            return Shaded { color: DVec3::ZERO, alpha: 1.0, switch_margin: f64::INFINITY };
        };
        let texel = self.texel(&s);
        let (color, switch_margin) = self.lit(&s, texel);
        let color = match &self.scene.fog {
            Some(fog) => {
                let eye = blend3(&s.exact, |k| self.vertex(&s, k).eye);
                apply_fog(fog, color, eye)
            }
            None => color,
        };
        Shaded { color, alpha: texel.map_or(1.0, |t| t.w), switch_margin }
    }

    fn vertex<'s>(&self, s: &Surface<'s>, k: usize) -> &'s crate::camera::Vertex {
        &s.object.vertices[s.vertices[k]]
    }

    /// The filtered texel, when the object is textured.
    fn texel(&self, s: &Surface<'_>) -> Option<DVec4> {
        s.object.texture.as_ref().map(|map| read(s, map))
    }

    /// A Cook–Torrance material's parameters at a per-sample (Phong)
    /// sample, its maps read (SPEC §5.2): metallic and roughness times the
    /// metallic–roughness texel's B and G, the occlusion 1 + strength·(R −
    /// 1) and the emissive texel.
    fn mapped(&self, s: &Surface<'_>, microfacet: &MicrofacetF64) -> (MicrofacetF64, SampleMaps) {
        let maps = &s.object.surface_maps;
        let microfacet = match &maps.metallic_roughness {
            Some(map) => {
                let t = read(s, map);
                microfacet.mapped(t.z, t.y)
            }
            None => *microfacet,
        };
        let occlusion = maps
            .occlusion
            .as_ref()
            .map_or(1.0, |(map, strength)| 1.0 + f64::from(*strength) * (read(s, map).x - 1.0));
        let emission = maps.emission.as_ref().map_or(DVec3::ONE, |map| read(s, map).truncate());
        (microfacet, SampleMaps { occlusion, emission })
    }

    /// The caller's shading function at a Phong-shaded sample at `point`
    /// with unit `normal` and base colour `base`, clamped to [0, 1].
    fn custom(
        &self,
        shader: Shader<'_>,
        s: &Surface<'_>,
        (point, normal): (DVec3, DVec3),
        base: DVec3,
    ) -> DVec3 {
        let m = &s.object.material;
        let (metallic_roughness, maps) = match &m.model {
            ModelF64::CookTorrance(microfacet) => {
                let (microfacet, maps) = self.mapped(s, microfacet);
                (Some((microfacet.metallic, microfacet.roughness)), maps)
            }
            ModelF64::Basic => (None, SampleMaps::NONE),
        };
        let input = SampleShading {
            point,
            normal,
            view: (-point).normalize_or_zero(),
            base,
            metallic_roughness,
            occlusion: maps.occlusion,
            emission: m.ke * maps.emission,
        };
        (shader.0)(&input).clamp(DVec3::ZERO, DVec3::ONE)
    }

    /// The clamped lit colour (SPEC §5–7) and the lighting's switch margin.
    fn lit(&self, s: &Surface<'_>, texel: Option<DVec4>) -> (DVec3, f64) {
        let (m, lights) = (&s.object.material, &self.lights);
        let side = if s.prim.back { -1.0 } else { 1.0 };
        let normal = |k: usize| self.vertex(s, k).normal * side;
        let eye = |k: usize| self.vertex(s, k).eye;
        let colors = &s.object.mesh.colors;
        let tint = (!colors.is_empty())
            .then(|| [0, 1, 2].map(|k| colors.get(s.vertices[k]).map_or(DVec3::ONE, |c| c.as_dvec3())));
        let tinted = |mut parts: Parts, color: Option<DVec3>| {
            if let Some(c) = color {
                parts.ambient_diffuse *= c;
            }
            parts
        };
        let parts = match s.object.mode {
            ShadingMode::Flat => {
                let v = [0, 1, 2].map(|k| self.vertex(s, k));
                let n = face_cross(&v).normalize_or_zero() * side;
                let mean = tint.map(|c| (c[0] + c[1] + c[2]) / 3.0);
                tinted(lights.shade(m, (eye(0) + eye(1) + eye(2)) / 3.0, n), mean)
            }
            ShadingMode::Gouraud => {
                let at_vertices =
                    [0, 1, 2].map(|k| tinted(lights.shade(m, eye(k), normal(k)), tint.map(|c| c[k])));
                if texel.is_none() {
                    let color = match self.scene.settings.gouraud_clamp {
                        GouraudClamp::PerVertex => blend3(&s.attr, |k| at_vertices[k].color()),
                        GouraudClamp::PerSample => Parts::blend(&at_vertices, &s.attr).color(),
                    };
                    let margin = at_vertices.iter().map(|p| p.switch_margin).fold(f64::INFINITY, f64::min);
                    return (color, margin);
                }
                Parts::blend(&at_vertices, &s.attr)
            }
            ShadingMode::Phong => {
                let n = match &s.object.normal_map {
                    None => blend3(&s.attr, normal).normalize_or_zero(),
                    Some(map) => {
                        let uv = |k: usize| {
                            s.object.mesh.uvs.get(s.vertices[k]).map_or(DVec2::ZERO, |t| t.as_dvec2())
                        };
                        let normals = [0, 1, 2].map(normal);
                        map.normal((s.vertices, &s.attr), normals, side, blend3(&s.attr, uv))
                    }
                };
                let color = tint.map(|c| blend3(&s.attr, |k| c[k]));
                let shadow = match &self.occluders {
                    Some(o) if s.object.receives_shadows => {
                        let on = TriangleId { object: s.prim.object, triangle: s.prim.triangle };
                        Some((o, blend3(&s.exact, eye), on))
                    }
                    _ => None,
                };
                // The texel and the vertex colour multiply the base colour
                // before c_diff and f0 are formed (SPEC §5.2).
                let mut base = m.kd;
                if let Some(t) = texel {
                    base *= t.truncate();
                }
                if let Some(c) = color {
                    base *= c;
                }
                let point = blend3(&s.attr, eye);
                if let Some(shader) = self.shader {
                    return (self.custom(shader, s, (point, n), base), f64::INFINITY);
                }
                if let ModelF64::CookTorrance(microfacet) = &m.model {
                    let (microfacet, maps) = self.mapped(s, microfacet);
                    let parts = lights.shade_microfacet(m, &microfacet, (point, n), shadow, (base, maps));
                    return (parts.color(), parts.switch_margin);
                }
                tinted(lights.shade_shadowed(m, blend3(&s.attr, eye), n, shadow), color)
            }
        };
        let color = match texel {
            Some(t) => (t.truncate() * parts.ambient_diffuse + parts.specular).clamp(DVec3::ZERO, DVec3::ONE),
            None => parts.color(),
        };
        (color, parts.switch_margin)
    }
}

/// The filtered value of `map` at the sample: the mesh's texture
/// coordinates interpolated, their exact derivatives for the level of
/// detail.
fn read(s: &Surface<'_>, map: &TextureMap) -> DVec4 {
    let uv = |k: usize| s.object.mesh.uvs.get(s.vertices[k]).map_or(DVec2::ZERO, |t| t.as_dvec2());
    let at = blend3(&s.attr, uv);
    let d = UvDerivatives {
        dx: (0..3).map(|k| uv(k) * s.d_attr[k].x).sum(),
        dy: (0..3).map(|k| uv(k) * s.d_attr[k].y).sum(),
    };
    texture::sample(&map.texture, &map.sampler, at, &d)
}

/// Σ_k w_k · f(k) over the three vertices.
fn blend3<T: std::ops::Mul<f64, Output = T> + std::iter::Sum>(w: &[f64; 3], f: impl Fn(usize) -> T) -> T {
    (0..3).map(|k| f(k) * w[k]).sum()
}
