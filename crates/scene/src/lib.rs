//! The zline scene model: the plain data a renderer takes in.
//!
//! Meshes, objects, camera, lights, fog and render settings, built by hand,
//! by the procedural meshes here or by the loaders of zline-io, and handed
//! to the pipeline and to the ground truth. It reads no files and knows no
//! file format, nothing of rasterization, screens or threads: its only
//! dependencies are zline-shading (materials, lights, textures) and glam.
//!
//! Modules: `model` (scene, objects, meshes, camera, settings), `mesh`
//! (validation and vertex normals; its errors in `error`), `limits` (the
//! largest render settings a scene may ask for, and what one load may
//! read and build), `primitives` (procedural
//! meshes), `area` and `area_auto` (area lights and the adaptive choice
//! of their samples), `occluders` (f64 ray tests against triangles in a
//! bounding-volume hierarchy: light visibility), [`trace_options`] (the
//! ray tracer's settings). The built-in scenes are in zline-scenes.

mod area;
mod area_auto;
mod error;
mod heightfield;
mod limits;
mod mesh;
mod model;
mod normal_map;
mod occluders;
mod primitives;
pub mod radiosity_options;
pub mod sah;
mod shadow;
pub mod trace_options;
mod visibility;

pub use area::{AreaLight, AreaShape};
pub use area_auto::{choose_area_samples, AreaChoice, PROBES as AREA_PROBES};
pub use error::MeshError;
pub use heightfield::{HeightField, HeightFieldError, MAX_HEIGHTFIELD_SAMPLES};
pub use limits::{
    MAX_ADAPTIVE_TOLERANCE, MAX_AREA_SAMPLES_PER_SIDE, MAX_IMAGE_FILE_BYTES, MAX_IMAGE_SIDE,
    MAX_MATERIAL_LIBRARIES, MAX_MODEL_FILE_BYTES, MAX_PRIMITIVE_DIVISIONS, MAX_PRIMITIVE_TRIANGLES,
    MAX_SHADOW_MAP_SIZE, MAX_SSAA, MAX_TEXTURE_PIXELS, MAX_TEXTURE_PIXELS_PER_MODEL, MAX_TEXT_FILE_BYTES,
    MAX_TRIANGLES, MAX_VERTICES,
};
pub use mesh::{face_normal, CLOSURE_TOLERANCE, FALLBACK_NORMAL};
pub use model::{
    Camera, DepthMode, GouraudClamp, Interpolation, LightingSides, Mesh, NormalEncoding, NormalMap, Object,
    Projection, RenderSettings, Scene, ShadowMode, ShadowPlane, Shadows, SurfaceMaps, TextureMap,
    DEFAULT_SHADOW_MAP_SIZE,
};
pub use occluders::{Occluders, TriangleId};
pub use primitives::{cube, plane, torus, uv_sphere};
pub use shadow::{light_position, shadow_matrix, shadow_matrix_f64};
pub use visibility::{Visibility, Wireframe, WireframeMode};
pub use zline_shading::{
    Attenuation, Cone, Fog, FogCoordinate, FogMode, Light, LightingModel, Material, ShadingMode,
};

// The command line's and the pipeline's limits (threads, tiles, samples).
pub use limits::{MAX_SAMPLES, MAX_THREADS, MAX_TILE_SIZE, MIN_TILE_SIZE};
