//! One frame, end to end: vertex stage, setup, binning, tiles in parallel.

use rayon::prelude::*;
use std::time::{Duration, Instant};

use glam::Vec3;
use zline_raster::Rect;
use zline_scene::{DepthMode, Interpolation, Mesh, Projection, Scene, TextureMap};
use zline_shading::{LightingModel, Material, PreparedLights, PreparedMaterial, ShadingMode};

use crate::adaptive::Adaptive;
use crate::bin::{bin_primitives, Bins, PrimitiveChunk, TileGrid};
use crate::clip::ClipVolume;
use crate::fog::FogPass;
use crate::image::{quantize_rgba, Image};
use crate::setup::{setup_triangle, DepthEncoding, SetupContext, Viewport};
use crate::tile::{ShadeContext, TileTarget, DEPTH_CLEAR, DEPTH_CLEAR_REVERSED};
use crate::vertex::{transform_mesh, ClipVertex, ObjectTransforms, Screen, VertexLighting};

/// Triangles per rayon task in setup.
const TRIANGLE_CHUNK: usize = 2048;

/// Settings of the pipeline itself (the scene's settings say what to draw).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderOptions {
    /// Tile edge in pixels. Any value ≥ 1 gives the same image.
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
/// primitives, bins) from frame to frame, so a steady stream of frames
/// allocates nothing. The image is the same as [`render`]'s.
#[derive(Debug, Default)]
pub struct Renderer {
    vertices: Vec<ClipVertex>,
    /// Setup output, one chunk per rayon task; `chunks[..used]` hold this
    /// frame's primitives in draw order.
    chunks: Vec<PrimitiveChunk>,
    used: usize,
    bins: Bins,
}

impl Renderer {
    /// Renders `scene` into `image` (resized as needed) with the current
    /// rayon thread pool.
    pub fn render_into(&mut self, scene: &Scene, options: &RenderOptions, image: &mut Image) -> RenderStats {
        let start = Instant::now();
        let s = &scene.settings;
        let (width, height) = (s.width.max(1), s.height.max(1));
        // Supersampling renders an n× larger window of samples (every stage
        // below works in samples) and box-filters it in the resolve.
        // Larger factors than scene files accept are taken as the largest.
        let n = s.ssaa.clamp(1, zline_scene::MAX_SSAA);
        let (sample_width, sample_height) = (width * n, height * n);
        let eye_from_world = scene.camera.eye_from_world();
        let clip_from_eye = scene.camera.clip_from_eye(width as f32 / height as f32);
        let reversed = s.depth == DepthMode::ReversedFloat;
        let depth = if reversed {
            let (a, b) = scene.camera.reversed_depth_coefficients();
            let perspective = matches!(scene.camera.projection, Projection::Perspective { .. });
            DepthEncoding::Reversed { a, b, perspective }
        } else {
            DepthEncoding::Normalized
        };
        let model = LightingModel { ambient: scene.ambient, lights: scene.lights.clone() };
        let lighting = PreparedLights::new(&model, &eye_from_world);
        let mut materials: Vec<PreparedMaterial> =
            scene.objects.iter().map(|o| PreparedMaterial::new(o.material().sanitized())).collect();
        let adaptive =
            s.adaptive_tolerance.and_then(|t| Adaptive::new(t, &model.transformed(&eye_from_world)));
        if adaptive.is_some() {
            // Each object's material without specular, at index objects + i.
            let plain =
                |m: &PreparedMaterial| PreparedMaterial::new(Material { ks: Vec3::ZERO, ..m.material });
            materials.extend(materials.clone().iter().map(plain));
        }
        let mut stats = RenderStats::default();
        let mut textures: Vec<TextureMap> = Vec::new();
        self.used = 0;
        for (index, object) in scene.objects.iter().enumerate() {
            stats.triangles += object.mesh.triangles.len() as u64;
            let texture = match (&object.mesh.diffuse_map, object.mesh.uvs.is_empty()) {
                (Some(map), false) => {
                    let mut map = map.clone();
                    if let Some(filter) = s.texture_filter {
                        map.sampler.filter = filter;
                    }
                    textures.push(map);
                    Some(textures.len() as u32 - 1)
                }
                _ => None,
            };
            let ctx = SetupContext {
                viewport: Viewport { width: sample_width, height: sample_height },
                volume: ClipVolume::new(sample_width, sample_height),
                depth,
                shading: object.shading.unwrap_or(s.shading),
                perspective: s.interpolation == Interpolation::PerspectiveCorrect,
                cull_back_faces: object.cull_back_faces,
                material: (&materials[index], index as u32),
                lighting: &lighting,
                adaptive: adaptive.as_ref(),
                diffuse_only: {
                    let i = if adaptive.is_some() { scene.objects.len() + index } else { index };
                    (&materials[i], i as u32)
                },
                texture,
                orthographic: matches!(scene.camera.projection, Projection::Orthographic { .. }),
                blend_texture_alpha: texture.is_some_and(|t| textures[t as usize].alpha_blend),
                vertex_colors: !object.mesh.colors.is_empty(),
            };
            let transforms = ObjectTransforms::new(clip_from_eye, eye_from_world, object.world_from_object);
            self.setup_object(&object.mesh, &transforms, &ctx);
        }
        let chunks = &self.chunks[..self.used];
        stats.primitives = chunks.iter().map(|c| c.prims.len() as u64).sum();
        stats.geometry = start.elapsed();

        let start = Instant::now();
        let tile_size = options.tile_size.max(1);
        let grid = TileGrid::new(sample_width, sample_height, tile_size * n);
        bin_primitives(chunks, &grid, &mut self.bins);
        stats.binning = start.elapsed();

        let start = Instant::now();
        let shade = ShadeContext { lighting: &lighting, materials: &materials, textures: &textures };
        image.width = width;
        image.height = height;
        image.pixels.resize(width as usize * height as usize, 0);
        let band_len = width as usize * tile_size as usize;
        let bins = &self.bins;
        let fog = scene.fog.map(|f| FogPass::new(f, clip_from_eye, sample_width, sample_height, reversed));
        let clear = if reversed { DEPTH_CLEAR_REVERSED } else { DEPTH_CLEAR };
        let background = quantize_rgba(scene.background.extend(1.0));
        stats.fragments = image
            .pixels
            .par_chunks_mut(band_len)
            .enumerate()
            .map(|(row, band)| {
                let mut target = TileTarget::default();
                let mut shaded = 0;
                let mut order = Vec::new();
                for col in 0..grid.cols {
                    let tile = row * grid.cols as usize + col as usize;
                    let (rect, opaque, transparent) =
                        (grid.rect(col, row as u32), &bins.opaque[tile], &bins.transparent[tile]);
                    if opaque.is_empty() && transparent.is_empty() {
                        // Nothing to draw: the background's bytes, without the buffers.
                        fill_rect(band, width as usize, pixels_of(rect, n), background);
                        continue;
                    }
                    target.clear(rect, scene.background, clear);
                    shaded += target.opaque_pass(chunks, opaque, &shade);
                    if let Some(fog) = &fog {
                        target.fog_pass(fog);
                    }
                    if !transparent.is_empty() {
                        shaded +=
                            target.transparency_pass(chunks, transparent, &shade, fog.as_ref(), &mut order);
                    }
                    if n == 1 {
                        target.resolve(band, width as usize);
                    } else {
                        target.resolve_supersampled(band, width as usize, n);
                    }
                }
                shaded
            })
            .sum();
        stats.raster = start.elapsed();
        stats
    }

    /// The vertex stage and setup of one object, appending its primitives
    /// in mesh order.
    fn setup_object(&mut self, mesh: &Mesh, transforms: &ObjectTransforms, ctx: &SetupContext<'_>) {
        let lighting = match ctx.shading {
            // Textured Gouraud lights its (clipped) vertices in setup, in
            // parts, and so does Gouraud with vertex colours (in `color`).
            ShadingMode::Gouraud if ctx.texture.is_none() && !ctx.vertex_colors => {
                VertexLighting::Gouraud(ctx.lighting, ctx.material.0)
            }
            _ => VertexLighting::None,
        };
        let screen = Screen { viewport: ctx.viewport, volume: ctx.volume };
        transform_mesh(mesh, transforms, lighting, &screen, &mut self.vertices);
        let vertices = &self.vertices;
        let (first, n) = (self.used, mesh.triangles.len().div_ceil(TRIANGLE_CHUNK));
        self.used += n;
        if self.chunks.len() < self.used {
            self.chunks.resize_with(self.used, PrimitiveChunk::default);
        }
        let tris = mesh.triangles.par_chunks(TRIANGLE_CHUNK);
        self.chunks[first..self.used].par_iter_mut().zip(tris).for_each(|(out, tris)| {
            out.prims.clear();
            out.textured.clear();
            out.colored_phong.clear();
            out.textured_colored.clear();
            out.transparent = ctx.material.0.material.opacity < 1.0 || ctx.blend_texture_alpha;
            for t in tris {
                if let Some(tri) = gather(vertices, t) {
                    setup_triangle(tri, ctx, out);
                }
            }
            out.bounds.clear();
            out.bounds.extend(out.prims.iter().map(|p| p.edges.bounds()));
        });
    }
}

/// The pixels whose samples a tile holds: with n×n samples per pixel, tiles
/// and the sample window are whole multiples of n.
fn pixels_of(samples: Rect, n: u32) -> Rect {
    let n = n as i32;
    Rect { x0: samples.x0 / n, y0: samples.y0 / n, x1: samples.x1 / n, y1: samples.y1 / n }
}

/// Fills a tile's pixels in `band` (the image rows from the tile's first
/// row) with one packed colour.
fn fill_rect(band: &mut [u32], width: usize, rect: Rect, color: u32) {
    for row in 0..rect.height() as usize {
        let start = row * width + rect.x0 as usize;
        band[start..start + rect.width() as usize].fill(color);
    }
}

/// The three vertices of a triangle; `None` when an index is out of range
/// (meshes are validated on load, but a hand-built one may not be).
#[inline]
fn gather<'a>(vertices: &'a [ClipVertex], t: &[u32; 3]) -> Option<[&'a ClipVertex; 3]> {
    Some([vertices.get(t[0] as usize)?, vertices.get(t[1] as usize)?, vertices.get(t[2] as usize)?])
}
