//! Framing: a bare model (or a scene without a camera) gets a camera, lights
//! and a background that show all of it.
//!
//! Contract: [`framing_camera`] returns a perspective camera (fovy 40°)
//! whose view contains the bounding sphere of the given box for the given
//! aspect ratio, looking from front-above-right ([`VIEW_DIRECTION`]), with
//! near and far planes hugging the sphere (near = max(dist − 1.1·r,
//! dist·10⁻³), far = dist + 1.1·r) so that depth precision is spent on the
//! model. The arithmetic is done in f64, so boxes with 1e30 coordinates
//! frame fine. A degenerate box (a point, or no geometry) is framed as a
//! sphere of radius 1, or of 10⁻⁵ of its distance from the origin when that
//! is larger, so that the eye never rounds onto the target. Every matrix
//! the camera yields is finite; if even f64 cannot frame the box (sizes
//! near f32::MAX), the camera frames the unit sphere at the origin instead.
//!
//! A model's own scene ([`scene_for_model`], [`scene_for_gltf`] without a
//! camera, and scene files without `[camera]`) is framed tighter by
//! [`model_camera`]: the same view direction and field of view, the
//! closest eye that shows every vertex with a 5 % margin
//! ([`crate::fit_camera`]), and [`framing_camera`] only when that fails.
//!
//! [`scene_for_gltf`] keeps the file's own camera and lights when it has
//! them.

use std::sync::Arc;

use glam::{DVec3, Mat4, Vec3};
use zline_scene::{Camera, Mesh, Object, Projection, RenderSettings, Scene};
use zline_shading::Light;

use crate::culling::default_culling;
use crate::gltf::GltfScene;

/// The direction from the target towards the eye, before normalization:
/// in front (+z), a little above (+y) and to the right (+x).
pub const VIEW_DIRECTION: Vec3 = Vec3::new(0.5, 0.35, 1.0);

/// Vertical field of view of framing cameras, in degrees.
pub const FRAMING_FOVY_DEGREES: f32 = 40.0;

/// Background of framed models: dark grey.
pub const DEFAULT_BACKGROUND: Vec3 = Vec3::new(0.12, 0.12, 0.13);

/// Ambient light of framed models.
pub const DEFAULT_AMBIENT: Vec3 = Vec3::splat(0.15);

/// The scene for a bare model: the meshes at the origin (identity model
/// matrices, the meshes' own materials), framed by [`framing_camera`] and
/// lit by [`default_lights`]. Back faces are culled on closed opaque meshes
/// only ([`Mesh::is_closed`]): culling an open mesh would show holes.
pub fn scene_for_model(meshes: Vec<Mesh>, settings: RenderSettings) -> Scene {
    let objects: Vec<Object> = meshes
        .into_iter()
        .map(|mesh| {
            let cull_back_faces = default_culling(&mesh, mesh.material.opacity);
            Object {
                mesh: Arc::new(mesh),
                world_from_object: Mat4::IDENTITY,
                material: None,
                shading: None,
                cull_back_faces,
            }
        })
        .collect();
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: model_camera(&objects, aspect(&settings)),
        background: DEFAULT_BACKGROUND,
        ambient: DEFAULT_AMBIENT,
        lights: default_lights(),
        objects,
        settings,
        fog: None,
    }
}

/// The scene for a bare glTF file: its objects where its nodes put them,
/// its own camera if it has one (else [`framing_camera`] over the objects'
/// world bounding box), its own lights if it has any (else
/// [`default_lights`], as for a bare OBJ model), and the framing
/// background and ambient light (glTF has neither).
pub fn scene_for_gltf(gltf: GltfScene, settings: RenderSettings) -> Scene {
    let aspect = aspect(&settings);
    let camera = gltf
        .camera
        .filter(|c| camera_is_finite(c, aspect))
        .unwrap_or_else(|| model_camera(&gltf.objects, aspect));
    let lights = if gltf.lights.is_empty() { default_lights() } else { gltf.lights };
    Scene {
        environment: None,
        shadows: Default::default(),
        camera,
        background: DEFAULT_BACKGROUND,
        ambient: DEFAULT_AMBIENT,
        lights,
        objects: gltf.objects,
        settings,
        fog: None,
    }
}

/// The camera of a model or scene that brings none: [`crate::fit_camera`]
/// along [`VIEW_DIRECTION`] with fovy [`FRAMING_FOVY_DEGREES`], else
/// [`framing_camera`] over the world bounding box.
pub fn model_camera(objects: &[Object], aspect: f32) -> Camera {
    crate::fit::fit_camera(objects, VIEW_DIRECTION, Vec3::Y, FRAMING_FOVY_DEGREES, aspect).unwrap_or_else(
        || {
            let (min, max) = world_bounds(objects).unwrap_or((Vec3::ZERO, Vec3::ZERO));
            framing_camera(min, max, aspect)
        },
    )
}

/// The bounding box of some points, `None` when there are none.
pub(crate) fn bounds_of(points: impl IntoIterator<Item = Vec3>) -> Option<(Vec3, Vec3)> {
    points.into_iter().fold(None, |acc, p| match acc {
        None => Some((p, p)),
        Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
    })
}

/// The world-space bounding box of some objects' vertices.
pub(crate) fn world_bounds(objects: &[Object]) -> Option<(Vec3, Vec3)> {
    bounds_of(
        objects
            .iter()
            .flat_map(|o| o.mesh.positions.iter().map(|&p| o.world_from_object.transform_point3(p))),
    )
}

/// The aspect ratio (width / height) of the settings' image.
pub(crate) fn aspect(settings: &RenderSettings) -> f32 {
    settings.width.max(1) as f32 / settings.height.max(1) as f32
}

/// A warm key light from the upper left front and a cool, dimmer fill
/// light from the right, both directional.
pub fn default_lights() -> Vec<Light> {
    vec![
        Light::Directional {
            direction: -Vec3::new(-0.6, 1.0, 0.8).normalize(),
            color: Vec3::new(1.0, 0.92, 0.8) * 0.85,
        },
        Light::Directional {
            direction: -Vec3::new(1.0, 0.1, 0.4).normalize(),
            color: Vec3::new(0.3, 0.36, 0.48),
        },
    ]
}

/// A camera that shows the whole box `min..max` in an image of the given
/// aspect ratio (see the module doc).
pub fn framing_camera(min: Vec3, max: Vec3, aspect: f32) -> Camera {
    let aspect = if aspect.is_finite() && aspect > 0.0 { f64::from(aspect) } else { 1.0 };
    let (min, max) = (min.as_dvec3(), max.as_dvec3());
    let camera = framing_camera_f64((min + max) / 2.0, (max - min).length() / 2.0, aspect);
    if camera_is_finite(&camera, aspect as f32) {
        camera
    } else {
        framing_camera_f64(DVec3::ZERO, 1.0, aspect)
    }
}

fn framing_camera_f64(center: DVec3, radius: f64, aspect: f64) -> Camera {
    let radius = radius.max(center.abs().max_element() * 1e-5);
    let radius = if radius > 0.0 && radius.is_finite() { radius } else { 1.0 };
    let half_fovy = f64::from(FRAMING_FOVY_DEGREES).to_radians() / 2.0;
    let half_fovx = (aspect * half_fovy.tan()).atan();
    // The sphere fits when its tangent lines are inside the narrower half angle;
    // 5 % margin keeps silhouettes off the image border.
    let dist = 1.05 * radius / half_fovy.min(half_fovx).sin();
    let eye = center + VIEW_DIRECTION.as_dvec3().normalize() * dist;
    Camera {
        eye: eye.as_vec3(),
        target: center.as_vec3(),
        up: Vec3::Y,
        projection: Projection::Perspective {
            fovy_degrees: FRAMING_FOVY_DEGREES,
            near: (dist - 1.1 * radius).max(dist * 1e-3) as f32,
            far: (dist + 1.1 * radius) as f32,
        },
    }
}

/// True when the camera's matrices are finite and it does not look at its
/// own eye.
pub(crate) fn camera_is_finite(camera: &Camera, aspect: f32) -> bool {
    camera.eye != camera.target
        && camera.eye_from_world().is_finite()
        && camera.clip_from_eye(aspect).is_finite()
}

#[cfg(test)]
mod tests {
    use super::*;
    use zline_scene::{cube, plane};

    #[track_caller]
    fn check_frames(min: Vec3, max: Vec3, aspect: f32) {
        let camera = framing_camera(min, max, aspect);
        assert!(camera_is_finite(&camera, aspect), "{camera:?}");
        let clip_from_world = camera.clip_from_eye(aspect) * camera.eye_from_world();
        let Projection::Perspective { near, far, .. } = camera.projection else { panic!() };
        assert!(near > 0.0 && far > near, "{near} {far}");
        for i in 0..8 {
            let corner = Vec3::select(glam::BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0), max, min);
            let clip = clip_from_world * corner.extend(1.0);
            let nc = clip.truncate() / clip.w;
            assert!(clip.w > 0.0 && nc.abs().max_element() <= 1.0, "corner {corner} at {nc} for {camera:?}");
        }
    }

    #[test]
    fn boxes_of_any_size_and_shape_are_framed() {
        for aspect in [1.0, 16.0 / 9.0, 0.3] {
            check_frames(Vec3::splat(-1.0), Vec3::splat(1.0), aspect);
            check_frames(Vec3::new(10.0, 0.0, 3.0), Vec3::new(11.0, 5.0, 3.0), aspect); // flat
            check_frames(Vec3::splat(-1e30), Vec3::splat(1e30), aspect);
            check_frames(Vec3::splat(1e30), Vec3::splat(1e30 + 1e25), aspect);
            check_frames(Vec3::splat(1e-7), Vec3::splat(2e-7), aspect);
        }
    }

    #[test]
    fn degenerate_boxes_give_finite_cameras() {
        for (min, max) in [
            (Vec3::ZERO, Vec3::ZERO),
            (Vec3::splat(1e30), Vec3::splat(1e30)),
            (Vec3::splat(-3e38), Vec3::splat(3e38)),
            (Vec3::splat(f32::NAN), Vec3::ZERO),
        ] {
            let camera = framing_camera(min, max, 1.5);
            assert!(camera_is_finite(&camera, 1.5), "{min} {max}: {camera:?}");
        }
    }

    #[test]
    fn scene_for_model_culls_closed_meshes_only() {
        let scene = scene_for_model(vec![cube(1.0), plane(1.0, 1)], RenderSettings::default());
        let cull: Vec<bool> = scene.objects.iter().map(|o| o.cull_back_faces).collect();
        assert_eq!(cull, [true, false]);
        assert_eq!(scene.lights.len(), 2);
        check_frames(Vec3::new(-0.5, -0.5, -0.5), Vec3::splat(0.5), 4.0 / 3.0);
    }
}
