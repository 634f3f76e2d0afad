//! The report's level-of-detail section ("Simplified meshes"): the bunny
//! (69k triangles, from the shared assets; skipped with a message when
//! missing) and the 1M-triangle sphere, pulled back until their triangles
//! are far below a pixel, rendered with the adaptive mode at τ = 2 and 8
//! with and without the simplified levels (`zline::pipeline::lod`).
//!
//! Each row gives the frame times (fastest of N interleaved frames) of the
//! plain renderer, of the adaptive mode drawing every mesh in full and of
//! the adaptive mode with its levels; the primitives drawn; and the error
//! of the level-of-detail image against the full-mesh image of the same
//! adaptive mode: the share of pixels whose largest channel differs by
//! more than τ, and the RMSE in 8-bit steps. The last two columns are the
//! same measures for the full mesh against itself moved ¼ px sideways:
//! how much a sub-pixel move already changes an image whose triangles are
//! below a pixel — the scale the level-of-detail error should be read on.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result};
use glam::Mat4;
use zline::pipeline::{Image, RenderOptions, RenderStats, Renderer};
use zline::scene::{Projection, RenderSettings, Scene, ShadingMode};

/// Image size of the section (the report's default benchmark size).
const SIZE: (u32, u32) = (1920, 1080);

/// How far the camera is pulled back from each scene's own framing.
const DISTANCES: [f32; 3] = [4.0, 8.0, 16.0];

/// The adaptive tolerances timed.
const TOLERANCES: [f32; 2] = [2.0, 8.0];

/// One scene of the section.
struct Subject {
    name: &'static str,
    scene: Scene,
}

fn subjects(assets: &Path) -> Result<Vec<Subject>> {
    let settings = RenderSettings {
        width: SIZE.0,
        height: SIZE.1,
        shading: ShadingMode::Phong,
        ..RenderSettings::default()
    };
    let mut out = Vec::new();
    match crate::bench::bunny(assets) {
        Some(path) => {
            let model = zline::io::load_obj(&path).with_context(|| format!("loading {}", path.display()))?;
            out.push(Subject { name: "bunny 69k", scene: zline::io::scene_for_model(model, settings) });
        }
        None => eprintln!("note: the bunny is not under {}; skipped (pass --assets)", assets.display()),
    }
    let mut sphere = crate::bench::sphere_scene(500, 1000, 2.6, ShadingMode::Phong);
    (sphere.settings.width, sphere.settings.height) = SIZE;
    out.push(Subject { name: "sphere 1M", scene: sphere });
    for s in &mut out {
        for o in &mut s.scene.objects {
            o.shading = None;
        }
    }
    Ok(out)
}

/// `scene` with the camera `factor` times as far from its target (near and
/// far scaled alike).
fn pulled_back(scene: &Scene, factor: f32) -> Scene {
    let mut s = scene.clone();
    let c = &mut s.camera;
    c.eye = c.target + (c.eye - c.target) * factor;
    if let Projection::Perspective { near, far, .. } = &mut c.projection {
        *near *= factor;
        *far *= factor;
    }
    s
}

/// `scene` with every object moved `pixels` to the right, as seen at the
/// camera's target.
fn moved(scene: &Scene, pixels: f32) -> Scene {
    let mut s = scene.clone();
    let c = &s.camera;
    let forward = c.target - c.eye;
    let right = forward.cross(c.up).normalize();
    let per_pixel = match c.projection {
        Projection::Perspective { fovy_degrees, .. } => {
            2.0 * forward.length() * (fovy_degrees.to_radians() * 0.5).tan() / s.settings.height as f32
        }
        Projection::Orthographic { height, .. } => height / s.settings.height as f32,
        Projection::Frustum { bottom, top, near, .. } => {
            forward.length() * (top - bottom) / near / s.settings.height as f32
        }
    };
    let shift = Mat4::from_translation(right * per_pixel * pixels);
    for o in &mut s.objects {
        o.world_from_object = shift * o.world_from_object;
    }
    s
}

/// Over the pixels where `a` or `b` shows the object (differs from
/// `background`): the share whose largest channel differs by more than
/// `tolerance` steps, and the RMSE over their channels in steps.
fn compare(a: &Image, b: &Image, background: &Image, tolerance: f32) -> (f64, f64) {
    let (mut pixels, mut over, mut squares) = (0usize, 0usize, 0.0f64);
    for ((p, q), g) in a.pixels.iter().zip(&b.pixels).zip(&background.pixels) {
        if p == g && q == g {
            continue;
        }
        let (p, q) = (p.to_le_bytes(), q.to_le_bytes());
        let d = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0);
        pixels += 1;
        over += usize::from(f32::from(d) > tolerance);
        squares += (0..3).map(|c| (f64::from(p[c]) - f64::from(q[c])).powi(2)).sum::<f64>();
    }
    let pixels = pixels.max(1) as f64;
    (over as f64 / pixels, (squares / (3.0 * pixels)).sqrt())
}

/// Pixels of `image` that differ from `background`.
fn covered(image: &Image, background: &Image) -> usize {
    image.pixels.iter().zip(&background.pixels).filter(|(a, b)| a != b).count()
}

/// One renderer, warmed up (the first frame builds the levels).
struct Timed {
    renderer: Renderer,
    image: Image,
    stats: RenderStats,
    /// The warm-up frame (with the level of detail: building the level).
    first: f64,
    times: Vec<f64>,
}

impl Timed {
    fn new(scene: &Scene, level_of_detail: bool) -> Timed {
        let mut renderer = Renderer::default();
        renderer.set_level_of_detail(level_of_detail);
        let mut image = Image::empty();
        let start = Instant::now();
        let stats = renderer.render_into(scene, &RenderOptions::default(), &mut image);
        let first = start.elapsed().as_secs_f64() * 1e3;
        Timed { renderer, image, stats, first, times: Vec::new() }
    }

    fn frame(&mut self, scene: &Scene) {
        let start = Instant::now();
        self.renderer.render_into(scene, &RenderOptions::default(), &mut self.image);
        self.times.push(start.elapsed().as_secs_f64() * 1e3);
    }

    fn fastest(&self) -> f64 {
        self.times.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// The section's markdown.
pub(crate) fn section(assets: &Path, frames: usize) -> Result<String> {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Simplified meshes (adaptive level of detail)\n\n\
         {}×{}, Phong; each scene's camera pulled back ×k from its framing. *plain*: no adaptive mode; \
         *full*: the adaptive mode at τ drawing every mesh in full; *LOD*: with its simplified levels \
         (fastest of {frames} interleaved frames, after a warm-up frame that builds the levels). *> τ* and \
         *RMSE*: the LOD image against the full one, over the pixels where either shows the object; *¼ px*: the full image against \
         itself moved ¼ px. *covered*: the object's pixels. *first*: the first LOD frame, which builds the level.\n\n\
         | scene | ×k | covered | τ | level | primitives full → LOD | ms plain | ms full | ms LOD | full/LOD | first ms | > τ | RMSE | > τ (¼ px) | RMSE (¼ px) |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        SIZE.0, SIZE.1
    );
    for subject in subjects(assets)? {
        for factor in DISTANCES {
            let base = pulled_back(&subject.scene, factor);
            let start = Instant::now();
            let mut plain = Timed::new(&base, true);
            let mut empty = base.clone();
            empty.objects.clear();
            let background = Timed::new(&empty, false).image;
            let covered = covered(&plain.image, &background);
            for tolerance in TOLERANCES {
                let mut scene = base.clone();
                scene.settings.adaptive_tolerance = Some(tolerance);
                let (mut full, mut lod) = (Timed::new(&scene, false), Timed::new(&scene, true));
                let mut shifted = moved(&scene, 0.25);
                shifted.settings.adaptive_tolerance = Some(tolerance);
                let shifted = Timed::new(&shifted, false).image;
                for _ in 0..frames.max(1) {
                    plain.frame(&base);
                    full.frame(&scene);
                    lod.frame(&scene);
                }
                let (over, rmse) = compare(&lod.image, &full.image, &background, tolerance);
                let (over_moved, rmse_moved) = compare(&shifted, &full.image, &background, tolerance);
                let level = match lod.renderer.levels_drawn().first().copied().flatten() {
                    Some(k) => k.to_string(),
                    None => "full".into(),
                };
                let _ = writeln!(
                    md,
                    "| {} | {factor} | {covered} | {tolerance} | {level} | {} → {} | {:.2} | {:.2} | {:.2} | {:.2}× | {:.0} | {:.3} % | {:.3} | {:.3} % | {:.3} |",
                    subject.name,
                    full.stats.primitives,
                    lod.stats.primitives,
                    plain.fastest(),
                    full.fastest(),
                    lod.fastest(),
                    full.fastest() / lod.fastest(),
                    lod.first,
                    100.0 * over,
                    rmse,
                    100.0 * over_moved,
                    rmse_moved,
                );
            }
            eprintln!("lod: {} ×{factor}: {:.1} s", subject.name, start.elapsed().as_secs_f64());
        }
    }
    md.push('\n');
    Ok(md)
}
