//! The report's renderers section: the Cornell box drawn by the z-buffer
//! pipeline, the Whitted ray tracer and radiosity, each timed (fastest of
//! three), with the differences between them as numbers and as images
//! (`docs/images/report-renderers.png`: the three pictures, then
//! |raster − ray traced| and |radiosity − ray traced| times 4).
//!
//! The three answer different questions: the rasterizer and the ray
//! tracer light by the area light's 4 × 4 point lights (direct light,
//! shadows; no light between surfaces), radiosity by the emitting ceiling
//! quad and every diffuse bounce (colour bleeding), its display scaled
//! (SPEC §13). The differences show what each model adds, not errors.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result};
use image::RgbImage;

/// The side of each picture.
const SIDE: u32 = 256;

/// Fastest of three runs of `f`, and its last result.
fn fastest<T>(mut f: impl FnMut() -> Result<T>) -> Result<(f64, T)> {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..3 {
        let start = Instant::now();
        let out = f()?;
        best = best.min(start.elapsed().as_secs_f64());
        last = Some(out);
    }
    Ok((best * 1e3, last.expect("three runs")))
}

pub(crate) fn section(image_path: &Path) -> Result<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask lives in the workspace");
    let mut scene = zline::io::load_scene(&root.join("assets/cornell/cornell_box.toml"))?;
    (scene.settings.width, scene.settings.height) = (SIDE, SIDE);
    let rgb = |image: &zline::pipeline::Image| image.to_rgb();
    let (raster_ms, raster) = fastest(|| Ok(rgb(&zline::pipeline::render(&scene, &Default::default()).0)))?;
    let (trace_ms, traced) = fastest(|| Ok(rgb(&zline::ray_traced_image(&scene, &scene.settings.trace).0)))?;
    let options = zline::radiosity::Options { patch_size: Some(50.0), ..scene.settings.radiosity };
    let mut patches = 0;
    let (radiosity_ms, radiosity) = fastest(|| {
        let solution = zline::radiosity::solve(&scene, &options)?;
        patches = solution.patches.patches.len();
        Ok(rgb(&zline::pipeline::render(&solution.display_scene(&scene), &Default::default()).0))
    })?;
    let rmse = |a: &[u8], b: &[u8]| {
        let sum: f64 = a.iter().zip(b).map(|(&x, &y)| (f64::from(x) - f64::from(y)).powi(2)).sum();
        (sum / a.len() as f64).sqrt()
    };
    let diff = |a: &[u8], b: &[u8]| -> Vec<u8> {
        a.iter().zip(b).map(|(&x, &y)| (u16::from(x.abs_diff(y)) * 4).min(255) as u8).collect()
    };
    let panels = [
        raster.clone(),
        traced.clone(),
        radiosity.clone(),
        diff(&raster, &traced),
        diff(&radiosity, &traced),
    ];
    let mut strip = RgbImage::new(SIDE * panels.len() as u32, SIDE);
    for (k, panel) in panels.iter().enumerate() {
        let image = RgbImage::from_raw(SIDE, SIDE, panel.clone()).context("panel size")?;
        image::imageops::replace(&mut strip, &image, i64::from(SIDE) * k as i64, 0);
    }
    if let Some(dir) = image_path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    strip.save(image_path).with_context(|| format!("writing {}", image_path.display()))?;
    let mut md = String::from("## One scene, three renderers\n\n");
    let _ = writeln!(
        md,
        "The Cornell box (`assets/cornell`, {SIDE}×{SIDE}): the z-buffer pipeline and the Whitted ray tracer light it by its area light's 4 × 4 point lights; radiosity by its emitting ceiling quad and every diffuse bounce ({patches} patches, progressive refinement to 10⁻³), its display scaled (SPEC §13). Fastest of three; RMSE in 8-bit steps against the ray-traced picture. Left to right in `{}`: raster, ray traced, radiosity, |raster − ray traced| × 4, |radiosity − ray traced| × 4.\n",
        image_path.display()
    );
    let _ = writeln!(md, "| renderer | time | RMSE vs ray traced |");
    let _ = writeln!(md, "|---|---:|---:|");
    let _ = writeln!(
        md,
        "| raster (flat shading, area light) | {raster_ms:.1} ms | {:.1} |",
        rmse(&raster, &traced)
    );
    let _ = writeln!(md, "| ray traced (Whitted) | {trace_ms:.1} ms | 0 |");
    let _ = writeln!(
        md,
        "| radiosity (solve + one frame) | {radiosity_ms:.0} ms | {:.1} |\n",
        rmse(&radiosity, &traced)
    );
    Ok(md)
}
