//! Scene files' bump maps: `bump = "file.png"` on an object puts a height
//! map on every mesh of it that has texture coordinates, with
//! `bump_scale = k` (default 1; `zline_scene::NormalMap` states the
//! formula) and MikkTSpace tangents where the file gave none. The image is
//! read with the default sampler (repeat; a height map is read at level
//! 0, bilinearly). Errors name the key: a file that cannot be read or
//! decoded, a non-finite scale, `bump_scale` without `bump`, an object no
//! mesh of which has texture coordinates.

use std::path::Path;
use std::sync::Arc;

use zline_scene::{NormalEncoding, NormalMap, TextureMap};
use zline_shading::Sampler;

use super::checks::{Checker, Result, S};
use super::models::ModelPart;
use crate::bump::bumped;
use crate::files::{resolve, LoadOptions};
use crate::texture_file::TextureCache;

/// An object's `bump` and `bump_scale` keys.
pub(super) struct BumpKeys<'a> {
    /// `bump`.
    pub(super) file: Option<&'a S<String>>,
    /// `bump_scale`.
    pub(super) scale: &'a Option<S<f32>>,
}

/// The object's meshes with its bump map (see the module documentation);
/// `parts` unchanged without a `bump` key.
pub(super) fn apply(
    check: &Checker<'_>,
    (options, textures): (LoadOptions, &mut TextureCache),
    keys: BumpKeys<'_>,
    key: &str,
    parts: Vec<ModelPart>,
) -> Result<Vec<ModelPart>> {
    let Some(file) = keys.file else {
        check.not_allowed(keys.scale, key, "bump_scale", "objects without 'bump'")?;
        return Ok(parts);
    };
    let bump_key = format!("{key}.bump");
    let scale = check.optional(keys.scale, &format!("{key}.bump_scale"), 1.0, f32::MIN, f32::MAX)?;
    let path = resolve(check.path, Path::new(file.get_ref()), options)
        .map_err(|why| check.error(file.span(), &bump_key, why))?;
    let mut warnings = Vec::new();
    let texture = textures.file(&path, &mut warnings).map_err(|e| check.error(file.span(), &bump_key, e))?;
    let Some(texture) = texture else {
        return Err(check.error(file.span(), &bump_key, warnings.join("; ")));
    };
    if parts.iter().all(|p| p.mesh.uvs.is_empty()) {
        let why = "needs texture coordinates, and no mesh of this object has them";
        return Err(check.error(file.span(), &bump_key, why));
    }
    let map = TextureMap { texture, sampler: Sampler::default(), alpha_blend: false, alpha_cutoff: None };
    let normal_map = NormalMap { map, encoding: NormalEncoding::Height, scale };
    Ok(parts
        .into_iter()
        .map(|part| match bumped(&part.mesh, &normal_map) {
            Some(mesh) => ModelPart { mesh: Arc::new(mesh), ..part },
            None => part,
        })
        .collect())
}
