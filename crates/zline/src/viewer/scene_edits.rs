//! Edits of the viewer's scene that need none of its state: the step
//! mode's truncation, the untextured objects of `T`, the fog of `F`, and
//! the zoom's measure.

use std::sync::Arc;

use glam::Vec3;
use zline_scene::{Camera, Fog, FogCoordinate, FogMode, Object, Projection, Scene};

/// Keeps the first `step` triangles of `scene` in draw order (all for
/// `None`).
pub(super) fn truncate(scene: &mut Scene, step: Option<usize>) {
    let Some(mut left) = step else { return };
    for object in &mut scene.objects {
        let keep = left.min(object.mesh.triangles.len());
        if keep < object.mesh.triangles.len() {
            let mut mesh = (*object.mesh).clone();
            mesh.triangles.truncate(keep);
            object.mesh = Arc::new(mesh);
        }
        left -= keep;
    }
}

/// How much `camera` magnifies against `home`: the ratio of their eye
/// distances (perspective) or view heights (orthographic).
pub fn magnification(camera: &Camera, home: &Camera) -> f32 {
    match (camera.projection, home.projection) {
        (Projection::Orthographic { height, .. }, Projection::Orthographic { height: home, .. }) => {
            home / height
        }
        _ => (home.eye - home.target).length() / (camera.eye - camera.target).length(),
    }
}

/// The objects with no diffuse map (their meshes copied once).
pub(super) fn untextured(objects: &[Object]) -> Vec<Object> {
    objects
        .iter()
        .map(|o| {
            let mesh = if o.mesh.diffuse_map.is_some() {
                Arc::new(zline_scene::Mesh { diffuse_map: None, ..(*o.mesh).clone() })
            } else {
                o.mesh.clone()
            };
            Object { mesh, ..o.clone() }
        })
        .collect()
}

/// A linear fog in the background's colour for a scene without one: clear
/// at the near side of the scene's bounding sphere seen from the home eye,
/// full two radii behind its far side.
pub(super) fn fitted_fog(scene: &Scene) -> Fog {
    let (mut min, mut max) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for o in &scene.objects {
        for p in &o.mesh.positions {
            let w = o.world_from_object.transform_point3(*p);
            if w.is_finite() {
                (min, max) = (min.min(w), max.max(w));
            }
        }
    }
    let (center, radius) = ((min + max) / 2.0, (max - min).length() / 2.0);
    let d = (scene.camera.eye - center).length();
    let (start, end) = ((d - radius).max(0.0), d + 3.0 * radius);
    let mode = if start.is_finite() && end.is_finite() && start < end {
        FogMode::Linear { start, end }
    } else {
        FogMode::Exponential { density: 0.1 }
    };
    Fog { mode, color: scene.background, coordinate: FogCoordinate::EyePlane }
}
