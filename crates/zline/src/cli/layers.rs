//! The command line's extra outputs, flattened into the common options:
//! `--transparent` (RGBA output with alpha = coverage), `--depth-image`
//! (the z-buffer as a 16-bit PNG), `--normal-image` (eye-space normals
//! as RGB) and `--id-image` (which object each pixel shows).

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context, Result};
use clap::Args;
use zline::pipeline::{DepthImage, Image, RenderOptions, RenderStats, Renderer};
use zline::raster::TieRule;
use zline::scene::{RenderSettings, Scene};

/// The options.
#[derive(Args, Debug, Clone)]
pub(crate) struct LayerArgs {
    /// RGBA PNG output with a transparent background: alpha 0 where nothing
    /// is drawn, otherwise the pixel's coverage (the share of its samples
    /// drawn, a transparent surface over nothing counting its opacity
    /// 1 − kt), colour straight (not premultiplied). Composited over a
    /// background B it gives the render on B within one step per channel.
    /// Replaces `[render] transparent_background`. Not with JPEG output.
    #[arg(long)]
    transparent: bool,
    /// Also write the z-buffer as a 16-bit greyscale PNG: eye-space depth
    /// (distance to the eye plane) of the nearest opaque surface, linear,
    /// the nearest drawn pixel 65535 (white), the farthest drawn 1, nothing
    /// drawn 0; the mapping is printed and stored in a tEXt chunk. With
    /// --ssaa: the nearest of the pixel's samples.
    #[arg(long, value_name = "PATH.png")]
    depth_image: Option<PathBuf>,
    /// Also write the eye-space shading normals as an RGB PNG, (n + 1)/2
    /// per axis (x right, y up, z toward the viewer), interpolated per
    /// sample as Phong does (flat-shaded objects: their face normal; bump
    /// and normal maps applied), turned toward the viewer; background
    /// (0, 0, 0), or transparent with --transparent.
    #[arg(long, value_name = "PATH.png")]
    normal_image: Option<PathBuf>,
    /// Also write which object each pixel shows as an RGB PNG: the index of
    /// the nearest opaque object at the pixel's centre plus one, as
    /// R + 256·G + 65536·B (objects in the order `zline info` lists them),
    /// 0 where none is; transparent objects are left out, as in the depth
    /// image.
    #[arg(long, value_name = "PATH.png")]
    id_image: Option<PathBuf>,
    /// Also write the overdraw as a heat map PNG: per pixel, how many
    /// fragments the triangles made there (every covered sample, before the
    /// depth test), black 0, blue 1, … red 7, white 8 or more; the mean and
    /// largest are printed.
    #[arg(long, value_name = "PATH.png")]
    overdraw: Option<PathBuf>,
    /// Which samples on a triangle's edge --overdraw counts as covered:
    /// top-left (the renderer's rule, SPEC §3: a shared edge drawn once),
    /// closed (every edge sample: shared edges drawn twice) or open (none:
    /// shared edges drawn by neither). "What breaks without the top-left
    /// rule", shown on the real mesh.
    #[arg(long, value_name = "RULE", default_value = "top-left", value_parser = parse_tie_rule, requires = "overdraw")]
    tie_rule: TieRule,
    /// Follow pixel X,Y through the frame (the pixel inspector) and print
    /// every fragment that touched it, in draw order: its object and
    /// triangle, window vertices, the edge table's span and the top-left
    /// rule's verdict, the depth and the depth test, the colour before and
    /// after, then fog, the resolve and the 8-bit result, checked against
    /// the image written. To standard output (so not with `-o -`).
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel)]
    inspect: Option<(u32, u32)>,
    /// With --inspect: the report as JSON.
    #[arg(long, requires = "inspect")]
    inspect_json: bool,
}

fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let (x, y) =
        s.split_once(',').ok_or_else(|| format!("expected X,Y (pixel column and row), got {s:?}"))?;
    let parse =
        |v: &str| v.trim().parse::<u32>().map_err(|_| format!("expected X,Y in whole pixels, got {s:?}"));
    Ok((parse(x)?, parse(y)?))
}

fn parse_tie_rule(s: &str) -> Result<TieRule, String> {
    TieRule::ALL
        .into_iter()
        .find(|r| r.name() == s)
        .ok_or_else(|| format!("expected top-left, closed or open, got {s:?}"))
}

impl LayerArgs {
    /// Checks the options against the main output before anything is
    /// loaded: JPEG output with --transparent is a usage error (exit code
    /// 2, as clap's); the extra images must be writable `.png` files.
    pub(crate) fn check(&self, output: &Path) -> Result<()> {
        if self.transparent && zline::is_jpeg(output) {
            clap::Error::raw(
                clap::error::ErrorKind::ArgumentConflict,
                format!(
                    "--transparent needs PNG output (JPEG has no alpha channel), got -o {}\n",
                    output.display()
                ),
            )
            .exit();
        }
        if self.inspect.is_some() && zline::is_stdout(output) {
            bail!("--inspect prints its report on standard output: write the image to a file, not -o -");
        }
        for (flag, path) in self.extra() {
            let png =
                path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("png"));
            if !png {
                bail!("{}: {flag} writes a PNG: the file must end in .png", path.display());
            }
            zline::check_output(path).map_err(|e| anyhow!("{}: {e}", path.display()))?;
        }
        Ok(())
    }

    /// Refuses the options where only one image per render is written
    /// (`turntable`, `batch`).
    pub(crate) fn refuse(&self, command: &str) -> Result<()> {
        let extra = self.depth_image.is_some() || self.normal_image.is_some() || self.id_image.is_some();
        if self.transparent || extra || self.overdraw.is_some() || self.inspect.is_some() {
            bail!("--transparent, --depth-image, --normal-image, --id-image, --overdraw and --inspect are options of render, demo and terrain, not of {command}");
        }
        Ok(())
    }

    /// Replaces the settings the options give.
    pub(crate) fn apply(&self, settings: &mut RenderSettings) {
        if self.transparent {
            settings.transparent_background = true;
        }
    }

    fn extra(&self) -> impl Iterator<Item = (&'static str, &PathBuf)> {
        let depth = self.depth_image.as_ref().map(|p| ("--depth-image", p));
        let normals = self.normal_image.as_ref().map(|p| ("--normal-image", p));
        let ids = self.id_image.as_ref().map(|p| ("--id-image", p));
        depth.into_iter().chain(normals).chain(ids).chain(self.overdraw.as_ref().map(|p| ("--overdraw", p)))
    }

    /// Renders the image, and the depth image when asked for (in the same
    /// frame).
    pub(crate) fn render(
        &self,
        scene: &Scene,
        options: &RenderOptions,
    ) -> (Image, RenderStats, Option<DepthImage>) {
        let mut image = Image::empty();
        let mut renderer = Renderer::default();
        if self.depth_image.is_none() {
            let stats = renderer.render_into(scene, options, &mut image);
            return (image, stats, None);
        }
        let mut depth = DepthImage::default();
        let stats = renderer.render_with_depth(scene, options, &mut image, &mut depth);
        (image, stats, Some(depth))
    }

    /// Writes the depth image and renders and writes the normals and ID
    /// images, each with a line on stderr.
    pub(crate) fn write(
        &self,
        scene: &Scene,
        options: &RenderOptions,
        pool: &rayon::ThreadPool,
        (depth, quiet): (Option<DepthImage>, bool),
    ) -> Result<()> {
        // The `wrote …` lines, unless `--quiet`.
        let say = |line: String| {
            if !quiet {
                eprintln!("{line}");
            }
        };
        if let (Some(path), Some(depth)) = (&self.depth_image, depth) {
            let range = zline::save_depth_png(&depth, path)
                .with_context(|| format!("{}: cannot write the depth image", path.display()))?;
            say(format!(
                "wrote {} (depth, 16-bit grey: {})",
                path.display(),
                zline::layers::describe_depth_range(range)
            ));
        }
        if let Some(path) = &self.normal_image {
            let (normals, _) = pool.install(|| zline::pipeline::render_normals(scene, options));
            zline::save_image(&normals, path)
                .with_context(|| format!("{}: cannot write the normal image", path.display()))?;
            say(format!("wrote {} (eye-space normals, RGB = (n + 1)/2)", path.display()));
        }
        if let Some(path) = &self.id_image {
            let (mut image, mut ids) = (Image::empty(), zline::pipeline::ObjectIds::default());
            pool.install(|| {
                Renderer::default().render_object_ids_into(scene, options, &mut image, &mut ids)
            })?;
            zline::save_image(&image, path)
                .with_context(|| format!("{}: cannot write the ID image", path.display()))?;
            let shown = ids.ids.iter().filter(|&&i| i >= 0).collect::<std::collections::BTreeSet<_>>().len();
            say(format!(
                "wrote {} (object IDs, RGB = index + 1: {shown} of {} objects seen)",
                path.display(),
                scene.objects.len()
            ));
        }
        if let Some(pixel) = self.inspect {
            let mut image = Image::empty();
            let trace = pool.install(|| Renderer::default().inspect(scene, options, pixel, &mut image))?;
            let report = if self.inspect_json {
                zline::inspect::json(&trace, scene)
            } else {
                zline::inspect::text(&trace, scene)
            };
            println!("{}", report.trim_end());
            if !trace.matches() {
                bail!("the inspector's pixel differs from the rendered image's: please report this");
            }
        }
        if let Some(path) = &self.overdraw {
            let count = |rule| pool.install(|| zline::pipeline::render_overdraw(scene, options, rule).0);
            let o = count(self.tie_rule);
            let top_left = (self.tie_rule != TieRule::TopLeft).then(|| count(TieRule::TopLeft));
            zline::save_image(&zline::layers::overdraw_heat_map(&o), path)
                .with_context(|| format!("{}: cannot write the overdraw image", path.display()))?;
            let line = zline::layers::describe_overdraw(&o, self.tie_rule, top_left.as_ref());
            say(format!("wrote {} ({line})", path.display()));
        }
        Ok(())
    }
}
