//! `--renderer raytrace` and the ray tracer's flags (docs/SPEC.md §12).

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use zline::scene::trace_options::Renderer;
use zline::scene::Scene;
use zline::trace::accel::AccelKind;
use zline::trace::antialias::Adaptive;
use zline::trace::whitted::ShadowRays;
use zline::trace::TraceOptions;

/// Which renderer draws the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub(crate) enum RendererChoice {
    /// The z-buffer pipeline.
    #[default]
    Raster,
    /// Whitted ray tracing.
    Raytrace,
    /// Radiosity, solved once and drawn by the z-buffer pipeline.
    Radiosity,
}

/// `--accel`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum AccelChoice {
    /// The SAH bounding-volume hierarchy.
    Bvh,
    /// The SAH kd-tree, traversed front to back.
    Kd,
    /// The uniform grid, stepped cell to cell (3D-DDA).
    Grid,
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
    /// The renderer: the z-buffer pipeline, Whitted ray tracing
    /// (reflection kr, refraction by the index of refraction,
    /// shadow rays; docs/SPEC.md §12), or radiosity (diffuse
    /// interreflection solved over patches, then drawn by the pipeline).
    /// Default: the scene file's `renderer`, else raster.
    #[arg(long, value_enum)]
    pub(crate) renderer: Option<RendererChoice>,
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
    /// True when a ray-tracing flag was given.
    fn given(&self) -> bool {
        self.ray_depth.is_some()
            || self.min_weight.is_some()
            || self.accel.is_some()
            || self.shadow_rays.is_some()
            || self.rays_per_axis.is_some()
            || self.adaptive_requested()
    }

    fn adaptive_requested(&self) -> bool {
        self.adaptive_aa || self.aa_depth.is_some() || self.aa_threshold.is_some()
    }

    /// True when `--renderer raytrace` was given.
    pub(crate) fn asks_to_trace(&self) -> bool {
        self.renderer == Some(RendererChoice::Raytrace)
    }

    /// Refuses the ray tracer for `command`, which only rasterizes.
    pub(crate) fn refuse(&self, command: &str) -> Result<()> {
        if self.asks_to_trace() || self.given() {
            bail!("{command} rasterizes only: --renderer raytrace and its flags work with render, demo and view");
        }
        Ok(())
    }

    /// What can be refused before the scene is loaded.
    pub(crate) fn check(&self) -> Result<()> {
        if self.given() && self.renderer == Some(RendererChoice::Raster) {
            bail!("{}", Self::NEED);
        }
        if self.rays_per_axis.is_some_and(|n| n > 1) && self.adaptive_requested() {
            bail!("--rays-per-axis and adaptive supersampling are two ways to anti-alias: give one");
        }
        Ok(())
    }

    const NEED: &str = "--ray-depth, --min-weight, --accel, --shadow-rays, --rays-per-axis, --adaptive-aa, --aa-depth and --aa-threshold need --renderer raytrace (or renderer = \"raytrace\" in the scene file)";

    /// True when radiosity draws `scene`: `--renderer`, else the scene's
    /// own choice.
    pub(crate) fn radiosity(&self, scene: &Scene) -> bool {
        match self.renderer {
            Some(r) => r == RendererChoice::Radiosity,
            None => scene.settings.renderer == Renderer::Radiosity,
        }
    }

    /// True when the ray tracer draws `scene`: `--renderer`, else the
    /// scene's own choice; ray-tracing flags for a rasterized scene are
    /// refused.
    pub(crate) fn traces(&self, scene: &Scene) -> Result<bool> {
        let traces = match self.renderer {
            Some(r) => r == RendererChoice::Raytrace,
            None => scene.settings.renderer == Renderer::RayTrace,
        };
        if self.given() && !traces {
            bail!("{}", Self::NEED);
        }
        Ok(traces)
    }

    /// The scene's ray-tracing options with the flags given on top.
    pub(crate) fn options(&self, base: TraceOptions) -> TraceOptions {
        let mut o = base;
        if let Some(d) = self.ray_depth {
            o.max_depth = d;
        }
        if let Some(w) = self.min_weight {
            o.min_weight = w;
        }
        if let Some(a) = self.accel {
            o.accel = match a {
                AccelChoice::Bvh => AccelKind::Bvh,
                AccelChoice::Kd => AccelKind::Kd,
                AccelChoice::Grid => AccelKind::Grid,
                AccelChoice::None => AccelKind::None,
            };
        }
        if let Some(s) = self.shadow_rays {
            o.shadows = match s {
                ShadowChoice::Filtered => ShadowRays::Filtered,
                ShadowChoice::Opaque => ShadowRays::Opaque,
            };
        }
        if let Some(n) = self.rays_per_axis {
            (o.samples, o.adaptive) = (n, None);
        }
        if self.adaptive_requested() {
            let d = o.adaptive.unwrap_or_default();
            let depth = self.aa_depth.unwrap_or(d.depth);
            let threshold = self.aa_threshold.unwrap_or(d.threshold);
            (o.samples, o.adaptive) = (1, Some(Adaptive { depth, threshold }));
        }
        o
    }
}
