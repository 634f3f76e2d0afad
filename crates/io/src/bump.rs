//! A bump map from an image file on every mesh of a scene that has
//! texture coordinates: the CLI's `--bump FILE` (`--bump-scale K`). The
//! scene file's `bump` key does the same per object (`scene_file`).

use std::path::Path;
use std::sync::Arc;

use zline_scene::{Mesh, NormalEncoding, NormalMap, Scene, TextureMap};
use zline_shading::Sampler;

use crate::error::SceneError;
use crate::texture_file::TextureCache;

/// `mesh` with `map` and MikkTSpace tangents (unless it has tangents);
/// `None` when it has no texture coordinates.
pub(crate) fn bumped(mesh: &Mesh, map: &NormalMap) -> Option<Mesh> {
    if mesh.uvs.is_empty() {
        return None;
    }
    let mut mesh = mesh.clone();
    if mesh.tangents.len() != mesh.positions.len() {
        mesh = mesh.with_generated_tangents();
    }
    Some(mesh.with_normal_map(map.clone()))
}

/// Puts the height map in the image `file` (the red channel; default
/// sampler: repeat, read at level 0 bilinearly) with scale `k` on every
/// mesh of `scene` that has texture coordinates, replacing any map it had
/// (see `zline_scene::NormalMap`). Returns how many meshes got it. Errors
/// name the file: it cannot be read, is not a PNG or JPEG, does not
/// decode, or `k` is not finite.
pub fn apply_bump_map(scene: &mut Scene, file: &Path, k: f32) -> Result<usize, SceneError> {
    let error = |message: String| SceneError::File { path: file.to_path_buf(), message };
    if !k.is_finite() {
        return Err(error(format!("bump scale must be finite, got {k}")));
    }
    let mut warnings = Vec::new();
    let Some(texture) = TextureCache::default().file(file, &mut warnings)? else {
        let why: Vec<&str> =
            warnings.iter().map(|w| w.split("; meshes using it").next().unwrap_or(w)).collect();
        return Err(error(format!("cannot use it as a bump map: {}", why.join("; "))));
    };
    let map = TextureMap { texture, sampler: Sampler::default(), alpha_blend: false, alpha_cutoff: None };
    let map = NormalMap { map, encoding: NormalEncoding::Height, scale: k };
    let mut count = 0;
    // A mesh shared by several objects is mapped once and stays shared.
    let mut done: Vec<(*const Mesh, Arc<Mesh>)> = Vec::new();
    for object in &mut scene.objects {
        let key = Arc::as_ptr(&object.mesh);
        if let Some((_, mapped)) = done.iter().find(|(k, _)| *k == key) {
            object.mesh = mapped.clone();
            continue;
        }
        if let Some(mesh) = bumped(&object.mesh, &map) {
            let mapped = Arc::new(mesh);
            done.push((key, mapped.clone()));
            object.mesh = mapped;
            count += 1;
        }
    }
    Ok(count)
}
