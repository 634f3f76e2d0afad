//! The zline scene model and its loaders.
//!
//! This is the one crate that reads files: OBJ+MTL (through tobj) and TOML
//! scene files. Every loader error is a [`SceneError`] whose one-line
//! message names the file, the place and what is wrong. It knows nothing of
//! rasterization, screens or threads.
//!
//! Steps, one module each: `model` (the plain data handed to the pipeline),
//! `mesh` (validation and vertex normals), `obj` (OBJ+MTL files),
//! `primitives` (procedural meshes), `framing` (camera and lights for a
//! bare model), `scene_file` (TOML scenes; the format is documented on
//! [`load_scene`]'s module, and `examples/scene.toml` shows every key),
//! `demo` (the built-in demo scene).

mod demo;
mod error;
mod framing;
mod mesh;
mod model;
mod obj;
mod primitives;
mod scene_file;

pub use demo::demo_scene;
pub use error::{MeshError, SceneError};
pub use framing::{
    default_lights, framing_camera, scene_for_model, DEFAULT_AMBIENT, DEFAULT_BACKGROUND,
    FRAMING_FOVY_DEGREES, VIEW_DIRECTION,
};
pub use mesh::{face_normal, FALLBACK_NORMAL};
pub use model::{Camera, Interpolation, Mesh, Object, Projection, RenderSettings, Scene, TextureMap};
pub use obj::{load_obj, load_obj_with_warnings};
pub use primitives::{cube, plane, torus, uv_sphere};
pub use scene_file::{load_scene, MAX_IMAGE_SIDE, MAX_PRIMITIVE_DIVISIONS};
pub use zline_shading::{
    Attenuation, Fog, FogCoordinate, FogMode, Light, LightingModel, Material, ShadingMode,
};
