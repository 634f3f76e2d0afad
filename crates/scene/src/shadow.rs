//! Shadows: a receiving plane found from its object, and the seed's planar
//! shadow matrix (the types, [`crate::Shadows`] and its parts, are in the
//! scene model).
//!
//! The planar method (the seed's `generateShadow`) projects every other
//! object onto a receiving plane from each light; where the projection
//! covers a sample of the receiver, that light's contribution is left out
//! of the sample's lighting (lit part minus the light, so coloured lights
//! cast coloured shadows).

use glam::{DMat4, DVec4, Mat4, Vec3, Vec4};

use crate::model::ShadowPlane;

impl ShadowPlane {
    /// The plane of `object`'s triangles in world space when every vertex
    /// lies on it (within `1e-4` of the object's size); `None` for a mesh
    /// without a triangle of positive area or one that is not flat.
    pub fn of_object(receiver: usize, object: &crate::model::Object) -> Option<ShadowPlane> {
        let m = object.world_from_object;
        let world: Vec<Vec3> = object.mesh.positions.iter().map(|&p| m.transform_point3(p)).collect();
        let normal = object.mesh.triangles.iter().find_map(|t| {
            let [a, b, c] = t.map(|i| world[i as usize]);
            let n = (b - a).cross(c - a);
            (n.length_squared() > 0.0 && n.is_finite()).then(|| n.normalize())
        })?;
        let origin =
            world[object.mesh.triangles.iter().find(|t| t.iter().all(|&i| (i as usize) < world.len()))?[0]
                as usize];
        let d = -normal.dot(origin);
        let size = world.iter().fold(0f32, |s, p| s.max((*p - origin).length()));
        let flat = world.iter().all(|p| (normal.dot(*p) + d).abs() <= 1e-4 * size.max(f32::MIN_POSITIVE));
        (flat && d.is_finite()).then_some(ShadowPlane { receiver, plane: normal.extend(d) })
    }
}

/// The seed's planar shadow matrix (`generateShadow(shadow, ground,
/// light)`): maps a point p to the point where the line from the light
/// through p meets the plane `ground` (a, b, c, d), for a light at the
/// homogeneous position `light` (a point light (x, y, z, 1); a directional
/// light (−direction, 0)).
///
/// M = (g·l)·I − l gᵀ: for p, M·p = (g·l)·p − (g·p)·l, which lies on the
/// plane (g·M·p = 0) and on the line through l and p. Points on the
/// plane's far side from the light, and points farther from the plane
/// than a point light, have no shadow on it; callers clip them away first.
pub fn shadow_matrix(ground: Vec4, light: Vec4) -> Mat4 {
    shadow_matrix_f64(ground.as_dvec4(), light.as_dvec4()).as_mat4()
}

/// [`shadow_matrix`] in f64. Near a point light's height above the plane
/// the projection divides by (g·l) − (g·p), a difference of nearly equal
/// values: a renderer that projects such points needs it in f64 (an f32
/// g·l is off by ~10⁻⁷ of the plane's offset, enough to flip the sign).
pub fn shadow_matrix_f64(ground: DVec4, light: DVec4) -> DMat4 {
    let dot = ground.dot(light);
    let g = ground.to_array();
    let l = light.to_array();
    let col =
        |j: usize| DVec4::from_array(std::array::from_fn(|i| if i == j { dot } else { 0.0 } - l[i] * g[j]));
    DMat4::from_cols(col(0), col(1), col(2), col(3))
}

/// The homogeneous position of a light for [`shadow_matrix`].
pub fn light_position(light: &zline_shading::Light) -> Vec4 {
    match *light {
        zline_shading::Light::Point { position, .. } | zline_shading::Light::Spot { position, .. } => {
            position.extend(1.0)
        }
        zline_shading::Light::Directional { direction, .. } => (-direction).extend(0.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_matrix_maps_points_to_their_shadows() {
        // Ground y = 0 (normal up), point light at (1, 4, -2).
        let ground = Vec4::new(0.0, 1.0, 0.0, 0.0);
        let light = Vec3::new(1.0, 4.0, -2.0);
        let m = shadow_matrix(ground, light.extend(1.0));
        for p in [Vec3::new(0.0, 2.0, 0.0), Vec3::new(3.0, 1.0, 1.0), Vec3::new(-2.0, 3.0, 5.0)] {
            // By hand: the line l + t (p − l) reaches y = 0 at t = l.y / (l.y − p.y).
            let t = light.y / (light.y - p.y);
            let want = light + t * (p - light);
            let got = m.project_point3(p);
            assert!(
                (got - want).length() <= 4.0 * f32::EPSILON * want.length().max(1.0),
                "{p}: {got} vs {want}"
            );
            assert_eq!(got.y.abs(), 0.0, "{p}: {got} is on the ground");
        }
        // (0, 2, 0) under (1, 4, -2): t = 2, shadow (-1, 0, 2), exactly.
        assert_eq!(m.project_point3(Vec3::new(0.0, 2.0, 0.0)), Vec3::new(-1.0, 0.0, 2.0));
    }

    #[test]
    fn a_directional_light_projects_along_its_direction() {
        // Tilted plane x + y = 1 (unnormalized normal is fine for the matrix).
        let ground = Vec4::new(1.0, 1.0, 0.0, -1.0);
        let direction = Vec3::new(0.0, -1.0, 0.0);
        let m = shadow_matrix(ground, (-direction).extend(0.0));
        // (0.25, 3, 7) travels straight down to x + y = 1: (0.25, 0.75, 7).
        let got = m.project_point3(Vec3::new(0.25, 3.0, 7.0));
        assert_eq!(got, Vec3::new(0.25, 0.75, 7.0));
    }

    #[test]
    fn flat_objects_give_their_plane_and_others_none() {
        let floor = crate::model::Object {
            mesh: std::sync::Arc::new(crate::primitives::plane(2.0, 3)),
            world_from_object: Mat4::from_translation(Vec3::new(0.0, -1.0, 0.0)),
            material: None,
            shading: None,
            cull_back_faces: false,
        };
        let p = ShadowPlane::of_object(4, &floor).expect("a plane is flat");
        assert_eq!(p.receiver, 4);
        let on = |q: Vec3| p.plane.truncate().dot(q) + p.plane.w;
        assert!(on(Vec3::new(0.3, -1.0, 0.7)).abs() < 1e-6, "{:?}", p.plane);
        assert!((p.plane.truncate().length() - 1.0).abs() < 1e-6);
        let ball = crate::model::Object {
            mesh: std::sync::Arc::new(crate::primitives::uv_sphere(8, 8, 1.0)),
            ..floor
        };
        assert_eq!(ShadowPlane::of_object(0, &ball), None);
    }
}
