//! The classic Whitted scene (Whitted 1980): a red and yellow checkerboard
//! floor, a mirror sphere behind and a glass sphere in front, under one
//! point light and a sky-blue background. It is made for the ray tracer
//! (`zline demo --scene whitted --renderer raytrace`): the mirror shows the
//! floor and the glass sphere, the glass sphere bends the floor behind it
//! upside down and reflects the light. The rasterizer draws the same
//! scene with the glass blended and the mirror as a plain sphere.

use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3};
use zline_scene::{plane, uv_sphere, Camera, Mesh, Object, Projection, RenderSettings, Scene, TextureMap};
use zline_shading::{Filter, Light, Material, Sampler, ShadingMode, Texture};

/// The glass sphere's index of refraction.
pub const WHITTED_GLASS_IOR: f32 = 1.5;

/// The Whitted scene (see the module doc).
pub fn whitted_scene() -> Scene {
    let floor = Material { ks: Vec3::ZERO, ..Material::plastic(Vec3::ONE, 0.0, 1.0) };
    let mirror =
        Material { kr: Vec3::splat(0.8), ..Material::plastic(Vec3::new(0.12, 0.12, 0.14), 0.6, 120.0) };
    let glass = Material {
        opacity: 0.1,
        ior: WHITTED_GLASS_IOR,
        kr: Vec3::splat(0.08),
        ..Material::plastic(Vec3::new(0.9, 0.95, 1.0), 0.8, 200.0)
    };
    let sphere = Arc::new(uv_sphere(48, 96, 1.0));
    let ball = |centre: Vec3, radius: f32, material: Material| Object {
        mesh: Arc::clone(&sphere),
        world_from_object: Mat4::from_translation(centre) * Mat4::from_scale(Vec3::splat(radius)),
        material: Some(material),
        shading: Some(ShadingMode::Phong),
        cull_back_faces: false,
    };
    let objects = vec![
        Object {
            mesh: Arc::new(checkered(plane(40.0, 8))),
            world_from_object: Mat4::IDENTITY,
            material: Some(floor),
            shading: Some(ShadingMode::Flat),
            cull_back_faces: false,
        },
        ball(Vec3::new(-1.3, 1.4, -2.6), 1.4, mirror),
        ball(Vec3::new(0.9, 1.1, 0.2), 1.1, glass),
    ];
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: Camera {
            eye: Vec3::new(0.6, 2.2, 7.0),
            target: Vec3::new(-0.2, 1.0, -1.0),
            up: Vec3::Y,
            projection: Projection::Perspective { fovy_degrees: 42.0, near: 0.5, far: 60.0 },
        },
        background: Vec3::new(0.35, 0.55, 0.85),
        ambient: Vec3::splat(0.25),
        lights: vec![Light::Point {
            position: Vec3::new(4.0, 9.0, 6.0),
            color: Vec3::splat(0.95),
            attenuation: Default::default(),
        }],
        objects,
        settings: RenderSettings {
            width: 640,
            height: 480,
            shading: ShadingMode::Phong,
            ..RenderSettings::default()
        },
        fog: None,
    }
}

/// The floor with texture coordinates (one unit per checker cell) and a
/// 2 × 2-texel red and yellow checkerboard read with the nearest texel,
/// repeating.
fn checkered(floor: Mesh) -> Mesh {
    let uvs = floor.positions.iter().map(|p| Vec2::new(p.x / 2.0, -p.z / 2.0)).collect();
    let (red, yellow) = ([235, 30, 25, 255], [250, 225, 40, 255]);
    let rgba: Vec<u8> = [red, yellow, yellow, red].concat();
    let texture = Texture::from_rgba8(2, 2, &rgba).expect("a 2 × 2 texture of 16 bytes is valid");
    let floor = floor.with_uvs(uvs).expect("one finite coordinate per vertex");
    floor.with_diffuse_map(TextureMap {
        texture: Arc::new(texture),
        sampler: Sampler { filter: Filter::Nearest, ..Sampler::default() },
        alpha_blend: false,
        alpha_cutoff: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mirror_a_glass_sphere_and_a_checkered_floor_in_view() {
        let scene = whitted_scene();
        let m: Vec<Material> = scene.objects.iter().map(|o| o.material()).collect();
        assert!(scene.objects[0].mesh.diffuse_map.is_some());
        assert!(m[1].kr.min_element() > 0.5 && m[1].opacity == 1.0, "a mirror");
        assert!(m[2].opacity < 0.5 && m[2].ior > 1.0, "a glass");
        let aspect = scene.settings.width as f32 / scene.settings.height as f32;
        let clip_from_world = scene.camera.clip_from_eye(aspect) * scene.camera.eye_from_world();
        for o in &scene.objects[1..] {
            for &p in &o.mesh.positions {
                let nc = clip_from_world.project_point3(o.world_from_object.transform_point3(p));
                assert!(nc.abs().max_element() < 1.0, "a sphere out of view at {nc}");
            }
        }
    }
}
