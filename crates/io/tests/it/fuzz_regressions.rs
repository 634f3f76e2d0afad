//! Inputs found by the fuzz targets in `fuzz/` (see `fuzz/README.md`),
//! minimized: each panicked, hung or ran out of memory before its fix and
//! must now load or fail with a one-line error naming the file.

use zline_io::load_gltf;

use crate::check_message;
use crate::gltf::quad_gltf;

/// fuzz target `gltf`: an image with neither `uri` nor `bufferView`, or a
/// `bufferView` without `mimeType`, passed the `gltf` crate's validation
/// and panicked in its `Image::source` (an `unwrap` on `None`).
#[test]
fn fuzz_gltf_image_without_a_source_is_an_error_not_a_panic() {
    let material = r#""nodes": [{"mesh": 0}],
        "materials": [{"name": "tex", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}],"#;
    let path = quad_gltf("fuzz-image-no-source", &format!(r#"{material} "images": [{{}}]"#));
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: image 0 has neither a uri nor a bufferView"]);

    let path = quad_gltf("fuzz-image-no-mime", &format!(r#"{material} "images": [{{"bufferView": 1}}]"#));
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: image 0 has a bufferView but no mimeType"]);
}

/// Found with the above, in the same family: a camera whose `type` names a
/// projection object it does not have panicked in `Camera::projection`.
#[test]
fn fuzz_gltf_camera_without_its_projection_is_an_error_not_a_panic() {
    let members = r#""nodes": [{"mesh": 0}, {"camera": 0}],
        "cameras": [{"type": "orthographic", "perspective": {"yfov": 0.8, "znear": 0.1}}]"#;
    let path = quad_gltf("fuzz-camera-type", members);
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: camera 0 is of type 'orthographic' but has no 'orthographic' object"]);
}
