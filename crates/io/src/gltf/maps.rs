//! A primitive's textures: the base colour, the normal texture and the
//! material's other maps (metallic–roughness, occlusion, emissive),
//! attached to its mesh when the mesh has their coordinates.

use std::sync::Arc;

use zline_scene::{Mesh, NormalEncoding, NormalMap, TextureMap};
use zline_shading::Texture;

use crate::error::SceneError;

/// Which of a material's other maps a texture is.
#[derive(Clone, Copy, Debug)]
pub(super) enum SurfaceMap {
    MetallicRoughness,
    /// With its strength.
    Occlusion(f32),
    Emission,
}

impl SurfaceMap {
    fn name(self) -> &'static str {
        match self {
            SurfaceMap::MetallicRoughness => "metallic-roughness",
            SurfaceMap::Occlusion(_) => "occlusion",
            SurfaceMap::Emission => "emissive",
        }
    }
}

/// What attaching a texture needs from the loader: its warnings, its
/// images (decoded once) and samplers, and the file's path for errors.
/// The attaching itself is this trait's provided methods, so this module
/// needs nothing of its parent.
pub(super) trait TextureSource {
    /// Records a warning.
    fn warn(&mut self, message: String);
    /// The decoded image, on first use; errors name the `material`.
    fn image(
        &mut self,
        image: &gltf::image::Image,
        material: &str,
    ) -> Result<Option<Arc<Texture>>, SceneError>;
    /// zline's sampler for a glTF sampler (warning about what it lacks).
    fn sampler(&mut self, sampler: &gltf::texture::Sampler) -> zline_shading::Sampler;
    /// The file being loaded.
    fn path(&self) -> &std::path::Path;

    /// The mesh with its base colour texture, when the mesh has the
    /// coordinates and the image can be used (warnings otherwise).
    fn attach_base_color(
        &mut self,
        mesh: Mesh,
        info: &gltf::texture::Info,
        set: u32,
        (alpha_blend, alpha_cutoff): (bool, Option<f32>),
        material: &str,
    ) -> Result<Mesh, SceneError> {
        if mesh.uvs.is_empty() {
            let name = &mesh.name;
            self.warn(format!("mesh '{name}': base colour texture but no TEXCOORD_{set}; drawn untextured"));
            return Ok(mesh);
        }
        let texture = info.texture();
        let Some(image) = self.image(&texture.source(), material)? else { return Ok(mesh) };
        let sampler = self.sampler(&texture.sampler());
        Ok(mesh.with_diffuse_map(TextureMap { texture: image, sampler, alpha_blend, alpha_cutoff }))
    }

    /// The mesh with one of its material's other maps (metallic–roughness:
    /// B metallic, G roughness; occlusion: R; emissive: RGB;
    /// `zline_scene::SurfaceMaps`), when the mesh has the texture's
    /// coordinates (one set per mesh: the base colour's, if any) and the
    /// image can be used; warnings otherwise. The maps are read with the
    /// base colour texture's coordinates, so a mesh without a base colour
    /// texture gets a white one (texels of 1 change nothing).
    fn attach_surface_map(
        &mut self,
        mut mesh: Mesh,
        which: SurfaceMap,
        (texture, theirs): (&gltf::Texture, u32),
        set: u32,
        material: &str,
    ) -> Result<Mesh, SceneError> {
        let (name, what) = (mesh.name.clone(), which.name());
        if theirs != set {
            self.warn(format!(
                "mesh '{name}': {what} texture on TEXCOORD_{theirs}, the others on TEXCOORD_{set}; \
                 one set per mesh is supported: drawn without it"
            ));
            return Ok(mesh);
        }
        if mesh.uvs.is_empty() {
            self.warn(format!("mesh '{name}': {what} texture but no TEXCOORD_{set}; drawn without it"));
            return Ok(mesh);
        }
        let Some(image) = self.image(&texture.source(), material)? else { return Ok(mesh) };
        let sampler = self.sampler(&texture.sampler());
        if mesh.diffuse_map.is_none() {
            let white = Arc::new(Texture::solid(glam::Vec4::ONE));
            mesh.diffuse_map =
                Some(TextureMap { texture: white, sampler, alpha_blend: false, alpha_cutoff: None });
        }
        let map = TextureMap { texture: image, sampler, alpha_blend: false, alpha_cutoff: None };
        let maps = &mut mesh.surface_maps;
        match which {
            SurfaceMap::MetallicRoughness => maps.metallic_roughness = Some(map),
            SurfaceMap::Occlusion(strength) => maps.occlusion = Some((map, strength)),
            SurfaceMap::Emission => maps.emission = Some(map),
        }
        Ok(mesh)
    }

    /// The mesh with its normal texture (glTF `normalTexture` and its
    /// `scale`, `zline_scene::NormalMap`) and tangents — the file's
    /// TANGENT, or MikkTSpace's when it has none, as glTF prescribes —
    /// when the mesh has the texture's coordinates (the set the base
    /// colour uses, if any) and the image can be used; warnings otherwise.
    fn attach_normal_map(
        &mut self,
        mesh: Mesh,
        normal: &gltf::material::NormalTexture,
        (set, tangents): (u32, Option<Vec<glam::Vec4>>),
        material: &str,
    ) -> Result<Mesh, SceneError> {
        let name = mesh.name.clone();
        if normal.tex_coord() != set {
            let (theirs, ours) = (normal.tex_coord(), set);
            self.warn(format!(
                "mesh '{name}': normal texture on TEXCOORD_{theirs}, base colour on TEXCOORD_{ours};                  one set per mesh is supported: drawn without the normal texture"
            ));
            return Ok(mesh);
        }
        if mesh.uvs.is_empty() {
            self.warn(format!("mesh '{name}': normal texture but no TEXCOORD_{set}; drawn without it"));
            return Ok(mesh);
        }
        let texture = normal.texture();
        let Some(image) = self.image(&texture.source(), material)? else { return Ok(mesh) };
        let sampler = self.sampler(&texture.sampler());
        let mesh_error =
            |source| SceneError::Mesh { path: self.path().to_path_buf(), mesh: name.clone(), source };
        let mesh = match tangents {
            Some(tangents) => mesh.with_tangents(tangents).map_err(mesh_error)?,
            None => mesh.with_generated_tangents(),
        };
        if mesh.tangents.is_empty() {
            self.warn(format!(
                "mesh '{name}': no tangents could be made for the normal texture; drawn without it"
            ));
            return Ok(mesh);
        }
        let map = TextureMap { texture: image, sampler, alpha_blend: false, alpha_cutoff: None };
        let scale = normal.scale();
        Ok(mesh.with_normal_map(NormalMap { map, encoding: NormalEncoding::Tangent, scale }))
    }
}
