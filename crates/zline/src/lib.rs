//! zline: a CPU renderer for the classical pipeline — transforms to
//! normalized coordinates, clipping, scan conversion with edge tables, the
//! z-buffer, the basic lighting model and flat/Gouraud/Phong shading.
//!
//! This crate is the front end: the `zline` binary and a facade that
//! re-exports the layers below, so a program can depend on `zline` alone:
//!
//! ```no_run
//! let scene = zline::scenes::demo_scene();
//! let (image, _stats) = zline::pipeline::render(&scene, &Default::default());
//! zline::save_png(&image, std::path::Path::new("demo.png")).unwrap();
//! ```

use std::path::Path;

pub use zline_io as io;
pub use zline_pipeline as pipeline;
pub use zline_raster as raster;
pub use zline_scene as scene;
pub use zline_scenes as scenes;
pub use zline_shading as shading;

/// Writes an image as an 8-bit RGB PNG.
///
/// Compression is the `png` crate's fast mode (fdeflate) with adaptive row
/// filters: the 1920×1080 bunny thumbnail encodes in about 4 ms to 297 KB,
/// where the default mode takes about 72 ms for 260 KB (BENCHMARKS.md).
pub fn save_png(image: &pipeline::Image, path: &Path) -> Result<(), image::ImageError> {
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    use image::ImageEncoder;
    let file = std::fs::File::create(path).map_err(image::ImageError::IoError)?;
    let mut out = std::io::BufWriter::new(file);
    PngEncoder::new_with_quality(&mut out, CompressionType::Fast, FilterType::Adaptive).write_image(
        &image.to_rgb(),
        image.width,
        image.height,
        image::ExtendedColorType::Rgb8,
    )?;
    std::io::Write::flush(&mut out).map_err(image::ImageError::IoError)
}
