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
//!   of the sampling itself, with the time each k costs; and the same
//!   light with `samples = "auto"` at several tolerances: the k the
//!   adaptive choice takes (`zline_scene::choose_area_samples`) and the
//!   error it gives.
//! - Shadow maps on the planar scene (every surface receives and casts) at
//!   512², 1024², 2048², 4096², with and without PCF, against the truth of
//!   map mode (a ray per sample and light against every triangle).
//! - Acne and peter-panning: a floor under a grazing sun (80° from the
//!   normal) with a thin slab lying on it, at bias scales 0 … 8: the share
//!   of pixels the map darkens wrongly (acne, or a shadow bleeding past
//!   its caster) and lights wrongly (a shadow detached from its caster).
//!
//! Every timed row is also a point on the shadow chart
//! (`docs/images/report-shadows.png`): time against error, each against
//! its own truth.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use zline::scene::{Scene, ShadowMode};
use zline_truth::{render_truth, ErrorStats};

use crate::chart::{Labels, Point};
use crate::timing::time_interleaved;

/// The shadow chart's words.
pub(crate) const CHART: Labels = Labels {
    title: "zline shadows: time against error (400×300)",
    x: "frame time (fastest of N frames), ms",
    y: "RMSE vs the f64 truth with shadows, 8-bit steps (log)",
    legend: "rows of the report's Shadows tables",
    log_time: true,
};

/// Image size of the shadow scenes (the truth lights 256 samples per pixel
/// for the dense area light).
const SIZE: (u32, u32) = (400, 300);

fn repo_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(name)
}

/// Loads a repository scene file, with its `samples = 4` replaced by
/// `samples` when given (a count or `"auto"` with a tolerance), at
/// [`SIZE`].
fn load(name: &str, samples: Option<&str>) -> Result<Scene> {
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

/// The markdown section and the chart's points.
pub(crate) fn section(frames: usize) -> Result<(String, Vec<Point>)> {
    let mut md = String::new();
    let mut points = Vec::new();
    let _ = writeln!(
        md,
        "## Shadows\n\n{}×{}, fastest and median of {frames} frames in interleaved rounds; errors in 8-bit \
         steps against the f64 truth, which casts a ray from each receiving sample (every sample with shadow maps) to each light \
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
        points.push(point(&format!("{name} (planar scene)"), *t, &e));
    }
    let dense = render_truth(&load("tests/scenes/shadows_area.toml", Some("16"))?);
    let ks = [1u32, 2, 3, 4, 5];
    let tolerances = [4.0f32, 2.0, 1.0, 0.5];
    let mut names: Vec<String> = ks.iter().map(|k| format!("{k} × {k}")).collect();
    let mut scenes = ks
        .iter()
        .map(|&k| load("tests/scenes/shadows_area.toml", Some(&k.to_string())))
        .collect::<Result<Vec<_>>>()?;
    for t in tolerances {
        let scene = load("tests/scenes/shadows_area.toml", Some(&format!("\"auto\"\ntolerance = {t}")))?;
        let k = (scene.lights.len() as f64).sqrt().round();
        names.push(format!("auto, tolerance {t}: {k} × {k}"));
        scenes.push(scene);
    }
    let (times, images) = time_interleaved(&scenes, frames);
    let _ = writeln!(
        md,
        "\n### Area light sampled k × k (`tests/scenes/shadows_area.toml`) against a 16 × 16 truth\n"
    );
    let _ = writeln!(md, "| k × k | ms (fastest) | ms (median) | RMSE | max | exact | > 1 |");
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|");
    for (name, (t, image)) in names.iter().zip(times.iter().zip(&images)) {
        let e = ErrorStats::of_rgb8(&image.to_rgb(), &dense);
        row(&mut md, name, *t, &e);
        points.push(point(&format!("area {name}"), *t, &e));
    }
    let _ = writeln!(
        md,
        "\n*auto*: `samples = \"auto\"` takes the fewest k whose diffuse light on a white surface differs from \
         16 × 16 by at most the tolerance (RMSE in 8-bit steps over up to 512 visible surface points, with \
         the shadows the scene models; `zline_scene::choose_area_samples`). With planar shadows it stops \
         at 5 × 5: the shadow mask holds 32 (plane, light) pairs."
    );
    md.push('\n');
    maps(&mut md, &mut points, frames)?;
    acne(&mut md)?;
    Ok((md, points))
}

fn point(name: &str, (fastest, _): (f64, f64), e: &ErrorStats) -> Point {
    Point { name: name.to_string(), ms: fastest, rmse: e.rmse, pareto: false }
}

/// Shadow maps at several sizes, with and without PCF.
fn maps(md: &mut String, points: &mut Vec<Point>, frames: usize) -> Result<()> {
    let mut scene = load("tests/scenes/shadows_planar.toml", None)?;
    scene.shadows.mode = ShadowMode::Map;
    let truth = render_truth(&scene);
    let variants: Vec<(String, Scene)> = [512u32, 1024, 2048, 4096]
        .iter()
        .flat_map(|&size| [true, false].map(|pcf| (size, pcf)))
        .map(|(size, pcf)| {
            let mut s = scene.clone();
            (s.shadows.map_size, s.shadows.pcf) = (size, pcf);
            (format!("{size}² {}", if pcf { "PCF 3 × 3" } else { "nearest" }), s)
        })
        .collect();
    let scenes: Vec<Scene> = variants.iter().map(|(_, s)| s.clone()).collect();
    let (times, images) = time_interleaved(&scenes, frames);
    let _ = writeln!(
        md,
        "### Shadow maps (`tests/scenes/shadows_planar.toml` in map mode: every surface receives and casts)\n"
    );
    let _ = writeln!(md, "| map | ms (fastest) | ms (median) | RMSE | max | exact | > 1 |");
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|");
    for ((name, _), (t, image)) in variants.iter().zip(times.iter().zip(&images)) {
        let e = ErrorStats::of_rgb8(&image.to_rgb(), &truth);
        row(md, name, *t, &e);
        points.push(point(&format!("map {name}"), *t, &e));
    }
    md.push('\n');
    Ok(())
}

/// The hard case for shadow-map bias: a grazing sun over a floor with a
/// thin slab on it.
fn grazing_scene() -> Scene {
    use std::sync::Arc;
    use zline::scene::{cube, plane, Camera, Material, Object, Projection, RenderSettings};
    use zline::shading::Light;
    let object = |mesh, m: glam::Mat4, color| Object {
        mesh: Arc::new(mesh),
        world_from_object: m,
        material: Some(Material::plastic(color, 0.0, 1.0)),
        shading: None,
        cull_back_faces: false,
    };
    let slab = glam::Mat4::from_translation(glam::Vec3::new(0.0, 0.02, 0.0))
        * glam::Mat4::from_scale(glam::Vec3::new(2.0, 0.04, 1.0));
    let angle = 80f32.to_radians();
    Scene {
        environment: None,
        camera: Camera {
            eye: glam::Vec3::new(0.0, 3.0, 4.0),
            target: glam::Vec3::ZERO,
            up: glam::Vec3::Y,
            projection: Projection::Perspective { fovy_degrees: 45.0, near: 0.5, far: 20.0 },
        },
        background: glam::Vec3::ZERO,
        ambient: glam::Vec3::splat(0.1),
        lights: vec![Light::Directional {
            direction: glam::Vec3::new(angle.sin(), -angle.cos(), 0.0),
            color: glam::Vec3::ONE,
        }],
        objects: vec![
            object(plane(8.0, 8), glam::Mat4::IDENTITY, glam::Vec3::splat(0.8)),
            object(cube(1.0), slab, glam::Vec3::new(0.3, 0.5, 0.8)),
        ],
        settings: RenderSettings { width: SIZE.0, height: SIZE.1, ..RenderSettings::default() },
        fog: None,
        shadows: zline::scene::Shadows { mode: ShadowMode::Map, ..Default::default() },
    }
}

/// Wrongly darkened and wrongly lit pixels at each bias scale.
fn acne(md: &mut String) -> Result<()> {
    let scene = grazing_scene();
    let truth = render_truth(&scene);
    let reference = truth.quantized_rgb8();
    let _ = writeln!(
        md,
        "### Acne and peter-panning (a floor under a sun 80° from its normal, a 4 cm slab lying on it; 1024², PCF)\n\n\
         *darker* is the share of pixels more than one step darker than the truth (acne; a shadow \
         reaching past its caster), *lighter* the share more than one step lighter (a shadow detached \
         from its caster, or light leaking under it).\n"
    );
    let _ = writeln!(md, "| bias scale | darker | lighter | RMSE |");
    let _ = writeln!(md, "|---:|---:|---:|---:|");
    for bias in [0.0f32, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0] {
        let mut s = scene.clone();
        s.shadows.bias = bias;
        let image = zline::pipeline::render(&s, &zline::pipeline::RenderOptions::default()).0.to_rgb();
        let pixels = image.len() / 3;
        let (mut darker, mut lighter) = (0usize, 0usize);
        for (got, want) in image.chunks(3).zip(reference.chunks(3)) {
            let d: i32 = got.iter().zip(want).map(|(&a, &b)| i32::from(a) - i32::from(b)).sum();
            darker +=
                usize::from(got.iter().zip(want).any(|(&a, &b)| i32::from(a) < i32::from(b) - 1) && d < 0);
            lighter +=
                usize::from(got.iter().zip(want).any(|(&a, &b)| i32::from(a) > i32::from(b) + 1) && d > 0);
        }
        let e = ErrorStats::of_rgb8(&image, &truth);
        let share = |n: usize| 100.0 * n as f64 / pixels as f64;
        let _ = writeln!(md, "| {bias} | {:.3} % | {:.3} % | {:.3} |", share(darker), share(lighter), e.rmse);
    }
    md.push('\n');
    Ok(())
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
