//! glTF 2.0 loading: a `.gltf` (external or `data:` buffers and images) or
//! `.glb` file → a [`GltfScene`]: objects placed by the default scene's
//! node hierarchy, its first camera and its punctual lights.
//!
//! Contract: [`load_gltf_with_warnings`] returns at least one object with at
//! least one triangle, or a [`SceneError`] naming the file and the problem
//! (bad JSON or GLB, a missing or short buffer, an accessor whose data lies
//! outside its buffer or has the wrong type, an invalid mesh). Features
//! zline does not model produce one-line warnings starting with the file,
//! never failures; [`load_gltf`] prints them to stderr.
//!
//! The JSON is parsed and validated by the `gltf` crate. Resources are read
//! here rather than by `gltf::import`, which fails as a whole on the first
//! image it cannot read and panics on some malformed input (a URI whose
//! percent-escapes are not UTF-8, accessor ranges that overflow): buffers
//! are required (a missing one is an error naming it), images follow the
//! OBJ loader's rule (a missing image file is a warning and the mesh is
//! drawn untextured with its base colour; a PNG or JPEG that does not
//! decode is an error naming the image), and every accessor is checked
//! against its buffer before it is read.
//!
//! **Nodes.** The default scene (else the first scene, else every root
//! node) is walked depth first, accumulating `world_from_node` from each
//! node's matrix or TRS. Each mesh primitive of mode TRIANGLES, indexed or
//! not, becomes a [`Mesh`] placed by an [`Object`] with the node's world
//! matrix; a mesh used by several nodes is shared. glTF's front faces are
//! counter-clockwise only under a transform with a positive determinant;
//! under a mirroring one the primitive's triangles are reversed (in a
//! separate copy) so that culling and the front faces stay right.
//! Attributes: POSITION, NORMAL (missing → computed by [`Mesh::new`]) and
//! the base colour texture's TEXCOORD set, with t = 1 − v (glTF's v runs
//! down the image, SPEC §7's t runs up).
//!
//! **Materials.** glTF's metallic–roughness material is the Cook–Torrance
//! model of SPEC §5.2 (GGX), which every material takes
//! ([`zline_shading::Model::CookTorrance`]): base colour kd =
//! baseColorFactor.rgb (times baseColorTexture and COLOR_0), metallic and
//! roughness their factors (times the metallicRoughnessTexture's B and G),
//! the ambient term times the occlusionTexture's 1 + strength·(R − 1),
//! ke = emissiveFactor × KHR_materials_emissive_strength (default 1;
//! clamped to [0, 1]) times the emissiveTexture. The textures are read per
//! sample by Phong shading; flat and Gouraud shading use the factors. For
//! the basic model (`--model basic`) the material also carries the
//! classical mapping:
//! - ka = kd;
//! - ks = mix(0.04, baseColor, metallic) · (1 − roughness): 0.04 is the
//!   reflectance of common dielectrics at normal incidence, metals reflect
//!   their own colour; an unnormalized Blinn–Phong lobe peaks at ks
//!   whatever its width, so the factor (1 − roughness) dims broad lobes
//!   that would otherwise reflect far more light than the rough surface;
//! - ns = 2/α² − 2 with α = roughness² (glTF's perceptual roughness), that
//!   is 2/roughness⁴ − 2, clamped to [1, 1024]: the Blinn–Phong exponent
//!   whose lobe matches a Beckmann/GGX lobe of width α (Walter et al.
//!   2007); the clamp keeps a mirror-smooth surface from an infinite
//!   exponent.
//!
//! And for both:
//! - opacity = baseColorFactor.a for alphaMode BLEND, 1 otherwise, times
//!   1 − KHR_materials_transmission's transmissionFactor (the ray tracer's
//!   kt = 1 − d, SPEC §12; the rasterizer blends such a surface; the
//!   transmissionTexture is not read), and the index of refraction
//!   KHR_materials_ior's ior (default 1.5, the extension's); the ray
//!   tracer's mirror coefficient kr = baseColor × metallic × (1 −
//!   roughness)² (factors, not maps: smooth metals mirror). MASK
//!   with a base colour texture discards samples whose alpha
//!   baseColorFactor.a × texel alpha is below alphaCutoff (default 0.5;
//!   stored as a cutoff on the texel alpha, alphaCutoff / factor.a, in
//!   [`TextureMap::alpha_cutoff`]); without
//!   one (none given, or the texture could not be used) the constant
//!   alpha baseColorFactor.a decides for the whole primitive: below the
//!   cutoff it draws nothing and is left out (a file whose every primitive
//!   is left out so has no triangles, an error), otherwise it is opaque;
//! - back faces are culled unless the material is doubleSided, and only
//!   on closed opaque meshes (the rule of bare OBJ models).
//!
//! Texture samplers: NEAREST → nearest, LINEAR → bilinear,
//! *_MIPMAP_LINEAR and LINEAR_MIPMAP_NEAREST → trilinear (the nearest match
//! zline has), NEAREST_MIPMAP_NEAREST → nearest; without a min filter the
//! mag filter decides (NEAREST → nearest, else the default trilinear).
//! REPEAT → repeat, CLAMP_TO_EDGE → clamp to edge, MIRRORED_REPEAT →
//! repeat with a warning. Texels are used as stored (no sRGB decode,
//! SPEC §7).
//!
//! **Cameras.** The first node with a camera, in walk order, gives the
//! camera: eye = the node's origin, looking down its −z with its +y up.
//! Perspective yfov/znear/zfar → [`Projection::Perspective`] (the
//! aspectRatio is the image's; a missing zfar, an infinite projection, is
//! replaced by a far plane just beyond the farthest corner of the scene's
//! bounding box); orthographic ymag → height 2·ymag (xmag: the image's
//! aspect).
//!
//! **Lights** (KHR_lights_punctual), colour = color × intensity:
//! point → [`Light::Point`] at the node's origin with attenuation
//! a0 = a1 = 0, a2 = 1, the inverse-square law glTF prescribes (SPEC §5's
//! clamp to 1 applies within unit distance), and `range` as the
//! attenuation's range window (SPEC §5.1). Spot → [`Light::Spot`] the same
//! way, pointing along the node's −z, with its cone's inner and outer
//! angles (a cone the extension forbids, e.g. inner ≥ outer or outer past
//! π/2, is warned about and clamped into one). Directional →
//! [`Light::Directional`] along the node's −z in world space.
//!
//! Vertex colours: COLOR_0 (RGB; an alpha below 1 is warned about and
//! ignored) becomes [`Mesh::colors`], a per-vertex factor on kd and ka as
//! glTF's base colour multiplication prescribes (applied by flat and
//! Gouraud shading; Phong shading does not apply it yet).
//!
//! Normal textures (`normalTexture` with its `scale`) perturb the normal
//! in Phong shading (`zline_scene::NormalMap`), with the file's TANGENT
//! or, without one, MikkTSpace tangents; they must use the base colour
//! texture's TEXCOORD set when there is one.
//!
//! All textures of a primitive must use one TEXCOORD set (the base
//! colour's, when it has one); a map on another set is warned about and
//! left out.
//!
//! **Warned and ignored:** COLOR_0 alpha, MIRRORED_REPEAT, primitive
//! modes other than TRIANGLES, skins (drawn in the bind pose), morph
//! targets (drawn without), animations (drawn at rest), extensions other
//! than the two above, a node reached twice
//! (the node graph must be a tree). An `extensionsRequired` entry that the
//! `gltf` crate does not know is an error: the file says it cannot be drawn
//! without it. A node whose world transform is not finite, or collapses
//! every mesh below it to a point (a zero 3 × 3 part, e.g. an all-zero
//! matrix or a zero scale), is skipped with its children and a warning;
//! any other singular transform (flattening) is drawn with a warning.
//!
//! **Checks and limits.** The file is read when at most
//! [`MAX_MODEL_FILE_BYTES`](zline_scene::MAX_MODEL_FILE_BYTES); the GLB
//! framing, `asset.version` (2.x only) and the accessor indices of every
//! primitive are checked before the `gltf` crate validates the document
//! (`document`). Buffer and image URIs must name files in the glTF file's
//! folder unless [`LoadOptions::allow_outside`]. The objects placed may
//! have at most [`MAX_TRIANGLES`](zline_scene::MAX_TRIANGLES) triangles
//! and [`MAX_VERTICES`](zline_scene::MAX_VERTICES) vertices in all. An
//! image error names the material that uses the image.

use std::collections::{HashMap, HashSet};
use std::path::Path;
use std::sync::Arc;

use glam::{Mat4, Vec3};
use gltf::mesh::Mode;
use zline_scene::{Camera, Mesh, Object, Projection};
use zline_shading::{Attenuation, Cone, Light, Sampler, Texture};

use crate::culling::default_culling;
use crate::error::SceneError;
use crate::files::{read_limited, FileKind, LoadOptions};
use crate::texture_file::{DecodeError, TextureCache};

mod attributes;
mod convert;
mod document;
mod maps;
mod resources;

use attributes::Attributes;
pub use convert::MAX_GLTF_SHININESS;
use convert::{
    fit_far_plane, material_from_gltf, material_name, primitive_name, projection_is_valid, reversed,
    sampler_from_gltf,
};
use maps::{SurfaceMap, TextureSource};
use resources::{decode_data_uri, read_buffers, uri_target, UriTarget};

/// Extensions the loader reads (others are warned about).
const SUPPORTED_EXTENSIONS: &[&str] = &[
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_transmission",
];

/// What a glTF file holds, in zline's model (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct GltfScene {
    /// Every mesh primitive placed by a node, in walk order.
    pub objects: Vec<Object>,
    /// The first camera in the node hierarchy, if any.
    pub camera: Option<Camera>,
    /// The KHR_lights_punctual lights, in world space.
    pub lights: Vec<Light>,
}

/// Loads a glTF or GLB file, printing warnings (unsupported features, a
/// missing image) to stderr as `warning: ...` lines.
pub fn load_gltf(path: &Path) -> Result<GltfScene, SceneError> {
    let (scene, warnings) = load_gltf_with_warnings(path)?;
    for w in warnings {
        eprintln!("warning: {w}");
    }
    Ok(scene)
}

/// Loads a glTF or GLB file and returns the scene with the warnings, each
/// a one-line message starting with the file it is about.
pub fn load_gltf_with_warnings(path: &Path) -> Result<(GltfScene, Vec<String>), SceneError> {
    load_gltf_with_options(path, LoadOptions::default())
}

/// [`load_gltf_with_warnings`] with options (files outside the glTF
/// file's folder).
pub fn load_gltf_with_options(
    path: &Path,
    options: LoadOptions,
) -> Result<(GltfScene, Vec<String>), SceneError> {
    let bytes = read_limited(path, FileKind::Model).map_err(|e| e.into_error(path))?;
    parse_gltf(path, bytes, options)
}

/// Loads glTF or GLB bytes read from `path` (which names the file in
/// messages and locates the files it refers to).
pub(crate) fn parse_gltf(
    path: &Path,
    bytes: Vec<u8>,
    options: LoadOptions,
) -> Result<(GltfScene, Vec<String>), SceneError> {
    let (document, blob) = document::parse(path, &bytes)
        .map_err(|message| SceneError::File { path: path.to_path_buf(), message })?;
    drop(bytes);
    let buffers = read_buffers(path, &document, blob, options)?;
    let mut loader = Loader {
        path,
        options,
        buffers,
        textures: TextureCache::default(),
        images: HashMap::new(),
        meshes: HashMap::new(),
        warnings: Vec::new(),
        scene: GltfScene { objects: Vec::new(), camera: None, lights: Vec::new() },
        camera_far_to_fit: false,
        placed: (0, 0),
    };
    loader.warn_about_document(&document);
    loader.walk(&document)?;
    loader.finish()
}

/// A primitive turned into a mesh, shared by every node that draws it.
#[derive(Clone)]
struct LoadedPrimitive {
    mesh: Arc<Mesh>,
    cull_back_faces: bool,
}

/// The state of one load.
struct Loader<'a> {
    path: &'a Path,
    options: LoadOptions,
    buffers: Vec<Vec<u8>>,
    textures: TextureCache,
    /// Decoded images by index; `None` when the image is unusable (warned).
    images: HashMap<usize, Option<Arc<Texture>>>,
    /// Meshes by (mesh, primitive, mirrored); `None` for skipped primitives.
    meshes: HashMap<(usize, usize, bool), Option<LoadedPrimitive>>,
    warnings: Vec<String>,
    scene: GltfScene,
    /// The camera had no zfar: fit it once the geometry is known.
    camera_far_to_fit: bool,
    /// Triangles and vertices of the objects placed so far.
    placed: (usize, usize),
}

impl Loader<'_> {
    fn warn(&mut self, message: String) {
        let message = format!("{}: {message}", self.path.display());
        if !self.warnings.contains(&message) {
            self.warnings.push(message);
        }
    }

    /// Warnings about the file as a whole: extensions and animations.
    fn warn_about_document(&mut self, document: &gltf::Document) {
        for ext in document.extensions_used().filter(|e| !SUPPORTED_EXTENSIONS.contains(e)) {
            self.warn(format!("extension '{ext}' is not supported; ignored"));
        }
        let animations = document.animations().count();
        if animations > 0 {
            self.warn(format!("{animations} animation(s) ignored; the scene is drawn at rest"));
        }
    }

    /// Walks the scene's nodes depth first (see the module doc).
    fn walk(&mut self, document: &gltf::Document) -> Result<(), SceneError> {
        let roots: Vec<gltf::Node> = match document.default_scene().or_else(|| document.scenes().next()) {
            Some(scene) => scene.nodes().collect(),
            None => {
                let children: HashSet<usize> =
                    document.nodes().flat_map(|n| n.children().map(|c| c.index())).collect();
                let roots: Vec<_> = document.nodes().filter(|n| !children.contains(&n.index())).collect();
                if !roots.is_empty() {
                    self.warn("no scene; drawing every root node".into());
                }
                roots
            }
        };
        let mut visited = HashSet::new();
        let mut stack: Vec<(gltf::Node, Mat4)> =
            roots.into_iter().rev().map(|n| (n, Mat4::IDENTITY)).collect();
        while let Some((node, parent)) = stack.pop() {
            if !visited.insert(node.index()) {
                self.warn(format!(
                    "node {} is reached twice (the nodes must form a tree); skipped",
                    node.index()
                ));
                continue;
            }
            let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
            if !world.is_finite() {
                self.warn(format!(
                    "node {} has a non-finite transform; skipped with its children",
                    node.index()
                ));
                continue;
            }
            if glam::Mat3::from_mat4(world) == glam::Mat3::ZERO {
                self.warn(format!(
                    "node {} has a transform that collapses everything to a point (a zero matrix or scale); \
                     skipped with its children",
                    node.index()
                ));
                continue;
            }
            if world.determinant() == 0.0 && node.mesh().is_some() {
                self.warn(format!(
                    "node {} has a singular transform: its meshes are drawn flat",
                    node.index()
                ));
            }
            self.visit(&node, world)?;
            stack.extend(node.children().map(|c| (c, world)).collect::<Vec<_>>().into_iter().rev());
        }
        Ok(())
    }

    /// One node: its mesh, camera and light.
    fn visit(&mut self, node: &gltf::Node, world: Mat4) -> Result<(), SceneError> {
        if node.skin().is_some() {
            self.warn("skins are not supported; skinned meshes are drawn in their bind pose".into());
        }
        if let Some(mesh) = node.mesh() {
            let mirrored = world.determinant() < 0.0;
            for primitive in mesh.primitives() {
                if let Some(loaded) = self.primitive(&mesh, &primitive, mirrored)? {
                    self.placed.0 += loaded.mesh.triangles.len();
                    self.placed.1 += loaded.mesh.positions.len();
                    SceneError::check_size(self.path, self.placed.0, self.placed.1)?;
                    self.scene.objects.push(Object {
                        mesh: loaded.mesh,
                        world_from_object: world,
                        material: None,
                        shading: None,
                        cull_back_faces: loaded.cull_back_faces,
                    });
                }
            }
        }
        if let Some(camera) = node.camera() {
            if self.scene.camera.is_none() {
                self.camera(&camera, world);
            }
        }
        if let Some(light) = node.light() {
            self.light(&light, world);
        }
        Ok(())
    }

    /// The mesh of a primitive, built on first use.
    fn primitive(
        &mut self,
        mesh: &gltf::Mesh,
        primitive: &gltf::Primitive,
        mirrored: bool,
    ) -> Result<Option<LoadedPrimitive>, SceneError> {
        let key = (mesh.index(), primitive.index(), mirrored);
        if let Some(loaded) = self.meshes.get(&key) {
            return Ok(loaded.clone());
        }
        let loaded = match self.meshes.get(&(mesh.index(), primitive.index(), !mirrored)) {
            Some(other) => {
                other.clone().map(|o| LoadedPrimitive { mesh: Arc::new(reversed((*o.mesh).clone())), ..o })
            }
            None => self.build_primitive(mesh, primitive)?.map(|(m, cull)| {
                let m = if mirrored { reversed(m) } else { m };
                LoadedPrimitive { mesh: Arc::new(m), cull_back_faces: cull }
            }),
        };
        self.meshes.insert(key, loaded.clone());
        Ok(loaded)
    }

    /// Reads a primitive into a mesh and its culling flag; `None` (warned)
    /// when it cannot be drawn as triangles.
    fn build_primitive(
        &mut self,
        mesh: &gltf::Mesh,
        primitive: &gltf::Primitive,
    ) -> Result<Option<(Mesh, bool)>, SceneError> {
        let name = primitive_name(mesh, primitive);
        if primitive.mode() != Mode::Triangles {
            self.warn(format!(
                "mesh '{name}': primitive mode {:?} is not supported; skipped",
                primitive.mode()
            ));
            return Ok(None);
        }
        if primitive.morph_targets().len() > 0 {
            self.warn(format!("mesh '{name}': morph targets are not supported; drawn without them"));
        }
        let attributes = Attributes { path: self.path, buffers: &self.buffers };
        let Some(positions) = attributes.read_positions(primitive, &name)? else {
            self.warn(format!("mesh '{name}': primitive has no POSITION; skipped"));
            return Ok(None);
        };
        let normals = attributes.read_normals(primitive, &name, positions.len())?;
        let triangles = attributes.read_triangles(primitive, &name, positions.len())?;
        if triangles.is_empty() {
            return Ok(None);
        }
        let material = primitive.material();
        let base_color = material.pbr_metallic_roughness().base_color_texture();
        let normal_texture = material.normal_texture();
        let metallic_roughness = material.pbr_metallic_roughness().metallic_roughness_texture();
        let (occlusion, emissive) = (material.occlusion_texture(), material.emissive_texture());
        let uv_set = base_color
            .as_ref()
            .map(|info| info.tex_coord())
            .or(normal_texture.as_ref().map(|n| n.tex_coord()))
            .or(metallic_roughness.as_ref().map(|info| info.tex_coord()))
            .or(occlusion.as_ref().map(|o| o.tex_coord()))
            .or(emissive.as_ref().map(|info| info.tex_coord()))
            .unwrap_or(0);
        let uvs = attributes.read_uvs(primitive, &name, uv_set)?;
        let tangents = match normal_texture {
            Some(_) => attributes.read_tangents(primitive, &name, positions.len())?,
            None => None,
        };
        let mesh_error =
            |source| SceneError::Mesh { path: self.path.to_path_buf(), mesh: name.clone(), source };
        let mut built = Mesh::new(name.clone(), positions, normals, triangles, material_from_gltf(&material))
            .map_err(mesh_error)?;
        if let Some(uvs) = uvs {
            built = built.with_uvs(uvs).map_err(mesh_error)?;
        }
        if let Some((colors, alpha_ignored)) = attributes.read_colors(primitive, &name)? {
            if alpha_ignored {
                self.warn(format!("mesh '{name}': vertex colour (COLOR_0) alpha is not supported; ignored"));
            }
            built = built.with_colors(colors).map_err(mesh_error)?;
        }
        let cutoff = material.alpha_cutoff().unwrap_or(0.5);
        if let Some(info) = base_color {
            // glTF masks on factor.a × texel.a ≥ cutoff; the pipeline tests
            // the texel alpha, so the cutoff is divided by the factor once
            // here (equal up to one rounding; a zero factor masks all).
            let factor = material.pbr_metallic_roughness().base_color_factor()[3];
            let texel_cutoff = match (cutoff <= 0.0, factor > 0.0) {
                (true, _) => cutoff,
                (false, true) => cutoff / factor,
                (false, false) => f32::INFINITY,
            };
            let alpha = match material.alpha_mode() {
                gltf::material::AlphaMode::Blend => (true, None),
                gltf::material::AlphaMode::Mask => (false, Some(texel_cutoff)),
                gltf::material::AlphaMode::Opaque => (false, None),
            };
            built = self.attach_base_color(built, &info, uv_set, alpha, &material_name(&material))?;
        }
        if let Some(normal) = normal_texture {
            built = self.attach_normal_map(built, &normal, (uv_set, tangents), &material_name(&material))?;
        }
        let surface = [
            metallic_roughness.map(|info| (SurfaceMap::MetallicRoughness, info.texture(), info.tex_coord())),
            occlusion.map(|o| (SurfaceMap::Occlusion(o.strength()), o.texture(), o.tex_coord())),
            emissive.map(|info| (SurfaceMap::Emission, info.texture(), info.tex_coord())),
        ];
        for (which, texture, set) in surface.into_iter().flatten() {
            built =
                self.attach_surface_map(built, which, (&texture, set), uv_set, &material_name(&material))?;
        }
        if material.alpha_mode() == gltf::material::AlphaMode::Mask && built.diffuse_map.is_none() {
            // MASK on the constant alpha: every sample has the factor's alpha.
            let alpha = material.pbr_metallic_roughness().base_color_factor()[3];
            if alpha < cutoff {
                return Ok(None);
            }
        }
        let cull = !material.double_sided() && default_culling(&built, built.material.opacity);
        Ok(Some((built, cull)))
    }

    /// The decoded image, on first use (see the module doc); errors name
    /// the `material` that uses it.
    fn image(
        &mut self,
        image: &gltf::image::Image,
        material: &str,
    ) -> Result<Option<Arc<Texture>>, SceneError> {
        if let Some(loaded) = self.images.get(&image.index()) {
            return Ok(loaded.clone());
        }
        let index = image.index();
        let image_error = |why: String| SceneError::File {
            path: self.path.to_path_buf(),
            message: format!("material '{material}': image {index}{why}"),
        };
        let colon = |why: String| format!(": {why}");
        let (bytes, hint) = match image.source() {
            gltf::image::Source::View { view, mime_type } => {
                let bytes = view.offset().checked_add(view.length()).and_then(|end| {
                    self.buffers.get(view.buffer().index())?.get(view.offset()..end).map(<[u8]>::to_vec)
                });
                let bytes = bytes
                    .ok_or_else(|| image_error(colon("buffer view reaches beyond its buffer".into())))?;
                (bytes, image::ImageFormat::from_mime_type(mime_type))
            }
            gltf::image::Source::Uri { uri, mime_type } => {
                match uri_target(self.path, uri, self.options).map_err(|e| image_error(colon(e)))? {
                    UriTarget::File(file) => {
                        let mut texture_warnings = Vec::new();
                        let loaded = self.textures.file(&file, &mut texture_warnings).map_err(|e| {
                            SceneError::Texture {
                                model: self.path.to_path_buf(),
                                material: material.to_owned(),
                                source: Box::new(e),
                            }
                        })?;
                        // Named with the model and material, like a texture error.
                        let model = self.path.display();
                        self.warnings.extend(
                            texture_warnings
                                .into_iter()
                                .map(|w| format!("{model}: material '{material}': {w}")),
                        );
                        self.images.insert(index, loaded.clone());
                        return Ok(loaded);
                    }
                    UriTarget::Data => {
                        let bytes = decode_data_uri(uri).map_err(|e| image_error(colon(e)))?;
                        (bytes, mime_type.and_then(image::ImageFormat::from_mime_type))
                    }
                }
            }
        };
        let loaded = match self.textures.decode(&bytes, hint) {
            Ok(texture) => Some(Arc::new(texture)),
            Err(DecodeError::Unsupported(why)) => {
                self.warn(format!("image {index} (embedded): {why}; meshes using it are drawn untextured"));
                None
            }
            Err(DecodeError::Corrupt(why)) => return Err(image_error(format!(" (embedded): {why}"))),
        };
        self.images.insert(index, loaded.clone());
        Ok(loaded)
    }

    /// The sampler mapping of the module doc, warning about mirrored
    /// repeat.
    fn sampler(&mut self, sampler: &gltf::texture::Sampler) -> Sampler {
        let (mapped, mirrored) = sampler_from_gltf(sampler);
        if mirrored {
            self.warn("texture wrap MIRRORED_REPEAT is not supported; using REPEAT".into());
        }
        mapped
    }

    /// Takes the node's camera as the scene's (see the module doc).
    fn camera(&mut self, camera: &gltf::Camera, world: Mat4) {
        let eye = world.transform_point3(Vec3::ZERO);
        let forward = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
        let up = world.transform_vector3(Vec3::Y).normalize_or_zero();
        let projection = match camera.projection() {
            gltf::camera::Projection::Perspective(p) => {
                self.camera_far_to_fit = p.zfar().is_none();
                let (near, far) = (p.znear(), p.zfar().unwrap_or(p.znear() * 2.0));
                Projection::Perspective { fovy_degrees: p.yfov().to_degrees(), near, far }
            }
            gltf::camera::Projection::Orthographic(o) => {
                Projection::Orthographic { height: 2.0 * o.ymag(), near: o.znear(), far: o.zfar() }
            }
        };
        let usable = forward != Vec3::ZERO && up != Vec3::ZERO && forward.cross(up) != Vec3::ZERO;
        if !usable || !projection_is_valid(&projection) {
            self.warn(format!("camera {} is unusable ({projection:?}); ignored", camera.index()));
            self.camera_far_to_fit = false;
            return;
        }
        self.scene.camera = Some(Camera { eye, target: eye + forward, up, projection });
    }

    /// Adds a KHR_lights_punctual light (see the module doc).
    fn light(&mut self, light: &gltf::khr_lights_punctual::Light, world: Mat4) {
        use gltf::khr_lights_punctual::Kind;
        let color = Vec3::from(light.color()) * light.intensity();
        let index = light.index();
        if !color.is_finite() || color.min_element() < 0.0 {
            self.warn(format!("light {index} has an unusable colour × intensity {color}; ignored"));
            return;
        }
        let range = match light.range() {
            Some(r) if r.is_finite() && r > 0.0 => r,
            Some(r) => {
                self.warn(format!(
                    "light {index} has range {r}, not a number > 0; the light reaches everywhere"
                ));
                f32::INFINITY
            }
            None => f32::INFINITY,
        };
        let attenuation = Attenuation::new(0.0, 0.0, 1.0).with_range(range);
        let position = world.transform_point3(Vec3::ZERO);
        let direction = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
        let added = match light.kind() {
            Kind::Directional => (direction != Vec3::ZERO).then_some(Light::Directional { direction, color }),
            Kind::Point => Some(Light::Point { position, color, attenuation }),
            Kind::Spot { inner_cone_angle, outer_cone_angle } => {
                let cone = Cone { inner: inner_cone_angle, outer: outer_cone_angle };
                let cone = match cone.check() {
                    Ok(()) => cone,
                    Err(why) => {
                        let clamped = clamped_cone(cone);
                        self.warn(format!(
                            "light {index}: {why}; drawn with inner {}, outer {}",
                            clamped.inner, clamped.outer
                        ));
                        clamped
                    }
                };
                (direction != Vec3::ZERO).then_some(Light::Spot {
                    position,
                    direction,
                    color,
                    attenuation,
                    cone,
                })
            }
        };
        match added {
            Some(l) => self.scene.lights.push(l),
            None => self.warn(format!("light {index} has a degenerate direction; ignored")),
        }
    }

    /// Fits the camera's far plane if needed and returns the result.
    fn finish(mut self) -> Result<(GltfScene, Vec<String>), SceneError> {
        if self.scene.objects.is_empty() {
            // An error drops the warnings, and they may say why nothing is
            // left (a node skipped, a primitive left out): the error says it.
            let prefix = format!("{}: ", self.path.display());
            let why: Vec<&str> = self.warnings.iter().map(|w| w.strip_prefix(&prefix).unwrap_or(w)).collect();
            if why.is_empty() {
                return Err(SceneError::NoTriangles { path: self.path.to_path_buf() });
            }
            return Err(SceneError::File {
                path: self.path.to_path_buf(),
                message: format!("no triangles ({})", why.join("; ")),
            });
        }
        if let (true, Some(camera)) = (self.camera_far_to_fit, self.scene.camera.as_mut()) {
            fit_far_plane(camera, &self.scene.objects);
        }
        Ok((self.scene, self.warnings))
    }
}

impl TextureSource for Loader<'_> {
    fn warn(&mut self, message: String) {
        Loader::warn(self, message);
    }

    fn image(
        &mut self,
        image: &gltf::image::Image,
        material: &str,
    ) -> Result<Option<Arc<Texture>>, SceneError> {
        Loader::image(self, image, material)
    }

    fn sampler(&mut self, sampler: &gltf::texture::Sampler) -> Sampler {
        Loader::sampler(self, sampler)
    }

    fn path(&self) -> &Path {
        self.path
    }
}

/// A cone the extension allows (0 ≤ inner < outer ≤ π/2) near `cone`:
/// angles that are not finite take glTF's defaults, the outer angle is
/// clamped to [10⁻³, π/2] and the inner one below it.
fn clamped_cone(cone: Cone) -> Cone {
    let pick = |a: f32, default: f32| if a.is_finite() { a } else { default };
    let outer = pick(cone.outer, Cone::GLTF_DEFAULT.outer).clamp(1e-3, std::f32::consts::FRAC_PI_2);
    let inner = pick(cone.inner, 0.0).clamp(0.0, outer * 0.999);
    Cone { inner, outer }
}
