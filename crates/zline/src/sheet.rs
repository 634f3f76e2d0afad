//! `--views LIST`: one contact sheet of named views of a scene, each cell
//! the image size, its name under it (`zline::views`).

use anyhow::{bail, Context, Result};
use rayon::ThreadPool;
use zline::pipeline::RenderOptions;
use zline::scene::{Scene, MAX_IMAGE_SIDE};
use zline::views::{contact_sheet, NamedView};

use crate::cli::common::Common;
use crate::flags::aim;

/// Renders `scene` (its camera not yet aimed; `framed` as judged on
/// loading) from each of `views` with the rasterizer and writes the sheet
/// to `--output`.
pub(crate) fn write(
    scene: &Scene,
    common: &Common,
    views: &[NamedView],
    framed: bool,
    pool: &ThreadPool,
    options: &RenderOptions,
) -> Result<()> {
    let columns = (views.len() as f64).sqrt().ceil() as usize;
    let rows = views.len().div_ceil(columns.max(1));
    let (w, h) = (scene.settings.width as usize, scene.settings.height as usize);
    if columns * (w + 4) + 4 > MAX_IMAGE_SIDE as usize || rows * (h + 28) + 4 > MAX_IMAGE_SIDE as usize {
        bail!("{} views of {w}x{h} make a sheet wider or taller than {MAX_IMAGE_SIDE} pixels: give a smaller --size", views.len());
    }
    let start = std::time::Instant::now();
    let cells: Vec<(String, zline::pipeline::Image)> = views
        .iter()
        .map(|&view| {
            let mut aimed = scene.clone();
            aim(&mut aimed, common, Some(view), framed, 0.0);
            let (image, _) = pool.install(|| zline::pipeline::render(&aimed, options));
            (view.name().to_string(), image)
        })
        .collect();
    let sheet = contact_sheet(&cells, columns);
    zline::save_image(&sheet, &common.output)
        .with_context(|| format!("{}: cannot write the image", common.output.display()))?;
    let names: Vec<&str> = views.iter().map(|v| v.name()).collect();
    eprintln!(
        "wrote {} ({}x{}, {} views: {}, {:.2} ms)",
        common.output.display(),
        sheet.width,
        sheet.height,
        views.len(),
        names.join(", "),
        start.elapsed().as_secs_f64() * 1e3
    );
    Ok(())
}
