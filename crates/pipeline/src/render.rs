//! One frame, end to end: vertex stage, setup, binning, tiles in parallel.

use rayon::prelude::*;
use zline_scene::{Interpolation, Scene};
use zline_shading::{LightingModel, PreparedLights, PreparedMaterial, ShadingMode};

use crate::bin::{bin_primitives, TileGrid};
use crate::clip::ClipVolume;
use crate::image::Image;
use crate::setup::{setup_triangle, Primitive, SetupContext, Viewport};
use crate::tile::{ShadeContext, TileTarget};
use crate::vertex::{transform_mesh, ObjectTransforms, VertexLighting};

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

/// Counts from one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Triangles in the scene.
    pub triangles: u64,
    /// Primitives drawn after culling and clipping.
    pub primitives: u64,
    /// Samples that passed the depth test and were shaded.
    pub fragments: u64,
}

/// Renders `scene` with the current rayon thread pool.
pub fn render(scene: &Scene, options: &RenderOptions) -> (Image, RenderStats) {
    let s = &scene.settings;
    let (width, height) = (s.width.max(1), s.height.max(1));
    let eye_from_world = scene.camera.eye_from_world();
    let clip_from_eye = scene.camera.clip_from_eye(width as f32 / height as f32);
    let model = LightingModel { ambient: scene.ambient, lights: scene.lights.clone() };
    let lighting = PreparedLights::new(&model, &eye_from_world);
    let materials: Vec<PreparedMaterial> =
        scene.objects.iter().map(|o| PreparedMaterial::new(o.material().sanitized())).collect();
    let viewport = Viewport { width, height };
    let volume = ClipVolume::new(width, height);

    let mut prims: Vec<Primitive> = Vec::new();
    let mut stats = RenderStats::default();
    for (index, object) in scene.objects.iter().enumerate() {
        let mesh = &object.mesh;
        stats.triangles += mesh.triangles.len() as u64;
        let shading = object.shading.unwrap_or(s.shading);
        let material = &materials[index];
        let transforms = ObjectTransforms::new(clip_from_eye, eye_from_world, object.world_from_object);
        let vertex_lighting = match shading {
            ShadingMode::Gouraud => VertexLighting::Gouraud(&lighting, material),
            _ => VertexLighting::None,
        };
        let vertices = transform_mesh(mesh, &transforms, vertex_lighting);
        let ctx = SetupContext {
            viewport,
            volume,
            shading,
            perspective: s.interpolation == Interpolation::PerspectiveCorrect,
            cull_back_faces: object.cull_back_faces,
            material: (material, index as u32),
            lighting: &lighting,
        };
        let chunks: Vec<Vec<Primitive>> = mesh
            .triangles
            .par_chunks(TRIANGLE_CHUNK)
            .map(|chunk| {
                let mut out = Vec::with_capacity(chunk.len());
                for t in chunk {
                    let Some(tri) = gather(&vertices, t) else { continue };
                    setup_triangle(tri, &ctx, &mut out);
                }
                out
            })
            .collect();
        for c in chunks {
            prims.extend(c);
        }
    }
    stats.primitives = prims.len() as u64;

    let grid = TileGrid::new(width, height, options.tile_size);
    let bins = bin_primitives(&prims, &grid);
    let shade = ShadeContext { lighting: &lighting, materials: &materials };
    let mut rgb = vec![0u8; width as usize * height as usize * 3];
    let band_len = width as usize * grid.tile_size as usize * 3;
    stats.fragments = rgb
        .par_chunks_mut(band_len)
        .enumerate()
        .map(|(row, band)| {
            let mut target = TileTarget::default();
            let mut shaded = 0;
            for col in 0..grid.cols {
                target.clear(grid.rect(col, row as u32), scene.background);
                let bin = &bins[row * grid.cols as usize + col as usize];
                shaded += target.opaque_pass(&prims, bin, &shade);
                target.resolve(band, width as usize);
            }
            shaded
        })
        .sum();
    (Image { width, height, rgb }, stats)
}

/// The three vertices of a triangle; `None` when an index is out of range
/// (meshes are validated on load, but a hand-built one may not be).
#[inline]
fn gather(vertices: &[crate::vertex::ClipVertex], t: &[u32; 3]) -> Option<[crate::vertex::ClipVertex; 3]> {
    Some([*vertices.get(t[0] as usize)?, *vertices.get(t[1] as usize)?, *vertices.get(t[2] as usize)?])
}
