//! The normals image (`Renderer::render_normals_into`): eye-space shading
//! normals encoded (n + 1)/2, against normals known by construction.

use std::sync::Arc;

use glam::{DVec3, Mat4, Vec3};
use zline_pipeline::{render_normals, Image, RenderOptions};
use zline_scene::{Camera, Object, Projection, Scene};
use zline_shading::{Light, Material, ShadingMode};

use crate::support::{mesh, object, scene, square};

const SIZE: u32 = 32;

fn normals(s: &Scene) -> Image {
    render_normals(s, &RenderOptions::default()).0
}

/// SPEC §10 of (n + 1)/2 for a normal known in f64.
fn encoded(n: DVec3) -> [u8; 3] {
    ((n + DVec3::ONE) * 0.5).to_array().map(|c| (c.clamp(0.0, 1.0) * 255.0 + 0.5).floor() as u8)
}

fn lit(objects: Vec<Object>) -> Scene {
    lit_sized(SIZE, objects)
}

fn lit_sized(size: u32, objects: Vec<Object>) -> Scene {
    let light = Light::Directional { direction: Vec3::new(-0.3, -0.5, -1.0), color: Vec3::ONE };
    let mut s = scene(size, Vec3::splat(0.2), vec![light], objects);
    s.background = Vec3::new(0.2, 0.4, 0.6);
    s
}

#[test]
fn a_sphere_faces_the_camera_at_its_centre() {
    let sphere = Arc::new(zline_scene::uv_sphere(48, 96, 1.0));
    // Gouraud: drawn with Phong's planes all the same. An odd size puts
    // the centre pixel's sample on the axis.
    let world = Mat4::from_translation(Vec3::new(0.0, 0.0, -2.5));
    let shading = Some(ShadingMode::Gouraud);
    let o = Object { mesh: sphere, world_from_object: world, material: None, shading, cull_back_faces: true };
    let image = normals(&lit_sized(33, vec![o]));
    let c = image.pixel(16, 16);
    for (k, want) in [128u8, 128, 255].into_iter().enumerate() {
        assert!(c[k].abs_diff(want) <= 1, "centre {c:?}");
    }
    // The background is black; to the right of the centre x grows.
    assert_eq!(image.pixel(0, 0), [0, 0, 0]);
    let right = image.pixel(20, 16);
    assert!(right[0] > 150 && right[1].abs_diff(128) <= 2, "{right:?}");
    let up = image.pixel(16, 12);
    assert!(up[1] > 150 && up[0].abs_diff(128) <= 2, "{up:?}");
}

#[test]
fn a_plane_facing_the_camera_gives_its_encoded_normal() {
    let image = normals(&lit(vec![object(square(0.0, 0.0, 1.0, -2.0, Material::default()), None)]));
    for (x, y) in [(16, 16), (10, 12), (21, 21)] {
        assert_eq!(image.pixel(x, y), [128, 128, 255], "({x}, {y})");
    }
    // A tilted plane, normal (0.28, 0, 0.96) (eye space is world space:
    // the camera sits at the origin looking down −z), vertex normals and
    // face normal alike.
    let n = Vec3::new(0.28, 0.0, 0.96);
    let p = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y): (f32, f32)| Vec3::new(x * 0.96, y, -2.0 - 0.28 * x))
        .to_vec();
    let tilted = mesh(p, vec![n; 4], vec![[0, 1, 2], [0, 2, 3]], Material::default());
    for shading in [ShadingMode::Phong, ShadingMode::Gouraud, ShadingMode::Flat] {
        let image = normals(&lit(vec![object(tilted.clone(), Some(shading))]));
        assert_eq!(image.pixel(16, 16), encoded(DVec3::new(0.28, 0.0, 0.96)), "{shading:?}");
    }
}

#[test]
fn a_flat_cube_face_gives_its_face_normal() {
    // A cube turned 30° about y, seen along −z: its +z face's normal is
    // (sin 30°, 0, cos 30°) whatever the vertex normals say.
    let mut cube = zline_scene::cube(2.0);
    cube.normals = vec![Vec3::Y; cube.positions.len()];
    let world = Mat4::from_translation(Vec3::new(0.0, 0.0, -5.0)) * Mat4::from_rotation_y(30f32.to_radians());
    let shading = Some(ShadingMode::Flat);
    let o = Object {
        mesh: Arc::new(cube),
        world_from_object: world,
        material: None,
        shading,
        cull_back_faces: true,
    };
    let image = normals(&lit(vec![o]));
    let a = 30f64.to_radians();
    // The +z face covers window x 14.4..20.7 of row 16, the −x face,
    // turned to the left, 11.9..14.4 with normal (−cos 30°, 0, sin 30°).
    assert_eq!(image.pixel(17, 16), encoded(DVec3::new(a.sin(), 0.0, a.cos())));
    assert_eq!(image.pixel(13, 16), encoded(DVec3::new(-a.cos(), 0.0, a.sin())));
}

#[test]
fn a_back_face_seen_faces_the_viewer() {
    // A square facing away (normal −z), drawn without culling.
    let p = [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)].map(|(x, y)| Vec3::new(x, y, -2.0)).to_vec();
    let back = mesh(p, vec![Vec3::NEG_Z; 4], vec![[0, 1, 2], [0, 2, 3]], Material::default());
    for shading in [ShadingMode::Phong, ShadingMode::Flat] {
        let mut o = object(back.clone(), Some(shading));
        o.cull_back_faces = false;
        let mut s = lit(vec![o]);
        s.settings.lighting_sides = zline_scene::LightingSides::OneSided; // the normals frame ignores it
        assert_eq!(normals(&s).pixel(16, 16), [128, 128, 255], "{shading:?}");
    }
}

#[test]
fn fog_transparency_and_textures_play_no_part() {
    let glass = Material { opacity: 0.3, ..Material::default() };
    let mut s = lit(vec![object(square(0.0, 0.0, 1.0, -2.0, glass), None)]);
    s.fog = Some(zline_scene::Fog {
        mode: zline_scene::FogMode::Linear { start: 0.0, end: 3.0 },
        color: Vec3::ONE,
        coordinate: zline_scene::FogCoordinate::EyePlane,
    });
    let image = normals(&s);
    assert_eq!(image.pixel(16, 16), [128, 128, 255]);
    assert!(!image.transparent);
    s.settings.transparent_background = true;
    let image = normals(&s);
    assert!(image.transparent);
    assert_eq!((image.alpha(16, 16), image.alpha(0, 0)), (255, 0));
    // Eye space: the camera turned 90° about y (looking down −x from
    // +x) sees a square facing +x as facing it.
    let p =
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(z, y)| Vec3::new(-2.0, y, -z)).to_vec();
    let facing_x = mesh(p, vec![Vec3::X; 4], vec![[0, 1, 2], [0, 2, 3]], Material::default());
    let mut s = lit(vec![object(facing_x, None)]);
    s.camera = Camera {
        eye: Vec3::ZERO,
        target: Vec3::NEG_X,
        up: Vec3::Y,
        projection: Projection::Perspective { fovy_degrees: 90.0, near: 0.5, far: 10.0 },
    };
    assert_eq!(normals(&s).pixel(16, 16), [128, 128, 255]);
}

#[test]
fn threads_and_tiles_do_not_change_it() {
    let mut s = zline_scenes::demo_scene();
    (s.settings.width, s.settings.height) = (90, 61);
    s.settings.ssaa = 2;
    let reference = normals(&s);
    for (threads, tile_size) in [(1, 8), (3, 16)] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let image = pool.install(|| render_normals(&s, &RenderOptions { tile_size }).0);
        assert!(image == reference, "threads {threads}, tile {tile_size}");
    }
}
