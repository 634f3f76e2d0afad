//! Reading files safely, shared by every loader: a file is read only when
//! it is a regular file no larger than its kind's limit, and a file named
//! by another (an `mtllib`, a `map_Kd`, a glTF URI, a scene's `model`) only
//! when it lies inside the folder of the file that names it.
//!
//! Contract: [`read_limited`] refuses directories, devices, FIFOs and
//! sockets (also behind symlinks) before opening them, refuses a file whose
//! size exceeds the limit before reading it, and reads through
//! `Read::take(limit + 1)` so that a file growing while it is read stops at
//! the limit too. [`resolve`] refuses absolute paths, `..` that climbs
//! above the folder and symlinks that lead out of it (the canonical paths
//! are compared), unless [`LoadOptions::allow_outside`] is set.

use std::io::Read;
use std::path::{Component, Path, PathBuf};

use zline_scene::{MAX_IMAGE_FILE_BYTES, MAX_MODEL_FILE_BYTES, MAX_TEXT_FILE_BYTES};

use crate::error::SceneError;

/// Options of a load, for files that a user trusts more than the default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Let a file named by a model or scene file (an `mtllib`, a `map_Kd`,
    /// a glTF buffer or image URI, a scene's `model`) lie outside the
    /// folder of the file that names it: absolute paths, `..` above the
    /// folder, symlinks leading out. Off by default, so that a model from
    /// the internet cannot read the user's other files. Directories,
    /// devices and FIFOs stay refused either way.
    pub allow_outside: bool,
}

/// What a file is, for its size limit and for messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FileKind {
    /// An OBJ, glTF or GLB file, or a glTF buffer.
    Model,
    /// A texture image.
    Image,
    /// An MTL or TOML scene file.
    Text,
}

impl FileKind {
    /// The largest size of a file of this kind, in bytes.
    pub(crate) fn limit(self) -> u64 {
        match self {
            FileKind::Model => MAX_MODEL_FILE_BYTES,
            FileKind::Image => MAX_IMAGE_FILE_BYTES,
            FileKind::Text => MAX_TEXT_FILE_BYTES,
        }
    }

    fn name(self) -> &'static str {
        match self {
            FileKind::Model => "model and buffer files",
            FileKind::Image => "image files",
            FileKind::Text => "MTL and scene files",
        }
    }
}

/// Why a file was not read.
#[derive(Debug)]
pub(crate) enum ReadError {
    /// The operating system's error (a missing file, no permission): some
    /// callers draw on without the file, with a warning.
    Io(std::io::Error),
    /// Not a regular file, or larger than its limit: always an error.
    Refused(String),
}

impl ReadError {
    /// The error about the file at `path`.
    pub(crate) fn into_error(self, path: &Path) -> SceneError {
        match self {
            ReadError::Io(source) => SceneError::Io { path: path.to_path_buf(), source },
            ReadError::Refused(message) => SceneError::File { path: path.to_path_buf(), message },
        }
    }
}

/// The whole of a regular file of at most `kind.limit()` bytes (see the
/// module doc).
pub(crate) fn read_limited(path: &Path, kind: FileKind) -> Result<Vec<u8>, ReadError> {
    let limit = kind.limit();
    // Follows symlinks: a link to /dev/zero is a device. Checked before
    // opening, since opening a FIFO waits for a writer.
    let metadata = std::fs::metadata(path).map_err(ReadError::Io)?;
    check_metadata(&metadata, kind)?;
    let file = std::fs::File::open(path).map_err(ReadError::Io)?;
    // The file opened may not be the one checked (replaced in between).
    check_metadata(&file.metadata().map_err(ReadError::Io)?, kind)?;
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    file.take(limit + 1).read_to_end(&mut bytes).map_err(ReadError::Io)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(kind, None));
    }
    Ok(bytes)
}

fn check_metadata(metadata: &std::fs::Metadata, kind: FileKind) -> Result<(), ReadError> {
    if metadata.is_dir() {
        return Err(ReadError::Refused("is a directory, not a file".into()));
    }
    if !metadata.is_file() {
        return Err(ReadError::Refused("is not a regular file (a device, FIFO or socket); refused".into()));
    }
    if metadata.len() > kind.limit() {
        return Err(too_large(kind, Some(metadata.len())));
    }
    Ok(())
}

fn too_large(kind: FileKind, size: Option<u64>) -> ReadError {
    let size = size.map_or_else(|| "more".to_owned(), |s| format!("{s} bytes, more"));
    ReadError::Refused(format!(
        "file of {size} than the limit of {} for {} ({} bytes)",
        human_bytes(kind.limit()),
        kind.name(),
        kind.limit()
    ))
}

/// A size in MiB or GiB when it is a whole number of them.
fn human_bytes(bytes: u64) -> String {
    match bytes {
        b if b >= 1 << 30 && b.is_multiple_of(1 << 30) => format!("{} GiB", b >> 30),
        b if b >= 1 << 20 && b.is_multiple_of(1 << 20) => format!("{} MiB", b >> 20),
        b => format!("{b} bytes"),
    }
}

/// Reads a text file (see [`read_limited`]); bytes that are not UTF-8
/// (Latin-1 comments, say) become U+FFFD rather than an error.
pub(crate) fn read_text(path: &Path, kind: FileKind) -> Result<String, ReadError> {
    let bytes = read_limited(path, kind)?;
    // Valid UTF-8 (nearly every file) is taken as it is, without a copy.
    Ok(String::from_utf8(bytes).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned()))
}

/// The file that `reference` names, relative to the folder of the file
/// `referrer`, or why it is refused (see the module doc). A file that does
/// not exist is returned as named, for the caller's own "cannot read".
pub(crate) fn resolve(referrer: &Path, reference: &Path, options: LoadOptions) -> Result<PathBuf, String> {
    let dir = referrer.parent().unwrap_or(Path::new(""));
    let joined = dir.join(reference);
    if options.allow_outside {
        return Ok(joined);
    }
    let refuse = |why: &str| {
        format!(
            "'{}' {why}: only files inside the folder of {} are read (allow with --allow-paths-outside)",
            reference.display(),
            referrer.display()
        )
    };
    let mut depth = 0usize;
    for component in reference.components() {
        match component {
            Component::Prefix(_) | Component::RootDir => return Err(refuse("is an absolute path")),
            Component::CurDir => {}
            Component::ParentDir if depth == 0 => return Err(refuse("leads outside the folder")),
            Component::ParentDir => depth -= 1,
            Component::Normal(_) => depth += 1,
        }
    }
    let dir = if dir.as_os_str().is_empty() { Path::new(".") } else { dir };
    if let (Ok(dir), Ok(target)) = (dir.canonicalize(), joined.canonicalize()) {
        if !target.starts_with(&dir) {
            return Err(refuse(&format!("leads outside the folder (to '{}')", target.display())));
        }
    }
    Ok(joined)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_as_people_do() {
        assert_eq!(human_bytes(1 << 30), "1 GiB");
        assert_eq!(human_bytes(16 << 20), "16 MiB");
        assert_eq!(human_bytes(1000), "1000 bytes");
    }

    #[test]
    fn lexical_escapes_are_refused_without_touching_the_disk() {
        let confined = LoadOptions::default();
        let model = Path::new("/nonexistent/models/a.obj");
        assert!(resolve(model, Path::new("/etc/passwd"), confined).unwrap_err().contains("absolute path"));
        let e = resolve(model, Path::new("x/../../b.mtl"), confined).unwrap_err();
        assert!(e.contains("'x/../../b.mtl' leads outside the folder"), "{e}");
        assert!(e.contains("/nonexistent/models/a.obj"), "names the referrer: {e}");
        assert_eq!(
            resolve(model, Path::new("x/../b.mtl"), confined).unwrap(),
            model.with_file_name("x/../b.mtl")
        );
        let open = LoadOptions { allow_outside: true };
        assert_eq!(resolve(model, Path::new("/etc/passwd"), open).unwrap(), Path::new("/etc/passwd"));
    }

    #[test]
    fn devices_and_directories_are_refused() {
        let e = read_limited(Path::new("/dev/zero"), FileKind::Text).unwrap_err();
        assert!(matches!(&e, ReadError::Refused(m) if m.contains("not a regular file")), "{e:?}");
        let e = read_limited(Path::new("/"), FileKind::Model).unwrap_err();
        assert!(matches!(&e, ReadError::Refused(m) if m.contains("directory")), "{e:?}");
        assert!(matches!(read_limited(Path::new("/nonexistent/x"), FileKind::Model), Err(ReadError::Io(_))));
    }
}
