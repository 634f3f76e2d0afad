//! Inputs read from a stream (standard input, `zline render -`) rather than
//! a named file: the bytes are read within the model-file limit, the format
//! is told from the bytes themselves (there is no extension), and the
//! format's loader parses them as it would a file's.
//!
//! A stream has no folder, so the files it names (an OBJ's `mtllib` and
//! textures, a glTF's buffers and images, a scene file's models) are looked
//! up from the current folder, with the same rule as for files: nothing
//! outside it unless [`LoadOptions::allow_outside`]. Messages name the
//! input by the name given (`<stdin>` for standard input).

use std::io::Read;
use std::path::Path;

use zline_scene::{Mesh, Scene, MAX_MODEL_FILE_BYTES};

use crate::error::SceneError;
use crate::files::LoadOptions;
use crate::gltf::GltfScene;

/// The name messages give standard input.
pub const STDIN_NAME: &str = "<stdin>";

/// The input formats zline reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputFormat {
    /// Wavefront OBJ (with MTL materials).
    Obj,
    /// glTF 2.0, JSON.
    Gltf,
    /// glTF 2.0, binary (GLB).
    Glb,
    /// STL, ASCII or binary.
    Stl,
    /// PLY, ASCII or binary.
    Ply,
    /// 3MF, a ZIP archive of XML parts.
    ThreeMf,
    /// A TOML scene file.
    Scene,
}

impl InputFormat {
    /// The format a file's extension names (any case), if any.
    pub fn from_extension(path: &Path) -> Option<InputFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "obj" => InputFormat::Obj,
            "gltf" => InputFormat::Gltf,
            "glb" => InputFormat::Glb,
            "stl" => InputFormat::Stl,
            "ply" => InputFormat::Ply,
            "3mf" => InputFormat::ThreeMf,
            "toml" => InputFormat::Scene,
            _ => return None,
        })
    }

    /// The format of `bytes`, told from their content: GLB, PLY and 3MF (a
    /// ZIP archive) by their magic words, binary STL by its size rule (84 + 50 bytes per
    /// triangle) and ASCII STL by `solid` then `facet`/`endsolid`, glTF as
    /// a JSON object with an `"asset"` key; of the remaining text, a TOML
    /// scene has a `[table]` header or a `key = value` line before any OBJ
    /// statement (`v`, `f`, …), and OBJ has such a statement. `None` when
    /// none of these holds.
    pub fn sniff(bytes: &[u8]) -> Option<InputFormat> {
        if bytes.starts_with(b"glTF") {
            return Some(InputFormat::Glb);
        }
        if bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n") {
            return Some(InputFormat::Ply);
        }
        if bytes.starts_with(b"PK\x03\x04") {
            return Some(InputFormat::ThreeMf);
        }
        if crate::stl::looks_like_stl(bytes) {
            return Some(InputFormat::Stl);
        }
        let head = String::from_utf8_lossy(&bytes[..bytes.len().min(1 << 16)]);
        let text = head.trim_start_matches('\u{feff}').trim_start();
        if text.starts_with('{') {
            return text.contains("\"asset\"").then_some(InputFormat::Gltf);
        }
        for line in text.lines().map(str::trim) {
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            if line.starts_with('[') || is_toml_assignment(line) {
                return Some(InputFormat::Scene);
            }
            let keyword = line.split_whitespace().next().unwrap_or("");
            if OBJ_KEYWORDS.contains(&keyword) {
                return Some(InputFormat::Obj);
            }
        }
        None
    }

    /// The format's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            InputFormat::Obj => "OBJ",
            InputFormat::Gltf => "glTF",
            InputFormat::Glb => "GLB",
            InputFormat::Stl => "STL",
            InputFormat::Ply => "PLY",
            InputFormat::ThreeMf => "3MF",
            InputFormat::Scene => "scene file",
        }
    }
}

/// The statements an OBJ file starts with (tobj reads these and ignores
/// the rest).
const OBJ_KEYWORDS: &[&str] =
    &["v", "vt", "vn", "vp", "f", "l", "p", "o", "g", "s", "mtllib", "usemtl", "cstype", "deg"];

/// `key = value`, with a bare TOML key: OBJ has no `=`.
fn is_toml_assignment(line: &str) -> bool {
    line.split_once('=').is_some_and(|(key, _)| {
        let key = key.trim();
        !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || "_-.\"".contains(c))
    })
}

/// What an input holds once loaded, before zline frames and lights it.
#[derive(Debug)]
pub enum LoadedInput {
    /// The meshes of an OBJ, STL or PLY model.
    Model(Vec<Mesh>),
    /// A glTF or GLB scene.
    Gltf(GltfScene),
    /// A scene file's scene (boxed: a scene is large beside a mesh list).
    Scene(Box<Scene>),
}

/// Reads all of `reader` (at most
/// [`MAX_MODEL_FILE_BYTES`](zline_scene::MAX_MODEL_FILE_BYTES)); `name`
/// names it in errors.
pub fn read_stream(reader: impl Read, name: &Path) -> Result<Vec<u8>, SceneError> {
    read_within(reader, name, MAX_MODEL_FILE_BYTES)
}

fn read_within(mut reader: impl Read, name: &Path, limit: u64) -> Result<Vec<u8>, SceneError> {
    let mut bytes = Vec::new();
    let file = |message: String| SceneError::File { path: name.to_path_buf(), message };
    reader
        .by_ref()
        .take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|source| SceneError::Io { path: name.to_path_buf(), source })?;
    if bytes.len() as u64 > limit {
        return Err(file(format!("more than the limit of {limit} bytes for a model")));
    }
    if bytes.is_empty() {
        return Err(file("empty input: no model was given".to_owned()));
    }
    Ok(bytes)
}

/// Loads `bytes` in `format` as the file `name` would be (files it names
/// are looked up beside `name`: in the current folder for
/// [`STDIN_NAME`]). Returns the input and the loader's warnings.
pub fn load_bytes(
    format: InputFormat,
    name: &Path,
    bytes: Vec<u8>,
    options: LoadOptions,
) -> Result<(LoadedInput, Vec<String>), SceneError> {
    let text = |bytes: Vec<u8>| {
        String::from_utf8(bytes).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
    };
    Ok(match format {
        InputFormat::Obj => {
            let (meshes, warnings) = crate::obj::parse_obj(name, &text(bytes), options)?;
            (LoadedInput::Model(meshes), warnings)
        }
        InputFormat::Gltf | InputFormat::Glb => {
            let (gltf, warnings) = crate::gltf::parse_gltf(name, bytes, options)?;
            (LoadedInput::Gltf(gltf), warnings)
        }
        InputFormat::Stl => (LoadedInput::Model(crate::stl::parse_stl(name, &bytes)?), vec![]),
        InputFormat::Ply => (LoadedInput::Model(crate::ply::parse_ply(name, &bytes)?), vec![]),
        InputFormat::ThreeMf => (LoadedInput::Model(crate::threemf::parse_3mf(name, &bytes)?), vec![]),
        InputFormat::Scene => {
            let text = text(bytes);
            if text.len() as u64 > zline_scene::MAX_TEXT_FILE_BYTES {
                let message = format!(
                    "a scene file of more than the limit of {} bytes",
                    zline_scene::MAX_TEXT_FILE_BYTES
                );
                return Err(SceneError::File { path: name.to_path_buf(), message });
            }
            (LoadedInput::Scene(Box::new(crate::scene_file::parse_scene(name, &text, options)?)), vec![])
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sniffs_each_format() {
        let binary_stl = {
            let mut b = vec![0u8; 84 + 50];
            b[80] = 1;
            b
        };
        let cases: [(&[u8], Option<InputFormat>); 10] = [
            (b"glTF\x02\0\0\0", Some(InputFormat::Glb)),
            (b"ply\nformat ascii 1.0\n", Some(InputFormat::Ply)),
            (&binary_stl, Some(InputFormat::Stl)),
            (b"solid cube\n  facet normal 0 0 1\n", Some(InputFormat::Stl)),
            (b" {\"asset\": {\"version\": \"2.0\"}}", Some(InputFormat::Gltf)),
            (b"# a triangle\nmtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", Some(InputFormat::Obj)),
            (b"# scene\nbackground = [0, 0, 0]\n", Some(InputFormat::Scene)),
            (b"[camera]\neye = [0, 0, 5]\n", Some(InputFormat::Scene)),
            (b"hello world\n", None),
            (b"{\"not\": \"gltf\"}", None),
        ];
        for (bytes, want) in cases {
            assert_eq!(InputFormat::sniff(bytes), want, "{:?}", String::from_utf8_lossy(bytes));
        }
    }

    #[test]
    fn binary_stl_whose_header_says_solid_is_binary() {
        let mut b = vec![b' '; 84 + 50 * 2];
        b[..11].copy_from_slice(b"solid part\n");
        b[80..84].copy_from_slice(&2u32.to_le_bytes());
        assert_eq!(InputFormat::sniff(&b), Some(InputFormat::Stl));
    }

    #[test]
    fn empty_and_oversized_streams_are_errors() {
        let name = Path::new(STDIN_NAME);
        let e = read_stream(&b""[..], name).unwrap_err().to_string();
        assert!(e.contains("<stdin>") && e.contains("empty"), "{e}");
        let e = read_within(std::io::repeat(b'v').take(1001), name, 1000).unwrap_err().to_string();
        assert!(e.contains("limit"), "{e}");
    }

    #[test]
    fn an_obj_from_bytes_loads_as_the_file_does() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let name = Path::new(STDIN_NAME);
        let (loaded, _) = load_bytes(InputFormat::Obj, name, text.into(), LoadOptions::default()).unwrap();
        let LoadedInput::Model(meshes) = loaded else { panic!("not a model") };
        assert_eq!(meshes.len(), 1);
        assert_eq!(meshes[0].triangles, vec![[0, 1, 2]]);
    }
}
