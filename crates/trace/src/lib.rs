//! zline-trace: the ray tracer of the course's first global illumination
//! model, Whitted's (SPEC §12), on the same scene model and lighting models
//! as the rasterizer (`zline-shading`), and independent of the rasterizing
//! pipeline.
//!
//! - [`ray`]: rays, hits and the watertight ray–triangle test, with the
//!   error bounds that place secondary rays off their surface.
//! - [`accel`]: the acceleration structures (a SAH bounding-volume
//!   hierarchy, a kd-tree, a uniform grid; brute force as the oracle), each
//!   answering as brute force.
//! - [`optics`]: reflection, and refraction by the course's formula.
//! - [`world`]: the scene's triangles in world space and the camera's rays.
//! - [`whitted`]: the ray tree, walked with an explicit stack.
//! - [`antialias`]: regular and adaptive supersampling.
//!
//! [`render`] draws a scene; the image is linear RGB, one colour a pixel,
//! the same for any number of threads.

use std::time::{Duration, Instant};

use glam::Vec3;
use rayon::prelude::*;
use zline_scene::Scene;
use zline_shading::LightingModel;

pub mod accel;
pub mod antialias;
pub mod optics;
pub mod ray;
pub mod whitted;
pub mod world;

pub use zline_scene::trace_options::{TraceOptions, MAX_DEPTH, MAX_SAMPLES};

use accel::{brute::Brute, bvh::Bvh, grid::Grid, kdtree::KdTree, AccelKind, Accelerator};
use antialias::Sampler;
use whitted::{Tracer, Work};
use world::{Camera, World};

/// A ray-traced image and what it cost.
#[derive(Clone, Debug, Default)]
pub struct Traced {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear RGB, row by row from the top; each pixel's tree sum, not
    /// clamped.
    pub pixels: Vec<Vec3>,
    /// Rays by kind, nodes, tests.
    pub work: Work,
    /// Building the acceleration structure.
    pub build: Duration,
    /// Tracing.
    pub trace: Duration,
    /// The warnings of [`TraceOptions::checked`] and of the scene.
    pub warnings: Vec<String>,
}

/// Ray-traces `scene` with `options` (checked first: see
/// [`TraceOptions::checked`]), in parallel over rows on the current rayon
/// pool; the image does not depend on the thread count.
pub fn render(scene: &Scene, options: &TraceOptions) -> Traced {
    let (options, mut warnings) = options.checked();
    let world = World::new(scene);
    let started = Instant::now();
    let accel: Box<dyn Accelerator> = match options.accel {
        AccelKind::Bvh => Box::new(Bvh::build(&world.triangles)),
        AccelKind::Kd => Box::new(KdTree::build(&world.triangles)),
        AccelKind::Grid => Box::new(Grid::build(&world.triangles)),
        AccelKind::None => Box::new(Brute),
    };
    let build = started.elapsed();
    let camera = Camera::new(scene);
    let lights = LightingModel {
        ambient: scene.ambient,
        lights: scene.lights.clone(),
        environment: scene.environment.clone(),
    };
    let tracer = Tracer {
        world: &world,
        accel: accel.as_ref(),
        lights: &lights,
        camera: &camera,
        fog: scene.fog,
        background: scene.background,
        sky: scene.environment.as_ref().filter(|e| e.background),
        max_depth: options.max_depth,
        min_weight: options.min_weight,
        shadows: options.shadows,
    };
    let (width, height) = camera.size();
    let started = Instant::now();
    let mut pixels = vec![Vec3::ZERO; width as usize * height as usize];
    let sampler = || Sampler {
        tracer: &tracer,
        tone: scene.settings.tone_mapping,
        work: Work::default(),
        stack: Vec::new(),
    };
    let work = if let Some(adaptive) = options.adaptive {
        // The pixel corners first, each traced once for the image.
        let mut corners = vec![Vec::new(); height as usize + 1];
        let corner_work = corners
            .par_iter_mut()
            .enumerate()
            .map(|(y, row)| {
                let mut s = sampler();
                *row = s.corner_row(y as u32, width);
                s.work
            })
            .reduce(Work::default, |a, b| a + b);
        let corners = &corners;
        let pixel_work = pixels
            .par_chunks_mut(width as usize)
            .enumerate()
            .map(|(y, row)| {
                let mut s = sampler();
                let (above, below) = (&corners[y], &corners[y + 1]);
                for (x, pixel) in row.iter_mut().enumerate() {
                    let c = [above[x], above[x + 1], below[x], below[x + 1]];
                    *pixel = s.adaptive(x as u32, y as u32, c, adaptive);
                }
                s.work
            })
            .reduce(Work::default, |a, b| a + b);
        corner_work + pixel_work
    } else {
        pixels
            .par_chunks_mut(width as usize)
            .enumerate()
            .map(|(y, row)| {
                let mut s = sampler();
                for (x, pixel) in row.iter_mut().enumerate() {
                    *pixel = s.uniform(x as u32, y as u32, options.samples);
                }
                s.work
            })
            .reduce(Work::default, |a, b| a + b)
    };
    if work.budget_cut > 0 {
        warnings.push(format!(
            "{} ray trees reached the budget of {} rays and were cut",
            work.budget_cut,
            whitted::RAY_BUDGET
        ));
    }
    Traced { width, height, pixels, work, build, trace: started.elapsed(), warnings }
}
