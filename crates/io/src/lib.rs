//! The zline loaders: files → the scene model of zline-scene.
//!
//! This is the one crate that reads files: OBJ+MTL (through tobj), glTF 2.0
//! (through the `gltf` crate), STL (`stl_io`), PLY (`ply-rs-bw`), 3MF
//! (`zip` and `quick-xml`), PNG and JPEG textures (through `image`) and
//! TOML scene files. Every loader error is a [`SceneError`] whose one-line
//! message names the file, the place and what is wrong; what a loader can
//! draw around (a missing MTL file or texture, an unsupported glTF feature)
//! is a warning instead. It knows nothing of rasterization, screens or
//! threads.
//!
//! Steps, one module each: `obj` (OBJ+MTL files and their textures), `gltf`
//! (glTF and GLB files: nodes, materials, cameras, lights), `stl` and `ply`
//! (single-mesh formats of CAD tools and scanners), `threemf` (3MF, the
//! 3D-printing format: objects, components, build items, colours),
//! `texture_file` (PNG/JPEG images → textures, shared by both loaders), `culling` (the
//! default back-face culling rule), `framing` (camera and lights for a bare
//! model or glTF file), `scene_file` (TOML scenes; the format is documented
//! on [`load_scene`], and `examples/scene.toml` shows every key), `heightfield` (elevation files: greyscale PNG and ESRI ASCII grids → a
//! `HeightField`), `error`
//! (the error type), `stream` (an input read from standard input: its
//! format told from its bytes), `files` (reading within the size limits and resolving
//! referenced files inside the folder of the file that names them; see
//! [`LoadOptions`]). The limits are constants of zline-scene
//! (`zline_scene::MAX_TRIANGLES` and the others).

mod bump;
mod culling;
mod environment_file;
mod error;
mod files;
mod fit;
mod framing;
mod gltf;
mod heightfield;
mod obj;
mod ply;
mod scene_file;
mod stl;
mod stream;
mod texture_file;
mod threemf;

pub use bump::apply_bump_map;
pub use environment_file::{load_environment, read_panorama, write_panorama, MAX_PANORAMA_TEXELS, SKY_NAME};
pub use error::SceneError;
pub use files::LoadOptions;
pub use fit::{fit_camera, FIT_MARGIN};
pub use framing::{
    default_lights, framing_camera, model_camera, scene_for_gltf, scene_for_model, DEFAULT_AMBIENT,
    DEFAULT_BACKGROUND, FRAMING_FOVY_DEGREES, VIEW_DIRECTION,
};
// `crate::` because `gltf` also names the glTF parsing crate.
pub use crate::gltf::{
    load_gltf, load_gltf_with_options, load_gltf_with_warnings, GltfScene, MAX_GLTF_SHININESS,
};
pub use heightfield::{load_heightfield, load_texture};
pub use obj::{load_obj, load_obj_with_options, load_obj_with_warnings};
pub use ply::load_ply;
pub use scene_file::{load_scene, load_scene_with_options};
pub use stl::load_stl;
pub use stream::{load_bytes, read_stream, InputFormat, LoadedInput, STDIN_NAME};
pub use threemf::{load_3mf, MAX_3MF_MESHES, MAX_ARCHIVE_ENTRIES, MAX_COMPONENT_DEPTH, MAX_PLACEMENTS};
