//! The built-in demo scene: zline's showcase, needing no files.
//!
//! Contract: [`demo_scene`] returns a 960 × 540 scene with a ground plane,
//! three low-poly spheres side by side shaded Flat, Gouraud and Phong (left
//! to right) so the three modes of SPEC §6 can be compared, a cube and a
//! torus behind them, a warm and a cool attenuated point light and a dim
//! directional light. The spheres are shiny (ns = 60), so Phong shows a
//! round highlight, Gouraud a smeared one and Flat a bright facet. The
//! ground carries a procedural checkerboard texture (trilinear, repeating),
//! a glass sphere in front is drawn by the transparency pass, and a light
//! linear fog in the background colour fades the distance (SPEC §7–9).

use std::sync::Arc;

use glam::{Mat4, Quat, Vec2, Vec3};
use zline_scene::{
    cube, plane, torus, uv_sphere, Camera, Interpolation, Mesh, Object, Projection, RenderSettings, Scene,
    TextureMap,
};
use zline_shading::{
    Attenuation, Fog, FogCoordinate, FogMode, Light, Material, Sampler, ShadingMode, Texture,
};

/// The demo scene (see the module doc).
pub fn demo_scene() -> Scene {
    let sphere = Arc::new(uv_sphere(8, 12, 0.8));
    let sphere_material = Material::plastic(Vec3::new(0.85, 0.25, 0.2), 0.7, 60.0);
    let mut objects = vec![object(
        checkered(plane(24.0, 24)),
        Mat4::IDENTITY,
        Material::plastic(Vec3::new(0.75, 0.72, 0.65), 0.1, 8.0),
        None,
    )];

    for (x, mode) in [(-2.1, ShadingMode::Flat), (0.0, ShadingMode::Gouraud), (2.1, ShadingMode::Phong)] {
        objects.push(Object {
            mesh: Arc::clone(&sphere),
            world_from_object: Mat4::from_translation(Vec3::new(x, 0.8, 0.0)),
            material: Some(sphere_material),
            shading: Some(mode),
            cull_back_faces: true,
        });
    }
    objects.push(object(
        cube(1.3),
        Mat4::from_rotation_translation(
            Quat::from_rotation_y(35f32.to_radians()),
            Vec3::new(-4.8, 0.65, -3.2),
        ),
        Material::plastic(Vec3::new(0.2, 0.4, 0.85), 0.4, 30.0),
        None,
    ));
    objects.push(object(
        torus(0.9, 0.3, 48, 24),
        Mat4::from_rotation_translation(Quat::from_rotation_x(60f32.to_radians()), Vec3::new(4.8, 1.0, -3.2)),
        Material::plastic(Vec3::new(0.9, 0.7, 0.2), 0.8, 80.0),
        None,
    ));
    // Last, so the spheres' shading modes stay the only overrides in order.
    let glass = Material { opacity: 0.35, ..Material::plastic(Vec3::new(0.55, 0.8, 0.95), 0.9, 90.0) };
    objects.push(Object {
        mesh: Arc::new(uv_sphere(24, 48, 0.55)),
        world_from_object: Mat4::from_translation(Vec3::new(1.05, 0.55, 1.6)),
        material: Some(glass),
        shading: None,
        cull_back_faces: false,
    });
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: Camera {
            eye: Vec3::new(0.0, 2.8, 7.5),
            target: Vec3::new(0.0, 0.7, -0.6),
            up: Vec3::Y,
            projection: Projection::Perspective { fovy_degrees: 40.0, near: 1.0, far: 40.0 },
        },
        background: BACKGROUND,
        ambient: Vec3::splat(0.12),
        lights: vec![
            Light::Point {
                position: Vec3::new(-3.5, 4.5, 4.0),
                color: Vec3::new(1.0, 0.82, 0.6) * 1.3,
                attenuation: Attenuation::new(1.0, 0.02, 0.012),
            },
            Light::Point {
                position: Vec3::new(4.5, 3.0, 2.5),
                color: Vec3::new(0.45, 0.6, 1.0),
                attenuation: Attenuation::new(1.0, 0.02, 0.015),
            },
            Light::Directional { direction: Vec3::new(0.3, -1.0, -0.4), color: Vec3::splat(0.15) },
        ],
        objects,
        settings: RenderSettings {
            width: 960,
            height: 540,
            shading: ShadingMode::Phong,
            interpolation: Interpolation::PerspectiveCorrect,
            texture_filter: None,
            ..RenderSettings::default()
        },
        fog: Some(Fog {
            mode: FogMode::Linear { start: 9.0, end: 26.0 },
            color: BACKGROUND,
            coordinate: FogCoordinate::EyePlane,
        }),
    }
}

/// The demo's background, also its fog colour.
const BACKGROUND: Vec3 = Vec3::new(0.06, 0.07, 0.1);

/// The ground with texture coordinates (one unit per checker cell) and a
/// procedural 64 × 64 checkerboard of 8 × 8-texel cells.
fn checkered(ground: Mesh) -> Mesh {
    let uvs = ground.positions.iter().map(|p| Vec2::new(p.x / 8.0, -p.z / 8.0)).collect();
    let side = 64u32;
    let rgba: Vec<u8> = (0..side * side)
        .flat_map(|i| {
            let (x, y) = (i % side, i / side);
            let v = if (x / 8 + y / 8).is_multiple_of(2) { 255 } else { 150 };
            [v, v, v, 255]
        })
        .collect();
    let texture =
        Texture::from_rgba8(side, side, &rgba).expect("a 64 × 64 texture of 64·64·4 bytes is valid");
    let ground = ground.with_uvs(uvs).expect("one finite coordinate per vertex");
    ground.with_diffuse_map(TextureMap {
        texture: Arc::new(texture),
        sampler: Sampler::default(),
        alpha_blend: false,
        alpha_cutoff: None,
    })
}

fn object(mesh: Mesh, world_from_object: Mat4, material: Material, shading: Option<ShadingMode>) -> Object {
    let cull_back_faces = mesh.is_closed();
    Object { mesh: Arc::new(mesh), world_from_object, material: Some(material), shading, cull_back_faces }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn demo_has_the_three_shading_modes_left_to_right_and_everything_in_view() {
        let scene = demo_scene();
        let modes: Vec<_> = scene.objects.iter().filter_map(|o| o.shading).collect();
        assert_eq!(modes, ShadingMode::ALL);
        assert!(scene.objects.iter().any(|o| o.material().opacity < 1.0), "a transparent object");
        assert!(
            scene.objects.iter().any(|o| o.mesh.diffuse_map.is_some() && !o.mesh.uvs.is_empty()),
            "a texture"
        );
        assert!(scene.fog.is_some());
        let aspect = scene.settings.width as f32 / scene.settings.height as f32;
        let clip_from_world = scene.camera.clip_from_eye(aspect) * scene.camera.eye_from_world();
        for o in &scene.objects[1..] {
            for &p in &o.mesh.positions {
                let nc = clip_from_world.project_point3(o.world_from_object.transform_point3(p));
                assert!(nc.abs().max_element() < 1.0, "{} out of view at {nc}", o.mesh.name);
            }
        }
        let x: Vec<f32> = scene.objects[1..4].iter().map(|o| o.world_from_object.w_axis.x).collect();
        assert!(x[0] < x[1] && x[1] < x[2]);
    }
}
