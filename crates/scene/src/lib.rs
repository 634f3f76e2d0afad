//! The zline scene model and its loaders.
//!
//! This is the one crate that reads files: OBJ+MTL (through tobj), glTF 2.0
//! (through the `gltf` crate), PNG and JPEG textures (through `image`) and
//! TOML scene files. Every loader error is a [`SceneError`] whose one-line
//! message names the file, the place and what is wrong; what a loader can
//! draw around (a missing MTL file or texture, an unsupported glTF feature)
//! is a warning instead. It knows nothing of rasterization, screens or
//! threads.
//!
//! Steps, one module each: `model` (the plain data handed to the pipeline),
//! `mesh` (validation and vertex normals), `obj` (OBJ+MTL files and their
//! textures), `gltf` (glTF and GLB files: nodes, materials, cameras,
//! lights), `texture_file` (PNG/JPEG images → textures, shared by both
//! loaders), `primitives` (procedural meshes), `framing` (camera and lights
//! for a bare model or glTF file), `scene_file` (TOML scenes; the format is
//! documented on [`load_scene`]'s module, and `examples/scene.toml` shows
//! every key), `demo` (the built-in demo scene).

mod culling;
mod demo;
mod error;
mod framing;
mod gltf;
pub mod hard_cases;
mod limits;
mod mesh;
mod model;
mod obj;
mod primitives;
mod scene_file;
mod texture_file;

pub use demo::demo_scene;
pub use error::{MeshError, SceneError};
pub use framing::{
    default_lights, framing_camera, scene_for_gltf, scene_for_model, DEFAULT_AMBIENT, DEFAULT_BACKGROUND,
    FRAMING_FOVY_DEGREES, VIEW_DIRECTION,
};
pub use hard_cases::{hard_cases, HardCase};
// `crate::` because `gltf` also names the glTF parsing crate.
pub use crate::gltf::{load_gltf, load_gltf_with_warnings, GltfScene, MAX_GLTF_SHININESS};
pub use limits::{MAX_ADAPTIVE_TOLERANCE, MAX_IMAGE_SIDE, MAX_PRIMITIVE_DIVISIONS, MAX_SSAA};
pub use mesh::{face_normal, FALLBACK_NORMAL};
pub use model::{
    Camera, DepthMode, Interpolation, Mesh, Object, Projection, RenderSettings, Scene, TextureMap,
};
pub use obj::{load_obj, load_obj_with_warnings};
pub use primitives::{cube, plane, torus, uv_sphere};
pub use scene_file::load_scene;
pub use zline_shading::{
    Attenuation, Fog, FogCoordinate, FogMode, Light, LightingModel, Material, ShadingMode,
};
