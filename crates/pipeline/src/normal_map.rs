//! Bump and normal maps in the frame's tables (`zline_scene::NormalMap`):
//! which objects draw one, and the map's place in the texture table. The
//! kernels that read them are `tile`'s perturbed kernels
//! ([`crate::setup::Kernel::Perturbed`]).

use zline_scene::Scene;

use crate::setup::NormalMapUse;
use crate::tile::FrameTexture;

/// Appends every object's map to the frame's `textures` and records its
/// use per object in `uses` (cleared first): `None` for an object without
/// a map, texture coordinates or tangents. The map keeps its own sampler
/// (the frame's filter override is for diffuse textures) and is read at
/// level 0.
pub(crate) fn prepare(scene: &Scene, textures: &mut Vec<FrameTexture>, uses: &mut Vec<Option<NormalMapUse>>) {
    uses.clear();
    for object in &scene.objects {
        let mesh = &object.mesh;
        let drawn = !mesh.uvs.is_empty() && mesh.tangents.len() == mesh.positions.len();
        let Some(map) = mesh.normal_map.as_ref().filter(|m| drawn && m.scale.is_finite()) else {
            uses.push(None);
            continue;
        };
        uses.push(Some(NormalMapUse {
            index: textures.len() as u32,
            encoding: map.encoding,
            scale: map.scale,
        }));
        textures.push(FrameTexture {
            texture: map.map.texture.clone(),
            sampler: map.map.sampler,
            cutoff: 0.0,
        });
    }
}
