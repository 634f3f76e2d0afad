//! glTF resources: buffers and images from the GLB chunk, `data:` URIs or
//! files next to the glTF file, read here so that one bad resource gives one
//! clear error or warning (see the parent module). A file URI must name a
//! file inside the glTF file's folder unless the options allow otherwise;
//! a buffer file is read when at most [`MAX_MODEL_FILE_BYTES`], and so
//! are all the buffers together.

use std::path::{Path, PathBuf};

use zline_scene::MAX_MODEL_FILE_BYTES;

use crate::error::SceneError;
use crate::files::{read_limited, resolve, FileKind, LoadOptions, ReadError};

/// Reads every buffer: the GLB's BIN chunk, a `data:` URI or a file
/// relative to the glTF file. A buffer that cannot be read, or is shorter
/// than its byteLength, is an error naming it; so are buffers whose
/// byteLengths add up to more than [`MAX_MODEL_FILE_BYTES`], before any is
/// read.
pub(super) fn read_buffers(
    path: &Path,
    document: &gltf::Document,
    mut blob: Option<Vec<u8>>,
    options: LoadOptions,
) -> Result<Vec<Vec<u8>>, SceneError> {
    let declared: u64 = document.buffers().map(|b| b.length() as u64).sum();
    if declared > MAX_MODEL_FILE_BYTES {
        return Err(SceneError::File {
            path: path.to_path_buf(),
            message: format!(
                "buffers of {declared} bytes in all (their byteLengths), more than the limit of \
                 {MAX_MODEL_FILE_BYTES}"
            ),
        });
    }
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let error = |what: String| SceneError::File {
            path: path.to_path_buf(),
            message: format!("buffer {}: {what}", buffer.index()),
        };
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => {
                blob.take().ok_or_else(|| error("the GLB has no BIN chunk".into()))?
            }
            gltf::buffer::Source::Uri(uri) => read_uri(path, uri, options).map_err(error)?,
        };
        if data.len() < buffer.length() {
            return Err(error(format!("holds {} bytes, byteLength says {}", data.len(), buffer.length())));
        }
        buffers.push(data);
    }
    Ok(buffers)
}

/// The bytes a buffer URI names, or what is wrong.
fn read_uri(path: &Path, uri: &str, options: LoadOptions) -> Result<Vec<u8>, String> {
    match uri_target(path, uri, options)? {
        UriTarget::Data => decode_data_uri(uri),
        UriTarget::File(file) => read_limited(&file, FileKind::Model).map_err(|e| match e {
            ReadError::Io(e) => format!("cannot read '{}': {e}", file.display()),
            ReadError::Refused(why) => format!("'{}' {why}", file.display()),
        }),
    }
}

/// Where a URI points.
pub(super) enum UriTarget {
    /// A `data:` URI: the bytes are in it.
    Data,
    /// A file (a relative reference, percent-decoded, joined to the base).
    File(PathBuf),
}

/// Where `uri`, found in the glTF file `path`, points.
pub(super) fn uri_target(path: &Path, uri: &str, options: LoadOptions) -> Result<UriTarget, String> {
    if uri.starts_with("data:") {
        return Ok(UriTarget::Data);
    }
    if uri.contains(':') {
        return Err(format!("unsupported URI '{}' (only relative file names and data: URIs)", short(uri)));
    }
    let decoded = percent_decode(uri).ok_or_else(|| format!("malformed URI '{}'", short(uri)))?;
    Ok(UriTarget::File(resolve(path, Path::new(&decoded), options)?))
}

/// The bytes of a base64 `data:` URI, decoded by the `gltf` crate.
pub(super) fn decode_data_uri(uri: &str) -> Result<Vec<u8>, String> {
    if !uri.contains(";base64,") {
        return Err("only base64 data: URIs are supported".into());
    }
    // With no base directory the gltf crate reads nothing but the URI.
    let data = gltf::buffer::Data::from_source(gltf::buffer::Source::Uri(uri), None)
        .map_err(|e| format!("cannot decode data: URI: {e}"))?;
    Ok(data.0)
}

/// Decodes `%XX` escapes; `None` when an escape is malformed or the result
/// is not UTF-8.
pub(super) fn percent_decode(uri: &str) -> Option<String> {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// At most 60 characters of a string, for messages (data: URIs are long).
pub(super) fn short(s: &str) -> String {
    let mut out: String = s.chars().take(60).flat_map(char::escape_debug).collect();
    if s.chars().count() > 60 {
        out.push('…');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_escapes_decode_or_fail_cleanly() {
        assert_eq!(percent_decode("a%20b.png").as_deref(), Some("a b.png"));
        assert_eq!(percent_decode("plain.bin").as_deref(), Some("plain.bin"));
        assert_eq!(percent_decode("bad%2"), None);
        assert_eq!(percent_decode("bad%zz"), None);
        assert_eq!(percent_decode("%FF"), None, "not UTF-8");
    }
}
