//! One frame, end to end, in named steps: [`Frame::new`] (sizes, matrices,
//! depth encoding), [`Renderer::prepare_tables`] (lights, materials and
//! textures of the frame), [`Renderer::setup_object`] (vertex stage and
//! setup per object), binning, and [`Renderer::draw_tiles`] (the tiles in
//! parallel, each: opaque pass → fog → transparency pass → resolve).

pub(crate) mod inspect;
pub(crate) mod overdraw;
mod tiles;

use rayon::prelude::*;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use glam::{Mat4, Vec3};
use zline_raster::Rect;
use zline_scene::{DepthMode, Object, Scene, ShadowMode, TextureMap, Visibility};
use zline_shading::{
    Filter, LightingModel, Material, PreparedLights, PreparedMaterial, ShadingMode, Texture,
};

use crate::adaptive::Adaptive;
use crate::bin::{bin_primitives, bin_primitives_painter, Bins, PrimitiveRef, TileGrid, MAX_PIECES};
use crate::image::Image;
use crate::lines::{LineFrame, Lines};
use crate::lod::{Choice, LodView};
use crate::setup::lanes::{LanesKind, SetupTriangles};
use crate::setup::{
    gather, setup_triangle, AlphaUse, DepthEncoding, Faces, LevelOfDetail, NormalMapUse, PassKind,
    PrimitiveChunk, SetupContext, TextureUse, VertexColors, Viewer,
};
use crate::shadow;
use crate::shadow_map::ShadowMaps;
use crate::tile::{FrameTexture, SurfaceUse, TileTarget};
use crate::vertex::{
    transform_compact, transform_mesh, ClipVertex, CompactVertices, ObjectTransforms, Screen, Source,
    VertexLighting, VertexLights, Viewport,
};
use crate::volume::ClipVolume;

/// Triangles per rayon task in setup.
const TRIANGLE_CHUNK: usize = 2048;

/// The smallest setup chunk: a small mesh is cut finer than
/// [`TRIANGLE_CHUNK`] so that every thread gets a few chunks (a 2k sphere in
/// one chunk was set up on one thread).
const MIN_TRIANGLE_CHUNK: usize = 256;

/// Settings of the pipeline itself (the scene's settings say what to draw).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderOptions {
    /// Tile edge in pixels. Any value gives the same image: 0 is taken as
    /// 1, and a value above [`MAX_TILE_SIZE`](zline_scene::MAX_TILE_SIZE)
    /// (up to `u32::MAX`) as that.
    pub tile_size: u32,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions { tile_size: 64 }
    }
}

/// Counts and stage times from one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Triangles in the scene.
    pub triangles: u64,
    /// Primitives drawn after culling and clipping.
    pub primitives: u64,
    /// Samples that passed the depth test and were shaded.
    pub fragments: u64,
    /// Primitives skipped whole in a tile by hierarchical depth: the
    /// tile's every sample drawn, and nearer than the primitive could be
    /// anywhere within its bounds there (`tile::coarse`). A primitive
    /// counts once for each tile and pass (opaque, transparent) it is
    /// skipped in; the count depends on the tile size, not on the threads.
    pub hidden: u64,
    /// Triangles of the meshes drawn: `triangles` less what the adaptive
    /// mode's simplified levels left out (`crate::lod`).
    pub triangles_drawn: u64,
    /// Objects the adaptive mode drew from a simplified level.
    pub simplified: u64,
    /// Time in the vertex stage and triangle setup.
    pub geometry: Duration,
    /// Time binning primitives into tiles.
    pub binning: Duration,
    /// Time rasterizing and resolving the tiles.
    pub raster: Duration,
}

/// Renders `scene` with the current rayon thread pool into a new image.
/// [`Renderer::render_into`] reuses buffers across frames.
pub fn render(scene: &Scene, options: &RenderOptions) -> (Image, RenderStats) {
    let mut image = Image::empty();
    let stats = Renderer::default().render_into(scene, options, &mut image);
    (image, stats)
}

/// A renderer that keeps its working buffers (transformed vertices,
/// primitives, bins, the frame's tables, the tile buffers) from frame to
/// frame, so that a steady stream of frames of the same scene allocates
/// nothing once the first has sized them (with the adaptive mode off; a
/// test counts). The image is the same as [`render`]'s.
#[derive(Debug, Default)]
pub struct Renderer {
    vertices: VertexBuffers,
    /// Setup output, one chunk per rayon task; `chunks[..used]` hold this
    /// frame's primitives in draw order.
    chunks: Vec<PrimitiveChunk>,
    used: usize,
    bins: Bins,
    tables: FrameTables,
    /// One per thread of the pool: a band is drawn with its thread's
    /// buffers, so the tile buffers a frame touches stay as few as the
    /// threads (hot in cache) rather than one set per band.
    buffers: Vec<Mutex<BandBuffers>>,
    /// Scratch for one (plane, light) pair's planar shadow mesh.
    shadow_mesh: Option<zline_scene::Mesh>,
    /// Scratch for the casters' world-space vertices and shadow polygons
    /// (planar shadows).
    shadow_scratch: shadow::CasterScratch,
    /// The frame's shadow maps (`ShadowMode::Map`).
    maps: ShadowMaps,
    /// True when this frame reads `maps` (`ShadowMode::Map` with lights).
    maps_drawn: bool,
    /// The frame's lines (`RenderSettings::wireframe`).
    lines: Lines,
    /// This frame is the normals frame (`Renderer::render_normals_into`).
    pub(crate) normals: bool,
    /// This frame counts overdraw under this rule instead of drawing
    /// (`Renderer::render_overdraw_into`).
    overdraw: Option<zline_raster::TieRule>,
    /// The pixel the inspector follows this frame (`Renderer::inspect`):
    /// setup then records each primitive's triangle.
    probe: Option<(u32, u32)>,
    /// With the adaptive mode, per object of the last frame: the
    /// simplified level drawn (`crate::lod`), `None` for the full mesh.
    levels: Vec<Option<usize>>,
    /// The adaptive mode draws every mesh in full
    /// ([`Renderer::set_level_of_detail`]).
    full_meshes: bool,
    /// Per band of tile rows in the last frame, top first, per piece
    /// (`pieces` used): the samples shaded and the time taken
    /// ([`Renderer::unit_times`]).
    bands: Vec<[(u64, Duration); MAX_PIECES]>,
    pieces: usize,
    /// [`Renderer::set_band_pieces`].
    band_pieces: Option<usize>,
}

/// The frame's lights, materials and textures, indexed by the primitives.
#[derive(Debug, Default)]
struct FrameTables {
    lighting: PreparedLights,
    /// No lights: what shadow primitives are set up with.
    unlit: PreparedLights,
    /// Each object's material at its index; with the adaptive mode, each
    /// object's material without specular at objects + index.
    materials: Vec<PreparedMaterial>,
    textures: Vec<FrameTexture>,
    /// Per object's material: its Cook–Torrance maps in `textures`.
    surfaces: Vec<SurfaceUse>,
    /// Per object: its texture's use.
    object_textures: Vec<Option<TextureUse>>,
    /// Per object: its bump or normal map, when it has one with texture
    /// coordinates and tangents.
    object_maps: Vec<Option<NormalMapUse>>,
    /// Colour textures decoded from sRGB (for a tone mapping that ends in
    /// sRGB), each beside the texture it was made from; kept from frame to
    /// frame.
    linear: Vec<(Arc<Texture>, Arc<Texture>)>,
}

impl FrameTables {
    /// `texture` as a frame reads a colour texture: decoded from sRGB
    /// when `decode` (once per texture, kept), else as stored.
    fn colour_texture(&mut self, texture: &Arc<Texture>, decode: bool) -> Arc<Texture> {
        if !decode {
            return texture.clone();
        }
        if let Some((_, linear)) = self.linear.iter().find(|(t, _)| Arc::ptr_eq(t, texture)) {
            return linear.clone();
        }
        let linear = Arc::new(texture.srgb_decoded());
        self.linear.push((texture.clone(), linear.clone()));
        linear
    }
}

/// A thread's tile buffers and the transparency pass's sort scratch,
/// aligned to 128 bytes so that two threads never write the same cache
/// line.
#[derive(Debug, Default)]
#[repr(align(128))]
struct BandBuffers {
    target: TileTarget,
    order: Vec<(f32, PrimitiveRef)>,
    /// The band's tiles with nothing to draw, as runs of neighbours,
    /// filled after the others.
    untouched: Vec<Rect>,
}

/// What the whole frame shares: sizes, matrices, depth encoding.
pub(crate) struct Frame {
    /// The image in pixels.
    pub(crate) width: u32,
    pub(crate) height: u32,
    /// Samples per pixel along each axis (supersampling).
    n: u32,
    /// The window in samples.
    viewport: Viewport,
    eye_from_world: Mat4,
    clip_from_eye: Mat4,
    depth: DepthEncoding,
    viewer: Viewer,
    adaptive: Option<Adaptive>,
    /// The level-of-detail choice, with the adaptive mode.
    lod: Option<LodView>,
}

impl Frame {
    fn new(scene: &Scene) -> Frame {
        let s = &scene.settings;
        // Sides and supersampling factors larger than scene files accept are
        // taken as the largest (the sample window then fits an i32).
        let side = |v: u32| v.clamp(1, zline_scene::MAX_IMAGE_SIDE);
        let (width, height) = (side(s.width), side(s.height));
        // Supersampling renders an n× larger window of samples (every stage
        // works in samples) and box-filters it in the resolve. Larger
        // factors than scene files accept are taken as the largest.
        let n = s.ssaa.clamp(1, zline_scene::MAX_SSAA);
        let depth = match s.depth {
            DepthMode::ReversedFloat => {
                let (a, b) = scene.camera.reversed_depth_coefficients();
                let perspective = scene.camera.projection.is_perspective();
                DepthEncoding::Reversed { a, b, perspective }
            }
            DepthMode::Normalized => DepthEncoding::Normalized,
        };
        let viewer =
            if scene.camera.projection.is_perspective() { Viewer::AtOrigin } else { Viewer::AlongMinusZ };
        let eye_from_world = scene.camera.eye_from_world();
        // The adaptive bounds assume the ambient light is the same in every
        // direction: an environment map leaves the frame at full evaluation.
        // Nor do they hold through a tone mapping (their tolerance is in
        // steps of the clamped colour).
        let uniform = scene.environment.is_none() && s.tone_mapping.is_identity();
        let adaptive = s.adaptive_tolerance.filter(|_| uniform).and_then(|t| {
            let model =
                LightingModel { ambient: scene.ambient, lights: scene.lights.clone(), environment: None };
            Adaptive::new(t, &model.transformed(&eye_from_world))
        });
        let clip_from_eye = scene.camera.clip_from_eye(width as f32 / height as f32);
        let lod = LodView::new(scene, eye_from_world, clip_from_eye, height * n, n);
        Frame {
            width,
            height,
            n,
            viewport: Viewport { width: width * n, height: height * n },
            eye_from_world,
            clip_from_eye,
            depth,
            viewer,
            adaptive,
            lod,
        }
    }
}

impl Renderer {
    /// Renders `scene` into `image` (resized as needed) with the current
    /// rayon thread pool.
    pub fn render_into(&mut self, scene: &Scene, options: &RenderOptions, image: &mut Image) -> RenderStats {
        self.normals = false;
        self.render_frame(scene, options, image, None)
    }

    /// Lets the adaptive mode draw simplified meshes (`crate::lod`; the
    /// default) or not (`false`: every mesh in full, every other shortcut
    /// kept), for comparing the two.
    pub fn set_level_of_detail(&mut self, on: bool) {
        self.full_meshes = !on;
    }

    /// With the adaptive mode, per object of the last frame, the simplified
    /// level it was drawn with (`crate::lod`; 0 is the coarsest), `None`
    /// for the full mesh; empty without the adaptive mode.
    pub fn levels_drawn(&self) -> &[Option<usize>] {
        &self.levels
    }

    /// [`Self::render_into`], and when `depth` is given, each pixel's
    /// nearest stored depth (the raw depth-buffer value, the far value
    /// where nothing was drawn; see `crate::layers`) into it, resized to
    /// the image.
    pub(crate) fn render_frame(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        image: &mut Image,
        depth: Option<&mut Vec<f32>>,
    ) -> RenderStats {
        let start = Instant::now();
        let frame = Frame::new(scene);
        self.prepare_tables(scene, &frame);
        let mut stats = RenderStats::default();
        self.used = 0;
        self.levels.clear();
        for (index, object) in scene.objects.iter().enumerate() {
            stats.triangles += object.mesh.triangles.len() as u64;
            stats.triangles_drawn += self.setup_object(scene, index, object, &frame) as u64;
        }
        stats.simplified = self.levels.iter().flatten().count() as u64;
        stats.primitives = self.chunks[..self.used].iter().map(|c| c.draws.len() as u64).sum();
        if scene.shadows.mode == ShadowMode::Planar {
            self.setup_shadows(scene, &frame);
        }
        self.maps_drawn = scene.shadows.mode == ShadowMode::Map && !scene.lights.is_empty();
        if self.maps_drawn {
            self.maps.rebuild(scene, &frame.eye_from_world);
        }
        if scene.settings.wireframe.drawn() {
            self.setup_lines(scene, &frame);
        }
        stats.geometry = start.elapsed();

        let start = Instant::now();
        let tile_size = options.tile_size.clamp(1, zline_scene::MAX_TILE_SIZE);
        let grid = TileGrid::new(frame.viewport.width, frame.viewport.height, tile_size * frame.n);
        match scene.settings.visibility {
            Visibility::ZBuffer => bin_primitives(&self.chunks[..self.used], &grid, &mut self.bins),
            Visibility::Painter => bin_primitives_painter(&self.chunks[..self.used], &grid, &mut self.bins),
        }
        if scene.settings.wireframe.drawn() {
            self.lines.bin(&grid, frame.n);
        }
        stats.binning = start.elapsed();

        let start = Instant::now();
        if let Some(rule) = self.overdraw {
            self.bands.clear(); // no tile is drawn: no unit times
            let size = (frame.width, frame.height, frame.n);
            self.count_tiles(&grid, size, rule, &mut image.pixels);
            (image.width, image.height) = (frame.width, frame.height);
            stats.raster = start.elapsed();
            return stats;
        }
        (stats.fragments, stats.hidden) = self.draw_tiles(scene, &frame, &grid, (image, depth));
        stats.raster = start.elapsed();
        stats
    }

    /// The frame's lights (in eye space), materials (sanitized; with the
    /// adaptive mode, also without specular) and textures (the frame's
    /// filter override applied; texels shared, not copied).
    fn prepare_tables(&mut self, scene: &Scene, frame: &Frame) {
        let t = &mut self.tables;
        t.lighting.prepare((scene.ambient, scene.environment.as_ref()), &scene.lights, &frame.eye_from_world);
        t.lighting.set_tone_mapping(&scene.settings.tone_mapping);
        t.materials.clear();
        t.materials.extend(scene.objects.iter().map(|o| PreparedMaterial::new(o.material().sanitized())));
        for (p, plane) in scene.shadows.planes.iter().enumerate() {
            let first = shadow::first_bit(p, scene.lights.len());
            if let (true, Some(m)) =
                (scene.shadows.receives(plane.receiver), t.materials.get_mut(plane.receiver))
            {
                m.shadow_bits = m.shadow_bits.or(first);
            }
        }
        if frame.adaptive.is_some() {
            for i in 0..scene.objects.len() {
                let plain = Material { ks: Vec3::ZERO, ..t.materials[i].material };
                let shadow_bits = t.materials[i].shadow_bits;
                t.materials.push(PreparedMaterial { shadow_bits, ..PreparedMaterial::new(plain) });
            }
        }
        t.textures.clear();
        t.object_textures.clear();
        // A tone mapping that ends in sRGB reads colour textures as linear
        // values (SPEC §7); without one they are used as stored.
        let decode_srgb = scene.settings.tone_mapping.operator != zline_shading::ToneMap::None;
        if !decode_srgb {
            t.linear.clear();
        }
        for object in &scene.objects {
            let map = object.mesh.diffuse_map.as_ref().filter(|_| !object.mesh.uvs.is_empty());
            let Some(map) = map else {
                t.object_textures.push(None);
                continue;
            };
            let mut sampler = map.sampler;
            if let Some(filter) = scene.settings.texture_filter {
                sampler.filter = filter;
            }
            let lod = match sampler.filter {
                Filter::Trilinear => LevelOfDetail::Derivatives,
                Filter::Nearest | Filter::Bilinear => LevelOfDetail::Base,
            };
            let alpha = match (map.alpha_cutoff, map.alpha_blend) {
                (Some(_), _) => AlphaUse::Mask,
                (None, true) => AlphaUse::Blend,
                (None, false) => AlphaUse::Ignore,
            };
            let index = t.textures.len() as u32;
            t.object_textures.push(Some(TextureUse { index, lod, alpha }));
            let cutoff = map.alpha_cutoff.unwrap_or(0.0);
            let texture = t.colour_texture(&map.texture, decode_srgb);
            t.textures.push(FrameTexture { texture, sampler, cutoff });
        }
        // A Cook–Torrance material's maps, read with the base colour
        // texture's coordinates (so only beside one).
        t.surfaces.clear();
        for (index, object) in scene.objects.iter().enumerate() {
            let maps = &object.mesh.surface_maps;
            let used = t.object_textures[index].is_some() && t.materials[index].microfacet.is_some();
            let mut push = |map: Option<&TextureMap>, colour: bool| {
                let map = map.filter(|_| used)?;
                let mut sampler = map.sampler;
                if let Some(filter) = scene.settings.texture_filter {
                    sampler.filter = filter;
                }
                let texture = t.colour_texture(&map.texture, colour && decode_srgb);
                t.textures.push(FrameTexture { texture, sampler, cutoff: 0.0 });
                Some(t.textures.len() as u32 - 1)
            };
            let metallic_roughness = push(maps.metallic_roughness.as_ref(), false);
            let occlusion = maps
                .occlusion
                .as_ref()
                .and_then(|(map, strength)| Some((push(Some(map), false)?, *strength)));
            let emission = push(maps.emission.as_ref(), true);
            t.surfaces.push(SurfaceUse { metallic_roughness, occlusion, emission });
        }
        crate::normal_map::prepare(scene, &mut t.textures, &mut t.object_maps);
    }

    /// The vertex stage and setup of one object, appending its primitives
    /// in mesh order. Every per-object decision is made here, once. Returns
    /// the triangles of the mesh drawn (a simplified level's, or the
    /// object's own).
    fn setup_object(&mut self, scene: &Scene, index: usize, object: &Object, frame: &Frame) -> usize {
        // The adaptive mode may draw a simplified level (`crate::lod`).
        let choice = frame.lod.filter(|_| !self.full_meshes).map(|view| view.choose(object));
        if let Some(choice) = &choice {
            self.levels.push(match choice {
                Choice::Full => None,
                Choice::Level { k, .. } => Some(*k),
            });
        }
        let mesh: &zline_scene::Mesh = match &choice {
            Some(Choice::Level { mesh, .. }) => mesh,
            _ => &object.mesh,
        };
        // A surface that receives planar shadows is lit per sample, where
        // the tile's shadow mask says which lights each sample sees.
        let receives = scene.shadows.receives(index) && !scene.lights.is_empty();
        let mut shading =
            if receives { ShadingMode::Phong } else { object.shading.unwrap_or(scene.settings.shading) };
        let mut texture = self.tables.object_textures[index];
        let mut vertex_colors =
            if mesh.colors.is_empty() { VertexColors::Absent } else { VertexColors::Present };
        if self.normals {
            // Normals: flat objects keep their face normal, every other is
            // interpolated per sample; no texture, no vertex colour.
            shading = if shading == ShadingMode::Flat { ShadingMode::Flat } else { ShadingMode::Phong };
            (texture, vertex_colors) = (None, VertexColors::Absent);
        }
        let vertex_lighting =
            VertexLighting::choose(shading, texture.is_some(), vertex_colors == VertexColors::Present);
        let normal_map = self.tables.object_maps[index]
            .filter(|_| shading == ShadingMode::Phong && vertex_colors == VertexColors::Absent);
        let t = &self.tables;
        let material = &t.materials[index];
        let diffuse_only = if frame.adaptive.is_some() { scene.objects.len() + index } else { index };
        let ctx = SetupContext {
            viewport: frame.viewport,
            volume: ClipVolume::new(frame.viewport.width, frame.viewport.height),
            depth: frame.depth,
            shading,
            vertex_lighting,
            interpolation: scene.settings.interpolation,
            faces: if object.cull_back_faces { Faces::Front } else { Faces::Both },
            sides: scene.settings.lighting_sides,
            gouraud_clamp: scene.settings.gouraud_clamp,
            viewer: frame.viewer,
            material: (material, index as u32),
            lighting: &t.lighting,
            // The adaptive mode's bounds know nothing of a normal map.
            adaptive: frame.adaptive.as_ref().filter(|_| !receives && normal_map.is_none()),
            diffuse_only: (&t.materials[diffuse_only], diffuse_only as u32),
            texture,
            vertex_colors,
            normal_map,
            normals: self.normals,
        };
        let opacity = material.material.opacity;
        let pass = if self.normals {
            PassKind::Opaque
        } else if is_transparent(object) {
            PassKind::Transparent { kt: 1.0 - opacity }
        } else {
            PassKind::Opaque
        };

        let lights = match vertex_lighting {
            VertexLighting::VertexStage => {
                // Two-sided lighting of triangles seen from behind reads
                // the vertex stage's turned colours (`setup::turned`).
                let clamp = scene.settings.gouraud_clamp;
                Some(VertexLights { lights: &t.lighting, material, clamp, turned: ctx.turns_back_faces() })
            }
            VertexLighting::Unlit | VertexLighting::Setup => None,
        };
        let transforms =
            ObjectTransforms::new(frame.clip_from_eye, frame.eye_from_world, object.world_from_object);
        let out = (&mut self.vertices, &mut self.chunks, &mut self.used);
        setup_mesh(mesh, (&transforms, lights), &ctx, (pass, self.probe.is_some()), out);
        mesh.triangles.len()
    }

    /// Planar shadows: for each receiving plane and light that has a bit in
    /// the shadow mask (`shadow::pairs`), every other object projected onto
    /// the plane (`shadow::project_casters`), set up flat in a
    /// [`PassKind::Shadow`] chunk of that bit.
    fn setup_shadows(&mut self, scene: &Scene, frame: &Frame) {
        let planes = &scene.shadows.planes;
        if scene.objects.is_empty() {
            return;
        }
        let mut mesh = self.shadow_mesh.take().unwrap_or_else(shadow::empty_mesh);
        let t = &self.tables;
        for (p, k, bit) in shadow::pairs(planes.len(), scene.lights.len()) {
            let casters = scene.objects.iter().enumerate().filter(|(i, _)| !scene.shadows.receives(*i));
            let Some(receiver) = scene.objects.get(planes[p].receiver) else {
                continue;
            };
            let casters = casters.map(|(_, o)| o);
            let out = (&mut mesh, &mut self.shadow_scratch);
            shadow::project_casters(&planes[p], &scene.lights[k], (receiver, casters), out);
            if mesh.triangles.is_empty() {
                continue;
            }
            let material = (&t.materials[0], 0);
            let ctx = SetupContext {
                viewport: frame.viewport,
                volume: ClipVolume::new(frame.viewport.width, frame.viewport.height),
                depth: frame.depth,
                shading: ShadingMode::Flat,
                vertex_lighting: VertexLighting::Unlit,
                interpolation: scene.settings.interpolation,
                faces: Faces::Both,
                sides: scene.settings.lighting_sides,
                gouraud_clamp: scene.settings.gouraud_clamp,
                viewer: frame.viewer,
                material,
                // Never drawn: no lights to light their flat colour with.
                lighting: &t.unlit,
                adaptive: None,
                diffuse_only: material,
                texture: None,
                vertex_colors: VertexColors::Absent,
                normal_map: None,
                normals: false,
            };
            let transforms = ObjectTransforms::new(frame.clip_from_eye, frame.eye_from_world, Mat4::IDENTITY);
            let out = (&mut self.vertices, &mut self.chunks, &mut self.used);
            setup_mesh(&mesh, (&transforms, None), &ctx, (PassKind::Shadow { bit }, false), out);
        }
        self.shadow_mesh = Some(mesh);
    }

    /// The mesh edges of every object as clipped window segments
    /// ([`crate::lines`]).
    fn setup_lines(&mut self, scene: &Scene, frame: &Frame) {
        let wireframe = scene.settings.wireframe;
        self.lines.reset(wireframe.mode, scene.background);
        let line_frame = LineFrame {
            width: frame.width,
            height: frame.height,
            depth: frame.depth,
            perspective: frame.viewer == Viewer::AtOrigin,
        };
        for object in &scene.objects {
            let transforms =
                ObjectTransforms::new(frame.clip_from_eye, frame.eye_from_world, object.world_from_object);
            self.lines.add_object(&object.mesh, &transforms, &line_frame, wireframe.feature_angle);
        }
    }
}

/// The vertex stage's output for the object being set up: whole records,
/// or compact ones for an object set up in lanes.
#[derive(Debug, Default)]
struct VertexBuffers {
    full: Vec<ClipVertex>,
    compact: CompactVertices,
}

/// Transforms `mesh` (`vertices`) and sets up its triangles in parallel
/// chunks appended after `chunks[..used]`, all in `pass`; with `sources`
/// (the pixel inspector), each chunk records which triangle made each
/// primitive.
fn setup_mesh(
    mesh: &zline_scene::Mesh,
    (transforms, lights): (&ObjectTransforms, Option<VertexLights<'_>>),
    ctx: &SetupContext<'_>,
    (pass, sources): (PassKind, bool),
    (vertices, chunks, used): (&mut VertexBuffers, &mut Vec<PrimitiveChunk>, &mut usize),
) {
    let screen = Screen { viewport: ctx.viewport, volume: ctx.volume };
    let lanes = LanesKind::choose(ctx, sources);
    match lanes {
        Some(kind) => {
            transform_compact(mesh, transforms, lights, &screen, kind.layout(ctx), &mut vertices.compact)
        }
        None => transform_mesh(mesh, transforms, lights, &screen, &mut vertices.full),
    }
    let (compact, vertices) = (&vertices.compact, vertices.full.as_slice());
    let source = Source { mesh, t: transforms, screen: &screen };
    let chunk = crate::tasks::task_len(mesh.triangles.len(), (MIN_TRIANGLE_CHUNK, TRIANGLE_CHUNK));
    let (first, n) = (*used, mesh.triangles.len().div_ceil(chunk));
    *used += n;
    if chunks.len() < *used {
        chunks.resize_with(*used, PrimitiveChunk::default);
    }
    let tris = mesh.triangles.par_chunks(chunk);
    chunks[first..*used].par_iter_mut().zip(tris).enumerate().for_each(|(k, (out, tris))| {
        out.reset(pass);
        (out.object, out.first_triangle) = (ctx.material.1, (k * chunk) as u32);
        if let Some(kind) = lanes {
            let (vertices, triangles) = (compact, tris);
            zline_simd::vectorize(SetupTriangles { vertices, source, triangles, ctx, kind, out });
            return;
        }
        for t in tris {
            if let Some(tri) = gather(vertices, t) {
                setup_triangle(tri, ctx, out);
            }
            if sources {
                out.triangle_ends.push(out.draws.len() as u32);
            }
        }
    });
}

/// The opaque primitives of a tile as (chunk, kernel, table index): its
/// opaque bin, or with the painter's algorithm (which bins every primitive
/// in `transparent`) the opaque chunks' primitives there.
fn opaque_primitives<'a>(
    chunks: &'a [PrimitiveChunk],
    opaque: &'a [crate::bin::OpaqueRef],
    transparent: &'a [PrimitiveRef],
) -> impl Iterator<Item = (u32, crate::setup::Kernel, u32)> + 'a {
    let zbuffer = opaque.iter().map(|r| (r.chunk, r.kernel, r.index));
    let painted = transparent.iter().filter_map(|r| {
        let chunk = &chunks[r.chunk as usize];
        let d = chunk.draws[r.index as usize];
        (chunk.pass == PassKind::Opaque).then_some((r.chunk, d.kernel, d.index))
    });
    zbuffer.chain(painted)
}

/// The pixels whose samples a tile holds: with n×n samples per pixel, tiles
/// and the sample window are whole multiples of n.
fn pixels_of(samples: Rect, n: u32) -> Rect {
    let n = n as i32;
    Rect { x0: samples.x0 / n, y0: samples.y0 / n, x1: samples.x1 / n, y1: samples.y1 / n }
}

/// Whether the pipeline draws `object` in the transparency pass: a
/// material opacity below 1 (NaN included: sanitized to 0) or a diffuse
/// texture, with texture coordinates to read it, whose alpha blends (glTF
/// BLEND). The object-ID frame leaves these objects out by the same test.
pub fn is_transparent(object: &Object) -> bool {
    let blends =
        object.mesh.diffuse_map.as_ref().is_some_and(|m| m.alpha_blend && !object.mesh.uvs.is_empty());
    object.material().sanitized().opacity < 1.0 || blends
}
