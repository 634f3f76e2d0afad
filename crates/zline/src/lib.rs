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

use std::io::{Error, ErrorKind, Write};
use std::path::Path;

pub mod check;
pub mod info;
pub mod inspect;
pub mod layers;
pub mod load;
pub mod order;
pub mod scan;
pub mod scan_page;
pub mod view;
#[cfg(feature = "view")]
pub mod viewer;
pub mod views;

pub use zline_io as io;
pub use zline_pipeline as pipeline;
pub use zline_radiosity as radiosity;
pub use zline_raster as raster;
pub use zline_scene as scene;
pub use zline_scenes as scenes;
pub use zline_shading as shading;
pub use zline_trace as trace;

/// An error and its causes on one line, as the command line prints it,
/// skipping a cause whose text the message already quotes (loader errors
/// name their source in their own message).
pub fn error_line(e: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

/// Ray-traces `scene` (`zline-trace`) and turns the linear colours into
/// the image the rasterizer would write: the scene's tone mapping, then 8
/// bits as SPEC §10 quantizes.
pub fn ray_traced_image(
    scene: &scene::Scene,
    options: &scene::trace_options::TraceOptions,
) -> (pipeline::Image, trace::Traced) {
    let traced = trace::render(scene, options);
    let tone = scene.settings.tone_mapping;
    let pixels =
        traced.pixels.iter().map(|&c| pipeline::image::quantize_rgba(tone.apply(c).extend(1.0))).collect();
    let image = pipeline::Image { width: traced.width, height: traced.height, pixels, transparent: false };
    (image, traced)
}

/// Whether `path` names a JPEG output (`.jpg` or `.jpeg`, any case), which
/// cannot hold a transparent image.
pub fn is_jpeg(path: &Path) -> bool {
    format_of(path) == Some(ImageFormat::Jpeg)
}

/// Checks, before any rendering, that an image can be written at `path`:
/// its extension is `.png`, `.jpg` or `.jpeg` (in any case; see
/// [`save_image`]), it is not a
/// folder, and its folder exists and takes a new file (a temporary file is
/// created and removed there, so a read-only folder or file system fails
/// here too, not after the render). The error says which, without the path
/// (the caller names it).
pub fn check_output(path: &Path) -> std::io::Result<()> {
    if is_stdout(path) {
        return Ok(());
    }
    if format_of(path).is_none() {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            "the output must be a .png, .jpg or .jpeg file (the format follows the extension)",
        ));
    }
    let path = &through_links(path);
    if path.is_dir() {
        return Err(Error::new(ErrorKind::IsADirectory, "the output is a folder"));
    }
    let folder = output_folder(path);
    if !folder.is_dir() {
        let what = if folder.exists() { "is not a folder" } else { "does not exist" };
        return Err(Error::new(ErrorKind::NotFound, format!("folder {} {what}", folder.display())));
    }
    temporary_beside(path).map(drop).map_err(|e| {
        Error::new(e.kind(), format!("cannot create a file in folder {}: {e}", folder.display()))
    })
}

/// Writes an image as an 8-bit RGB PNG (RGBA when the image is
/// [`transparent`](pipeline::Image::transparent)), atomically: the PNG is encoded to a
/// temporary file in `path`'s folder, flushed to disk, and renamed over
/// `path` only when whole. A failed or interrupted write leaves an existing
/// file at `path` as it was (and a failed one removes the temporary file).
/// The new file gets the old one's permissions, or the usual ones for a new
/// file (0666 less the umask on Unix). A symbolic link at `path` is
/// followed, as `File::create` would: the file it names is replaced, the
/// link stays.
///
/// Compression is the `png` crate's fast mode (fdeflate) with adaptive row
/// filters: the 1920×1080 bunny thumbnail encodes in about 4 ms to 297 KB,
/// where the default mode takes about 72 ms for 260 KB (BENCHMARKS.md as
/// of `138c02a^`).
pub fn save_png(image: &pipeline::Image, path: &Path) -> Result<(), image::ImageError> {
    save_as(image, path, ImageFormat::Png)
}

/// The image formats zline writes, chosen by the output's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ImageFormat {
    /// `.png`: lossless, the default.
    Png,
    /// `.jpg` / `.jpeg`: baseline JPEG at quality [`JPEG_QUALITY`].
    Jpeg,
}

/// The quality of JPEG output (1..=100): 90 keeps a render's edges and
/// gradients free of visible blocks at about a tenth of the PNG's size.
pub const JPEG_QUALITY: u8 = 90;

fn format_of(path: &Path) -> Option<ImageFormat> {
    let ext = path.extension().and_then(|e| e.to_str())?.to_ascii_lowercase();
    match ext.as_str() {
        "png" => Some(ImageFormat::Png),
        "jpg" | "jpeg" => Some(ImageFormat::Jpeg),
        _ => None,
    }
}

/// Writes `image` as PNG or JPEG by `path`'s extension (`.png`, `.jpg`,
/// `.jpeg`, any case; anything else is PNG), atomically as
/// [`save_png`] does. JPEG is baseline at quality [`JPEG_QUALITY`]. A
/// [`transparent`](pipeline::Image::transparent) image is written as RGBA
/// PNG; JPEG has no alpha, so it is refused as JPEG (before any file is
/// touched).
pub fn save_image(image: &pipeline::Image, path: &Path) -> Result<(), image::ImageError> {
    save_as(image, path, format_of(path).unwrap_or(ImageFormat::Png))
}

/// True for `-`, the output path that means standard output: [`save_image`]
/// writes a PNG there, in one piece after it is encoded.
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == "-"
}

fn save_as(image: &pipeline::Image, path: &Path, format: ImageFormat) -> Result<(), image::ImageError> {
    use image::codecs::jpeg::JpegEncoder;
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    use image::ImageEncoder;
    if image.transparent && format == ImageFormat::Jpeg {
        let why = "JPEG has no alpha channel: write a transparent image as .png";
        return Err(image::ImageError::IoError(Error::new(ErrorKind::InvalidInput, why)));
    }
    let (rgb, rgb8) = match image.transparent {
        false => (image.to_rgb(), image::ExtendedColorType::Rgb8),
        true => (image.to_rgba(), image::ExtendedColorType::Rgba8),
    };
    let (w, h) = (image.width, image.height);
    // The encoder's own error, kept apart from the file's I/O errors.
    let mut encoding = Ok(());
    let mut write = |out: &mut dyn Write| {
        encoding = match format {
            ImageFormat::Png => {
                PngEncoder::new_with_quality(&mut *out, CompressionType::Fast, FilterType::Adaptive)
                    .write_image(&rgb, w, h, rgb8)
            }
            ImageFormat::Jpeg => {
                JpegEncoder::new_with_quality(&mut *out, JPEG_QUALITY).write_image(&rgb, w, h, rgb8)
            }
        };
        Ok(())
    };
    let written = if is_stdout(path) {
        let mut bytes = Vec::new();
        write(&mut bytes)?;
        let mut stdout = std::io::stdout().lock();
        stdout.write_all(&bytes).and_then(|()| stdout.flush())
    } else {
        write_atomically(path, |out| write(out))
    };
    encoding?;
    written.map_err(image::ImageError::IoError)
}

/// Writes a depth image as a 16-bit greyscale PNG
/// ([`layers::encode_depth_png`]: nearest drawn pixel 65535, farthest 1,
/// nothing drawn 0, the mapping in a tEXt chunk), atomically as
/// [`save_image`] does. Returns the mapping.
pub fn save_depth_png(
    depth: &pipeline::DepthImage,
    path: &Path,
) -> std::io::Result<Option<pipeline::DepthRange>> {
    let (png, range) = layers::encode_depth_png(depth)?;
    write_atomically(path, |out| out.write_all(&png))?;
    Ok(range)
}

/// Writes a file atomically: `write` fills a temporary file in `path`'s
/// folder (through a buffer), which is flushed to disk, given the old
/// file's permissions when there was one, and renamed over `path` (a
/// symbolic link there is followed). A failed write leaves an existing
/// file as it was and removes the temporary file.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let path = &through_links(path);
    let mut temp = temporary_beside(path)?;
    let mut out = std::io::BufWriter::new(temp.as_file_mut());
    write(&mut out)?;
    out.flush()?;
    drop(out);
    if let Ok(old) = std::fs::metadata(path) {
        temp.as_file().set_permissions(old.permissions())?;
    }
    temp.as_file().sync_all()?;
    temp.persist(path).map(drop).map_err(|e| e.error)
}

/// Checks that `path`'s folder exists and takes a new file (a temporary
/// file is created and removed there).
pub fn check_writable(path: &Path) -> std::io::Result<()> {
    temporary_beside(&through_links(path)).map(drop)
}

/// `path` with symbolic links at its end followed (at most 40, as Linux
/// does), so that the file they name is replaced rather than the link; a
/// link to a missing file gives that file.
fn through_links(path: &Path) -> std::path::PathBuf {
    let mut path = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::read_link(&path) {
            Ok(target) => path = output_folder(&path).join(target),
            Err(_) => break,
        }
    }
    path
}

/// The folder a file is written in (`.` for a bare file name).
fn output_folder(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// A new, empty temporary file in `path`'s folder, named after it
/// (`.NAME.XXXXXX.tmp`), removed when dropped unless persisted.
fn temporary_beside(path: &Path) -> std::io::Result<tempfile::NamedTempFile> {
    let name = path.file_name().map_or_else(|| "zline".into(), |n| n.to_string_lossy());
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(output_folder(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image() -> pipeline::Image {
        pipeline::Image { width: 3, height: 2, pixels: vec![0x00ff_8040; 6], transparent: false }
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut n: Vec<String> =
            std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        n.sort();
        n
    }

    #[test]
    fn check_output_takes_png_and_jpeg_files_in_writable_folders_only() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        for ok in ["a.png", "b.PNG", "c.Png", "d.jpg", "e.JPEG"] {
            check_output(&d.join(ok)).unwrap();
        }
        for (bad, kind) in [("a.bmp", ErrorKind::InvalidInput), ("png", ErrorKind::InvalidInput)] {
            assert_eq!(check_output(&d.join(bad)).unwrap_err().kind(), kind, "{bad}");
        }
        std::fs::create_dir(d.join("sub.png")).unwrap();
        assert_eq!(check_output(&d.join("sub.png")).unwrap_err().kind(), ErrorKind::IsADirectory);
        let missing = check_output(&d.join("nowhere/a.png")).unwrap_err();
        assert!(missing.to_string().contains("does not exist"), "{missing}");
        assert_eq!(names(d), ["sub.png"], "the check left files behind");
    }

    #[test]
    fn save_png_replaces_a_file_whole_and_cleans_up_when_it_cannot() {
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("out.png");
        std::fs::write(&png, b"old").unwrap();
        save_png(&image(), &png).unwrap();
        let back = ::image::open(&png).unwrap().to_rgb8();
        assert_eq!((back.width(), back.height()), (3, 2));
        assert_eq!(back.get_pixel(2, 1).0, image().pixel(2, 1));
        // A folder in the way: the rename fails, the folder and its file
        // stay, and the temporary file is removed.
        let folder = dir.path().join("folder.png");
        std::fs::create_dir(&folder).unwrap();
        std::fs::write(folder.join("inside"), b"kept").unwrap();
        assert!(save_png(&image(), &folder).is_err());
        assert_eq!(std::fs::read(folder.join("inside")).unwrap(), b"kept");
        assert_eq!(names(dir.path()), ["folder.png", "out.png"]);
    }

    #[cfg(unix)]
    #[test]
    fn save_png_writes_through_symbolic_links() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("real")).unwrap();
        let (real, link) = (dir.path().join("real/a.png"), dir.path().join("link.png"));
        std::fs::write(&real, b"old").unwrap();
        std::os::unix::fs::symlink("real/a.png", &link).unwrap();
        check_output(&link).unwrap();
        save_png(&image(), &link).unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink(), "the link was replaced");
        assert_eq!(::image::open(&real).unwrap().width(), 3);
        // A dangling link: the file it names is created.
        let (missing, dangling) = (dir.path().join("real/b.png"), dir.path().join("dangling.png"));
        std::os::unix::fs::symlink(&missing, &dangling).unwrap();
        save_png(&image(), &dangling).unwrap();
        assert_eq!(::image::open(&missing).unwrap().width(), 3);
        assert_eq!(names(&dir.path().join("real")), ["a.png", "b.png"]);
    }

    #[cfg(unix)]
    #[test]
    fn save_png_keeps_the_replaced_files_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("out.png");
        std::fs::write(&png, b"old").unwrap();
        std::fs::set_permissions(&png, std::fs::Permissions::from_mode(0o640)).unwrap();
        save_png(&image(), &png).unwrap();
        assert_eq!(std::fs::metadata(&png).unwrap().permissions().mode() & 0o777, 0o640);
        let fresh = dir.path().join("fresh.png");
        save_png(&image(), &fresh).unwrap();
        let mode = std::fs::metadata(&fresh).unwrap().permissions().mode() & 0o777;
        // As `File::create` would make it (not the temporary file's 0600),
        // when the umask can be read (Linux).
        let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
        let umask = status.lines().find_map(|l| l.strip_prefix("Umask:"));
        if let Some(umask) = umask.and_then(|u| u32::from_str_radix(u.trim(), 8).ok()) {
            assert_eq!(mode, 0o666 & !umask, "a new PNG's mode {mode:o}, umask {umask:o}");
        }
    }
}
