//! Bump and normal maps in f64 (`zline_scene::NormalMap` states the
//! formulas): the tangent frame interpolated with the sample's attribute
//! weights, the map read at level 0 through `Texture::texel` (nearest, or
//! bilinear for bilinear and trilinear samplers), the height gradient by
//! central differences one texel apart, and
//! n′ = normalize(m.x·T + m.y·B + m.z·normalize(N)).
//!
//! The fast renderer's choices, followed here: maps only with Phong
//! shading and without vertex colours; tangents to eye space by
//! eye_from_object's linear part with the handedness flipped under a
//! mirroring transform; B = w·(N × T) formed at each vertex; two-sided
//! lighting turns N, T and B around together.

use glam::{DMat3, DVec2, DVec3, DVec4};
use zline_scene::{Mesh, NormalEncoding, NormalMap};
use zline_shading::ShadingMode;

use crate::camera::ObjectTransforms;
use crate::texture::{self, UvDerivatives};

/// An object's map with its eye-space tangent frame per vertex.
#[derive(Debug)]
pub(crate) struct FrameNormalMap {
    map: NormalMap,
    /// T (eye space) and the handedness w, per vertex.
    tangents: Vec<DVec4>,
}

impl FrameNormalMap {
    /// The map of `mesh` as drawn with `mode`: `None` when it is not
    /// drawn (another mode, vertex colours, no texture coordinates or
    /// tangents, a non-finite scale).
    pub(crate) fn new(mesh: &Mesh, mode: ShadingMode, t: &ObjectTransforms) -> Option<FrameNormalMap> {
        let map = mesh.normal_map.as_ref()?;
        let drawn = mode == ShadingMode::Phong
            && mesh.colors.is_empty()
            && !mesh.uvs.is_empty()
            && mesh.tangents.len() == mesh.positions.len()
            && map.scale.is_finite();
        if !drawn {
            return None;
        }
        let linear = DMat3::from_mat4(t.eye_from_object);
        let mirror = if linear.determinant() < 0.0 { -1.0 } else { 1.0 };
        let tangents =
            mesh.tangents.iter().map(|v| (linear * v.truncate().as_dvec3()).extend(f64::from(v.w) * mirror));
        Some(FrameNormalMap { map: map.clone(), tangents: tangents.collect() })
    }

    /// The perturbed normal at texture coordinates `uv`: `normals[k]` the
    /// unit vertex normals (already turned for a back face, `side` = −1),
    /// `weights` the attribute weights of `vertices`.
    pub(crate) fn normal(
        &self,
        (vertices, weights): ([usize; 3], &[f64; 3]),
        normals: [DVec3; 3],
        side: f64,
        uv: DVec2,
    ) -> DVec3 {
        let frame = |k: usize| {
            let t = self.tangents.get(vertices[k]).copied().unwrap_or_default();
            // normals[k] is side·N: B = side·w·(N × T) = w·(normals[k] × T).
            let tangent = t.truncate() * side;
            (tangent, normals[k].cross(t.truncate()) * t.w)
        };
        let blend = |f: &dyn Fn(usize) -> DVec3| (0..3).map(|k| f(k) * weights[k]).sum::<DVec3>();
        let n = blend(&|k| normals[k]).normalize_or_zero();
        let tangent = blend(&|k| frame(k).0);
        let bitangent = blend(&|k| frame(k).1);
        let m = self.tangent_normal(uv);
        (tangent * m.x + bitangent * m.y + n * m.z).normalize_or_zero()
    }

    /// m at `uv` (see the module documentation).
    fn tangent_normal(&self, uv: DVec2) -> DVec3 {
        let (texture, sampler) = (&self.map.map.texture, &self.map.map.sampler);
        let read = |uv: DVec2| texture::sample(texture, sampler, uv, &UvDerivatives::default());
        let k = f64::from(self.map.scale);
        match self.map.encoding {
            NormalEncoding::Height => {
                let (w, h) = (f64::from(texture.width()), f64::from(texture.height()));
                let (ds, dt) = (DVec2::new(1.0 / w, 0.0), DVec2::new(0.0, 1.0 / h));
                let dh_ds = (read(uv + ds).x - read(uv - ds).x) * w / 2.0;
                let dh_dt = (read(uv + dt).x - read(uv - dt).x) * h / 2.0;
                DVec3::new(-k * dh_ds, -k * dh_dt, 1.0)
            }
            NormalEncoding::Tangent => {
                let c = read(uv).truncate() * 2.0 - DVec3::ONE;
                DVec3::new(c.x * k, c.y * k, c.z)
            }
        }
    }
}
