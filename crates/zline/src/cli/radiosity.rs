//! `--renderer radiosity` and the solver's flags (docs/SPEC.md §13).

use anyhow::{bail, Context, Result};
use clap::{Args, ValueEnum};
use zline::radiosity::{Method, Options};
use zline::scene::Scene;

/// `--solver`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum SolverChoice {
    /// Sweeps over the form-factor matrix, each from the previous one's values.
    Jacobi,
    /// Sweeps reading the values already updated.
    GaussSeidel,
    /// Shooting the most unshot power first (no matrix).
    Progressive,
}

#[derive(Args)]
pub(crate) struct RadiosityArgs {
    /// Radiosity: the longest patch edge, in world units (default: 1/16 of
    /// the scene's largest extent).
    #[arg(long, value_name = "LENGTH")]
    pub(crate) patch_size: Option<f32>,
    /// Radiosity: the hemicube's resolution, pixels along its top face
    /// (default 100).
    #[arg(long, value_name = "N")]
    pub(crate) hemicube: Option<usize>,
    /// Radiosity: the solver (default progressive).
    #[arg(long, value_enum)]
    pub(crate) solver: Option<SolverChoice>,
    /// Radiosity: stop when the power left to move is at most this share
    /// of the emitted power (default 0.001).
    #[arg(long, value_name = "FRACTION")]
    pub(crate) radiosity_tolerance: Option<f64>,
    /// Radiosity: keep the solution in FILE and reuse it while the scene
    /// and these settings are unchanged (a turntable, the next render).
    #[arg(long, value_name = "FILE")]
    pub(crate) radiosity_cache: Option<std::path::PathBuf>,
    /// Radiosity: whether the scene's lights (point, spot, directional,
    /// area) shoot first besides the emitting surfaces (default on).
    #[arg(long, value_name = "on|off", value_parser = parse_on_off)]
    pub(crate) radiosity_lights: Option<bool>,
    /// Radiosity: near patches' form factors by the analytic contour
    /// integral instead of the hemicube's pixels (the hemicube still
    /// decides what is seen).
    #[arg(long)]
    pub(crate) analytic_near: bool,
    /// Radiosity: times to cut the patches where radiosity changes fast
    /// and solve again (0 to 4; default 0).
    #[arg(long, value_name = "LEVELS", value_parser = clap::value_parser!(u32).range(0..=4))]
    pub(crate) subdivide: Option<u32>,
}

/// `on` or `off`.
fn parse_on_off(s: &str) -> Result<bool, String> {
    match s {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(format!("expected on or off, got {s:?}")),
    }
}

impl RadiosityArgs {
    /// True when a radiosity flag was given.
    fn given(&self) -> bool {
        self.patch_size.is_some()
            || self.hemicube.is_some()
            || self.solver.is_some()
            || self.radiosity_tolerance.is_some()
            || self.radiosity_cache.is_some()
            || self.radiosity_lights.is_some()
            || self.analytic_near
            || self.subdivide.is_some()
    }

    /// Refuses the flags for a scene radiosity does not draw.
    pub(crate) fn check_unused(&self) -> Result<()> {
        if self.given() {
            bail!("--patch-size, --hemicube, --solver, --radiosity-tolerance, --radiosity-lights, --analytic-near, --subdivide and --radiosity-cache need --renderer radiosity (or renderer = \"radiosity\" in the scene file)");
        }
        Ok(())
    }

    /// The solver's options: the scene file's (`base`), with the flags
    /// given over them.
    pub(crate) fn options(&self, base: Options) -> Options {
        let mut o = base;
        if let Some(size) = self.patch_size {
            o.patch_size = Some(size);
        }
        if let Some(lights) = self.radiosity_lights {
            o.lights = lights;
        }
        o.analytic_near |= self.analytic_near;
        if let Some(levels) = self.subdivide {
            o.subdivide = levels;
        }
        if let Some(n) = self.hemicube {
            o.resolution = n;
        }
        if let Some(s) = self.solver {
            o.method = match s {
                SolverChoice::Jacobi => Method::Jacobi,
                SolverChoice::GaussSeidel => Method::GaussSeidel,
                SolverChoice::Progressive => Method::Progressive,
            };
        }
        if let Some(t) = self.radiosity_tolerance {
            o.tolerance = t;
        }
        o
    }

    /// Solves `scene` and returns the scene the rasterizer draws in its
    /// place, after telling what the solve did.
    pub(crate) fn display(&self, scene: &Scene) -> Result<Scene> {
        use zline::radiosity::{cache, mesh, replay, solve_refined, Solution};
        let start = std::time::Instant::now();
        let (patches, options) = mesh(scene, &self.options(scene.settings.radiosity))?;
        for warning in &patches.warnings {
            eprintln!("warning: {warning}");
        }
        let key = cache::fingerprint(&patches, &options);
        let kept = self.radiosity_cache.as_deref().and_then(|path| {
            let usable = cache::load(path, key).and_then(|kept| match kept {
                None => Ok(None),
                Some(kept) => match replay(scene, patches.clone(), &kept.splits, &options) {
                    Some(replayed) if replayed.patches.len() == kept.radiosity.len() => {
                        Ok(Some((replayed, kept)))
                    }
                    _ => Err("its subdivision does not fit these patches".to_string()),
                },
            });
            usable.unwrap_or_else(|why| {
                eprintln!("warning: {}: {why}; solving again", path.display());
                None
            })
        });
        if let (Some((replayed, kept)), Some(path)) = (kept, &self.radiosity_cache) {
            eprintln!(
                "radiosity: {} patches read from {} ({:.2} s)",
                replayed.patches.len(),
                path.display(),
                start.elapsed().as_secs_f64()
            );
            let solution = Solution {
                patches: replayed,
                radiosity: kept.radiosity,
                convergence: Default::default(),
                options,
                splits: kept.splits,
                took: start.elapsed(),
            };
            return Ok(solution.display_scene(scene));
        }
        let solution = solve_refined(scene, patches, &options)?;
        if let Some(path) = &self.radiosity_cache {
            let kept = cache::Kept { splits: solution.splits.clone(), radiosity: solution.radiosity.clone() };
            cache::save(path, key, &kept)
                .with_context(|| format!("{}: cannot write the radiosity cache", path.display()))?;
        }
        let residual = solution.convergence.residuals.last().copied().unwrap_or(0.0);
        eprintln!(
            "radiosity: {} patches of {:.3} at most{}, {} by {} steps ({} hemicubes of {}²), residual {residual:.1e}, {:.2} s",
            solution.patches.patches.len(),
            solution.options.patch_size.unwrap_or(0.0),
            match solution.splits.len() {
                0 => String::new(),
                levels => format!(
                    " ({} cut in {levels} subdivision levels)",
                    solution.splits.iter().map(Vec::len).sum::<usize>()
                ),
            },
            solution.options.method.name(),
            solution.convergence.residuals.len(),
            solution.convergence.hemicubes,
            solution.options.resolution,
            solution.took.as_secs_f64()
        );
        Ok(solution.display_scene(scene))
    }
}
