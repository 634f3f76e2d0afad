//! A tight framing: the closest perspective camera, looking along a given
//! direction, whose view contains every vertex of the objects, each at
//! least a margin inside the frame's edges.
//!
//! In the camera's basis (right r, up u, back b = the direction from the
//! target towards the eye), a vertex at (x, y, z) lies inside the view of an
//! eye at (ex, ey, ez) when |x − ex| ≤ tx·(ez − z) and |y − ey| ≤
//! ty·(ez − z), with tx, ty the tangents of the half fields of view. For
//! each axis these are two families of half-planes in (ex, ez), and the
//! smallest ez meeting all of them is
//!
//!   ez = (max(x + tx·z) − min(x − tx·z)) / (2·tx), ex = (max(x + tx·z) + min(x − tx·z)) / 2,
//!
//! the larger of the two axes' ez deciding (the other axis then has room
//! and is centred the same way). This is exact for the vertices given —
//! tighter than a bounding sphere, which leaves a long model such as the
//! Fox small in the frame — and costs one pass over them, in f64.

use glam::{DVec3, Vec3};
use zline_scene::{Camera, Object, Projection};

/// The share of each half of the frame left empty around the model.
pub const FIT_MARGIN: f64 = 0.05;

/// The tightest camera looking along −`back` (the direction from target to
/// eye) with `up`, vertical field of view `fovy_degrees` and the given
/// aspect ratio, that shows every finite vertex of `objects`, each at
/// least [`FIT_MARGIN`] of the half frame inside its edges. `None` without
/// finite vertices, with a degenerate direction, or when the numbers
/// overflow; callers fall back to a bounding-box framing.
pub fn fit_camera(
    objects: &[Object],
    back: Vec3,
    up: Vec3,
    fovy_degrees: f32,
    aspect: f32,
) -> Option<Camera> {
    let b = back.as_dvec3().normalize_or_zero();
    let r = up.as_dvec3().cross(b).normalize_or_zero();
    if b == DVec3::ZERO || r == DVec3::ZERO || !(aspect.is_finite() && aspect > 0.0) {
        return None;
    }
    let u = b.cross(r);
    let ty = (f64::from(fovy_degrees).to_radians() / 2.0).tan() * (1.0 - FIT_MARGIN);
    let tx = ty * f64::from(aspect);
    if !(ty.is_finite() && ty > 0.0) {
        return None;
    }
    // max(a + t·z) and min(a − t·z) for a = x, then y; and the depth range.
    let mut hi = [f64::NEG_INFINITY; 2];
    let mut lo = [f64::INFINITY; 2];
    let (mut z_min, mut z_max) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut extent = 0.0f64;
    let mut first = None;
    for object in objects {
        let m = object.world_from_object.as_dmat4();
        for p in &object.mesh.positions {
            let w = m.transform_point3(p.as_dvec3());
            if !w.is_finite() {
                continue;
            }
            let (x, y, z) = (w.dot(r), w.dot(u), w.dot(b));
            for (k, (a, t)) in [(x, tx), (y, ty)].into_iter().enumerate() {
                hi[k] = hi[k].max(a + t * z);
                lo[k] = lo[k].min(a - t * z);
            }
            (z_min, z_max) = (z_min.min(z), z_max.max(z));
            let origin = *first.get_or_insert(w);
            extent = extent.max((w - origin).abs().max_element());
        }
    }
    // No finite vertex: the depth range stayed empty.
    if z_min > z_max || first.is_none() {
        return None;
    }
    let ez_x = (hi[0] - lo[0]) / (2.0 * tx);
    let ez_y = (hi[1] - lo[1]) / (2.0 * ty);
    let (ex, ey) = ((hi[0] + lo[0]) / 2.0, (hi[1] + lo[1]) / 2.0);
    // A flat or single-point model seen edge-on needs some distance: at
    // least its depth extent, or a hair of its distance from the origin.
    let floor = z_max + (1e-3 * extent).max(1e-6 * DVec3::new(ex, ey, z_max).length()).max(1e-6);
    let ez = ez_x.max(ez_y).max(floor);
    let eye = r * ex + u * ey + b * ez;
    let (near, far) = ((ez - z_max) * 0.9, (ez - z_min) * 1.1);
    // Look along −b, at the point of the model's depth middle.
    let target = eye - b * (ez - (z_min + z_max) / 2.0).max(near);
    let camera = Camera {
        eye: eye.as_vec3(),
        target: target.as_vec3(),
        up,
        projection: Projection::Perspective {
            fovy_degrees,
            near: (near.max(far * 1e-4)) as f32,
            far: far as f32,
        },
    };
    let finite = camera.eye.is_finite()
        && camera.target.is_finite()
        && camera.eye != camera.target
        && camera.eye_from_world().is_finite()
        && camera.clip_from_eye(aspect).is_finite();
    finite.then_some(camera)
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::{Mat4, Vec4};
    use zline_scene::{cube, Mesh};

    use super::*;

    fn object(mesh: Mesh, m: Mat4) -> Object {
        Object {
            mesh: Arc::new(mesh),
            world_from_object: m,
            material: None,
            shading: None,
            cull_back_faces: true,
        }
    }

    /// Every vertex projects inside the frame shrunk by the margin, and
    /// the extreme ones touch it on one axis: the fit is tight.
    fn check_tight(objects: &[Object], back: Vec3, aspect: f32) {
        let camera = fit_camera(objects, back, Vec3::Y, 40.0, aspect).unwrap();
        let clip = camera.clip_from_eye(aspect) * camera.eye_from_world();
        let (mut max_x, mut max_y) = (0.0f32, 0.0f32);
        for o in objects {
            for p in &o.mesh.positions {
                let c = clip * Vec4::from((o.world_from_object.transform_point3(*p), 1.0));
                let (x, y, z) = (c.x / c.w, c.y / c.w, c.z / c.w);
                assert!(c.w > 0.0 && z.abs() <= 1.0, "{p}: depth {z}");
                (max_x, max_y) = (max_x.max(x.abs()), max_y.max(y.abs()));
            }
        }
        let edge = (1.0 - FIT_MARGIN) as f32;
        assert!(max_x <= edge + 1e-4 && max_y <= edge + 1e-4, "{max_x} {max_y}");
        assert!(max_x >= edge - 1e-3 || max_y >= edge - 1e-3, "not tight: {max_x} {max_y}");
    }

    #[test]
    fn a_cube_and_a_long_box_fill_the_frame() {
        check_tight(&[object(cube(1.0), Mat4::IDENTITY)], Vec3::new(0.5, 0.35, 1.0), 4.0 / 3.0);
        let long = Mat4::from_scale(Vec3::new(8.0, 1.0, 1.0));
        check_tight(&[object(cube(1.0), long)], Vec3::new(0.5, 0.35, 1.0), 4.0 / 3.0);
        check_tight(&[object(cube(1.0), long)], Vec3::new(0.0, 0.0, 1.0), 0.5);
        // Away from the origin (the check itself is f32: 1e2 keeps it exact to 1e-4).
        let far_away = Mat4::from_translation(Vec3::splat(100.0));
        check_tight(&[object(cube(1.0), far_away)], Vec3::new(-1.0, 2.0, 0.3), 1.0);
    }

    #[test]
    fn nothing_to_fit_or_a_bad_direction_is_none() {
        assert!(fit_camera(&[], Vec3::Z, Vec3::Y, 40.0, 1.0).is_none());
        let one = [object(cube(1.0), Mat4::IDENTITY)];
        assert!(fit_camera(&one, Vec3::ZERO, Vec3::Y, 40.0, 1.0).is_none());
        assert!(fit_camera(&one, Vec3::Y, Vec3::Y, 40.0, 1.0).is_none(), "looking along up");
        assert!(fit_camera(&one, Vec3::Z, Vec3::Y, 40.0, f32::NAN).is_none());
    }
}
