//! The depth image (`Renderer::render_with_depth`): eye-space depth from
//! the tiles' depth buffers, against depths computed by hand, in both
//! depth encodings, perspective and orthographic, for any tiling.

use std::sync::Arc;

use glam::Vec3;
use zline_pipeline::{render_depth, DepthImage, RenderOptions};
use zline_scene::{DepthMode, Mesh, Projection, Scene, Visibility};
use zline_shading::Material;

use crate::support::{mesh, object, scene, square};

const SIZE: u32 = 32;

fn unlit() -> Material {
    Material { ka: Vec3::splat(0.5), kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::default() }
}

/// A quadrilateral in the plane z_eye = −3 + slope·x_eye, corners at
/// x = −6 and x = 4 chosen so that (for slope ½) they project onto the
/// 1/256-pixel grid exactly in both test cameras: the depth plane is then
/// the plane's own, not one through snapped corners.
fn tilted(slope: f32) -> Arc<Mesh> {
    let z = |x: f32| -3.0 + slope * x;
    let p = vec![
        Vec3::new(-6.0, -6.0, z(-6.0)),
        Vec3::new(4.0, -4.0, z(4.0)),
        Vec3::new(4.0, 4.0, z(4.0)),
        Vec3::new(-6.0, 6.0, z(-6.0)),
    ];
    let n = Vec3::new(-slope, 0.0, 1.0).normalize();
    mesh(p, vec![n; 4], vec![[0, 1, 2], [0, 2, 3]], unlit())
}

fn depth_of(s: &Scene) -> DepthImage {
    let (image, depth, _) = render_depth(s, &RenderOptions::default());
    assert_eq!((depth.width, depth.height), (image.width, image.height));
    // Asking for the depth changes nothing in the image.
    assert_eq!(image, zline_pipeline::render(s, &RenderOptions::default()).0);
    depth
}

/// Relative error allowed: the depth buffer is f32 (2⁻²⁴ relative in NC
/// depth, amplified by the projection's slope near the far plane), read
/// back in f64.
fn close(got: f32, want: f64, tolerance: f64) -> bool {
    (f64::from(got) - want).abs() <= tolerance * want
}

#[test]
fn a_plane_facing_the_camera_is_at_its_distance() {
    for mode in [DepthMode::Normalized, DepthMode::ReversedFloat] {
        for ortho in [false, true] {
            let mut s =
                scene(SIZE, Vec3::ONE, vec![], vec![object(square(0.0, 0.0, 1.0, -3.0, unlit()), None)]);
            s.settings.depth = mode;
            if ortho {
                s.camera.projection = Projection::Orthographic { height: 4.0, near: 0.5, far: 10.0 };
            }
            let d = depth_of(&s);
            // The square spans x_eye ±1: window x 10.67..21.33 in the 90°
            // view (half-width 3 at distance 3), 8..24 in the orthographic
            // one (half-width 2).
            let covered = |x: u32| if ortho { (8..24).contains(&x) } else { (11..21).contains(&x) };
            for x in 0..SIZE {
                let v = d.at(x, 16);
                if covered(x) {
                    assert!(close(v, 3.0, 1e-5), "{mode:?} ortho {ortho}: ({x}, 16) = {v}");
                } else {
                    assert!(v.is_nan(), "{mode:?} ortho {ortho}: ({x}, 16) = {v}");
                }
            }
            let (grey, range) = d.to_gray16();
            let range = range.unwrap();
            assert!(close(range.near, 3.0, 1e-5) && close(range.far, 3.0, 1e-5));
            assert_eq!(grey[16 * SIZE as usize + 16], 65535);
            assert_eq!(grey[0], 0);
        }
    }
}

#[test]
fn a_tilted_plane_has_its_linear_depth() {
    let slope = 0.5f64;
    for mode in [DepthMode::Normalized, DepthMode::ReversedFloat] {
        // Perspective, 90°: pixel (i, j)'s ray is t·(u, v, −1) with
        // u = (i + ½)/16 − 1; it meets z = −3 + slope·x at depth
        // t = 3/(1 + slope·u).
        let mut s = scene(SIZE, Vec3::ONE, vec![], vec![object(tilted(slope as f32), None)]);
        s.settings.depth = mode;
        let d = depth_of(&s);
        for i in 0..SIZE {
            let u = (f64::from(i) + 0.5) / 16.0 - 1.0;
            let want = 3.0 / (1.0 + slope * u);
            for j in [0, 9, 31] {
                assert!(close(d.at(i, j), want, 1e-5), "{mode:?}: ({i}, {j}) = {}, want {want}", d.at(i, j));
            }
        }
        // Orthographic, view height 4: x_eye = ((i + ½)/16 − 1)·2, depth 3 − slope·x.
        s.camera.projection = Projection::Orthographic { height: 4.0, near: 0.5, far: 10.0 };
        let d = depth_of(&s);
        for i in 0..SIZE {
            let x = ((f64::from(i) + 0.5) / 16.0 - 1.0) * 2.0;
            let want = 3.0 - slope * x;
            assert!(close(d.at(i, 5), want, 1e-5), "{mode:?} ortho: ({i}, 5) = {}, want {want}", d.at(i, 5));
        }
        // The mapping: nearest 65535, farthest 1, linear between.
        let (grey, range) = d.to_gray16();
        let r = range.unwrap();
        let at = |i: u32| grey[5 * SIZE as usize + i as usize];
        assert_eq!((at(SIZE - 1), at(0)), (65535, 1));
        let mid = 1.0
            + ((f64::from(r.far) - f64::from(d.at(16, 5))) / f64::from(r.far - r.near) * 65534.0 + 0.5)
                .floor();
        assert_eq!(f64::from(at(16)), mid);
    }
}

#[test]
fn supersampling_keeps_the_nearest_sample() {
    // A square at depth 2 whose right edge (x_eye = 1/32, window x 16.25)
    // cuts pixel 16 (4×4 samples) over one at depth 4: pixel 16 holds
    // both and shows the nearer.
    let near = square(-1.0 + 0.03125, 0.0, 1.0, -2.0, unlit());
    let far = square(2.0, 0.0, 4.0, -4.0, unlit());
    let mut s = scene(SIZE, Vec3::ONE, vec![], vec![object(near, None), object(far, None)]);
    s.settings.ssaa = 4;
    let d = depth_of(&s);
    assert!(close(d.at(16, 16), 2.0, 1e-5), "{}", d.at(16, 16));
    assert!(close(d.at(17, 16), 4.0, 1e-5), "{}", d.at(17, 16));
}

#[test]
fn the_painter_gives_the_z_buffer_depth() {
    let objects = vec![object(square(0.3, 0.0, 1.0, -2.0, unlit()), None), object(tilted(0.25), None)];
    let mut s = scene(SIZE, Vec3::ONE, vec![], objects);
    let z = depth_of(&s);
    s.settings.visibility = Visibility::Painter;
    let p = depth_of(&s);
    assert_eq!(bits(&z), bits(&p));
}

fn bits(d: &DepthImage) -> Vec<u32> {
    d.depth.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn threads_and_tiles_do_not_change_it() {
    let mut s = zline_scenes::demo_scene();
    (s.settings.width, s.settings.height) = (90, 61);
    for (ssaa, depth) in [(1, DepthMode::Normalized), (3, DepthMode::ReversedFloat)] {
        s.settings.ssaa = ssaa;
        s.settings.depth = depth;
        let reference = render_depth(&s, &RenderOptions::default()).1;
        assert!(reference.depth.iter().any(|d| !d.is_nan()));
        for (threads, tile_size) in [(1, 8), (3, 16), (2, 1000)] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let d = pool.install(|| render_depth(&s, &RenderOptions { tile_size }).1);
            assert_eq!(bits(&d), bits(&reference), "threads {threads}, tile {tile_size}");
        }
    }
}
