//! The ray tracer against its f64 truth and beside the rasterizer
//! (`cargo xtask trace-report`): per scene the ray tracer's time, rays a
//! pixel and tree depth, its 8-bit error against `zline-truth`'s
//! `WhittedTruth` on the pixels away from silhouettes and on all pixels,
//! and how far the rasterized frame of the same scene is from it.

use std::time::Instant;

use anyhow::Result;
use zline::scene::trace_options::TraceOptions;
use zline::scene::Scene;
use zline_truth::WhittedTruth;

/// The largest channel difference of every pixel, in 8-bit steps.
fn steps(a: &[u8], b: &[u8]) -> Vec<i32> {
    a.chunks(3)
        .zip(b.chunks(3))
        .map(|(p, q)| (0..3).map(|k| (i32::from(p[k]) - i32::from(q[k])).abs()).max().unwrap_or(0))
        .collect()
}

fn share(steps: &[i32], keep: impl Fn(usize) -> bool, most: i32) -> f64 {
    let (mut kept, mut within) = (0usize, 0usize);
    for (_, &d) in steps.iter().enumerate().filter(|(i, _)| keep(*i)) {
        kept += 1;
        within += usize::from(d <= most);
    }
    100.0 * within as f64 / kept.max(1) as f64
}

pub(crate) fn run(width: u32) -> Result<()> {
    println!("## Against the f64 truth, beside the rasterizer\n");
    println!(
        "{width} pixels wide, one ray a pixel, the default tree (depth 8, weight 1/512, filtered shadow rays), 2 threads. \"Away from silhouettes\": pixels whose tree (the objects hit by every node, their faces and texels, each light's path) equals all their neighbours'.\n"
    );
    println!("| scene | ray tracer | rays/pixel | tree depth | truth | away from silhouettes | within 1 step there | within 1 step, all pixels | worst | rasterized frame within 1 step of the truth |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let scenes: [(&str, Scene); 3] = [
        ("Whitted scene", zline::scenes::whitted_scene()),
        ("demo", zline::scenes::demo_scene()),
        ("room", zline::scenes::room_scene()),
    ];
    for (name, mut scene) in scenes {
        let aspect = scene.settings.height as f32 / scene.settings.width as f32;
        scene.settings.width = width;
        scene.settings.height = ((width as f32 * aspect).round() as u32).max(1);
        let options = TraceOptions::default();
        let started = Instant::now();
        let (image, traced) = zline::ray_traced_image(&scene, &options);
        let fast_time = started.elapsed();
        let started = Instant::now();
        let truth = WhittedTruth::new(&scene, &options).render(true);
        let truth_time = started.elapsed();
        let reference = truth.image.quantized_rgb8();
        let mask = truth.away_from_silhouettes().unwrap_or_default();
        let fast = steps(&image.to_rgb(), &reference);
        let (raster, _) = zline::pipeline::render(&scene, &zline::pipeline::RenderOptions::default());
        let rasterized = steps(&raster.to_rgb(), &reference);
        let w = traced.work;
        let pixels = fast.len().max(1) as f64;
        let masked = mask.iter().filter(|&&m| m).count();
        println!(
            "| {name} | {:.0} ms | {:.2} | {} | {:.2} s | {:.1} % | {:.3} % | {:.3} % | {} steps | {:.1} % |",
            fast_time.as_secs_f64() * 1e3,
            (w.primary.rays + w.secondary.rays + w.shadow.rays) as f64 / pixels,
            w.depth,
            truth_time.as_secs_f64(),
            100.0 * masked as f64 / pixels,
            share(&fast, |i| mask.get(i).copied().unwrap_or(false), 1),
            share(&fast, |_| true, 1),
            fast.iter().max().copied().unwrap_or(0),
            share(&rasterized, |_| true, 1),
        );
    }
    println!();
    Ok(())
}
