//! The repository's example scene must always load, so it never rots.

use std::sync::Arc;

use zline_io::{load_scene_with_options, LoadOptions};
use zline_scene::{Projection, ShadingMode};

use crate::repo;

#[test]
fn example_scene_loads() {
    // The example's models are in assets/, outside its folder.
    let options = LoadOptions { allow_outside: true };
    let scene =
        load_scene_with_options(&repo("examples/scene.toml"), options).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((scene.settings.width, scene.settings.height), (960, 540));
    assert_eq!(scene.lights.len(), 2);
    // plane, spot, cube, suzanne, sphere, torus: one mesh each.
    let names: Vec<&str> = scene.objects.iter().map(|o| o.mesh.name.as_str()).collect();
    assert_eq!(names.len(), 6, "{names:?}");
    assert_eq!(scene.objects[3].shading, Some(ShadingMode::Gouraud));
    assert!(!scene.objects[3].cull_back_faces);
    assert_eq!(scene.objects[4].material().opacity, 0.5);
    assert!(!scene.objects[4].cull_back_faces, "transparent objects are not culled");
    assert!(matches!(scene.camera.projection, Projection::Perspective { near: 2.0, .. }));
    // Every object's bounding box lies in the view volume.
    let aspect = 960.0 / 540.0;
    let clip_from_world = scene.camera.clip_from_eye(aspect) * scene.camera.eye_from_world();
    for o in &scene.objects[1..] {
        for &p in &o.mesh.positions {
            let nc = clip_from_world.project_point3(o.world_from_object.transform_point3(p));
            assert!(nc.abs().max_element() < 1.0, "{} out of view at {nc}", o.mesh.name);
        }
    }
    assert!(!Arc::ptr_eq(&scene.objects[1].mesh, &scene.objects[3].mesh));
}
