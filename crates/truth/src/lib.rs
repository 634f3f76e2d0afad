//! The zline ground truth: a [`Scene`] rendered by evaluating every quantity
//! of `SPEC.md` directly per sample in f64 — slow and plainly right. It is
//! the oracle for tests and for speed-versus-error reports.
//!
//! It shares the scene model (`zline-scene`, and the material, light, fog
//! and texture types of `zline-shading`) and none of the fast code: it never
//! depends on `zline-raster` or `zline-pipeline`, and reads textures only
//! through `Texture::texel`, `level_size` and `levels`, and an environment
//! map's panorama only through `Panorama::texels`, `width` and `height`
//! (with the environment's intensity, rotation and background flag).
//! (The pipeline is a
//! dev-dependency: the property tests compare it with the truth.) Lighting, fog,
//! filtering and level of detail are re-derived here from the spec; where
//! the spec leaves a choice, the truth follows the fast renderer's stated
//! convention (SPEC §11), so that it is the truth of the same model —
//! including the two the scene chooses: where untextured Gouraud clamps
//! (`RenderSettings::gouraud_clamp`) and whether back faces are lit
//! two-sided (`RenderSettings::lighting_sides`).
//!
//! Steps, one module each: `camera` (f64 matrices, window mapping onto the
//! sample grid), `clip` (near/far in clip space), `frame` (vertices and the
//! drawn triangles, culling, two- or one-sided lighting), `coverage` (edge
//! functions, top-left rule, depth), `tile` (binning, opaque and
//! transparency passes, box filter, diagnostics), `shade` (interpolation and
//! shading modes), `lighting` (the basic and Cook–Torrance models),
//! `environment` (light from an environment map, SPEC §5.3: E(N)/π from
//! the truth's own f64 SH projection, L_pre by direct integration of
//! GGX's lobe over the panorama, and the panorama drawn as the
//! background),
//! `microfacet` (Cook–Torrance's per-light terms), [`split_sum`] (its
//! environment term, by quadrature), `shadow` (light visibility on shadow
//! receivers), `texture`, `fog`, `image` and [`metrics`].
//!
//! Shadows (`ShadowMode::Planar` and `ShadowMode::Map`) are exact light
//! visibility: a receiver (`Shadows::receives`; every object in Map mode)
//! is lit per sample as with Phong shading, and a light drops out of a
//! sample's diffuse and specular terms when a caster triangle crosses the
//! segment (or, for a directional light, the ray) from the exact surface
//! point to the light. Casters are, in Planar mode, the triangles of every
//! object that does not receive; in Map mode every triangle of every
//! object, the sample's own object included (self-shadowing), except the
//! triangle the sample lies on, skipped by identity. The `shadow` module
//! states the rule in full; without receivers the image is the one
//! without shadows, bit for bit.
//!
//! The ray tracer's model (SPEC §12, `zline-trace`) has its own truth:
//! [`trace_truth`] and [`WhittedTruth`] (module `whitted`, with its f64
//! ray–triangle test and hierarchy in `whitted_hit`, the world and its
//! shadow rays in `whitted_world`, what it records in `whitted_record`)
//! walk the Whitted
//! tree in f64 — camera rays unprojected through the truth's matrices,
//! the nearest hit among all triangles, the truth's lighting, texture
//! and fog at each hit with the viewer at the ray's origin, texture
//! alpha, filtered or opaque shadow rays, reflection and refraction by the
//! course's formula, the depth limit, the weight cutoff, the ray budget
//! and what a ray that misses sees — and can record
//! each pixel's tree, from which [`TracedTruth::away_from_silhouettes`]
//! masks the pixels a sub-pixel move of an edge cannot reach. Its module
//! doc states every rule and the differences to expect from the fast
//! tracer; `zline-trace` is a dev-dependency only, for the comparison
//! tests.
//!
//! With [`TruthOptions::diagnostics`] the image carries, per pixel, how far
//! it is from an edge or a depth intersection and how fast its colour
//! changes under a 1/256-pixel move ([`Diagnostics`]): what a comparison
//! with a renderer that snaps and rounds must allow for.
//!
//! Invariants:
//! - every sample is covered, depth-tested and shaded with exact f64
//!   evaluation: no fixed point, no incremental stepping, no f32 (but for
//!   the f32 data of zline's split-sum table when
//!   [`SplitSum::ZlineTable`] asks for it);
//! - shared edges cover each sample exactly once (canonical edge functions
//!   and the top-left rule);
//! - nothing with w ≤ 0 is divided; degenerate and non-finite triangles draw
//!   nothing and never panic;
//! - the image is the same for any number of threads.
//!
//! Settings the fast renderer uses to trade accuracy for speed
//! (`RenderSettings::depth`, `adaptive_tolerance`) are ignored: the truth's
//! depth is exact. Expected differences from the fast renderer: its
//! vertices are snapped to 1/256 pixel and it computes in f32, so samples
//! within about 1/512 pixel of an edge or a depth intersection may differ,
//! and colours by rounding; it sorts transparent triangles by mean depth,
//! the truth sorts fragments per sample (they differ where transparent
//! surfaces intersect); with Cook–Torrance materials (SPEC §5.2) it reads
//! the environment's split sum from a 32 × 32 table of 2,048-sample
//! estimates, the truth from the integral (by quadrature, tabulated
//! finely: [`split_sum`]): they differ by up to 0.1 in E_s at grazing N·V
//! and 0.012 for N·V ≥ 0.1, Ia·255 times that in 8-bit steps
//! ([`TruthOptions::split_sum`] = [`SplitSum::ZlineTable`] gives the truth
//! of the model with zline's table instead); and the highlights of
//! near-mirrors (roughness < 0.1), which f32 cannot resolve, count as
//! lighting switches in the diagnostics. Both interpolate the lit values
//! of a clipped Gouraud triangle's new vertices (SPEC §2) and, with Phong
//! shading, multiply ka and kd (Cook–Torrance: the base colour) by the
//! vertex colour interpolated to each sample. With an environment map
//! (SPEC §5.3) the fast renderer reads E(N)/π from f32 SH coefficients
//! (the same projection) and L_pre from six octahedral prefiltered
//! levels, linear in r between them; the truth integrates the lobe at the
//! material's own roughness, so near a small bright source (a sun) they
//! differ by tens of percent of the specular term, elsewhere by a few
//! (measured in `tests/it/environment.rs`).

mod camera;
mod clip;
mod coverage;
mod environment;
mod fog;
mod frame;
mod image;
mod lighting;
pub mod metrics;
mod microfacet;
mod normal_map;
mod sample;
mod shade;
mod shadow;
pub mod split_sum;
mod texture;
mod tile;
mod whitted;
mod whitted_hit;
mod whitted_record;
mod whitted_world;

use rayon::prelude::*;
use zline_scene::Scene;

pub use image::{quantize, Diagnostics, TruthImage};
pub use metrics::ErrorStats;
pub use sample::SampleShading;
pub use split_sum::SplitSum;
pub use whitted::{
    LightPath, RayKind, TracedTruth, TreeNode, WhittedTruth, RAY_BUDGET, SAME_CROSSING, SHADOW_SEGMENT_END,
};

/// What to compute besides the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TruthOptions {
    /// Fill [`TruthImage::diagnostics`]. Costs an evaluation of every
    /// triangle over its bounds widened by 2 pixels, a record of every
    /// fragment and four more shadings per sample: meant for small test
    /// scenes.
    pub diagnostics: bool,
    /// Where Cook–Torrance's environment term takes its split sum (A, B)
    /// from: the integral (the default), or zline's own table
    /// ([`SplitSum`]).
    pub split_sum: SplitSum,
}

/// Renders `scene` with the current rayon thread pool.
pub fn render_truth(scene: &Scene) -> TruthImage {
    render_truth_with(scene, &TruthOptions::default())
}

/// Renders `scene` with options, with the current rayon thread pool.
pub fn render_truth_with(scene: &Scene, options: &TruthOptions) -> TruthImage {
    render_frame(frame::Frame::new(scene, options.split_sum), options)
}

/// Renders `scene` with options, every Phong-shaded sample (shadow
/// receivers included) lit by `shader` instead of the truth's lighting
/// model: it receives the sample's geometry and material parameters
/// ([`SampleShading`]) and returns the unclamped colour, which the truth
/// clamps to [0, 1] and fogs. Shadows are the shader's business (it sees
/// none); flat and Gouraud shading keep the truth's model. Coverage,
/// interpolation, textures, normal maps, blending and the box filter are
/// the truth's: a test can compare another transcription of a lighting
/// model with the fast renderer on the same geometry. Diagnostics report
/// edges and depth intersections only (no lighting switches). An
/// environment map's light is the shader's business too (it is not
/// passed); the environment drawn as the background stays the truth's.
pub fn render_truth_shaded(
    scene: &Scene,
    options: &TruthOptions,
    shader: &(dyn Fn(&SampleShading) -> glam::DVec3 + Sync),
) -> TruthImage {
    let mut frame = frame::Frame::new(scene, options.split_sum);
    frame.shader = Some(frame::Shader(shader));
    render_frame(frame, options)
}

/// Ray-traces `scene` by the Whitted model (SPEC §12) in f64 with
/// `options` (checked first), with the current rayon thread pool: linear
/// RGB per pixel, the mean of its n × n samples' tree sums, not clamped.
/// Adaptive supersampling is not modelled (see [`WhittedTruth`]); the
/// image does not depend on the thread count.
pub fn trace_truth(scene: &Scene, options: &zline_scene::trace_options::TraceOptions) -> TruthImage {
    WhittedTruth::new(scene, options).render(false).image
}

fn render_frame(frame: frame::Frame<'_>, options: &TruthOptions) -> TruthImage {
    let margin = if options.diagnostics { tile::DIAGNOSTIC_RANGE * f64::from(frame.n) } else { 0.0 };
    let bins = tile::bin(&frame, margin);
    let tiles: Vec<tile::TileOutput> = (0..bins.cols * bins.rows)
        .into_par_iter()
        .map(|t| tile::render_tile(&frame, &bins, t % bins.cols, t / bins.cols, options.diagnostics))
        .collect();
    let (width, height) = frame.size;
    let mut rgb = vec![glam::DVec3::ZERO; width as usize * height as usize];
    let mut diagnostics = options
        .diagnostics
        .then(|| Diagnostics { boundary_distance: vec![0.0; rgb.len()], sensitivity: vec![0.0; rgb.len()] });
    for (t, out) in tiles.iter().enumerate() {
        let (col, row) = (t as u32 % bins.cols, t as u32 / bins.cols);
        let (x0, y0) = ((col * tile::TILE_PIXELS) as usize, (row * tile::TILE_PIXELS) as usize);
        let tw = (width as usize - x0).min(tile::TILE_PIXELS as usize);
        for (k, c) in out.rgb.iter().enumerate() {
            let i = (y0 + k / tw) * width as usize + x0 + k % tw;
            rgb[i] = *c;
            if let Some(d) = &mut diagnostics {
                d.boundary_distance[i] = out.boundary[k];
                d.sensitivity[i] = out.sensitivity[k];
            }
        }
    }
    TruthImage { width, height, rgb, diagnostics }
}
