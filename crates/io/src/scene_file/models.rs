//! Model files named by a scene file's objects: OBJ (with its MTL files),
//! glTF/GLB, STL or PLY, chosen by extension. Each distinct file is loaded once and its
//! meshes shared by every object that names it.
//!
//! A glTF file brings its node hierarchy (each mesh keeps its node's
//! transform, below the object's placement) and its double-sided flags; its
//! cameras and lights are not used, since the scene file has its own.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::Mat4;
use zline_scene::Mesh;

use crate::culling::default_culling;
use crate::error::SceneError;
use crate::files::LoadOptions;
use crate::gltf::load_gltf_with_options;
use crate::obj::load_obj_with_options;

/// One mesh of a model file, placed in the model's space.
#[derive(Clone)]
pub(super) struct ModelPart {
    /// The mesh, shared between the objects naming the file.
    pub(super) mesh: Arc<Mesh>,
    /// The mesh's placement in the model file (glTF node transforms;
    /// identity for OBJ).
    pub(super) model_from_mesh: Mat4,
    /// False when the file says the mesh is seen from both sides (a glTF
    /// double-sided material): then it is never culled by default.
    pub(super) cullable: bool,
}

impl ModelPart {
    /// A mesh of its own (a primitive), in place and cullable.
    pub(super) fn alone(mesh: Mesh) -> ModelPart {
        ModelPart { mesh: Arc::new(mesh), model_from_mesh: Mat4::IDENTITY, cullable: true }
    }
}

/// The distinct model files loaded by a scene, by path.
#[derive(Default)]
pub(super) struct ModelCache {
    loaded: HashMap<PathBuf, Vec<ModelPart>>,
}

impl ModelCache {
    /// The meshes of the model file at `path`, loading it on first use
    /// (its warnings are printed to stderr as `warning: ...` lines).
    pub(super) fn get(&mut self, path: &Path, options: LoadOptions) -> Result<Vec<ModelPart>, SceneError> {
        if let Some(parts) = self.loaded.get(path) {
            return Ok(parts.clone());
        }
        let parts = match extension(path).as_deref() {
            Some("gltf" | "glb") => gltf_parts(path, options)?,
            Some("stl") => crate::stl::load_stl(path)?.into_iter().map(ModelPart::alone).collect(),
            Some("ply") => crate::ply::load_ply(path)?.into_iter().map(ModelPart::alone).collect(),
            Some("3mf") => crate::threemf::load_3mf(path)?.into_iter().map(ModelPart::alone).collect(),
            _ => obj_parts(path, options)?,
        };
        self.loaded.insert(path.to_path_buf(), parts.clone());
        Ok(parts)
    }
}

/// The extension in lower case: `.gltf` and `.glb` are glTF, `.stl` STL,
/// `.ply` PLY; anything else is read as OBJ.
fn extension(path: &Path) -> Option<String> {
    path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase)
}

fn print(warnings: Vec<String>) {
    for w in warnings {
        eprintln!("warning: {w}");
    }
}

fn obj_parts(path: &Path, options: LoadOptions) -> Result<Vec<ModelPart>, SceneError> {
    let (meshes, warnings) = load_obj_with_options(path, options)?;
    print(warnings);
    Ok(meshes.into_iter().map(ModelPart::alone).collect())
}

fn gltf_parts(path: &Path, options: LoadOptions) -> Result<Vec<ModelPart>, SceneError> {
    let (gltf, warnings) = load_gltf_with_options(path, options)?;
    print(warnings);
    let parts = gltf.objects.into_iter().map(|o| ModelPart {
        // The loader culls the meshes `default_culling` would unless their
        // material is double-sided; a mesh it would not cull anyway stays
        // cullable, so that the scene's material override decides.
        cullable: o.cull_back_faces || !default_culling(&o.mesh, o.mesh.material.opacity),
        mesh: o.mesh,
        model_from_mesh: o.world_from_object,
    });
    Ok(parts.collect())
}
