//! Regular and adaptive supersampling (SPEC §12) on scenes whose pixel
//! colours are areas: white emissive triangles on a black background, so
//! a pixel's exact value is the share of it the triangles cover.

use glam::Vec3;
use zline_scene::Scene;
use zline_trace::antialias::Adaptive;
use zline_trace::{render, TraceOptions, Traced};

/// White triangles on black whose pixels are areas (`zline-scenes`).
fn scene(triangles: &[[(f32, f32); 3]], size: u32) -> Scene {
    zline_scenes::coverage_scene(triangles, size)
}

/// Edges: long slanted ones, near-horizontal and near-vertical ones, and
/// corners sharper than a pixel.
fn edges() -> Scene {
    scene(
        &[
            [(-0.9, -0.9), (0.7, -0.6), (-0.2, 0.8)],
            [(0.3, 0.95), (0.95, 0.9), (0.96, 0.6)],
            [(-0.95, 0.85), (-0.05, 0.87), (-0.95, 0.97)],
            [(0.6, -0.95), (0.72, -0.95), (0.8, 0.6)],
        ],
        96,
    )
}

fn with(options: TraceOptions) -> impl Fn(&Scene) -> Traced {
    move |s| render(s, &options)
}

fn uniform(n: u32) -> impl Fn(&Scene) -> Traced {
    with(TraceOptions { samples: n, ..TraceOptions::default() })
}

fn adaptive(depth: u32, threshold: f32) -> impl Fn(&Scene) -> Traced {
    with(TraceOptions { adaptive: Some(Adaptive { depth, threshold }), ..TraceOptions::default() })
}

/// The root mean square difference of the red channel.
fn rmse(a: &Traced, b: &Traced) -> f64 {
    let sum: f64 = a.pixels.iter().zip(&b.pixels).map(|(p, q)| f64::from(p.x - q.x).powi(2)).sum();
    (sum / a.pixels.len() as f64).sqrt()
}

fn rays_per_pixel(t: &Traced) -> f64 {
    t.work.primary.rays as f64 / t.pixels.len() as f64
}

/// Where nothing differs, adaptive sampling traces each corner once and
/// one centre a pixel, and returns the colour exactly.
#[test]
fn a_flat_image_costs_corners_and_centres() {
    let s = scene(&[[(-5.0, -5.0), (5.0, -5.0), (0.0, 5.0)]], 10);
    let t = adaptive(4, 0.0)(&s);
    assert_eq!(t.work.primary.rays, 11 * 11 + 10 * 10);
    assert!(t.pixels.iter().all(|&p| p == Vec3::ONE), "{:?}", t.pixels);
}

/// A vertical edge 0.3 of the way across a pixel: a leaf square that
/// straddles it counts half (two corners on each side), so at depth d the
/// error is at most half a column of width 2^−d.
#[test]
fn an_edge_converges_with_the_depth() {
    // The middle pixel of 5 spans x ∈ [−0.2, 0.2] of the view; the edge
    // x = −0.08 leaves 0.7 of it covered.
    let s = scene(&[[(-0.08, -5.0), (5.0, -5.0), (-0.08, 5.0)]], 5);
    for depth in 1..=4 {
        let t = adaptive(depth, 0.1)(&s);
        let mid = t.pixels[2 * 5 + 2].x;
        let bound = 0.5f32.powi(depth as i32 + 1);
        assert!((mid - 0.7).abs() <= bound + 1e-6, "depth {depth}: {mid}");
        assert_eq!(t.pixels[2 * 5], Vec3::ZERO);
        assert_eq!(t.pixels[2 * 5 + 4], Vec3::ONE);
    }
}

/// A sliver narrower than a pixel that no corner sees is found by the
/// centre ray and refined.
#[test]
fn a_sliver_between_the_corners_is_not_missed() {
    // A horizontal band 0.05 high through the middle row of a 5-pixel
    // image (rows 0.4 apart): no pixel corner lies in it.
    let s = scene(
        &[[(-5.0, -0.025), (5.0, -0.025), (5.0, 0.025)], [(-5.0, -0.025), (5.0, 0.025), (-5.0, 0.025)]],
        5,
    );
    let t = adaptive(3, 0.05)(&s);
    let truth = 0.05 / 0.4;
    for x in 0..5 {
        let p = t.pixels[2 * 5 + x].x;
        assert!(p > 0.0 && (p - truth).abs() < 0.07, "pixel ({x}, 2): {p} against {truth}");
    }
}

/// The course's claim, measured on edges: at most a third of the rays of
/// the regular 4 × 4 grid for no larger error against a 16 × 16
/// reference. (Features smaller than a pixel can fall between the samples
/// and be missed: `cargo xtask trace-report` measures those too.)
#[test]
fn adaptive_matches_the_regular_grid_with_a_third_of_the_rays() {
    let s = edges();
    let reference = uniform(16)(&s);
    let grid = uniform(4)(&s);
    let a = adaptive(3, 1.0 / 16.0)(&s);
    let (e_grid, e_a) = (rmse(&grid, &reference), rmse(&a, &reference));
    let (r_grid, r_a) = (rays_per_pixel(&grid), rays_per_pixel(&a));
    assert!(e_a <= e_grid, "adaptive RMSE {e_a} against the 4×4 grid's {e_grid}");
    assert!(r_a * 3.0 <= r_grid, "adaptive {r_a} rays a pixel against the 4×4 grid's {r_grid}");
}

/// The image and the ray count do not depend on the number of threads.
#[test]
fn threads_do_not_change_the_adaptive_image() {
    let mut s = edges();
    s.settings.width = 32;
    s.settings.height = 32;
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| adaptive(3, 0.05)(&s))
    };
    let (one, three) = (run(1), run(3));
    assert_eq!(one.pixels, three.pixels);
    assert_eq!(one.work, three.work);
}

/// Out-of-range adaptive settings are clamped with a warning.
#[test]
fn adaptive_settings_are_checked() {
    let bad = TraceOptions {
        samples: 4,
        adaptive: Some(Adaptive { depth: 1_000_000_000, threshold: f32::NAN }),
        ..TraceOptions::default()
    };
    let (o, warnings) = bad.checked();
    assert_eq!(o.adaptive, Some(Adaptive { depth: 4, threshold: Adaptive::default().threshold }));
    assert_eq!(o.samples, 1);
    assert_eq!(warnings.len(), 3, "{warnings:?}");
}
