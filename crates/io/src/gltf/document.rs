//! The glTF document: GLB framing and JSON, checked before the `gltf` crate
//! validates it, so that a malformed file gives a message that says what is
//! wrong rather than a panic or a vague parse error.
//!
//! Contract: [`parse`] returns the validated document and the GLB's BIN
//! chunk, or the message of what is wrong: a `.glb` file whose magic is not
//! `glTF` ("not a GLB file"), a GLB cut short ("truncated GLB", with the
//! bytes expected and found), a primitive naming an accessor the file does
//! not have (the `gltf` crate's validation indexes POSITION unchecked and
//! panics), an image with neither a `uri` nor a `bufferView` or with a
//! `bufferView` but no `mimeType`, a camera whose `type` names a
//! projection it does not have (the `gltf` crate unwraps these), an
//! `asset.version` other than 2.x, then the `gltf` crate's own
//! validation errors. A panic inside the `gltf` crate is caught as a last
//! line and reported as an error.

use std::path::Path;

use gltf::json;

/// The 4 bytes every GLB file starts with.
const GLB_MAGIC: &[u8; 4] = b"glTF";

/// The GLB header's size: magic, version, length.
const GLB_HEADER: usize = 12;

/// The validated document and the BIN chunk of a GLB file.
pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<(gltf::Document, Option<Vec<u8>>), String> {
    let is_glb_name = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    if is_glb_name || bytes.starts_with(GLB_MAGIC) {
        check_glb(bytes)?;
    }
    let parsed = std::panic::catch_unwind(|| {
        let gltf::Gltf { document, blob } =
            gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| format!("cannot read glTF: {e}"))?;
        let root = document.into_json();
        check_version(&root)?;
        check_accessor_indices(&root)?;
        check_images_and_cameras(&root)?;
        let document = gltf::Document::from_json(root).map_err(|e| format!("invalid glTF: {e}"))?;
        Ok((document, blob))
    });
    parsed.unwrap_or_else(|_| Err("invalid glTF: the gltf crate failed on this file (it panicked)".into()))
}

/// The GLB framing: magic, version, length and chunk lengths against the
/// bytes there are.
fn check_glb(bytes: &[u8]) -> Result<(), String> {
    let found = bytes.len();
    if !bytes.starts_with(GLB_MAGIC) {
        let magic: String =
            bytes.iter().take(4).flat_map(|&b| std::ascii::escape_default(b)).map(char::from).collect();
        return Err(format!("not a GLB file (magic '{magic}', expected 'glTF')"));
    }
    let word = |at: usize| -> Option<usize> {
        let b = bytes.get(at..at + 4)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let (Some(version), Some(length)) = (word(4), word(8)) else {
        return Err(format!("truncated GLB: expected a {GLB_HEADER}-byte header, found {found} bytes"));
    };
    if version != 2 {
        return Err(format!("GLB version {version} is not supported (only 2)"));
    }
    if length > found {
        return Err(format!("truncated GLB: expected {length} bytes (the header's length), found {found}"));
    }
    let mut at = GLB_HEADER;
    let mut chunk = 0;
    while at < length {
        let (Some(chunk_length), Some(_)) = (word(at).filter(|_| at + 8 <= length), word(at + 4)) else {
            return Err(format!(
                "truncated GLB: chunk {chunk} header at byte {at} is cut off at byte {length}"
            ));
        };
        let end = at + 8 + chunk_length;
        if end > length {
            return Err(format!(
                "truncated GLB: chunk {chunk} at byte {at} expects {chunk_length} bytes, found {}",
                length - at - 8
            ));
        }
        at = end;
        chunk += 1;
    }
    if chunk == 0 {
        return Err("GLB without a JSON chunk".into());
    }
    Ok(())
}

/// Refuses an `asset.version` (or `minVersion`) other than 2.x.
fn check_version(root: &json::Root) -> Result<(), String> {
    let asset = &root.asset;
    let is_2x = |v: &str| v.split('.').next() == Some("2");
    if !is_2x(&asset.version) {
        return Err(format!("glTF version '{}' is not supported (only 2.x)", short(&asset.version)));
    }
    match &asset.min_version {
        Some(v) if !is_2x(v) => Err(format!("glTF minVersion '{}' is not supported (only 2.x)", short(v))),
        _ => Ok(()),
    }
}

/// Refuses a primitive whose attributes, indices or morph targets name an
/// accessor the file does not have.
fn check_accessor_indices(root: &json::Root) -> Result<(), String> {
    let count = root.accessors.len();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let targets =
                primitive.targets.iter().flatten().flat_map(|t| [t.positions, t.normals, t.tangents]);
            let named = primitive
                .attributes
                .iter()
                .map(|(semantic, &index)| (attribute_name(semantic), Some(index)))
                .chain(std::iter::once(("indices".to_owned(), primitive.indices)))
                .chain(targets.map(|t| ("a morph target".to_owned(), t)));
            for (what, index) in named {
                if let Some(index) = index.filter(|i| i.value() >= count) {
                    return Err(format!(
                        "mesh {m}, primitive {p}: {what} names accessor {}, but the file has {count} accessor(s)",
                        index.value()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Refuses what the `gltf` crate's validation lets through but its
/// accessors unwrap: an image with no source (neither `uri` nor
/// `bufferView`), a `bufferView` image without `mimeType` (both required by
/// the glTF spec), a camera whose `type` names a projection object it does
/// not have.
fn check_images_and_cameras(root: &json::Root) -> Result<(), String> {
    for (i, image) in root.images.iter().enumerate() {
        match (&image.uri, &image.buffer_view, &image.mime_type) {
            (None, None, _) => return Err(format!("image {i} has neither a uri nor a bufferView")),
            (None, Some(_), None) => return Err(format!("image {i} has a bufferView but no mimeType")),
            _ => {}
        }
    }
    for (c, camera) in root.cameras.iter().enumerate() {
        use json::camera::Type;
        use json::validation::Checked::Valid;
        let missing = match camera.type_ {
            Valid(Type::Perspective) if camera.perspective.is_none() => "perspective",
            Valid(Type::Orthographic) if camera.orthographic.is_none() => "orthographic",
            _ => continue,
        };
        return Err(format!("camera {c} is of type '{missing}' but has no '{missing}' object"));
    }
    Ok(())
}

fn attribute_name(semantic: &json::validation::Checked<json::mesh::Semantic>) -> String {
    "attribute ".to_owned() + &semantic.to_string()
}

/// At most 20 characters of a string, for messages.
fn short(s: &str) -> String {
    s.chars().take(20).flat_map(char::escape_debug).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glb(json: &str, declared: Option<u32>) -> Vec<u8> {
        let mut json = json.as_bytes().to_vec();
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let length = (GLB_HEADER + 8 + json.len()) as u32;
        let mut out = GLB_MAGIC.to_vec();
        out.extend(2u32.to_le_bytes());
        out.extend(declared.unwrap_or(length).to_le_bytes());
        out.extend((json.len() as u32).to_le_bytes());
        out.extend(b"JSON");
        out.extend(json);
        out
    }

    const MINIMAL: &str = r#"{"asset":{"version":"2.0"}}"#;

    #[test]
    fn glb_framing_errors_say_what_is_wrong() {
        let good = glb(MINIMAL, None);
        assert!(check_glb(&good).is_ok());
        let e = check_glb(&good[..30]).unwrap_err();
        assert_eq!(
            e,
            format!("truncated GLB: expected {} bytes (the header's length), found 30", good.len())
        );
        let e = check_glb(&good[..7]).unwrap_err();
        assert_eq!(e, "truncated GLB: expected a 12-byte header, found 7 bytes");
        let e = check_glb(&glb(MINIMAL, Some(30))).unwrap_err();
        assert!(e.starts_with("truncated GLB: chunk 0 at byte 12 expects"), "{e}");
        let e = check_glb(b"{\"asset\": {}}").unwrap_err();
        assert_eq!(e, "not a GLB file (magic '{\\\"as', expected 'glTF')");
        let mut v1 = good.clone();
        v1[4] = 1;
        assert_eq!(check_glb(&v1).unwrap_err(), "GLB version 1 is not supported (only 2)");
    }

    #[test]
    fn a_glb_extension_is_checked_as_glb_even_without_the_magic() {
        let e = parse(Path::new("x.glb"), MINIMAL.as_bytes()).unwrap_err();
        assert!(e.starts_with("not a GLB file"), "{e}");
        assert!(parse(Path::new("x.gltf"), MINIMAL.as_bytes()).is_ok());
        assert!(parse(Path::new("x.glb"), &glb(MINIMAL, None)).is_ok());
    }

    #[test]
    fn versions_other_than_2_are_refused() {
        let e = parse(Path::new("x.gltf"), br#"{"asset":{"version":"1.0"}}"#).unwrap_err();
        assert_eq!(e, "glTF version '1.0' is not supported (only 2.x)");
        let e = parse(Path::new("x.gltf"), br#"{"asset":{"version":"2.0","minVersion":"3.0"}}"#).unwrap_err();
        assert_eq!(e, "glTF minVersion '3.0' is not supported (only 2.x)");
        assert!(parse(Path::new("x.gltf"), br#"{"asset":{"version":"2.1"}}"#).is_ok());
    }

    #[test]
    fn an_accessor_index_out_of_range_is_an_error_not_a_panic() {
        let json = r#"{"asset":{"version":"2.0"},
            "accessors":[{"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}],
            "meshes":[{"primitives":[{"attributes":{"POSITION":99}}]}]}"#;
        let e = parse(Path::new("x.gltf"), json.as_bytes()).unwrap_err();
        assert_eq!(
            e,
            "mesh 0, primitive 0: attribute POSITION names accessor 99, but the file has 1 accessor(s)"
        );
        let json = json.replace(r#"{"POSITION":99}"#, r#"{"POSITION":0},"indices":7"#);
        let e = parse(Path::new("x.gltf"), json.as_bytes()).unwrap_err();
        assert!(e.contains("indices names accessor 7"), "{e}");
    }
}
