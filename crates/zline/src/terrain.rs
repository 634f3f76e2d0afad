//! `zline terrain`: an elevation file (greyscale PNG or ESRI ASCII grid)
//! rendered as a lit, fogged landscape, its grid simplified to a
//! screen-space error bound (`zline::scenes::terrain`).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use anyhow::{anyhow, Result};
use clap::Args;
use zline::scene::{Scene, TextureMap};
use zline::scenes::terrain::{terrain_scene, ErrorPyramid, Surface, DEFAULT_TERRAIN_ERROR};
use zline::shading::Sampler;

/// The image size when `--size` is not given.
pub(crate) const DEFAULT_TERRAIN_SIZE: (u32, u32) = (1280, 720);

/// The options of `zline terrain` besides the common ones.
#[derive(Args)]
pub(crate) struct TerrainArgs {
    /// A PNG or JPEG image draped over the whole terrain (its top edge on
    /// the north edge), instead of the height colour ramp.
    #[arg(long, value_name = "FILE")]
    texture: Option<PathBuf>,
    /// Spacing between samples in world units (default: a PNG's 1, an
    /// .asc file's cellsize).
    #[arg(long, value_name = "UNITS", value_parser = positive)]
    cell_size: Option<f32>,
    /// Heights are multiplied by this (default: for a PNG, whose samples
    /// read as 0 to 1, a quarter of the terrain's width, so that white is a
    /// mountain a quarter as high as the map is wide; for an .asc file 1,
    /// its own units).
    #[arg(long, value_name = "FACTOR", value_parser = positive)]
    height_scale: Option<f32>,
    /// The simplified mesh's largest vertical error, projected to the
    /// screen, in pixels; 0 draws the full grid.
    #[arg(long, value_name = "PIXELS", default_value_t = DEFAULT_TERRAIN_ERROR, value_parser = non_negative)]
    terrain_error: f32,
    /// No fog (by default a linear fog in the sky's colour fades the far
    /// side of the terrain); `--fog` replaces the default fog's mode.
    #[arg(long)]
    no_fog: bool,
}

fn positive(s: &str) -> Result<f32, String> {
    s.trim()
        .parse::<f32>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(|| format!("expected a finite number greater than 0, got '{s}'"))
}

fn non_negative(s: &str) -> Result<f32, String> {
    s.trim()
        .parse::<f32>()
        .ok()
        .filter(|v| v.is_finite() && *v >= 0.0)
        .ok_or_else(|| format!("expected a finite number of pixels, 0 or more, got '{s}'"))
}

/// The terrain scene of `heights` for an image of `size` (or
/// [`DEFAULT_TERRAIN_SIZE`]); prints the triangles drawn against the full
/// grid's, and the time of each step, on stderr.
pub(crate) fn scene(heights: &Path, args: &TerrainArgs, size: Option<(u32, u32)>) -> Result<Scene> {
    let start = Instant::now();
    let named = |e: zline::scene::HeightFieldError| anyhow!("{}: {e}", heights.display());
    let field = zline::io::load_heightfield(heights)?;
    let field = match args.cell_size {
        Some(cell) => field.with_cell_size(cell).map_err(named)?,
        None => field,
    };
    let is_png = heights.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"));
    let width = (field.columns().max(field.rows()) - 1) as f32 * field.cell_size();
    let scale = args.height_scale.unwrap_or(if is_png { width / 4.0 } else { 1.0 });
    let field = if scale == 1.0 { field } else { field.scaled(scale).map_err(named)? };
    // The camera stands a few widths away and squares distances: keep
    // every coordinate far inside f32.
    let (lo, hi) = field.range();
    let extent = width.max(hi.abs()).max(lo.abs());
    if extent.is_nan() || extent > 1e15 {
        return Err(anyhow!(
            "{}: the terrain spans {extent:e} units (cell size × samples, or heights × --height-scale); \
             keep it below 1e15",
            heights.display()
        ));
    }
    let surface = match &args.texture {
        Some(path) => Surface::Texture(TextureMap {
            texture: Arc::new(zline::io::load_texture(path)?),
            sampler: Sampler::default(),
            alpha_blend: false,
            alpha_cutoff: None,
        }),
        None => Surface::HeightRamp,
    };
    let loaded = start.elapsed();
    let pyramid_start = Instant::now();
    let pyramid = ErrorPyramid::new(&field);
    let pyramid_time = pyramid_start.elapsed();
    let mesh_start = Instant::now();
    let size = size.unwrap_or(DEFAULT_TERRAIN_SIZE);
    let (scene, stats) = terrain_scene(&field, &pyramid, &surface, size, args.terrain_error, !args.no_fog)
        .map_err(|e| anyhow!("{}: {e}", heights.display()))?;
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    eprintln!(
        "terrain: {}x{} samples; {} triangles drawn of the full grid's {} ({:.2} %) at {} px error; \
         load {:.1} ms, error pyramid {:.1} ms, mesh {:.1} ms",
        field.columns(),
        field.rows(),
        stats.triangles,
        stats.full_grid_triangles,
        100.0 * stats.triangles as f64 / stats.full_grid_triangles as f64,
        args.terrain_error,
        ms(loaded),
        ms(pyramid_time),
        ms(mesh_start.elapsed()),
    );
    Ok(scene)
}
