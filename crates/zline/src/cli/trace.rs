//! `--renderer raytrace` and the ray tracer's flags (docs/SPEC.md §12).

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use zline::pipeline::image::{quantize_rgba, Image};
use zline::scene::Scene;
use zline::trace::accel::AccelKind;
use zline::trace::antialias::Adaptive;
use zline::trace::whitted::ShadowRays;
use zline::trace::{TraceOptions, Traced};

/// Which renderer draws the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub(crate) enum RendererChoice {
    /// The z-buffer pipeline.
    #[default]
    Raster,
    /// Whitted ray tracing.
    Raytrace,
}

/// `--accel`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum AccelChoice {
    /// The SAH bounding-volume hierarchy.
    Bvh,
    /// Every triangle for every ray (the oracle).
    None,
}

/// `--shadow-rays`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum ShadowChoice {
    /// A transparent occluder passes kt = 1 − d of the light.
    Filtered,
    /// Any occluder stops the light.
    Opaque,
}

#[derive(Args)]
pub(crate) struct TraceArgs {
    /// The renderer: the z-buffer pipeline, or Whitted ray tracing
    /// (reflection kr, refraction by the index of refraction,
    /// shadow rays; docs/SPEC.md §12).
    #[arg(long, value_enum, default_value_t = RendererChoice::Raster)]
    pub(crate) renderer: RendererChoice,
    /// Ray tracing: the ray tree's depth limit (1: camera rays only).
    #[arg(long, value_name = "N")]
    pub(crate) ray_depth: Option<u32>,
    /// Ray tracing: branches whose weight falls below W are not traced.
    #[arg(long, value_name = "W")]
    pub(crate) min_weight: Option<f32>,
    /// Ray tracing: the acceleration structure.
    #[arg(long, value_enum)]
    pub(crate) accel: Option<AccelChoice>,
    /// Ray tracing: shadow rays through transparent surfaces.
    #[arg(long, value_enum)]
    pub(crate) shadow_rays: Option<ShadowChoice>,
    /// Ray tracing: N×N camera rays a pixel on a regular grid, averaged.
    #[arg(long, value_name = "N")]
    pub(crate) rays_per_axis: Option<u32>,
    /// Ray tracing: the course's adaptive supersampling (pixel corners and
    /// centre, squares cut where they differ).
    #[arg(long)]
    pub(crate) adaptive_aa: bool,
    /// Ray tracing: adaptive supersampling cutting a pixel at most N times
    /// (0 to 4; default 3). Implies --adaptive-aa.
    #[arg(long, value_name = "N")]
    pub(crate) aa_depth: Option<u32>,
    /// Ray tracing: adaptive supersampling cuts a square whose samples
    /// differ by more than T in a display channel (0 to 1; default 1/16).
    /// Implies --adaptive-aa.
    #[arg(long, value_name = "T")]
    pub(crate) aa_threshold: Option<f32>,
}

impl TraceArgs {
    /// True when the ray tracer draws.
    pub(crate) fn traces(&self) -> bool {
        self.renderer == RendererChoice::Raytrace
    }

    /// Refuses the ray tracer for `command`, which only rasterizes.
    pub(crate) fn refuse(&self, command: &str) -> Result<()> {
        if self.traces() {
            bail!("{command} rasterizes only: --renderer raytrace works with render and demo");
        }
        self.options().map(|_| ())
    }

    /// The options, refusing ray-tracing flags given to the rasterizer.
    pub(crate) fn options(&self) -> Result<TraceOptions> {
        let given = self.ray_depth.is_some()
            || self.min_weight.is_some()
            || self.accel.is_some()
            || self.shadow_rays.is_some()
            || self.rays_per_axis.is_some()
            || self.adaptive_aa
            || self.aa_depth.is_some()
            || self.aa_threshold.is_some();
        if given && !self.traces() {
            bail!(
                "--ray-depth, --min-weight, --accel, --shadow-rays, --rays-per-axis, --adaptive-aa, --aa-depth and --aa-threshold need --renderer raytrace"
            );
        }
        let adaptive_aa = self.adaptive_aa || self.aa_depth.is_some() || self.aa_threshold.is_some();
        if self.rays_per_axis.is_some_and(|n| n > 1) && adaptive_aa {
            bail!("--rays-per-axis and adaptive supersampling are two ways to anti-alias: give one");
        }
        let adaptive = adaptive_aa.then(|| {
            let d = Adaptive::default();
            Adaptive {
                depth: self.aa_depth.unwrap_or(d.depth),
                threshold: self.aa_threshold.unwrap_or(d.threshold),
            }
        });
        let d = TraceOptions::default();
        Ok(TraceOptions {
            max_depth: self.ray_depth.unwrap_or(d.max_depth),
            min_weight: self.min_weight.unwrap_or(d.min_weight),
            accel: match self.accel {
                Some(AccelChoice::Bvh) | None => AccelKind::Bvh,
                Some(AccelChoice::None) => AccelKind::None,
            },
            shadows: match self.shadow_rays {
                Some(ShadowChoice::Filtered) | None => ShadowRays::Filtered,
                Some(ShadowChoice::Opaque) => ShadowRays::Opaque,
            },
            samples: self.rays_per_axis.unwrap_or(d.samples),
            adaptive,
        })
    }
}

/// Ray-traces `scene` and turns the linear colours into the image the
/// rasterizer would write (the scene's tone mapping, then 8 bits).
pub(crate) fn render(scene: &Scene, options: &TraceOptions) -> (Image, Traced) {
    let traced = zline::trace::render(scene, options);
    let tone = scene.settings.tone_mapping;
    let pixels = traced.pixels.iter().map(|&c| quantize_rgba(tone.apply(c).extend(1.0))).collect();
    let image = Image { width: traced.width, height: traced.height, pixels, transparent: false };
    (image, traced)
}
