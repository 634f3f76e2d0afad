//! Triangles crossing the near plane: clipped in clip space, and the pixels
//! drawn are exactly those whose viewing ray meets the triangle between the
//! near and far planes (no stray pixels from vertices behind the eye).

use glam::{DVec3, Vec3};
use zline_shading::{Material, ShadingMode};

use crate::support::{draw, mesh, object, scene};

const SIZE: u32 = 80;
const NEAR: f64 = 0.5;
const FAR: f64 = 10.0;
/// Pixels whose ray passes within this barycentric (or depth) margin of the
/// triangle's boundary are not judged: snapping to 1/256 px and f32 clipping
/// may move the boundary by that much.
const MARGIN: f64 = 2e-3;

/// What the ray through pixel (i, j) hits: Some(true) inside, Some(false)
/// outside, None too close to call.
fn oracle(tri: &[DVec3; 3], i: u32, j: u32) -> Option<bool> {
    let x = (f64::from(i) + 0.5) / f64::from(SIZE) * 2.0 - 1.0;
    let y = 1.0 - (f64::from(j) + 0.5) / f64::from(SIZE) * 2.0;
    let dir = DVec3::new(x, y, -1.0); // fovy 90°, aspect 1
    let (e1, e2) = (tri[1] - tri[0], tri[2] - tri[0]);
    let n = e1.cross(e2);
    let denom = n.dot(dir);
    if denom.abs() < 1e-12 {
        return Some(false);
    }
    let t = n.dot(tri[0]) / denom;
    let p = dir * t;
    let depth = -p.z;
    let area = n.length_squared();
    let b1 = (p - tri[0]).cross(e2).dot(n) / area;
    let b2 = e1.cross(p - tri[0]).dot(n) / area;
    let b = [1.0 - b1 - b2, b1, b2];
    let inside = t > 0.0 && b.iter().all(|&v| v > 0.0) && depth > NEAR && depth < FAR;
    let margin = b.iter().map(|v| v.abs()).fold(f64::INFINITY, f64::min).min((depth - NEAR).abs() / NEAR);
    if margin < MARGIN {
        None
    } else {
        Some(inside)
    }
}

#[track_caller]
fn check_clipped(tri: [DVec3; 3]) {
    let white = Material {
        ka: Vec3::ONE,
        kd: Vec3::ZERO,
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity: 1.0,
        ..Material::default()
    };
    let p = tri.map(|v| v.as_vec3()).to_vec();
    let mut o = object(mesh(p, vec![Vec3::Z; 3], vec![[0, 1, 2]], white), Some(ShadingMode::Flat));
    o.cull_back_faces = false;
    let mut s = scene(SIZE, Vec3::ONE, vec![], vec![o]);
    s.camera = crate::support::origin_camera(NEAR as f32, FAR as f32);
    let image = draw(&s);
    let (mut judged, mut drawn) = (0, 0);
    for j in 0..SIZE {
        for i in 0..SIZE {
            let got = image.pixel(i, j) == [255, 255, 255];
            assert!(got || image.pixel(i, j) == [0, 0, 0], "pixel ({i}, {j}) is neither lit nor background");
            drawn += usize::from(got);
            if let Some(want) = oracle(&tri, i, j) {
                judged += 1;
                assert_eq!(got, want, "pixel ({i}, {j}): drawn {got}, ray says {want}");
            }
        }
    }
    assert!(judged > (SIZE * SIZE) as usize * 9 / 10, "too few pixels judged: {judged}");
    assert!(drawn > 100, "the visible part was not drawn ({drawn} pixels)");
}

#[test]
fn triangle_with_a_vertex_behind_the_eye_draws_only_its_visible_part() {
    check_clipped([DVec3::new(-1.0, -1.0, -3.0), DVec3::new(1.5, -0.8, -3.0), DVec3::new(0.2, 4.0, 1.0)]);
}

#[test]
fn triangle_with_a_vertex_on_the_eye_plane_w_zero() {
    check_clipped([DVec3::new(-1.0, -1.0, -3.0), DVec3::new(1.5, -0.8, -3.0), DVec3::new(0.2, 0.6, 0.0)]);
}

#[test]
fn triangle_crossing_near_and_far_planes() {
    check_clipped([DVec3::new(-3.0, -1.0, -12.0), DVec3::new(2.0, -1.0, -12.0), DVec3::new(0.0, 0.2, -0.2)]);
}

#[test]
fn triangle_entirely_behind_the_eye_draws_nothing() {
    let white = Material {
        ka: Vec3::ONE,
        kd: Vec3::ZERO,
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity: 1.0,
        ..Material::default()
    };
    let p = vec![Vec3::new(-1.0, -1.0, 3.0), Vec3::new(1.0, -1.0, 3.0), Vec3::new(0.0, 1.0, 3.0)];
    let mut o = object(mesh(p, vec![Vec3::Z; 3], vec![[0, 1, 2]], white), None);
    o.cull_back_faces = false;
    let image = draw(&scene(SIZE, Vec3::ONE, vec![], vec![o]));
    assert!((0..SIZE * SIZE).all(|i| image.pixel(i % SIZE, i / SIZE) == [0, 0, 0]));
}

#[test]
fn non_finite_and_huge_vertices_never_panic() {
    let white = Material {
        ka: Vec3::ONE,
        kd: Vec3::ZERO,
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity: 1.0,
        ..Material::default()
    };
    let p = vec![
        Vec3::new(f32::NAN, 0.0, -2.0),
        Vec3::new(1.0, 0.0, -2.0),
        Vec3::new(0.0, 1.0, -2.0),
        Vec3::new(1e30, -1e30, -2.0),
        Vec3::new(f32::INFINITY, 1.0, -1.0),
        Vec3::new(-1e6, 1e6, -3.0),
    ];
    let tris = vec![[0, 1, 2], [3, 1, 2], [4, 1, 2], [5, 1, 2], [3, 5, 1]];
    for mode in ShadingMode::ALL {
        let mut o = object(mesh(p.clone(), vec![Vec3::Z; 6], tris.clone(), white), Some(mode));
        o.cull_back_faces = false;
        let image = draw(&scene(SIZE, Vec3::ONE, vec![], vec![o]));
        assert_eq!(image.pixels.len(), (SIZE * SIZE) as usize);
    }
}
