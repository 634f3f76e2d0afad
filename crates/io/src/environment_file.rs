//! Environment maps: a Radiance HDR (`.hdr`) equirectangular panorama, or
//! the built-in procedural sky (`sky`), prepared into an
//! [`EnvironmentLight`] (SPEC §5.3).
//!
//! Contract: [`load_environment`] returns the prepared light, or a
//! [`SceneError`] naming the file and the problem (missing, too large, not
//! a Radiance HDR image, corrupt). The pixels are linear RGB radiance as
//! the file stores them; a texel that is not finite or negative becomes 0,
//! with one warning counting them.
//!
//! Limits: the file is read when at most
//! [`MAX_IMAGE_FILE_BYTES`](zline_scene::MAX_IMAGE_FILE_BYTES); its header
//! is read first and a panorama wider or taller than
//! [`MAX_PANORAMA_SIDE`] or of more than [`MAX_PANORAMA_TEXELS`] texels is
//! refused before any pixel is decoded.
//!
//! Preparation (the SH projection and the prefiltered chain, about 0.1–1 s)
//! is kept for the last few environments loaded in the process, so a batch
//! of renders with one environment prepares it once.

use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use glam::Vec3;
use image::{ImageFormat, ImageReader, Limits};
use zline_shading::{EnvironmentLight, Panorama, MAX_PANORAMA_SIDE};

use crate::error::SceneError;
use crate::files::{read_limited, FileKind};

/// The name that selects the procedural sky instead of a file.
pub const SKY_NAME: &str = "sky";

/// The most texels of a panorama (8192 × 4096; 384 MiB as f32 RGB).
pub const MAX_PANORAMA_TEXELS: u64 = 8192 * 4096;

/// Side of the procedural sky's panorama (width; the height is half).
const SKY_WIDTH: u32 = 512;

/// Prepared environments kept for reuse.
const KEPT: usize = 4;

/// What identifies a loaded environment: the file (canonical path, length,
/// modification time), or the sky.
#[derive(Clone, PartialEq, Eq)]
struct Key(PathBuf, u64, Option<std::time::SystemTime>);

static CACHE: Mutex<Vec<(Key, Arc<EnvironmentLight>)>> = Mutex::new(Vec::new());

/// The environment `spec` names: [`SKY_NAME`] for the procedural sky, else
/// a Radiance HDR file. Returns it prepared, with the warnings it raised.
pub fn load_environment(spec: &Path) -> Result<(Arc<EnvironmentLight>, Vec<String>), SceneError> {
    let key = if spec == Path::new(SKY_NAME) {
        Key(PathBuf::from(SKY_NAME), 0, None)
    } else {
        let meta = std::fs::metadata(spec).map_err(|e| SceneError::File {
            path: spec.to_path_buf(),
            message: format!("cannot read environment map: {e}"),
        })?;
        let canonical = spec.canonicalize().unwrap_or_else(|_| spec.to_path_buf());
        Key(canonical, meta.len(), meta.modified().ok())
    };
    if let Some((_, light)) = CACHE.lock().ok().and_then(|c| c.iter().find(|(k, _)| *k == key).cloned()) {
        return Ok((light, Vec::new()));
    }
    let (panorama, warnings) = if key.0 == Path::new(SKY_NAME) {
        (Panorama::sky(SKY_WIDTH, SKY_WIDTH / 2), Vec::new())
    } else {
        read_panorama(spec)?
    };
    let light = Arc::new(EnvironmentLight::new(panorama));
    if let Ok(mut cache) = CACHE.lock() {
        if cache.len() == KEPT {
            cache.remove(0);
        }
        cache.push((key, light.clone()));
    }
    Ok((light, warnings))
}

/// Decodes a Radiance HDR file into a panorama (see the module doc).
pub fn read_panorama(path: &Path) -> Result<(Panorama, Vec<String>), SceneError> {
    let error = |message: String| SceneError::File { path: path.to_path_buf(), message };
    let bytes = read_limited(path, FileKind::Image).map_err(|e| e.into_error(path))?;
    match image::guess_format(&bytes) {
        Ok(ImageFormat::Hdr) => {}
        Ok(other) => {
            let name = other.extensions_str().first().copied().unwrap_or("unknown");
            return Err(error(format!(
                "a '{name}' image is not an environment map: zline reads Radiance HDR (.hdr) panoramas"
            )));
        }
        Err(_) => return Err(error("not a Radiance HDR (.hdr) image".into())),
    }
    let (width, height) = ImageReader::with_format(Cursor::new(&bytes), ImageFormat::Hdr)
        .into_dimensions()
        .map_err(|e| error(format!("cannot decode environment map: {e}")))?;
    let texels = u64::from(width) * u64::from(height);
    if width > MAX_PANORAMA_SIDE || height > MAX_PANORAMA_SIDE || texels > MAX_PANORAMA_TEXELS {
        return Err(error(format!(
            "a {width}x{height} panorama is larger than the limit of {MAX_PANORAMA_TEXELS} texels \
             (8192x4096) and {MAX_PANORAMA_SIDE} per side; not decoded"
        )));
    }
    let mut reader = ImageReader::with_format(Cursor::new(&bytes), ImageFormat::Hdr);
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_PANORAMA_SIDE);
    limits.max_image_height = Some(MAX_PANORAMA_SIDE);
    limits.max_alloc = Some(MAX_PANORAMA_TEXELS * 16);
    reader.limits(limits);
    let rgb =
        reader.decode().map_err(|e| error(format!("cannot decode environment map: {e}")))?.into_rgb32f();
    let texels: Vec<Vec3> = rgb.pixels().map(|p| Vec3::from_array(p.0)).collect();
    let (panorama, replaced) = Panorama::new(rgb.width(), rgb.height(), texels)
        .map_err(|e| error(format!("unusable panorama: {e}")))?;
    let mut warnings = Vec::new();
    if replaced > 0 {
        warnings.push(format!("{}: {replaced} texels not finite or negative; taken as 0", path.display()));
    }
    if width != 2 * height {
        warnings.push(format!(
            "{}: a {width}x{height} panorama is not 2:1; read as equirectangular all the same",
            path.display()
        ));
    }
    Ok((panorama, warnings))
}

/// Writes `panorama` as a Radiance HDR file (for tests and for users who
/// want the procedural sky as a file).
pub fn write_panorama(path: &Path, panorama: &Panorama) -> Result<(), SceneError> {
    let error = |message: String| SceneError::File { path: path.to_path_buf(), message };
    let file = std::fs::File::create(path).map_err(|e| error(format!("cannot create: {e}")))?;
    let pixels: Vec<image::Rgb<f32>> = panorama.texels().iter().map(|t| image::Rgb(t.to_array())).collect();
    image::codecs::hdr::HdrEncoder::new(std::io::BufWriter::new(file))
        .encode(&pixels, panorama.width() as usize, panorama.height() as usize)
        .map_err(|e| error(format!("cannot write Radiance HDR: {e}")))
}
