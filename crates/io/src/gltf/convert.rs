//! glTF values → zline's model: samplers, materials, cameras, mirrored
//! meshes, names (see the parent module for the mappings' reasons).

use glam::Vec3;
use gltf::texture::{MagFilter, MinFilter, WrappingMode};
use zline_shading::{Distribution, Filter, Material, Microfacet, Model, Sampler, Wrap};

use zline_scene::{Camera, Mesh, Object, Projection};

/// Largest ns the metallic–roughness mapping yields (see the parent
/// module's doc).
pub const MAX_GLTF_SHININESS: f32 = 1024.0;

/// The far plane of a camera without zfar lies this factor beyond the
/// farthest corner of the scene's bounding box.
const FITTED_FAR_MARGIN: f32 = 1.05;

/// The far plane of an infinite perspective camera: beyond the farthest
/// corner of the objects' world bounding box, and beyond the near plane.
pub(super) fn fit_far_plane(camera: &mut Camera, objects: &[Object]) {
    let Projection::Perspective { near, far, .. } = &mut camera.projection else { return };
    let corners = objects.iter().flat_map(|o| {
        let (min, max) = o.mesh.bounds();
        (0..8).map(move |i| {
            let corner = Vec3::select(glam::BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0), max, min);
            o.world_from_object.transform_point3(corner)
        })
    });
    let farthest = corners.map(|c| c.distance(camera.eye)).fold(0.0f32, f32::max);
    *far = (farthest * FITTED_FAR_MARGIN).max(*near * 2.0);
}

pub(super) fn projection_is_valid(projection: &Projection) -> bool {
    let ok = |x: f32| x.is_finite() && x > 0.0;
    match *projection {
        Projection::Perspective { fovy_degrees, near, far } => {
            ok(fovy_degrees) && fovy_degrees < 180.0 && ok(near) && far.is_finite() && far > near
        }
        Projection::Orthographic { height, near, far } => {
            ok(height) && near.is_finite() && near >= 0.0 && far.is_finite() && far > near
        }
        Projection::Frustum { left, right, bottom, top, near, far } => {
            let sides = [left, right, bottom, top].iter().all(|x| x.is_finite());
            sides && left < right && bottom < top && ok(near) && far.is_finite() && far > near
        }
    }
}

/// The sampler mapping of the module doc, and whether a MIRRORED_REPEAT
/// was replaced by REPEAT.
pub(super) fn sampler_from_gltf(sampler: &gltf::texture::Sampler) -> (Sampler, bool) {
    let filter = match (sampler.min_filter(), sampler.mag_filter()) {
        (Some(MinFilter::Nearest | MinFilter::NearestMipmapNearest), _) => Filter::Nearest,
        (Some(MinFilter::Linear), _) => Filter::Bilinear,
        (Some(_), _) => Filter::Trilinear,
        (None, Some(MagFilter::Nearest)) => Filter::Nearest,
        (None, _) => Filter::Trilinear,
    };
    let wrap = |mode: WrappingMode| match mode {
        WrappingMode::Repeat | WrappingMode::MirroredRepeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::ClampToEdge,
    };
    let mirrored = [sampler.wrap_s(), sampler.wrap_t()].contains(&WrappingMode::MirroredRepeat);
    (Sampler { filter, wrap_s: wrap(sampler.wrap_s()), wrap_t: wrap(sampler.wrap_t()) }, mirrored)
}

/// The metallic–roughness mapping of the module doc.
pub(super) fn material_from_gltf(material: &gltf::Material) -> Material {
    let pbr = material.pbr_metallic_roughness();
    let [r, g, b, a] = pbr.base_color_factor();
    let base = Vec3::new(r, g, b);
    let metallic = pbr.metallic_factor().clamp(0.0, 1.0);
    let roughness = pbr.roughness_factor().clamp(0.0, 1.0);
    let ks = Vec3::splat(0.04).lerp(base, metallic) * (1.0 - roughness);
    let ns = (2.0 / roughness.powi(4) - 2.0).clamp(1.0, MAX_GLTF_SHININESS);
    let alpha = if material.alpha_mode() == gltf::material::AlphaMode::Blend { a } else { 1.0 };
    let transmission = material.transmission().map_or(0.0, |t| t.transmission_factor().clamp(0.0, 1.0));
    let opacity = alpha * (1.0 - transmission);
    // KHR_materials_ior's default; `sanitized` replaces one that is not a
    // finite number > 0 (the extension allows 0, meaning infinity) by 1.
    let ior = material.ior().unwrap_or(1.5);
    let ke = Vec3::from(material.emissive_factor()) * material.emissive_strength().unwrap_or(1.0);
    let model = Model::CookTorrance(Microfacet { metallic, roughness, distribution: Distribution::Ggx });
    // The ray tracer's mirror coefficient: a metal reflects its colour,
    // the more the smoother (the factors only, not the maps).
    let kr = base * metallic * (1.0 - roughness).powi(2);
    Material { ke, ka: base, kd: base, ks, ns, opacity, model, kr, ior }.sanitized()
}

/// The same mesh with every triangle's winding reversed.
pub(super) fn reversed(mut mesh: Mesh) -> Mesh {
    for t in &mut mesh.triangles {
        t.swap(1, 2);
    }
    mesh
}

pub(super) fn primitive_name(mesh: &gltf::Mesh, primitive: &gltf::Primitive) -> String {
    let base = mesh.name().map_or_else(|| format!("mesh {}", mesh.index()), str::to_owned);
    if mesh.primitives().len() > 1 {
        format!("{base}/{}", primitive.index())
    } else {
        base
    }
}

pub(super) fn material_name(material: &gltf::Material) -> String {
    match (material.name(), material.index()) {
        (Some(name), _) => name.to_owned(),
        (None, Some(i)) => format!("material {i}"),
        (None, None) => "default".to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A document with only the given JSON members (and `asset`).
    fn document(members: &str) -> gltf::Document {
        let json = format!(r#"{{"asset": {{"version": "2.0"}}, {members}}}"#);
        gltf::Gltf::from_slice(json.as_bytes()).unwrap().document
    }

    #[test]
    fn metallic_roughness_maps_to_ks_and_ns() {
        let doc = document(
            r#""materials": [
                {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 0.4], "metallicFactor": 1, "roughnessFactor": 0.5},
                 "alphaMode": "BLEND"},
                {"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0}, "alphaMode": "MASK"},
                {}
            ]"#,
        );
        let m: Vec<Material> = doc.materials().map(|m| material_from_gltf(&m)).collect();
        assert_eq!((m[0].kd, m[0].ka), (Vec3::new(0.5, 0.25, 1.0), Vec3::new(0.5, 0.25, 1.0)));
        assert_eq!(m[0].ks, Vec3::new(0.25, 0.125, 0.5), "metal: its own colour, halved by roughness 0.5");
        assert_eq!((m[0].ns, m[0].opacity), (30.0, 0.4), "2/0.5⁴ − 2 = 30; BLEND keeps alpha");
        assert_eq!(m[0].kr, Vec3::new(0.125, 0.0625, 0.25), "metal: its colour times (1 − 0.5)²");
        assert_eq!(m[1].ks, Vec3::splat(0.04), "smooth dielectric");
        assert_eq!(m[1].kr, Vec3::ZERO, "no mirror: not metallic");
        assert_eq!((m[1].ns, m[1].opacity), (MAX_GLTF_SHININESS, 1.0), "MASK draws opaque");
        // The glTF default material: white, metallic 1, roughness 1.
        assert_eq!((m[2].kd, m[2].ks, m[2].ns, m[2].kr), (Vec3::ONE, Vec3::ZERO, 1.0, Vec3::ZERO));
    }

    #[test]
    fn samplers_map_to_the_nearest_filter_and_wrap() {
        let doc = document(
            r#""samplers": [
                {"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 10497},
                {"minFilter": 9729},
                {"minFilter": 9987},
                {"minFilter": 9986},
                {"minFilter": 9985},
                {"minFilter": 9984, "wrapS": 33648},
                {"magFilter": 9728},
                {}
            ]"#,
        );
        let mapped: Vec<(Sampler, bool)> = doc.samplers().map(|s| sampler_from_gltf(&s)).collect();
        let filters: Vec<Filter> = mapped.iter().map(|(s, _)| s.filter).collect();
        use Filter::*;
        assert_eq!(
            filters,
            [Nearest, Bilinear, Trilinear, Trilinear, Trilinear, Nearest, Nearest, Trilinear]
        );
        assert_eq!((mapped[0].0.wrap_s, mapped[0].0.wrap_t), (Wrap::ClampToEdge, Wrap::Repeat));
        assert_eq!(
            mapped[5],
            (Sampler { filter: Nearest, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat }, true)
        );
        assert!(mapped.iter().filter(|m| m.1).count() == 1);
    }
}
