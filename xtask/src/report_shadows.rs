//! The report's shadow section: planar shadows and area lights, timed and
//! compared with the truth, which decides each light's visibility by an f64
//! ray per sample (`crates/truth/src/shadow.rs`).
//!
//! - Planar shadows (`tests/scenes/shadows_planar.toml`): the image with
//!   shadows against the truth with shadows, and the image without them
//!   against the same truth (what the shadows are worth), each with its
//!   time.
//! - An area light (`tests/scenes/shadows_area.toml`) sampled as k × k
//!   point lights, k = 1 … 5 (up to 25 lights: the shadow mask has 32 bits
//!   per plane), against the truth of a dense 16 × 16 sampling: the error
//!   of the sampling itself, with the time each k costs.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use zline::scene::{Scene, ShadowMode};
use zline_truth::{render_truth, ErrorStats};

use crate::timing::time_interleaved;

/// Image size of the shadow scenes (the truth lights 256 samples per pixel
/// for the dense area light).
const SIZE: (u32, u32) = (400, 300);

fn repo_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(name)
}

/// Loads a repository scene file, with its `samples = 4` replaced when
/// `samples` is given, at [`SIZE`].
fn load(name: &str, samples: Option<u32>) -> Result<Scene> {
    let path = repo_file(name);
    let text = std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let text = match samples {
        Some(k) => text.replace("samples = 4", &format!("samples = {k}")),
        None => text,
    };
    let dir = std::env::temp_dir().join(format!("zline-report-shadows-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let file = dir.join(path.file_name().context("a scene file name")?);
    std::fs::write(&file, text)?;
    let mut scene = zline::io::load_scene(&file).map_err(anyhow::Error::from)?;
    (scene.settings.width, scene.settings.height) = SIZE;
    Ok(scene)
}

/// The markdown section.
pub(crate) fn section(frames: usize) -> Result<String> {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Shadows\n\n{}×{}, fastest and median of {frames} frames in interleaved rounds; errors in 8-bit \
         steps against the f64 truth, which casts a ray from each sample of a receiving plane to each light \
         (`crates/truth/src/shadow.rs`).\n",
        SIZE.0, SIZE.1
    );
    let planar = load("tests/scenes/shadows_planar.toml", None)?;
    let truth = render_truth(&planar);
    let none = Scene {
        shadows: zline::scene::Shadows { mode: ShadowMode::None, ..planar.shadows.clone() },
        ..planar.clone()
    };
    let (times, images) = time_interleaved(&[planar.clone(), none], frames);
    let _ = writeln!(md, "### Planar shadows (`tests/scenes/shadows_planar.toml`, three lights)\n");
    let _ = writeln!(md, "| mode | ms (fastest) | ms (median) | RMSE | max | exact | > 1 |");
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|");
    for (name, (t, image)) in ["planar", "none"].iter().zip(times.iter().zip(&images)) {
        let e = ErrorStats::of_rgb8(&image.to_rgb(), &truth);
        row(&mut md, name, *t, &e);
    }
    let dense = render_truth(&load("tests/scenes/shadows_area.toml", Some(16))?);
    let ks = [1u32, 2, 3, 4, 5];
    let scenes =
        ks.iter().map(|&k| load("tests/scenes/shadows_area.toml", Some(k))).collect::<Result<Vec<_>>>()?;
    let (times, images) = time_interleaved(&scenes, frames);
    let _ = writeln!(
        md,
        "\n### Area light sampled k × k (`tests/scenes/shadows_area.toml`) against a 16 × 16 truth\n"
    );
    let _ = writeln!(md, "| k × k | ms (fastest) | ms (median) | RMSE | max | exact | > 1 |");
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|");
    for (k, (t, image)) in ks.iter().zip(times.iter().zip(&images)) {
        let e = ErrorStats::of_rgb8(&image.to_rgb(), &dense);
        row(&mut md, &format!("{k} × {k}"), *t, &e);
    }
    md.push('\n');
    Ok(md)
}

fn row(md: &mut String, name: &str, (fastest, median): (f64, f64), e: &ErrorStats) {
    let _ = writeln!(
        md,
        "| {name} | {fastest:.2} | {median:.2} | {:.3} | {:.0} | {:.3} % | {:.3} % |",
        e.rmse,
        e.max_abs,
        100.0 * e.share_exact,
        100.0 * e.share_over_1
    );
}
