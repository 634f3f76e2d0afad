//! Transforms (SPEC §1) in f64: eye_from_world and clip_from_eye from the
//! [`Camera`]'s fields, the window mapping into sample space, and the
//! per-vertex transform of an object.
//!
//! Conventions, as in the fast renderer: the view matrix is `gluLookAt`
//! (right-handed, looking down −z, +y up); the projection is
//! `gluPerspective` or a symmetric `glOrtho` with NC depth in [−1, 1];
//! normals go through the inverse transpose of eye_from_object and are
//! normalized at the vertices (zero when that matrix is singular).
//!
//! Sample space is window space scaled by the supersampling factor n: the
//! sample grid is an image n× larger, sample (I, J) sits at (I + ½, J + ½),
//! and sample (a, b) of pixel (i, j) is (i·n + a, j·n + b). Derivatives in
//! sample space are derivatives with respect to the sample spacing.

use glam::{DMat3, DMat4, DVec2, DVec3, DVec4};
use zline_scene::{Camera, Projection};

/// `gluLookAt` in f64 (the same matrix as `Camera::eye_from_world`, without
/// its f32 rounding).
pub(crate) fn eye_from_world(camera: &Camera) -> DMat4 {
    let (eye, target, up) = (camera.eye.as_dvec3(), camera.target.as_dvec3(), camera.up.as_dvec3());
    let f = (target - eye).normalize();
    let s = f.cross(up).normalize();
    let u = s.cross(f);
    DMat4::from_cols(
        DVec4::new(s.x, u.x, -f.x, 0.0),
        DVec4::new(s.y, u.y, -f.y, 0.0),
        DVec4::new(s.z, u.z, -f.z, 0.0),
        DVec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
    )
}

/// The projection for a viewport aspect ratio (width / height), OpenGL's
/// NC depth range (the same matrix as `Camera::clip_from_eye`).
pub(crate) fn clip_from_eye(camera: &Camera, aspect: f64) -> DMat4 {
    match camera.projection {
        Projection::Perspective { fovy_degrees, near, far } => {
            let (near, far) = (f64::from(near), f64::from(far));
            let f = 1.0 / (0.5 * f64::from(fovy_degrees).to_radians()).tan();
            DMat4::from_cols(
                DVec4::new(f / aspect, 0.0, 0.0, 0.0),
                DVec4::new(0.0, f, 0.0, 0.0),
                DVec4::new(0.0, 0.0, (near + far) / (near - far), -1.0),
                DVec4::new(0.0, 0.0, 2.0 * near * far / (near - far), 0.0),
            )
        }
        Projection::Orthographic { height, near, far } => {
            let h = f64::from(height) / 2.0;
            let w = h * aspect;
            DMat4::orthographic_rh_gl(-w, w, -h, h, f64::from(near), f64::from(far))
        }
        Projection::Frustum { left, right, bottom, top, near, far } => {
            let [l, r, b, t, n, f] = [left, right, bottom, top, near, far].map(f64::from);
            DMat4::from_cols(
                DVec4::new(2.0 * n / (r - l), 0.0, 0.0, 0.0),
                DVec4::new(0.0, 2.0 * n / (t - b), 0.0, 0.0),
                DVec4::new((r + l) / (r - l), (t + b) / (t - b), (n + f) / (n - f), -1.0),
                DVec4::new(0.0, 0.0, 2.0 * n * f / (n - f), 0.0),
            )
        }
    }
}

/// The matrices of one object.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ObjectTransforms {
    /// View · model.
    pub(crate) eye_from_object: DMat4,
    /// Inverse transpose of eye_from_object's linear part.
    pub(crate) normal_from_object: DMat3,
    /// The projection.
    pub(crate) clip_from_eye: DMat4,
}

impl ObjectTransforms {
    /// The matrices for a model matrix under a camera.
    pub(crate) fn new(clip_from_eye: DMat4, eye_from_world: DMat4, world_from_object: DMat4) -> Self {
        let eye_from_object = eye_from_world * world_from_object;
        let normal_from_object = DMat3::from_mat4(eye_from_object).inverse().transpose();
        ObjectTransforms { eye_from_object, normal_from_object, clip_from_eye }
    }

    /// One vertex in eye and clip space, projected when it lies between the
    /// near and far planes.
    pub(crate) fn vertex(&self, position: DVec3, normal: DVec3, space: &SampleSpace) -> Vertex {
        let eye = self.eye_from_object.transform_point3(position);
        let clip = self.clip_from_eye * eye.extend(1.0);
        let inside = clip.is_finite() && clip.z + clip.w >= 0.0 && clip.w - clip.z >= 0.0;
        let corner = if inside { space.project(clip) } else { None };
        Vertex { eye, normal: (self.normal_from_object * normal).normalize_or_zero(), clip, corner }
    }
}

/// A transformed vertex of an object's mesh.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Vertex {
    /// Eye-space position.
    pub(crate) eye: DVec3,
    /// Unit eye-space normal (zero when the normal matrix is singular).
    pub(crate) normal: DVec3,
    /// Clip-space position.
    pub(crate) clip: DVec4,
    /// The projected vertex, when no clipping plane separates it from the
    /// view volume's depth range (near ≤ z ≤ far, w > 0).
    pub(crate) corner: Option<Corner>,
}

/// A vertex after the divide, in sample space.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Corner {
    /// Position in sample space (y down).
    pub(crate) pos: DVec2,
    /// NC depth z/w.
    pub(crate) z: f64,
    /// 1/w.
    pub(crate) inv_w: f64,
}

/// The window mapping (SPEC §1) onto the sample grid.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SampleSpace {
    /// Samples per row: n·W.
    pub(crate) width: f64,
    /// Sample rows: n·H.
    pub(crate) height: f64,
}

impl SampleSpace {
    /// Divides by w and maps to sample space; `None` unless w > 0 and the
    /// result is finite (nothing with w ≤ 0 is divided).
    pub(crate) fn project(&self, clip: DVec4) -> Option<Corner> {
        // NaN fails too.
        if clip.w.is_nan() || clip.w <= 0.0 {
            return None;
        }
        let nc = clip.truncate() / clip.w;
        let corner = Corner {
            pos: DVec2::new((nc.x + 1.0) * 0.5 * self.width, (1.0 - nc.y) * 0.5 * self.height),
            z: nc.z,
            inv_w: 1.0 / clip.w,
        };
        (corner.pos.is_finite() && corner.z.is_finite() && corner.inv_w.is_finite()).then_some(corner)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn camera(projection: Projection) -> Camera {
        Camera { eye: Vec3::new(1.0, 2.0, 5.0), target: Vec3::new(0.5, 0.0, -1.0), up: Vec3::Y, projection }
    }

    #[test]
    fn matrices_match_the_scene_model_to_f32_rounding() {
        for projection in [
            Projection::Perspective { fovy_degrees: 50.0, near: 0.1, far: 100.0 },
            Projection::Orthographic { height: 4.0, near: 0.5, far: 20.0 },
        ] {
            let c = camera(projection);
            let view = eye_from_world(&c);
            assert!(view.as_mat4().abs_diff_eq(c.eye_from_world(), 1e-5), "{view} vs {}", c.eye_from_world());
            let proj = clip_from_eye(&c, 1.5);
            assert!(proj.as_mat4().abs_diff_eq(c.clip_from_eye(1.5), 1e-5), "{proj}");
        }
    }

    #[test]
    fn window_mapping_puts_row_zero_on_top() {
        let space = SampleSpace { width: 100.0, height: 50.0 };
        let c = space.project(DVec4::new(-2.0, 2.0, 0.0, 2.0)).unwrap();
        assert_eq!((c.pos, c.z, c.inv_w), (DVec2::new(0.0, 0.0), 0.0, 0.5));
        assert!(space.project(DVec4::new(0.0, 0.0, 0.0, 0.0)).is_none());
        assert!(space.project(DVec4::new(0.0, 0.0, 0.0, -1.0)).is_none());
    }
}
