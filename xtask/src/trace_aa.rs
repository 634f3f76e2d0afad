//! The ray tracer's anti-aliasing measured (`cargo xtask trace-report`):
//! regular n × n grids and adaptive supersampling against a 16 × 16
//! reference, in display values (the scene's tone mapping, clamped to
//! [0, 1]), with rays a pixel, RMSE, the worst pixel, and the rays the
//! regular grid needs for the same RMSE.

use anyhow::Result;
use glam::Vec3;
use zline::scene::Scene;
use zline::trace::antialias::Adaptive;
use zline::trace::{render, TraceOptions, Traced};

/// White triangles on black whose pixels are areas.
fn flat(triangles: &[[(f32, f32); 3]], size: u32) -> Scene {
    zline::scenes::coverage_scene(triangles, size)
}

fn cases() -> Vec<(&'static str, Scene)> {
    let edges = flat(
        &[
            [(-0.9, -0.9), (0.7, -0.6), (-0.2, 0.8)],
            [(0.3, 0.95), (0.95, 0.9), (0.96, 0.6)],
            [(-0.95, 0.85), (-0.05, 0.87), (-0.95, 0.97)],
            [(0.6, -0.95), (0.72, -0.95), (0.8, 0.6)],
        ],
        96,
    );
    // Features of a third of a pixel to about a pixel at 24 × 24.
    let small = flat(
        &[
            [(-0.95, 0.5), (-0.05, 0.52), (-0.95, 0.53)],
            [(0.5, -0.2), (0.58, -0.18), (0.51, -0.12)],
            [(-0.5, -0.9), (-0.45, -0.9), (-0.3, 0.2)],
            [(0.1, 0.1), (0.18, 0.12), (0.13, 0.2)],
        ],
        24,
    );
    let mut whitted = zline::scenes::whitted_scene();
    whitted.settings.width = 320;
    whitted.settings.height = 240;
    vec![("edges, 96×96", edges), ("sub-pixel features, 24×24", small), ("Whitted scene, 320×240", whitted)]
}

/// Display values of a traced image.
fn display(scene: &Scene, t: &Traced) -> Vec<Vec3> {
    t.pixels.iter().map(|&c| scene.settings.tone_mapping.apply(c).clamp(Vec3::ZERO, Vec3::ONE)).collect()
}

/// RMSE over pixels and channels, and the worst pixel (error, x, y).
fn error(a: &[Vec3], b: &[Vec3], width: u32) -> (f64, (f32, u32, u32)) {
    let mut sum = 0.0;
    let mut worst = (0.0f32, 0, 0);
    for (i, (p, q)) in a.iter().zip(b).enumerate() {
        let d = *p - *q;
        sum += f64::from(d.length_squared());
        let e = d.abs().max_element();
        if e > worst.0 {
            worst = (e, i as u32 % width, i as u32 / width);
        }
    }
    ((sum / (3 * a.len()) as f64).sqrt(), worst)
}

pub(crate) fn run() -> Result<()> {
    println!("## Ray-traced anti-aliasing against a 16×16 reference\n");
    println!("Display values (0–1). \"grid rays at equal RMSE\": the camera rays a pixel the regular grid needs for the same RMSE, interpolated between the n×n grids that bracket it.\n");
    println!(
        "| scene | sampling | camera rays/pixel | RMSE | worst pixel | grid rays at equal RMSE | ratio |"
    );
    println!("|---|---|---:|---:|---|---:|---:|");
    for (name, scene) in cases() {
        let trace = |o: TraceOptions| {
            let t = render(&scene, &o);
            let rays = t.work.primary.rays as f64 / t.pixels.len() as f64;
            (display(&scene, &t), rays)
        };
        let uniform = |n| TraceOptions { samples: n, ..TraceOptions::default() };
        let (reference, _) = trace(uniform(16));
        let w = scene.settings.width;
        let mut grid: Vec<(f64, f64)> = Vec::new();
        for n in 1..=8 {
            let (img, rays) = trace(uniform(n));
            let (rmse, worst) = error(&img, &reference, w);
            grid.push((rays, rmse));
            println!(
                "| {name} | {n}×{n} grid | {rays:.2} | {rmse:.4} | {:.3} at ({}, {}) | | |",
                worst.0, worst.1, worst.2
            );
        }
        for (depth, threshold) in
            [1, 2, 3, 4].into_iter().flat_map(|d| [(d, 1.0 / 16.0), (d, 0.125), (d, 0.25)])
        {
            let a = Adaptive { depth, threshold };
            let (img, rays) = trace(TraceOptions { adaptive: Some(a), ..TraceOptions::default() });
            let (rmse, worst) = error(&img, &reference, w);
            let (equal, ratio) = match equal_rmse(&grid, rmse) {
                Some(g) => (format!("{g:.1}"), format!("{:.2}", rays / g)),
                None => ("beyond 8×8".into(), "—".into()),
            };
            println!(
                "| {name} | adaptive, depth {depth}, threshold {:.4} | {rays:.2} | {rmse:.4} | {:.3} at ({}, {}) | {equal} | {ratio} |",
                a.threshold, worst.0, worst.1, worst.2
            );
        }
    }
    println!();
    Ok(())
}

/// The grid's rays a pixel at `rmse`: log-linear between the first grid
/// at or below it and the one before; None when no grid reaches it; the
/// 1×1 grid's rays when that one already does.
fn equal_rmse(grid: &[(f64, f64)], rmse: f64) -> Option<f64> {
    let i = grid.iter().position(|&(_, e)| e <= rmse)?;
    if i == 0 {
        return Some(grid[0].0);
    }
    let ((r0, e0), (r1, e1)) = (grid[i - 1], grid[i]);
    if e0 <= e1 {
        return Some(r1);
    }
    let f = (e0.ln() - rmse.ln()) / (e0.ln() - e1.ln());
    Some((r0.ln() + f * (r1.ln() - r0.ln())).exp())
}
