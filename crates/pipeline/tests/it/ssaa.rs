//! Supersampling (`RenderSettings::ssaa`): n×n ordered sample grids,
//! box-filtered, with answers computed by hand; and the same bytes for any
//! tiling and thread count.

use glam::{DVec3, Vec3};
use zline_pipeline::{render, RenderOptions};
use zline_scene::Scene;
use zline_shading::{Material, ShadingMode};

use crate::support::{draw, mesh, object, quantize_robust, scene};

const KA: Vec3 = Vec3::new(0.61, 0.23, 0.41);
const BACKGROUND: Vec3 = Vec3::new(0.12, 0.33, 0.87);

/// An ambient-only rectangle at z = −1 spanning x ∈ [x0, x1], y ∈ [y0, y1]
/// in front of the origin camera (90° field of view, so at z = −1 the
/// window coordinate of x is (x + 1)·size/2).
fn rect_scene(size: u32, [x0, x1, y0, y1]: [f32; 4], ssaa: u32) -> Scene {
    let p = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)].map(|(x, y)| Vec3::new(x, y, -1.0)).to_vec();
    let material = Material { ka: KA, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::DEFAULT };
    let m = mesh(p, vec![Vec3::Z; 4], vec![[0, 1, 2], [0, 2, 3]], material);
    let mut s = scene(size, Vec3::ONE, Vec::new(), vec![object(m, Some(ShadingMode::Flat))]);
    s.background = BACKGROUND;
    s.settings.ssaa = ssaa;
    s
}

fn mean(parts: &[(f64, Vec3)]) -> DVec3 {
    parts.iter().map(|&(w, c)| c.as_dvec3() * w).sum()
}

#[test]
fn an_edge_through_the_middle_of_a_pixel_averages_surface_and_background() {
    // size 64: x_win = (x + 1)·32. The right edge at x = 17/64 lies at
    // x_win = 40.5, halfway across pixel 40: for n = 2 and n = 4 exactly
    // half of its sample columns (centres at 40 + (a + ½)/n) are inside.
    for n in [2, 4] {
        let image = draw(&rect_scene(64, [-2.0, 17.0 / 64.0, -2.0, 2.0], n));
        let half = quantize_robust(mean(&[(0.5, KA), (0.5, BACKGROUND)]));
        let (inside, outside) = (quantize_robust(KA.as_dvec3()), quantize_robust(BACKGROUND.as_dvec3()));
        for y in [0, 17, 63] {
            assert_eq!(image.pixel(39, y), inside, "n = {n}, row {y}");
            assert_eq!(image.pixel(40, y), half, "n = {n}, row {y}");
            assert_eq!(image.pixel(41, y), outside, "n = {n}, row {y}");
        }
    }
}

#[test]
fn a_corner_covers_the_share_of_samples_it_contains() {
    // The corner at window (40.5, 20.25) with y_win = (1 − y)·32: y = 47/128.
    // n = 2: pixel (40, 20) has sample columns 40.25 | 40.75 and rows
    // 20.25 | 20.75; the rectangle (x < 40.5, y_win > 20.25) holds 40.25 in
    // x and 20.75 in y (20.25 lies on the top edge, which the top-left rule
    // includes), so 2 of 4 samples. n = 4: columns 40.125, 40.375 of four;
    // rows 20.125 (outside), 20.375, 20.625, 20.875: 2 × 3 = 6 of 16.
    for (n, covered) in [(2, 2.0 / 4.0), (4, 6.0 / 16.0)] {
        let image = draw(&rect_scene(64, [-2.0, 17.0 / 64.0, -2.0, 47.0 / 128.0], n));
        let want = quantize_robust(mean(&[(covered, KA), (1.0 - covered, BACKGROUND)]));
        assert_eq!(image.pixel(40, 20), want, "n = {n}");
    }
}

#[test]
fn one_sample_per_pixel_is_the_plain_render() {
    let mut s = rect_scene(48, [-0.3, 0.41, -0.7, 0.2], 1);
    let plain = draw(&s);
    s.settings.ssaa = 0; // taken as 1
    assert!(draw(&s) == plain);
}

#[test]
fn supersampled_images_do_not_depend_on_tiles_or_threads() {
    let lights = vec![zline_shading::Light::Directional {
        direction: Vec3::new(-0.3, -0.2, -1.0),
        color: Vec3::new(0.8, 0.7, 0.5),
    }];
    for mode in ShadingMode::ALL {
        let mut s = scene(
            67,
            Vec3::splat(0.1),
            lights.clone(),
            vec![object(crate::support::wavy_grid(24, -3.0), Some(mode))],
        );
        s.settings.ssaa = 3;
        let reference = render(&s, &RenderOptions { tile_size: 64 }).0;
        for tile_size in [1, 5, 16] {
            for threads in [1, 2] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let image = pool.install(|| render(&s, &RenderOptions { tile_size }).0);
                assert!(image == reference, "{mode:?}: tile {tile_size}, {threads} threads differ");
            }
        }
    }
}
