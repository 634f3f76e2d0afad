//! Scenes whose pixel values are areas: white emissive triangles on black,
//! seen by an orthographic camera whose view is the square [−1, 1]², so a
//! pixel's exact value is the share of it the triangles cover. Anti-aliasing
//! is measured on them (the ray tracer's tests and `cargo xtask
//! trace-report`).

use std::sync::Arc;

use glam::{Mat4, Vec3};
use zline_scene::{Camera, Mesh, Object, Projection, RenderSettings, Scene};
use zline_shading::Material;

/// White emissive triangles, given by their (x, y) corners in [−1, 1]²,
/// in the plane z = −1, drawn at `size` × `size` pixels. A triangle that
/// is not a valid mesh (degenerate corners) is left out.
pub fn coverage_scene(triangles: &[[(f32, f32); 3]], size: u32) -> Scene {
    let white =
        Material { ka: Vec3::ZERO, kd: Vec3::ZERO, ks: Vec3::ZERO, ke: Vec3::ONE, ..Material::DEFAULT };
    let objects = triangles
        .iter()
        .filter_map(|t| {
            let p = t.iter().map(|&(x, y)| Vec3::new(x, y, -1.0)).collect();
            let mesh = Mesh::new("triangle", p, None, vec![[0, 1, 2]], white).ok()?;
            Some(Object {
                mesh: Arc::new(mesh),
                world_from_object: Mat4::IDENTITY,
                material: None,
                shading: None,
                cull_back_faces: false,
            })
        })
        .collect();
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: Camera {
            eye: Vec3::ZERO,
            target: Vec3::NEG_Z,
            up: Vec3::Y,
            projection: Projection::Orthographic { height: 2.0, near: 0.5, far: 2.0 },
        },
        background: Vec3::ZERO,
        ambient: Vec3::ZERO,
        lights: Vec::new(),
        objects,
        settings: RenderSettings { width: size, height: size, ..RenderSettings::default() },
        fog: None,
    }
}
