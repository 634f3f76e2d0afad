//! `cargo xtask regress` and `cargo xtask bless`: render regression.
//!
//! Every scene file `tests/scenes/<name>.toml` is rendered with
//! `zline::pipeline::render` and the default `RenderOptions` (or ray-traced
//! with its `[raytrace]` options when its `renderer` says so), and compared
//! with its reference image `tests/scenes/<name>.png`, pixel by pixel and
//! exactly ([`TOLERANCE`], [`PIXEL_BUDGET`]). The pipeline's images are
//! bit-identical for any thread count and tile size, so a difference is a
//! change of behaviour, never noise.
//!
//! `regress` prints one line per scene, writes each failing scene's
//! expected | difference | actual picture to `target/regress/<name>.png`
//! (the difference is |expected − actual| × [`AMPLIFY`] per channel), and
//! fails when any scene fails; a missing reference is a failure. `bless`
//! rewrites the references that changed and says what changed. Scenes are
//! rendered in parallel (rayon), results printed in name order.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use image::{Rgb, RgbImage};
use rayon::prelude::*;
use zline::io::{load_scene_with_options, LoadOptions};
use zline::pipeline::{render, RenderOptions};
use zline::scene::trace_options::Renderer;

/// Scene files and their reference images, relative to the workspace root.
const SCENES: &str = "tests/scenes";

/// Where failing comparisons are written, relative to the workspace root
/// (under the git-ignored `target/`).
const OUT: &str = "target/regress";

/// The largest channel difference, in 8-bit units, for which two pixels
/// still count as equal. Zero: the pipeline is deterministic for any
/// thread count and tile size and performs the same IEEE operations at
/// every vector width, so the reference images are matched bit for bit.
const TOLERANCE: u8 = 0;

/// Pixels per scene that may differ by more than [`TOLERANCE`] before the
/// scene fails. Zero, for the same reason: no scene needs a budget.
const PIXEL_BUDGET: usize = 0;

/// Factor applied to |expected − actual| in the difference picture, so
/// that a difference of one level shows as 32.
const AMPLIFY: u16 = 32;

/// Pixels between the panels of a difference picture.
const GAP: u32 = 4;
const GAP_COLOR: Rgb<u8> = Rgb([255, 0, 255]);
/// Where only one of two differently sized images has a pixel.
const MISSING_COLOR: Rgb<u8> = Rgb([255, 0, 0]);

/// What the task does with each rendered scene.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mode {
    /// Compare with the reference; fail on a difference.
    Check,
    /// Rewrite the reference.
    Bless,
}

/// One scene rendered.
struct Rendered {
    name: String,
    /// The image, or why the scene could not be rendered.
    image: Result<RgbImage>,
    time: Duration,
}

/// How two images differ.
#[derive(Debug, PartialEq, Eq)]
struct Difference {
    /// Pixels with a channel differing by more than [`TOLERANCE`] (every
    /// pixel outside the common area when the sizes differ).
    pixels: usize,
    /// The largest channel difference (255 outside the common area).
    max: u8,
}

/// Runs `regress` or `bless` on the scenes whose name contains `filter`.
pub(crate) fn run(mode: Mode, filter: Option<&str>) -> Result<()> {
    let root = workspace_root();
    let scenes = scene_files(&root.join(SCENES), filter)?;
    if scenes.is_empty() {
        bail!("no scene in {SCENES} matches {:?}", filter.unwrap_or(""));
    }
    let start = Instant::now();
    let rendered: Vec<Rendered> = scenes.par_iter().map(|path| render_scene(path)).collect();
    let render_time = start.elapsed();
    let width = rendered.iter().map(|r| r.name.len()).max().unwrap_or(0);
    let mut failed = 0;
    for r in &rendered {
        let outcome = match mode {
            Mode::Check => check(&root, r),
            Mode::Bless => bless(&root, r),
        };
        let time = format!("{:6.1} ms", r.time.as_secs_f64() * 1e3);
        match outcome {
            Ok(message) => println!("{:width$}  {time}  {message}", r.name),
            Err(e) => {
                failed += 1;
                println!("{:width$}  {time}  FAIL: {e:#}", r.name);
            }
        }
    }
    let verb = if mode == Mode::Check { "regress" } else { "bless" };
    let (n, seconds) = (rendered.len(), render_time.as_secs_f64());
    println!("{verb}: {n} scenes, {} ok, {failed} failed; rendered in {seconds:.2} s", n - failed);
    if mode == Mode::Check {
        warn_about_orphans(&root.join(SCENES))?;
    }
    if failed > 0 {
        // Each failure is reported above; an error here would only repeat
        // it (with a backtrace when RUST_BACKTRACE is set).
        std::process::exit(1);
    }
    Ok(())
}

/// The workspace root: the parent of this crate's folder.
fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask lives in the workspace").to_path_buf()
}

/// The `*.toml` files of `dir` whose stem contains `filter`, by name.
fn scene_files(dir: &Path, filter: Option<&str>) -> Result<Vec<PathBuf>> {
    let entries = std::fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))?;
    let mut scenes = Vec::new();
    for entry in entries {
        let path = entry?.path();
        let name = scene_name(&path);
        if path.extension().is_some_and(|e| e == "toml") && filter.is_none_or(|f| name.contains(f)) {
            scenes.push(path);
        }
    }
    scenes.sort();
    Ok(scenes)
}

fn scene_name(path: &Path) -> String {
    path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default()
}

fn render_scene(path: &Path) -> Rendered {
    let start = Instant::now();
    // The scenes' models are in assets/, outside tests/scenes.
    let options = LoadOptions { allow_outside: true };
    let image = load_scene_with_options(path, options).map_err(anyhow::Error::from).and_then(|scene| {
        let (image, _) = match scene.settings.renderer {
            Renderer::RayTrace => zline::ray_traced_image(&scene, &scene.settings.trace),
            Renderer::Raster => {
                let (image, _) = render(&scene, &RenderOptions::default());
                (image, Default::default())
            }
            Renderer::Radiosity => {
                let solution = zline::radiosity::solve(&scene, &Default::default())?;
                let (image, _) = render(&solution.display_scene(&scene), &RenderOptions::default());
                (image, Default::default())
            }
        };
        RgbImage::from_raw(image.width, image.height, image.to_rgb()).context("image size")
    });
    Rendered { name: scene_name(path), image, time: start.elapsed() }
}

fn reference_path(root: &Path, name: &str) -> PathBuf {
    root.join(SCENES).join(format!("{name}.png"))
}

/// The reference image, or `None` when there is none.
fn read_reference(path: &Path) -> Result<Option<RgbImage>> {
    if !path.exists() {
        return Ok(None);
    }
    let image = image::open(path).with_context(|| format!("cannot read {}", path.display()))?;
    Ok(Some(image.to_rgb8()))
}

/// `regress` for one scene: `ok`, or an error saying what differs.
fn check(root: &Path, r: &Rendered) -> Result<String> {
    let actual = r.image.as_ref().map_err(|e| anyhow::anyhow!("{e:#}"))?;
    let path = reference_path(root, &r.name);
    let Some(expected) = read_reference(&path)? else {
        bail!("no reference image {SCENES}/{}.png; run `cargo xtask bless`", r.name);
    };
    let d = difference(&expected, actual);
    let fails = d.pixels > PIXEL_BUDGET || expected.dimensions() != actual.dimensions();
    if !fails {
        return Ok("ok".to_owned());
    }
    let out = root.join(OUT);
    std::fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
    let picture = out.join(format!("{}.png", r.name));
    side_by_side(&expected, actual)
        .save(&picture)
        .with_context(|| format!("cannot write {}", picture.display()))?;
    let size = size_note(&expected, actual);
    bail!("{} pixels differ, max diff {}{size}, wrote {OUT}/{}.png", d.pixels, d.max, r.name)
}

/// `bless` for one scene: writes the reference when it is new or changed.
fn bless(root: &Path, r: &Rendered) -> Result<String> {
    let actual = r.image.as_ref().map_err(|e| anyhow::anyhow!("{e:#}"))?;
    let path = reference_path(root, &r.name);
    let message = match read_reference(&path)? {
        None => "new".to_owned(),
        Some(expected) => {
            let d = difference(&expected, actual);
            if d.pixels == 0 {
                return Ok("unchanged".to_owned());
            }
            format!("changed: {} pixels (max diff {}){}", d.pixels, d.max, size_note(&expected, actual))
        }
    };
    actual.save(&path).with_context(|| format!("cannot write {}", path.display()))?;
    Ok(message)
}

fn size_note(expected: &RgbImage, actual: &RgbImage) -> String {
    if expected.dimensions() == actual.dimensions() {
        return String::new();
    }
    let ((ew, eh), (aw, ah)) = (expected.dimensions(), actual.dimensions());
    format!(", size {aw}x{ah} instead of {ew}x{eh}")
}

/// Notes reference images without a scene file (left over after a rename).
fn warn_about_orphans(dir: &Path) -> Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.extension().is_some_and(|e| e == "png") && !path.with_extension("toml").exists() {
            println!("note: {} has no scene file; delete it?", path.display());
        }
    }
    Ok(())
}

/// The channel difference of two pixels where both images have one.
fn pixel_difference(a: Option<&Rgb<u8>>, b: Option<&Rgb<u8>>) -> Option<[u8; 3]> {
    let (a, b) = (a?, b?);
    Some(std::array::from_fn(|c| a[c].abs_diff(b[c])))
}

fn difference(expected: &RgbImage, actual: &RgbImage) -> Difference {
    let (w, h) = (expected.width().max(actual.width()), expected.height().max(actual.height()));
    let mut d = Difference { pixels: 0, max: 0 };
    for (x, y) in (0..h).flat_map(|y| (0..w).map(move |x| (x, y))) {
        let channel = match pixel_difference(expected.get_pixel_checked(x, y), actual.get_pixel_checked(x, y))
        {
            Some(delta) => delta.into_iter().max().unwrap_or(0),
            None => u8::MAX,
        };
        if channel > TOLERANCE {
            d.pixels += 1;
        }
        d.max = d.max.max(channel);
    }
    d
}

/// expected | |expected − actual| × AMPLIFY | actual, with gaps between.
fn side_by_side(expected: &RgbImage, actual: &RgbImage) -> RgbImage {
    let (w, h) = (expected.width().max(actual.width()), expected.height().max(actual.height()));
    let mut out = RgbImage::from_pixel(3 * w + 2 * GAP, h, GAP_COLOR);
    for (x, y) in (0..h).flat_map(|y| (0..w).map(move |x| (x, y))) {
        let (e, a) = (expected.get_pixel_checked(x, y), actual.get_pixel_checked(x, y));
        let diff = match pixel_difference(e, a) {
            Some(delta) => Rgb(delta.map(|c| (u16::from(c) * AMPLIFY).min(255) as u8)),
            None => MISSING_COLOR,
        };
        out.put_pixel(x, y, *e.unwrap_or(&MISSING_COLOR));
        out.put_pixel(w + GAP + x, y, diff);
        out.put_pixel(2 * (w + GAP) + x, y, *a.unwrap_or(&MISSING_COLOR));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(w: u32, h: u32, pixels: &[(u32, u32, [u8; 3])]) -> RgbImage {
        let mut image = RgbImage::from_pixel(w, h, Rgb([10, 20, 30]));
        for &(x, y, c) in pixels {
            image.put_pixel(x, y, Rgb(c));
        }
        image
    }

    #[test]
    fn equal_images_do_not_differ() {
        let a = image(4, 3, &[(1, 1, [200, 0, 0])]);
        assert_eq!(difference(&a, &a.clone()), Difference { pixels: 0, max: 0 });
    }

    #[test]
    fn differing_pixels_are_counted_with_the_largest_channel_difference() {
        let a = image(4, 3, &[]);
        let b = image(4, 3, &[(0, 0, [11, 20, 30]), (3, 2, [10, 20, 25])]);
        assert_eq!(difference(&a, &b), Difference { pixels: 2, max: 5 });
    }

    #[test]
    fn a_size_change_counts_the_pixels_outside_the_common_area() {
        let (a, b) = (image(4, 3, &[]), image(5, 3, &[]));
        assert_eq!(difference(&a, &b), Difference { pixels: 3, max: 255 });
        assert_eq!(size_note(&a, &b), ", size 5x3 instead of 4x3");
    }

    #[test]
    fn the_side_by_side_picture_shows_expected_amplified_difference_and_actual() {
        let a = image(2, 1, &[]);
        let b = image(2, 1, &[(1, 0, [12, 20, 30])]);
        let out = side_by_side(&a, &b);
        assert_eq!(out.dimensions(), (3 * 2 + 2 * GAP, 1));
        assert_eq!(out.get_pixel(1, 0), &Rgb([10, 20, 30]), "expected");
        assert_eq!(out.get_pixel(2, 0), &GAP_COLOR);
        assert_eq!(out.get_pixel(2 + GAP, 0), &Rgb([0, 0, 0]), "no difference");
        assert_eq!(out.get_pixel(2 + GAP + 1, 0), &Rgb([64, 0, 0]), "2 × 32");
        assert_eq!(out.get_pixel(2 * (2 + GAP) + 1, 0), &Rgb([12, 20, 30]), "actual");
    }
}
