//! The report's lighting-model section: the basic model (SPEC §5.1) and
//! Cook–Torrance (§5.2, GGX and Beckmann) on the same scenes, each timed
//! and compared with the f64 truth of the same model
//! (`crates/truth/src/microfacet.rs`).
//!
//! - `tests/scenes/cook_torrance.toml`: six spheres (dielectric and metal,
//!   rough to smooth, both distributions) and a box whose material reads
//!   metallic–roughness, occlusion and emissive textures, in Phong,
//!   Gouraud and flat shading, and with 2 × 2 supersampling.
//! - The same scene with every material forced to each model
//!   (`Material::with_model`, what `--model` does): what the model costs
//!   and what its error is, against its own truth.
//! - The scene under the procedural sky as environment map (SPEC §5.3):
//!   its cost, and its error against the truth's own SH projection and
//!   direct lobe integrals.
//! - `tests/scenes/lights_spot.toml`: spot lights with ranges (SPEC §5.1).
//! - Where the shared assets are present, Suzanne and FlightHelmet (glTF
//!   metallic–roughness materials with textures) under two lights.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, Result};
use zline::scene::{Scene, ShadingMode, ShadowMode};
use zline::shading::{Distribution, Light, ModelChoice};
use zline_truth::{render_truth, ErrorStats};

use crate::timing::time_interleaved;

/// Image size of the section's scenes.
const SIZE: (u32, u32) = (400, 250);

fn repo_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(name)
}

/// `scene` with every material (objects' and meshes') lit by `model`.
fn with_model(scene: &Scene, model: ModelChoice) -> Scene {
    let mut s = scene.clone();
    for o in &mut s.objects {
        o.material = o.material.map(|m| m.with_model(model));
        let mut mesh = (*o.mesh).clone();
        mesh.material = mesh.material.with_model(model);
        o.mesh = Arc::new(mesh);
    }
    s
}

/// The markdown section.
pub(crate) fn section(assets: &Path, frames: usize) -> Result<String> {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Lighting models\n\n{}×{}, fastest and median of {frames} frames in interleaved rounds; errors in 8-bit \
         steps against the f64 truth of the same model and shading (SPEC §5.1, §5.2).\n",
        SIZE.0, SIZE.1
    );
    let path = repo_file("tests/scenes/cook_torrance.toml");
    let options = zline::io::LoadOptions { allow_outside: true };
    let mut scene = zline::io::load_scene_with_options(&path, options).map_err(anyhow::Error::from)?;
    (scene.settings.width, scene.settings.height) = SIZE;
    let mut rows: Vec<(String, Scene)> = Vec::new();
    for (name, shading, ssaa) in [
        ("phong", ShadingMode::Phong, 1),
        ("gouraud", ShadingMode::Gouraud, 1),
        ("flat", ShadingMode::Flat, 1),
        ("phong ssaa 2x2", ShadingMode::Phong, 2),
    ] {
        let mut s = scene.clone();
        (s.settings.shading, s.settings.ssaa) = (shading, ssaa);
        rows.push((format!("as authored, {name}"), s));
    }
    for (name, model) in [
        ("basic", ModelChoice::Basic),
        ("cook-torrance (ggx)", ModelChoice::CookTorrance(Distribution::Ggx)),
        ("cook-torrance (beckmann)", ModelChoice::CookTorrance(Distribution::Beckmann)),
    ] {
        rows.push((format!("every material {name}, phong"), with_model(&scene, model)));
    }
    // The procedural sky as environment map (SPEC §5.3), drawn behind.
    let (sky, _) =
        zline::io::load_environment(Path::new(zline::io::SKY_NAME)).map_err(anyhow::Error::from)?;
    let mut environment = zline::shading::Environment::new(sky);
    (environment.intensity, environment.background) = (0.6, true);
    for (name, model) in [("as authored", None), ("every material basic", Some(ModelChoice::Basic))] {
        let mut s = model.map_or_else(|| scene.clone(), |m| with_model(&scene, m));
        s.environment = Some(environment.clone());
        rows.push((format!("{name}, phong, environment sky"), s));
    }
    table(
        &mut md,
        "`tests/scenes/cook_torrance.toml` (7 objects, a point and a directional light)",
        &rows,
        frames,
    );
    spot_table(&mut md, frames)?;
    let models = ["Suzanne/glTF/Suzanne.gltf", "FlightHelmet/glTF/FlightHelmet.gltf"];
    let mut rows = Vec::new();
    for model in models {
        let path = assets.join("gltf").join(model);
        if !path.exists() {
            eprintln!("note: {} is missing; skipped (pass --assets)", path.display());
            continue;
        }
        let gltf = zline::io::load_gltf(&path).with_context(|| format!("loading {}", path.display()))?;
        let settings = zline::scene::RenderSettings { width: SIZE.0, height: SIZE.1, ..Default::default() };
        let mut s = zline::io::scene_for_gltf(gltf, settings);
        s.lights = vec![
            Light::Directional {
                direction: glam::Vec3::new(-0.5, -0.7, -1.0),
                color: glam::Vec3::splat(2.0),
            },
            Light::Directional {
                direction: glam::Vec3::new(0.8, -0.2, -0.4),
                color: glam::Vec3::new(0.6, 0.7, 1.0),
            },
        ];
        let name = model.split('/').next().unwrap_or(model);
        rows.push((format!("{name}, cook-torrance"), s.clone()));
        rows.push((format!("{name}, basic"), with_model(&s, ModelChoice::Basic)));
    }
    if !rows.is_empty() {
        table(&mut md, "glTF models (their textures; two directional lights)", &rows, frames);
    }
    Ok(md)
}

/// `tests/scenes/lights_spot.toml`: two spot lights with a range and a
/// hard or soft cone (SPEC §5.1), without shadows and with its shadow maps.
fn spot_table(md: &mut String, frames: usize) -> Result<()> {
    let path = repo_file("tests/scenes/lights_spot.toml");
    let options = zline::io::LoadOptions { allow_outside: true };
    let mut scene = zline::io::load_scene_with_options(&path, options).map_err(anyhow::Error::from)?;
    (scene.settings.width, scene.settings.height) = SIZE;
    let mut rows = Vec::new();
    for (name, shading, shadows) in [
        ("phong, no shadows", ShadingMode::Phong, ShadowMode::None),
        ("gouraud, no shadows", ShadingMode::Gouraud, ShadowMode::None),
        ("phong, shadow maps", ShadingMode::Phong, ShadowMode::Map),
    ] {
        let mut s = scene.clone();
        (s.settings.shading, s.shadows.mode) = (shading, shadows);
        rows.push((name.to_string(), s));
    }
    table(
        md,
        "`tests/scenes/lights_spot.toml` (two spot lights with ranges; basic and Cook–Torrance)",
        &rows,
        frames,
    );
    Ok(())
}

fn table(md: &mut String, title: &str, rows: &[(String, Scene)], frames: usize) {
    let scenes: Vec<Scene> = rows.iter().map(|(_, s)| s.clone()).collect();
    let (times, images) = time_interleaved(&scenes, frames);
    let _ = writeln!(md, "### {title}\n");
    let _ = writeln!(md, "| setting | ms (fastest) | ms (median) | RMSE | max | exact | > 1 |");
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|");
    for (((name, scene), (fastest, median)), image) in rows.iter().zip(&times).zip(&images) {
        let e = ErrorStats::of_rgb8(&image.to_rgb(), &render_truth(scene));
        let _ = writeln!(
            md,
            "| {name} | {fastest:.2} | {median:.2} | {:.3} | {:.0} | {:.3} % | {:.3} % |",
            e.rmse,
            e.max_abs,
            100.0 * e.share_exact,
            100.0 * e.share_over_1
        );
    }
    md.push('\n');
}
