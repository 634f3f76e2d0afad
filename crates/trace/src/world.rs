//! The scene as the ray tracer reads it: every triangle in world space
//! with its shading attributes, the surfaces' materials and textures, and
//! the camera's rays.

use glam::{DMat4, DVec4, Mat3, Mat4, Vec2, Vec3};
use zline_scene::{Scene, TextureMap};
use zline_shading::{Material, ShadingMode};

use crate::ray::Ray;

/// What a triangle is made of: its object's material and texture.
#[derive(Clone, Debug)]
pub struct Surface {
    /// The material, sanitized (SPEC §12 reads kr, opacity and ior).
    pub material: Material,
    /// The diffuse texture, when the mesh has one and texture coordinates.
    pub texture: Option<TextureMap>,
    /// Flat shading: the face's normal, not the vertex normals (the object's
    /// shading mode; Gouraud and Phong both interpolate the normal per hit).
    pub flat: bool,
}

/// A triangle's shading attributes.
#[derive(Clone, Copy, Debug)]
pub struct Attributes {
    /// The unit vertex normals in world space.
    pub normals: [Vec3; 3],
    /// The texture coordinates (zero without a texture).
    pub uvs: [Vec2; 3],
    /// The index of its surface in [`World::surfaces`].
    pub surface: u32,
}

impl Attributes {
    /// The shading normal at barycentrics `b`: the interpolated vertex
    /// normal, or `None` for a flat-shaded object (its face normal then).
    #[inline]
    pub fn normal(&self, surface: &Surface, b: [f32; 3]) -> Option<Vec3> {
        let [n0, n1, n2] = self.normals;
        (!surface.flat).then(|| b[0] * n0 + b[1] * n1 + b[2] * n2)
    }
}

/// The world: triangles for the accelerators, and what shades them.
#[derive(Clone, Debug, Default)]
pub struct World {
    /// Corners in world space, by triangle index.
    pub triangles: Vec<[Vec3; 3]>,
    /// Shading attributes, by triangle index.
    pub attributes: Vec<Attributes>,
    /// One per scene object.
    pub surfaces: Vec<Surface>,
}

impl World {
    /// Every object's triangles, moved to world space (normals by the
    /// inverse transpose). Triangles with a non-finite corner are kept: the
    /// ray test never hits them.
    pub fn new(scene: &Scene) -> World {
        let count = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
        let mut world = World {
            triangles: Vec::with_capacity(count),
            attributes: Vec::with_capacity(count),
            surfaces: Vec::with_capacity(scene.objects.len()),
        };
        for (index, object) in scene.objects.iter().enumerate() {
            let mesh = &object.mesh;
            let m: Mat4 = object.world_from_object;
            let normal_matrix = Mat3::from_mat4(m).inverse().transpose();
            let textured = mesh.diffuse_map.is_some() && mesh.uvs.len() == mesh.positions.len();
            world.surfaces.push(Surface {
                material: object.material().sanitized(),
                texture: mesh.diffuse_map.clone().filter(|_| textured).map(|mut map| {
                    // `--filter` replaces every texture's own (SPEC §7).
                    if let Some(filter) = scene.settings.texture_filter {
                        map.sampler.filter = filter;
                    }
                    map
                }),
                flat: object.shading.unwrap_or(scene.settings.shading) == ShadingMode::Flat,
            });
            for tri in &mesh.triangles {
                let at = |i: u32| mesh.positions.get(i as usize).copied().unwrap_or(Vec3::NAN);
                let corners = tri.map(|i| m.transform_point3(at(i)));
                let normal = |i: u32| {
                    let n = mesh.normals.get(i as usize).copied().unwrap_or(Vec3::ZERO);
                    (normal_matrix * n).normalize_or_zero()
                };
                let uv = |i: u32| if textured { mesh.uvs[i as usize] } else { Vec2::ZERO };
                world.triangles.push(corners);
                world.attributes.push(Attributes {
                    normals: tri.map(normal),
                    uvs: tri.map(uv),
                    surface: index as u32,
                });
            }
        }
        world
    }
}

/// The camera's rays: through each image point, between the near and the
/// far plane of the rasterizer's view volume, so that the ray tracer sees
/// what the rasterizer's clipping keeps (SPEC §12).
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    world_from_clip: DMat4,
    eye_from_world: Mat4,
    size: (u32, u32),
}

impl Camera {
    /// The camera of `scene` for its image size.
    pub fn new(scene: &Scene) -> Camera {
        let (w, h) = (scene.settings.width.max(1), scene.settings.height.max(1));
        let aspect = w as f32 / h as f32;
        let eye_from_world = scene.camera.eye_from_world();
        let clip_from_world = scene.camera.clip_from_eye(aspect).as_dmat4() * eye_from_world.as_dmat4();
        Camera { world_from_clip: clip_from_world.inverse(), eye_from_world, size: (w, h) }
    }

    /// The image size.
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// The ray through the image point (x, y) in pixels (the centre of
    /// pixel (i, j) is (i + ½, j + ½); y grows downwards): from the near
    /// plane (t = 0) to the far plane (t = 1). Unprojected in f64.
    pub fn ray(&self, x: f64, y: f64) -> Ray {
        let (w, h) = (f64::from(self.size.0), f64::from(self.size.1));
        let (xn, yn) = (2.0 * x / w - 1.0, 1.0 - 2.0 * y / h);
        let unproject = |z: f64| {
            let p = self.world_from_clip * DVec4::new(xn, yn, z, 1.0);
            p.truncate() / p.w
        };
        let (near, far) = (unproject(-1.0), unproject(1.0));
        Ray { origin: near.as_vec3(), dir: (far - near).as_vec3(), t_max: 1.0 }
    }

    /// The fog coordinate of a world point (SPEC §8): −z_eye, or the
    /// distance to the eye.
    pub fn fog_distance(&self, p: Vec3, radial: bool) -> f32 {
        let e = self.eye_from_world.transform_point3(p);
        if radial {
            e.length()
        } else {
            -e.z
        }
    }
}
