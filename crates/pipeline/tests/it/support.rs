//! Small scene builders shared by the tests.

use std::sync::Arc;

use glam::{Mat4, Vec3};
use zline_pipeline::{render, Image, RenderOptions};
use zline_scene::{Camera, Mesh, Object, Projection, RenderSettings, Scene};
use zline_shading::{Light, Material, ShadingMode};

/// A mesh from positions and triangles, with the given normals.
pub(crate) fn mesh(
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    material: Material,
) -> Arc<Mesh> {
    Arc::new(Mesh {
        name: "test".into(),
        positions,
        normals,
        triangles,
        material,
        uvs: Vec::new(),
        colors: Vec::new(),
        diffuse_map: None,
        tangents: Vec::new(),
        normal_map: None,
        surface_maps: Default::default(),
    })
}

/// An axis-aligned square in the plane z = `z`, facing +z, corners at ±`half`
/// around (cx, cy), split along the diagonal from (−,−) to (+,+).
pub(crate) fn square(cx: f32, cy: f32, half: f32, z: f32, material: Material) -> Arc<Mesh> {
    let p = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y)| Vec3::new(cx + x * half, cy + y * half, z))
        .to_vec();
    mesh(p, vec![Vec3::Z; 4], vec![[0, 1, 2], [0, 2, 3]], material)
}

/// An object with identity transform.
pub(crate) fn object(mesh: Arc<Mesh>, shading: Option<ShadingMode>) -> Object {
    Object { mesh, world_from_object: Mat4::IDENTITY, material: None, shading, cull_back_faces: true }
}

/// A camera at the origin looking down −z with a 90° vertical field of view.
pub(crate) fn origin_camera(near: f32, far: f32) -> Camera {
    Camera {
        eye: Vec3::ZERO,
        target: Vec3::NEG_Z,
        up: Vec3::Y,
        projection: Projection::Perspective { fovy_degrees: 90.0, near, far },
    }
}

/// A scene with the origin camera, black background and the given parts.
pub(crate) fn scene(size: u32, ambient: Vec3, lights: Vec<Light>, objects: Vec<Object>) -> Scene {
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: origin_camera(0.5, 10.0),
        background: Vec3::ZERO,
        ambient,
        lights,
        objects,
        settings: RenderSettings { width: size, height: size, ..RenderSettings::default() },
        fog: None,
    }
}

/// Renders with the default options on the current thread pool.
pub(crate) fn draw(scene: &Scene) -> Image {
    render(scene, &RenderOptions::default()).0
}

/// A wavy, finely tessellated height field: many small triangles sharing
/// edges, facing the origin camera.
pub(crate) fn wavy_grid(n: u32, z: f32) -> Arc<Mesh> {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (u, v) = (i as f32 / n as f32 * 4.0 - 2.0, j as f32 / n as f32 * 4.0 - 2.0);
            let h = 0.3 * (3.0 * u).sin() * (2.0 * v).cos();
            positions.push(Vec3::new(u, v, z + h));
            let dhdu = 0.9 * (3.0 * u).cos() * (2.0 * v).cos();
            let dhdv = -0.6 * (3.0 * u).sin() * (2.0 * v).sin();
            normals.push(Vec3::new(-dhdu, -dhdv, 1.0).normalize());
        }
    }
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    mesh(positions, normals, triangles, Material::plastic(Vec3::new(0.8, 0.5, 0.3), 0.5, 24.0))
}

/// SPEC §10 for a value computed here in f64, with a check that it is not
/// within 0.01 of a rounding boundary (so f32 arithmetic in the renderer
/// cannot honestly land on the other side).
#[track_caller]
pub(crate) fn quantize_robust(c: glam::DVec3) -> [u8; 3] {
    c.to_array().map(|x| {
        let s = x.clamp(0.0, 1.0) * 255.0 + 0.5;
        let frac = s - s.floor();
        assert!(frac > 0.01 && frac < 0.99, "expected value {x} is too close to a rounding boundary");
        s.floor() as u8
    })
}

/// `mesh` with vertex colours that vary smoothly with the position (every
/// channel in [0.2, 1]).
pub(crate) fn colored(mesh: &Mesh) -> Arc<Mesh> {
    let colors = mesh
        .positions
        .iter()
        .map(|p| {
            Vec3::new(
                0.6 + 0.4 * (2.0 * p.x).sin(),
                0.6 + 0.4 * (3.0 * p.y).cos(),
                0.6 + 0.4 * (p.x * p.y).sin(),
            )
        })
        .collect();
    Arc::new(mesh.clone().with_colors(colors).expect("one colour per vertex"))
}
