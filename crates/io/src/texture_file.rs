//! Texture images: PNG and JPEG bytes (a file next to an MTL or glTF file,
//! or bytes embedded in a glTF file) → [`Texture`]s, each file decoded once
//! per load.
//!
//! Contract: [`TextureCache::file`] returns the texture of an image file,
//! `Ok(None)` with one warning when the file cannot be read or holds a
//! format zline does not read (the caller then draws the mesh untextured,
//! the documented fallback of both loaders), and a [`SceneError`] naming the
//! image file when it is a PNG or JPEG that does not decode — a corrupt
//! texture is an error, not something to paper over. [`decode_texture`] does
//! the decoding for bytes that are not a file of their own.
//!
//! The format is recognised from the bytes' signature, or else from the
//! file extension; the pixels become RGBA8, rows top to bottom, used as
//! stored (no sRGB decode, SPEC §7).
//!
//! Limits: an image file is read only when it is a regular file of at most
//! [`MAX_IMAGE_FILE_BYTES`](zline_scene::MAX_IMAGE_FILE_BYTES) (a larger
//! one, a device or a directory is an error, unlike a missing file); the
//! image's header is read first and an image wider or taller than
//! [`MAX_TEXTURE_SIZE`] or of more than [`MAX_TEXTURE_PIXELS`] pixels is
//! refused, with its size and the limit, before any pixel is decoded; so
//! is an image that would bring the pixels decoded in one load (one model
//! file) over [`MAX_TEXTURE_PIXELS_PER_MODEL`].

use std::collections::HashMap;
use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use image::{ImageFormat, ImageReader, Limits};
use zline_scene::{MAX_TEXTURE_PIXELS, MAX_TEXTURE_PIXELS_PER_MODEL};
use zline_shading::{Texture, MAX_TEXTURE_SIZE};

use crate::error::SceneError;
use crate::files::{read_limited, FileKind, ReadError};

/// Why bytes did not become a texture.
#[derive(Debug)]
pub(crate) enum DecodeError {
    /// A format zline does not read (BMP, TGA, …): the caller warns.
    Unsupported(String),
    /// A PNG or JPEG (or unrecognisable bytes) that does not decode, or
    /// an image larger than the limits: the caller fails.
    Corrupt(String),
}

/// Decodes PNG or JPEG bytes; `hint` is the format a file name or MIME
/// type suggests, used when the bytes carry no known signature. `decoded`
/// counts the pixels decoded so far in the load, for
/// [`MAX_TEXTURE_PIXELS_PER_MODEL`].
fn decode_texture(
    bytes: &[u8],
    hint: Option<ImageFormat>,
    decoded: &mut u64,
) -> Result<Texture, DecodeError> {
    let format = image::guess_format(bytes).ok().or(hint);
    match format {
        Some(ImageFormat::Png | ImageFormat::Jpeg) => {}
        Some(other) => {
            let name = other.extensions_str().first().copied().unwrap_or("unknown");
            return Err(DecodeError::Unsupported(format!(
                "'{name}' images are not supported (PNG and JPEG are)"
            )));
        }
        None => return Err(DecodeError::Corrupt("not a PNG or JPEG image".into())),
    }
    let format = format.unwrap_or(ImageFormat::Png);
    let (width, height) = ImageReader::with_format(Cursor::new(bytes), format)
        .into_dimensions()
        .map_err(|e| DecodeError::Corrupt(format!("cannot decode image: {e}")))?;
    check_size(width, height)?;
    let pixels = u64::from(width) * u64::from(height);
    if *decoded + pixels > MAX_TEXTURE_PIXELS_PER_MODEL {
        return Err(DecodeError::Corrupt(format!(
            "image of {width}x{height} pixels would bring the model's textures to {} pixels, more than the \
             limit of {MAX_TEXTURE_PIXELS_PER_MODEL}; not decoded",
            *decoded + pixels
        )));
    }
    let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_TEXTURE_SIZE);
    limits.max_image_height = Some(MAX_TEXTURE_SIZE);
    // 16-bit RGBA, the widest PNG, at the largest size allowed.
    limits.max_alloc = Some(MAX_TEXTURE_PIXELS * 8);
    reader.limits(limits);
    let rgba =
        reader.decode().map_err(|e| DecodeError::Corrupt(format!("cannot decode image: {e}")))?.into_rgba8();
    let texture = Texture::from_rgba8(rgba.width(), rgba.height(), rgba.as_raw())
        .map_err(|e| DecodeError::Corrupt(format!("unusable image: {e}")))?;
    *decoded += pixels;
    Ok(texture)
}

/// Refuses an image larger than the limits of the module doc.
fn check_size(width: u32, height: u32) -> Result<(), DecodeError> {
    let pixels = u64::from(width) * u64::from(height);
    if width > MAX_TEXTURE_SIZE || height > MAX_TEXTURE_SIZE || pixels > MAX_TEXTURE_PIXELS {
        return Err(DecodeError::Corrupt(format!(
            "image of {width}x{height} pixels is larger than the texture limit of {MAX_TEXTURE_PIXELS} \
             pixels (4096x4096) and {MAX_TEXTURE_SIZE} pixels per side; not decoded"
        )));
    }
    Ok(())
}

/// Image files decoded so far in one load, by path, so that a texture
/// shared by many materials is decoded and stored once, and the pixels
/// decoded in all.
#[derive(Default)]
pub(crate) struct TextureCache {
    files: HashMap<PathBuf, Option<Arc<Texture>>>,
    decoded: u64,
}

impl TextureCache {
    /// Decodes bytes that are not a file of their own (an image embedded
    /// in a glTF file), counting their pixels with the load's.
    pub(crate) fn decode(&mut self, bytes: &[u8], hint: Option<ImageFormat>) -> Result<Texture, DecodeError> {
        decode_texture(bytes, hint, &mut self.decoded)
    }

    /// The texture in the image file at `path` (see the module doc):
    /// `Ok(None)` and a warning, given once per file, when it cannot be
    /// used but drawing can go on without it.
    pub(crate) fn file(
        &mut self,
        path: &Path,
        warnings: &mut Vec<String>,
    ) -> Result<Option<Arc<Texture>>, SceneError> {
        if let Some(loaded) = self.files.get(path) {
            return Ok(loaded.clone());
        }
        let loaded = load_file(path, warnings, &mut self.decoded)?.map(Arc::new);
        self.files.insert(path.to_path_buf(), loaded.clone());
        Ok(loaded)
    }
}

fn load_file(
    path: &Path,
    warnings: &mut Vec<String>,
    decoded: &mut u64,
) -> Result<Option<Texture>, SceneError> {
    let fallback = "meshes using it are drawn untextured";
    let bytes = match read_limited(path, FileKind::Image) {
        Ok(bytes) => bytes,
        Err(ReadError::Io(e)) => {
            warnings.push(format!("{}: cannot read texture: {e}; {fallback}", path.display()));
            return Ok(None);
        }
        Err(refused) => return Err(refused.into_error(path)),
    };
    match decode_texture(&bytes, ImageFormat::from_path(path).ok(), decoded) {
        Ok(texture) => Ok(Some(texture)),
        Err(DecodeError::Unsupported(why)) => {
            warnings.push(format!("{}: {why}; {fallback}", path.display()));
            Ok(None)
        }
        Err(DecodeError::Corrupt(message)) => Err(SceneError::File { path: path.to_path_buf(), message }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(bytes: &[u8], hint: Option<ImageFormat>) -> Result<Texture, DecodeError> {
        TextureCache::default().decode(bytes, hint)
    }

    /// A 2 × 1 PNG: red then green.
    fn tiny_png() -> Vec<u8> {
        let image = image::RgbaImage::from_raw(2, 1, vec![255, 0, 0, 255, 0, 255, 0, 255]).unwrap();
        let mut bytes = Vec::new();
        image.write_to(&mut Cursor::new(&mut bytes), ImageFormat::Png).unwrap();
        bytes
    }

    #[test]
    fn png_bytes_decode_to_rgba() {
        let texture = decode(&tiny_png(), None).unwrap();
        assert_eq!((texture.width(), texture.height()), (2, 1));
    }

    #[test]
    fn garbage_is_corrupt_and_other_formats_unsupported() {
        assert!(matches!(decode(b"hello", Some(ImageFormat::Png)), Err(DecodeError::Corrupt(_))));
        assert!(matches!(decode(b"hello", None), Err(DecodeError::Corrupt(_))));
        let truncated = &tiny_png()[..40];
        assert!(matches!(decode(truncated, None), Err(DecodeError::Corrupt(_))));
        // "BM" is the BMP signature.
        assert!(matches!(decode(b"BM\0\0\0\0", None), Err(DecodeError::Unsupported(_))));
    }

    /// A PNG header claiming `width` × `height` pixels, with no pixel data.
    fn png_header(width: u32, height: u32) -> Vec<u8> {
        let mut ihdr = b"IHDR".to_vec();
        ihdr.extend(width.to_be_bytes());
        ihdr.extend(height.to_be_bytes());
        ihdr.extend([8, 6, 0, 0, 0]); // 8-bit RGBA
        let crc = crc32fast::hash(&ihdr);
        let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
        png.extend(13u32.to_be_bytes());
        png.extend(ihdr);
        png.extend(crc.to_be_bytes());
        // An empty IDAT: the decoder reads the header up to the first one.
        png.extend(0u32.to_be_bytes());
        png.extend(b"IDAT");
        png.extend(crc32fast::hash(b"IDAT").to_be_bytes());
        png
    }

    #[test]
    fn images_over_the_pixel_limit_are_refused_from_their_header() {
        for (w, h) in [(12000, 12000), (4097, 4096), (16385, 16), (8192, 8192)] {
            match decode(&png_header(w, h), None) {
                Err(DecodeError::Corrupt(m)) => {
                    assert!(
                        m.contains(&format!("image of {w}x{h} pixels is larger than the texture limit")),
                        "{m}"
                    )
                }
                other => panic!("{w}x{h}: {:?}", other.map(|t| t.width())),
            }
        }
        // Over the budget of a load, a texture within its own limit is refused.
        let mut decoded = MAX_TEXTURE_PIXELS_PER_MODEL - 1;
        match decode_texture(&tiny_png(), None, &mut decoded) {
            Err(DecodeError::Corrupt(m)) => assert!(m.contains("would bring the model's textures to"), "{m}"),
            other => panic!("{:?}", other.map(|t| t.width())),
        }
        let mut decoded = MAX_TEXTURE_PIXELS_PER_MODEL - 2;
        decode_texture(&tiny_png(), None, &mut decoded).unwrap();
        assert_eq!(decoded, MAX_TEXTURE_PIXELS_PER_MODEL, "counted");
        // Within the limits the header passes and the missing data fails.
        match decode(&png_header(4096, 4096), None) {
            Err(DecodeError::Corrupt(m)) => assert!(m.starts_with("cannot decode image"), "{m}"),
            other => panic!("{:?}", other.map(|t| t.width())),
        }
    }
}
