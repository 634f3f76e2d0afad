//! Perspective-correct against screen-linear interpolation (SPEC §6), and
//! the orthographic projection (SPEC §1), checked against values computed
//! here from the definitions.
//!
//! A triangle receding from z = −1.5 to z = −6 is Gouraud-shaded with a
//! directional light along −z and a grey kd, so each vertex colour is the
//! scalar N·L of its normal. At every pixel well inside the triangle the
//! expected colour is Σ bᵢ·cᵢ with barycentrics bᵢ taken either on the
//! triangle in eye space, where the pixel's viewing ray meets it
//! (perspective-correct), or in window space (screen-linear).

use glam::{DVec2, DVec3, Vec3};
use zline_scene::{Interpolation, Projection};
use zline_shading::{Light, Material, ShadingMode};

use crate::support::{draw, mesh, object, scene};

const SIZE: u32 = 81;
const TRI: [[f64; 3]; 3] = [[-2.0, -1.5, -1.5], [2.0, -1.5, -1.5], [0.0, 1.2, -6.0]];
const NORMALS: [[f64; 3]; 3] = [[0.0, 0.0, 1.0], [0.9, 0.0, 0.6], [0.0, 0.8, 0.3]];

fn unit(n: [f64; 3]) -> DVec3 {
    DVec3::from_array(n).normalize()
}

/// Barycentrics of `p` in the 2D triangle `t`.
fn barycentric(t: [DVec2; 3], p: DVec2) -> [f64; 3] {
    let cross = |a: DVec2, b: DVec2| a.x * b.y - a.y * b.x;
    let area = cross(t[1] - t[0], t[2] - t[0]);
    let b1 = cross(p - t[0], t[2] - t[0]) / area;
    let b2 = cross(t[1] - t[0], p - t[0]) / area;
    [1.0 - b1 - b2, b1, b2]
}

/// The window position of an eye-space point (fovy 90°, aspect 1).
fn window(p: DVec3) -> DVec2 {
    let s = f64::from(SIZE);
    DVec2::new((p.x / -p.z + 1.0) * 0.5 * s, (1.0 - p.y / -p.z) * 0.5 * s)
}

/// Expected colour at pixel (i, j), or None near an edge.
fn expected(i: u32, j: u32, perspective: bool) -> Option<f64> {
    let t = TRI.map(DVec3::from_array);
    let c = NORMALS.map(|n| unit(n).z); // N·L with L = +z
    let centre = DVec2::new(f64::from(i) + 0.5, f64::from(j) + 0.5);
    let screen = barycentric(t.map(window), centre);
    if screen.iter().any(|&b| b < 0.02) {
        return None;
    }
    let b = if perspective {
        // b_eye ∝ b_screen / w, w = −z (SPEC §6: interpolate a/w and 1/w).
        let q = [0, 1, 2].map(|k| screen[k] / -t[k].z);
        let sum: f64 = q.iter().sum();
        q.map(|v| v / sum)
    } else {
        screen
    };
    Some(b[0] * c[0] + b[1] * c[1] + b[2] * c[2])
}

fn render(interpolation: Interpolation) -> zline_pipeline::Image {
    let m = Material {
        ka: Vec3::ZERO,
        kd: Vec3::ONE,
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity: 1.0,
        ..Material::default()
    };
    let positions = TRI.map(|p| DVec3::from_array(p).as_vec3()).to_vec();
    let normals = NORMALS.map(|n| unit(n).as_vec3()).to_vec();
    let light = Light::Directional { direction: Vec3::NEG_Z, color: Vec3::ONE };
    let mut s = scene(
        SIZE,
        Vec3::ZERO,
        vec![light],
        vec![object(mesh(positions, normals, vec![[0, 1, 2]], m), None)],
    );
    s.settings.shading = ShadingMode::Gouraud;
    s.settings.interpolation = interpolation;
    s.camera.projection = Projection::Perspective { fovy_degrees: 90.0, near: 0.5, far: 20.0 };
    draw(&s)
}

#[track_caller]
fn check_mode(interpolation: Interpolation) {
    let perspective = interpolation == Interpolation::PerspectiveCorrect;
    let image = render(interpolation);
    let mut judged = 0;
    for j in 0..SIZE {
        for i in 0..SIZE {
            let Some(want) = expected(i, j, perspective) else { continue };
            let scaled = want * 255.0 + 0.5;
            if (scaled - scaled.round()).abs() < 0.01 {
                continue; // within f32 error of a rounding boundary: either byte is right
            }
            judged += 1;
            let q = scaled.floor() as u8;
            assert_eq!(image.pixel(i, j), [q, q, q], "{interpolation:?} at ({i}, {j}): expected {want}");
        }
    }
    assert!(judged > 300, "only {judged} pixels judged");
}

#[test]
fn perspective_correct_gouraud_matches_eye_space_barycentrics() {
    check_mode(Interpolation::PerspectiveCorrect);
}

#[test]
fn screen_linear_gouraud_matches_window_barycentrics() {
    check_mode(Interpolation::ScreenLinear);
}

#[test]
fn the_two_modes_differ_visibly_on_a_receding_triangle() {
    let (a, b) = (render(Interpolation::PerspectiveCorrect), render(Interpolation::ScreenLinear));
    let most = (0..SIZE * SIZE)
        .map(|k| {
            let (p, q) = (a.pixel(k % SIZE, k / SIZE), b.pixel(k % SIZE, k / SIZE));
            (i32::from(p[0]) - i32::from(q[0])).abs()
        })
        .max()
        .unwrap_or(0);
    assert!(most >= 10, "largest difference between the modes is only {most} levels");
}

#[test]
fn orthographic_square_covers_exactly_its_pixels() {
    // Height 4 across 64 pixels: the square |x|, |y| ≤ 1 covers pixel
    // centres 16.5 … 47.5 in both directions — 32 × 32 pixels.
    let m = Material {
        ka: Vec3::ONE,
        kd: Vec3::ZERO,
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity: 1.0,
        ..Material::default()
    };
    let mut s =
        scene(64, Vec3::ONE, vec![], vec![object(crate::support::square(0.0, 0.0, 1.0, -3.0, m), None)]);
    s.camera.projection = Projection::Orthographic { height: 4.0, near: 1.0, far: 10.0 };
    let image = draw(&s);
    let lit: Vec<(u32, u32)> = (0..64 * 64)
        .map(|k| (k % 64, k / 64))
        .filter(|&(x, y)| image.pixel(x, y) == [255, 255, 255])
        .collect();
    assert_eq!(lit.len(), 32 * 32);
    assert!(lit.iter().all(|&(x, y)| (16..48).contains(&x) && (16..48).contains(&y)));
}
