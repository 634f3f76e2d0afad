//! Moving the camera from the command line: orbit (azimuth, elevation),
//! distance or zoom, field of view and up vector, applied to a loaded
//! scene's camera.
//!
//! The rules ([`ViewChange::apply`]):
//! - **Orbit**: the eye turns about the target, `azimuth` degrees about
//!   the up vector (positive: the camera moves to its right, the model
//!   turns left) and `elevation` degrees towards up, stopping 1° short of
//!   looking straight along up.
//! - A scene whose camera is zline's framing (a bare model, or a scene file
//!   without `[camera]`) is framed again after the orbit, field of view and
//!   up change: the tight fit along the new direction
//!   ([`zline_io::fit_camera`]), so the model fills the frame from any
//!   side. A file's own camera keeps its distance.
//! - **Distance** sets the eye's distance from the target; **zoom** divides
//!   it (perspective) or the view height (orthographic) by the factor.
//! - Near and far then hug the scene's bounding sphere from the new eye
//!   (near = max(d − 1.1·r, far·10⁻⁴), far = d + 1.1·r), so moving the
//!   camera never clips the model.

use glam::{Quat, Vec3};
use zline_scene::{Camera, Projection, Scene};

/// What the command line asks of the camera; `None` leaves it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ViewChange {
    /// Degrees about the up vector.
    pub azimuth: Option<f32>,
    /// Degrees towards up.
    pub elevation: Option<f32>,
    /// The eye's distance from the target, world units (> 0).
    pub distance: Option<f32>,
    /// Magnification (> 0): 2 halves the distance or the view height.
    pub zoom: Option<f32>,
    /// Vertical field of view, degrees (perspective cameras).
    pub fov: Option<f32>,
    /// The world's up direction.
    pub up: Option<Vec3>,
}

impl ViewChange {
    /// True when nothing is asked.
    pub fn is_empty(&self) -> bool {
        *self == ViewChange::default()
    }

    /// Applies the change to `scene`'s camera (see the module
    /// documentation), for an image of the given aspect ratio; `framed`
    /// says the camera is zline's framing (see [`is_framed`]).
    pub fn apply(&self, scene: &mut Scene, aspect: f32, framed: bool) {
        if self.is_empty() {
            return;
        }
        let mut camera = scene.camera;
        if let Some(up) = self.up.filter(|u| u.is_finite() && *u != Vec3::ZERO) {
            camera.up = up;
        }
        if let (Some(fov), Projection::Perspective { fovy_degrees, .. }) = (self.fov, &mut camera.projection)
        {
            *fovy_degrees = fov;
        }
        let back = orbit(
            camera.eye - camera.target,
            camera.up,
            self.azimuth.unwrap_or(0.0),
            self.elevation.unwrap_or(0.0),
        );
        let fovy = match camera.projection {
            Projection::Perspective { fovy_degrees, .. } => Some(fovy_degrees),
            Projection::Orthographic { .. } | Projection::Frustum { .. } => None,
        };
        let refit = match (framed, fovy) {
            (true, Some(fovy)) => zline_io::fit_camera(&scene.objects, back, camera.up, fovy, aspect),
            _ => None,
        };
        camera = match refit {
            Some(c) => c,
            None => Camera { eye: camera.target + back, ..camera },
        };
        let offset = camera.eye - camera.target;
        if let Some(d) = self.distance.filter(|d| d.is_finite() && *d > 0.0) {
            camera.eye = camera.target + offset.normalize_or(Vec3::Z) * d;
        }
        if let Some(z) = self.zoom.filter(|z| z.is_finite() && *z > 0.0) {
            match &mut camera.projection {
                Projection::Perspective { .. } | Projection::Frustum { .. } => {
                    camera.eye = camera.target + (camera.eye - camera.target) / z
                }
                Projection::Orthographic { height, .. } => *height /= z,
            }
        }
        hug(&mut camera, scene);
        scene.camera = camera;
    }
}

/// True when `scene`'s camera is zline's framing of its objects for the
/// aspect ratio of its settings (a bare model, or a scene file without
/// `[camera]`).
pub fn is_framed(scene: &Scene) -> bool {
    scene.camera == zline_io::model_camera(&scene.objects, aspect_of(scene))
}

/// The aspect ratio of `scene`'s image.
pub fn aspect_of(scene: &Scene) -> f32 {
    scene.settings.width.max(1) as f32 / scene.settings.height.max(1) as f32
}

/// `back` (target → eye) turned `azimuth` degrees about `up` and
/// `elevation` degrees towards it, at most 89° from the horizontal.
fn orbit(back: Vec3, up: Vec3, azimuth: f32, elevation: f32) -> Vec3 {
    let up = up.normalize_or(Vec3::Y);
    let length = back.length();
    let dir = back.normalize_or(Vec3::Z);
    let turned = Quat::from_axis_angle(up, azimuth.to_radians()) * dir;
    let height = turned.dot(up).clamp(-1.0, 1.0);
    let flat = (turned - up * height).normalize_or(up.any_orthonormal_vector());
    let angle = (height.asin().to_degrees() + elevation).clamp(-89.0, 89.0).to_radians();
    (flat * angle.cos() + up * angle.sin()) * length
}

/// Near and far around the scene's bounding sphere from the camera's eye
/// (the rule of the module documentation; `zline view` applies it after a
/// pan).
pub fn hug(camera: &mut Camera, scene: &Scene) {
    let mut min = Vec3::splat(f32::INFINITY);
    let mut max = Vec3::splat(f32::NEG_INFINITY);
    for o in &scene.objects {
        for p in &o.mesh.positions {
            let w = o.world_from_object.transform_point3(*p);
            if w.is_finite() {
                (min, max) = (min.min(w), max.max(w));
            }
        }
    }
    if !min.cmple(max).all() {
        return;
    }
    let (center, radius) = ((min + max) / 2.0, (max - min).length() / 2.0);
    let d = (camera.eye - center).length();
    let far = d + 1.1 * radius;
    let near = (d - 1.1 * radius).max(far * 1e-4);
    if !(near.is_finite() && far.is_finite() && near < far) {
        return;
    }
    match &mut camera.projection {
        Projection::Perspective { near: n, far: f, .. } => (*n, *f) = (near, far),
        // The sides are given at the near plane: they scale with it.
        Projection::Frustum { left, right, bottom, top, near: n, far: f } => {
            let k = near / *n;
            if k.is_finite() && k > 0.0 {
                for side in [left, right, bottom, top] {
                    *side *= k;
                }
                (*n, *f) = (near, far);
            }
        }
        Projection::Orthographic { near: n, far: f, .. } => (*n, *f) = ((d - 1.1 * radius).min(near), far),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn orbit_turns_about_up_and_raises_towards_it() {
        let z = Vec3::new(0.0, 0.0, 2.0);
        assert!(close(orbit(z, Vec3::Y, 90.0, 0.0), Vec3::new(2.0, 0.0, 0.0)));
        assert!(close(orbit(z, Vec3::Y, 0.0, 30.0), Vec3::new(0.0, 1.0, 3f32.sqrt())));
        // Past the pole it stops 1° short.
        let top = orbit(z, Vec3::Y, 0.0, 120.0);
        assert!((top.normalize().y - 89f32.to_radians().sin()).abs() < 1e-5, "{top}");
        assert!((top.length() - 2.0).abs() < 1e-5);
    }

    #[test]
    fn a_framed_model_is_framed_again_from_the_new_side() {
        let mut scene = zline_io::scene_for_model(vec![zline_scene::cube(1.0)], Default::default());
        let aspect = 4.0 / 3.0;
        let change = ViewChange { azimuth: Some(180.0), ..ViewChange::default() };
        assert!(is_framed(&scene));
        change.apply(&mut scene, aspect, true);
        let view = (scene.camera.eye - scene.camera.target).normalize();
        let before = zline_io::VIEW_DIRECTION.normalize();
        // Turned half way round about y: x and z flip, y stays.
        assert!(close(view, Vec3::new(-before.x, before.y, -before.z)), "{view}");
        // And framed: the same distance as from the front (a cube).
        let front = zline_io::scene_for_model(vec![zline_scene::cube(1.0)], Default::default()).camera;
        let (d0, d1) =
            ((front.eye - front.target).length(), (scene.camera.eye - scene.camera.target).length());
        assert!((d0 - d1).abs() < 1e-3 * d0, "{d0} {d1}");
        // Zoom 2 halves the distance; near and far still hold the cube.
        let d = (scene.camera.eye - scene.camera.target).length();
        ViewChange { zoom: Some(2.0), ..ViewChange::default() }.apply(&mut scene, aspect, false);
        assert!(((scene.camera.eye - scene.camera.target).length() - d / 2.0).abs() < 1e-5);
        let Projection::Perspective { near, far, .. } = scene.camera.projection else { panic!() };
        let to_center = scene.camera.eye.length();
        assert!(near < to_center - 0.87 && far > to_center + 0.87, "{near} {far} {to_center}");
    }
}
