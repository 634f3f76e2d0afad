//! The zline scene model and its loaders.
//!
//! This is the one crate that reads files: OBJ+MTL (through tobj) and TOML
//! scene files. Every loader error names the file and what is wrong. It
//! knows nothing of rasterization, screens or threads.

mod error;
mod framing;
mod mesh;
mod model;
mod obj;
mod primitives;

pub use error::{MeshError, SceneError};
pub use framing::{
    default_lights, framing_camera, scene_for_model, DEFAULT_AMBIENT, DEFAULT_BACKGROUND, FRAMING_FOVY_DEGREES,
    VIEW_DIRECTION,
};
pub use mesh::{face_normal, FALLBACK_NORMAL};
pub use model::{Camera, Interpolation, Mesh, Object, Projection, RenderSettings, Scene};
pub use obj::{load_obj, load_obj_with_warnings};
pub use primitives::{cube, plane, torus, uv_sphere};
pub use zline_shading::{Attenuation, Light, LightingModel, Material, ShadingMode};
