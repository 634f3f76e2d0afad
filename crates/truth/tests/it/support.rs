//! Small scene builders shared by the tests.

use std::sync::Arc;

use glam::{DVec3, Mat4, Vec3};
use zline_scene::{Camera, Mesh, Object, Projection, RenderSettings, Scene};
use zline_shading::{Attenuation, Light, Material, ShadingMode};

/// A mesh from positions, normals and triangles.
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
        diffuse_map: None,
        tangents: Vec::new(),
        normal_map: None,
        colors: Vec::new(),
        surface_maps: Default::default(),
    })
}

/// An axis-aligned square in the plane z = `z` facing +z, corners at
/// ±`half` around (cx, cy), split along the diagonal from (−,−) to (+,+).
pub(crate) fn square(cx: f32, cy: f32, half: f32, z: f32, material: Material) -> Arc<Mesh> {
    let p = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y)| Vec3::new(cx + x * half, cy + y * half, z))
        .to_vec();
    mesh(p, vec![Vec3::Z; 4], vec![[0, 1, 2], [0, 2, 3]], material)
}

/// An object with identity transform and no culling.
pub(crate) fn object(mesh: Arc<Mesh>, shading: Option<ShadingMode>) -> Object {
    Object { mesh, world_from_object: Mat4::IDENTITY, material: None, shading, cull_back_faces: false }
}

/// A material that shows `color` under white ambient light and nothing else.
pub(crate) fn emissive(color: Vec3, opacity: f32) -> Material {
    Material {
        ka: color,
        kd: Vec3::ZERO,
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity,
        ke: Vec3::ZERO,
        model: zline_shading::Model::Basic,
        ..Material::DEFAULT
    }
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

/// A scene with the origin camera (near 0.5, far 10), black background.
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

/// An f32 constant as the f64 the renderers see.
pub(crate) fn d(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

/// Asserts two colours agree to `tolerance` per channel.
#[track_caller]
pub(crate) fn check_close(got: DVec3, want: DVec3, tolerance: f64) {
    assert!((got - want).abs().max_element() <= tolerance, "got {got}, want {want}");
}

/// The truth computes in f64 from f32 inputs; the expectations here use
/// the same f32 inputs, so only f64 rounding separates them.
pub(crate) const F64_TOLERANCE: f64 = 1e-12;

/// The one point light of the hand-computed scenes, its colour and
/// attenuation, and the ambient light.
pub(crate) const LIGHT: Vec3 = Vec3::new(0.3, 0.8, -0.9);
pub(crate) const LIGHT_COLOR: Vec3 = Vec3::new(1.0, 0.85, 0.7);
pub(crate) const ATTENUATION: Attenuation = Attenuation::new(1.0, 0.2, 0.5);
pub(crate) const AMBIENT: Vec3 = Vec3::new(0.15, 0.1, 0.05);

/// The two parts of SPEC §5 for `m` under the one point light, the eye at
/// the origin, unclamped: (ka·Ia + diffuse, ke + specular).
pub(crate) fn parts(m: &Material, p: DVec3, n: DVec3) -> (DVec3, DVec3) {
    let to_light = d(LIGHT) - p;
    let dist = to_light.length();
    let l = to_light / dist;
    let h = (l + (-p).normalize()).normalize();
    let (a0, a1, a2) = (f64::from(ATTENUATION.a0), f64::from(ATTENUATION.a1), f64::from(ATTENUATION.a2));
    let f = (1.0 / (a0 + a1 * dist + a2 * dist * dist)).min(1.0);
    let n_dot_l = n.dot(l).max(0.0);
    let spec = if n_dot_l > 0.0 { n.dot(h).max(0.0).powf(f64::from(m.ns)) } else { 0.0 };
    let ambient_diffuse = d(m.ka) * d(AMBIENT) + f * d(LIGHT_COLOR) * d(m.kd) * n_dot_l;
    (ambient_diffuse, d(m.ke) + f * d(LIGHT_COLOR) * d(m.ks) * spec)
}
