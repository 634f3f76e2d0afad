//! The painter's algorithm (`Visibility::Painter`): the z-buffer's image
//! where nothing overlaps, the same image for any tile size and thread
//! count, and wrong exactly where the geometry says it must be.

use glam::{DMat4, DVec2, DVec3, Vec3};
use zline_pipeline::{render, RenderOptions};
use zline_scene::{Camera, Fog, FogCoordinate, FogMode, Projection, Scene, Visibility};
use zline_shading::{Light, Material, ShadingMode};

use crate::support::{draw, mesh, object, scene, square};

fn material(ke: Vec3, opacity: f32) -> Material {
    Material {
        ke,
        ka: Vec3::ZERO,
        kd: Vec3::ZERO,
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity,
        model: Default::default(),
        ..Material::DEFAULT
    }
}

fn painted(mut s: Scene) -> (zline_pipeline::Image, zline_pipeline::Image) {
    let zbuffer = draw(&s);
    s.settings.visibility = Visibility::Painter;
    (draw(&s), zbuffer)
}

#[test]
fn without_overlaps_the_painter_paints_the_z_buffer_s_image() {
    let lit =
        Material { ke: Vec3::ZERO, ka: Vec3::splat(0.3), kd: Vec3::new(0.8, 0.5, 0.3), ..Material::DEFAULT };
    let glass = Material { opacity: 0.4, ..lit };
    let objects = vec![
        object(square(-1.2, 0.0, 0.5, -3.0, lit), Some(ShadingMode::Phong)),
        object(square(0.0, 1.0, 0.4, -4.0, lit), Some(ShadingMode::Gouraud)),
        object(square(1.2, 0.0, 0.5, -2.5, glass), Some(ShadingMode::Flat)),
    ];
    let light = Light::Directional { direction: Vec3::new(-0.2, -0.3, -1.0), color: Vec3::ONE };
    let mut s = scene(64, Vec3::splat(0.2), vec![light], objects);
    s.background = Vec3::new(0.1, 0.2, 0.3);
    let (p, z) = painted(s.clone());
    assert!(p == z, "no overlaps: the painter's image must be the z-buffer's");
    s.fog = Some(Fog {
        mode: FogMode::Linear { start: 1.0, end: 6.0 },
        color: Vec3::splat(0.7),
        coordinate: FogCoordinate::EyePlane,
    });
    let (p, z) = painted(s);
    assert!(p == z, "with fog, painted per primitive, the same as the fog pass");
}

#[test]
fn the_painter_gives_one_image_for_any_tile_size_and_thread_count() {
    let mut s = zline_scenes::demo_scene();
    (s.settings.width, s.settings.height) = (120, 72);
    s.settings.visibility = Visibility::Painter;
    let reference = render(&s, &RenderOptions { tile_size: 64 }).0;
    let zbuffer = Scene {
        settings: zline_scene::RenderSettings { visibility: Visibility::ZBuffer, ..s.settings },
        ..s.clone()
    };
    assert!(
        reference != render(&zbuffer, &RenderOptions { tile_size: 64 }).0,
        "the demo's overlaps come out differently"
    );
    for tile_size in [1, 7, 33, 1000] {
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let image = pool.install(|| render(&s, &RenderOptions { tile_size }).0);
            assert!(image == reference, "tile {tile_size}, {threads} threads differ");
        }
    }
}

/// Window position (pixels) and NC depth of a world point.
fn project(m: &DMat4, p: DVec3, size: f64) -> DVec3 {
    let c = *m * p.extend(1.0);
    DVec3::new((c.x / c.w + 1.0) * 0.5 * size, (1.0 - c.y / c.w) * 0.5 * size, c.z / c.w)
}

/// For a pixel centre: inside the triangle, its depth there, and its
/// distance in pixels to the nearest edge.
fn at(t: &[DVec3; 3], q: DVec2) -> (bool, f64, f64) {
    let edge = |a: DVec3, b: DVec3| {
        let (a, b) = (a.truncate(), b.truncate());
        (b - a).perp_dot(q - a) / (b - a).length()
    };
    let e = [edge(t[0], t[1]), edge(t[1], t[2]), edge(t[2], t[0])];
    let inside = e.iter().all(|&v| v > 0.0) || e.iter().all(|&v| v < 0.0);
    let area = (t[1] - t[0]).truncate().perp_dot((t[2] - t[0]).truncate());
    let (u, v) = (
        (t[2] - t[1]).truncate().perp_dot(q - t[1].truncate()) / area,
        (t[0] - t[2]).truncate().perp_dot(q - t[2].truncate()) / area,
    );
    let z = u * t[0].z + v * t[1].z + (1.0 - u - v) * t[2].z;
    (inside, z, e.iter().map(|v| v.abs()).fold(f64::INFINITY, f64::min))
}

/// Two intersecting triangles, orthographic: A, tilted, reaches farther
/// (larger farthest NC depth), so it is painted first and B covers it
/// wherever they overlap. The z-buffer shows A where it is nearer. So the
/// pixels where the two images differ are exactly those whose centre lies
/// in both triangles with A nearer than B, computed here in f64 from the
/// geometry; a pixel whose centre is within 1 pixel of an edge of either
/// triangle or of their intersection line may go either way (the pipeline
/// snaps vertices to 1/256 pixel and sets up in f32).
#[test]
fn intersecting_triangles_fail_exactly_where_the_later_one_covers_the_nearer_part() {
    let size = 96u32;
    let a = [Vec3::new(-1.2, 0.9, -0.8), Vec3::new(0.0, -1.3, 1.0), Vec3::new(1.2, 0.9, -0.8)];
    let b = [Vec3::new(-1.3, -1.0, 0.0), Vec3::new(1.3, -1.0, 0.0), Vec3::new(0.0, 1.3, 0.0)];
    let tri = |v: [Vec3; 3], ke: Vec3| {
        let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
        let mut o =
            object(mesh(v.to_vec(), vec![n; 3], vec![[0, 1, 2]], material(ke, 1.0)), Some(ShadingMode::Flat));
        o.cull_back_faces = false;
        o
    };
    let mut s = scene(
        size,
        Vec3::ZERO,
        vec![],
        vec![tri(a, Vec3::new(1.0, 0.0, 0.0)), tri(b, Vec3::new(0.0, 0.0, 1.0))],
    );
    s.camera = Camera {
        eye: Vec3::new(0.0, 0.0, 5.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        projection: Projection::Orthographic { height: 3.0, near: 1.0, far: 10.0 },
    };
    let m = (s.camera.clip_from_eye(1.0) * s.camera.eye_from_world()).as_dmat4();
    let pa = a.map(|p| project(&m, p.as_dvec3(), f64::from(size)));
    let pb = b.map(|p| project(&m, p.as_dvec3(), f64::from(size)));
    assert!(pa.iter().map(|p| p.z).fold(f64::MIN, f64::max) > pb[0].z, "A is keyed farther: painted first");
    let (painter, zbuffer) = painted(s);
    let (mut predicted, mut agreed, mut uncertain) = (0, 0, 0);
    for y in 0..size {
        for x in 0..size {
            let q = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
            let ((in_a, za, ea), (in_b, zb, eb)) = (at(&pa, q), at(&pb, q));
            // Distance to the intersection line: |za − zb| over the slope of za − zb.
            let slope = {
                let d =
                    |dx: f64, dy: f64| at(&pa, q + DVec2::new(dx, dy)).1 - at(&pb, q + DVec2::new(dx, dy)).1;
                DVec2::new(d(1.0, 0.0) - (za - zb), d(0.0, 1.0) - (za - zb)).length()
            };
            let to_line = (za - zb).abs() / slope;
            if ea < 1.0 || eb < 1.0 || (in_a && in_b && to_line < 1.0) {
                uncertain += 1;
                continue;
            }
            let wrong = in_a && in_b && za < zb;
            let differs = painter.pixel(x, y) != zbuffer.pixel(x, y);
            assert_eq!(differs, wrong, "pixel ({x}, {y}): predicted wrong = {wrong}");
            predicted += usize::from(wrong);
            agreed += 1;
        }
    }
    assert!(predicted > 200, "the case must have wrong pixels to predict, got {predicted}");
    assert!(uncertain * 5 < agreed, "too many pixels near edges: {uncertain} of {}", agreed + uncertain);
}
