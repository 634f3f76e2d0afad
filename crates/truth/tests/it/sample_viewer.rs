//! zline's Cook–Torrance against an independent f64 transcription of the
//! Khronos glTF Sample Viewer's punctual-light shading
//! (KhronosGroup/glTF-Sample-Viewer, `source/Renderer/shaders/brdf.glsl`:
//! `F_Schlick`, `V_GGX`, `D_GGX`, `BRDF_lambertian`, `BRDF_specularGGX`;
//! `punctual.glsl` and the main shader's light loop), written from those
//! shaders and not from zline's code. The truth supplies each sample's
//! geometry — eye-space point, normal after the normal map, view vector,
//! base colour (factor ⊙ texel ⊙ COLOR_0), metallic and roughness after
//! their texture — through `render_truth_shaded`; the transcription
//! replaces only the lighting. Two directional lights and a point light
//! with a `range` (`getRangeAttenuation`: the window over d², placed at
//! least 1.5 from every surface, where zline's clamp of 1/d² to 1 (SPEC §5)
//! never acts), no environment
//! (ambient 0), no emission in these models, linear output (no tone
//! mapping, no sRGB encoding; texels as stored, SPEC §7). Pixels within one
//! pixel of a triangle edge (the truth's `boundary_distance`) are left
//! out, as in `versus_fast`: there the fast renderer's 1/256-pixel vertex
//! snap decides coverage.

use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use zline_pipeline::{render, RenderOptions};
use zline_scene::Scene;
use zline_shading::{Attenuation, Light};
use zline_truth::{render_truth_shaded, SampleShading, TruthOptions};

/// A KHR_lights_punctual light in eye space, as the Sample Viewer's light
/// loop takes it.
enum ViewerLight {
    /// Unit vector towards the light, intensity × colour.
    Directional(DVec3, DVec3),
    /// Position, intensity × colour, range.
    Point(DVec3, DVec3, f64),
}

/// `punctual.glsl`'s `getRangeAttenuation`: unlimited for range ≤ 0.
fn range_attenuation(range: f64, distance: f64) -> f64 {
    if range <= 0.0 {
        return 1.0 / distance.powi(2);
    }
    (1.0 - (distance / range).powi(4)).clamp(0.0, 1.0) / distance.powi(2)
}

/// The Sample Viewer's punctual lighting at one sample.
fn sample_viewer(s: &SampleShading, lights: &[ViewerLight]) -> DVec3 {
    let Some((metallic, roughness)) = s.metallic_roughness else { return DVec3::ZERO };
    let clamped_dot = |a: DVec3, b: DVec3| a.dot(b).clamp(0.0, 1.0);
    // mix(x, y, a) = x·(1 − a) + y·a, as GLSL defines it.
    let mix = |x: DVec3, y: DVec3, a: f64| x * (1.0 - a) + y * a;
    let c_diff = mix(s.base, DVec3::ZERO, metallic);
    let f0 = mix(DVec3::splat(0.04), s.base, metallic);
    let f90 = DVec3::ONE;
    let alpha_roughness = roughness * roughness;
    let (n, v) = (s.normal, s.view);
    let mut color = DVec3::ZERO;
    for light in lights {
        let (l, intensity) = match *light {
            ViewerLight::Directional(l, intensity) => (l, intensity),
            ViewerLight::Point(position, color, range) => {
                let point_to_light = position - s.point;
                let distance = point_to_light.length();
                (point_to_light / distance, color * range_attenuation(range, distance))
            }
        };
        let h = (l + v).normalize_or_zero();
        let (n_dot_l, n_dot_v) = (clamped_dot(n, l), clamped_dot(n, v));
        let (n_dot_h, v_dot_h) = (clamped_dot(n, h), clamped_dot(v, h));
        if n_dot_l > 0.0 || n_dot_v > 0.0 {
            // F_Schlick(f0, f90, VdotH)
            let f = f0 + (f90 - f0) * (1.0 - v_dot_h).clamp(0.0, 1.0).powi(5);
            // V_GGX(NdotL, NdotV, alphaRoughness)
            let a2 = alpha_roughness * alpha_roughness;
            let ggxv = n_dot_l * (n_dot_v * n_dot_v * (1.0 - a2) + a2).sqrt();
            let ggxl = n_dot_v * (n_dot_l * n_dot_l * (1.0 - a2) + a2).sqrt();
            let ggx = ggxv + ggxl;
            let vis = if ggx > 0.0 { 0.5 / ggx } else { 0.0 };
            // D_GGX(NdotH, alphaRoughness)
            let d_f = (n_dot_h * n_dot_h) * (a2 - 1.0) + 1.0;
            let d = a2 / (std::f64::consts::PI * d_f * d_f);
            // BRDF_lambertian and BRDF_specularGGX (specularWeight 1)
            let diffuse = (DVec3::ONE - f) * (c_diff / std::f64::consts::PI);
            let specular = f * vis * d;
            color += intensity * n_dot_l * (diffuse + specular);
        }
    }
    color + s.emission
}

fn shared(model: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/assets/gltf").join(model)
}

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(path)
}

/// (pixels compared, pixels within one step in every channel, the
/// largest difference) of zline against the transcription on the model at
/// `path`, 400 × 400, two directional lights and a ranged point light, no environment: the pixels
/// the model covers, more than a pixel from every triangle edge.
fn compare(path: &Path) -> (usize, usize, u8) {
    let gltf = zline_io::load_gltf(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let settings = zline_scene::RenderSettings { width: 400, height: 400, ..Default::default() };
    let mut scene: Scene = zline_io::scene_for_gltf(gltf, settings);
    scene.ambient = Vec3::ZERO;
    // A background no lit pixel of these models has: its pixels are left out.
    scene.background = Vec3::new(1.0, 0.0, 1.0);
    // The point light 1.5 beyond the model's bounding sphere, its range
    // reaching 1.5 past the far side, its colour scaled to its distance.
    let (lo, hi) = scene.objects.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), o| {
        o.mesh
            .positions
            .iter()
            .map(|&p| o.world_from_object.transform_point3(p))
            .fold((lo, hi), |(a, b), p| (a.min(p), b.max(p)))
    });
    let (centre, radius) = ((lo + hi) * 0.5, (hi - lo).length() * 0.5);
    let distance = radius + 1.5;
    let position = centre + Vec3::new(0.4, 0.8, 0.6).normalize() * distance;
    scene.lights = vec![
        Light::Directional { direction: Vec3::new(-0.5, -0.7, -1.0), color: Vec3::new(1.6, 1.5, 1.4) },
        Light::Directional { direction: Vec3::new(0.8, -0.2, -0.4), color: Vec3::new(0.5, 0.6, 0.9) },
        Light::Point {
            position,
            color: Vec3::new(0.9, 0.8, 1.2) * distance * distance,
            attenuation: Attenuation::new(0.0, 0.0, 1.0).with_range(distance + radius + 1.5),
        },
    ];
    let eye_from_world = scene.camera.eye_from_world().as_dmat4();
    let lights: Vec<ViewerLight> = scene
        .lights
        .iter()
        .map(|l| match *l {
            Light::Directional { direction, color } => ViewerLight::Directional(
                -eye_from_world.transform_vector3(direction.as_dvec3()).normalize(),
                color.as_dvec3(),
            ),
            Light::Point { position, color, attenuation } => ViewerLight::Point(
                eye_from_world.transform_point3(position.as_dvec3()),
                color.as_dvec3(),
                f64::from(attenuation.range),
            ),
            Light::Spot { .. } => unreachable!("no spot lights here"),
        })
        .collect();
    let options = TruthOptions { diagnostics: true, ..Default::default() };
    let reference = render_truth_shaded(&scene, &options, &|s| sample_viewer(s, &lights));
    let want = reference.quantized_rgb8();
    let got = render(&scene, &RenderOptions::default()).0.to_rgb();
    let diagnostics = reference.diagnostics.as_ref().expect("diagnostics were asked for");
    let (mut compared, mut within, mut worst) = (0, 0, 0u8);
    for (i, &d) in diagnostics.boundary_distance.iter().enumerate() {
        if d < 1.0 || want[3 * i..3 * i + 3] == [255, 0, 255] {
            continue;
        }
        compared += 1;
        let diff = (0..3).map(|k| got[3 * i + k].abs_diff(want[3 * i + k])).max().unwrap_or(0);
        worst = worst.max(diff);
        within += usize::from(diff <= 1);
    }
    (compared, within, worst)
}

#[test]
fn zline_is_within_one_step_of_the_sample_viewer_on_gltf_models() {
    let mut models = vec![("Box", repo("assets/gltf/Box/glTF-Binary/Box.glb"))];
    for name in ["Avocado", "Suzanne", "FlightHelmet"] {
        let path = shared(&format!("{name}/glTF/{name}.gltf"));
        if path.exists() {
            models.push((name, path));
        } else {
            eprintln!("note: {} is missing; skipped (the shared assets are not in a clone)", path.display());
        }
    }
    for (name, path) in models {
        let (compared, within, worst) = compare(&path);
        let share = within as f64 / compared as f64;
        eprintln!(
            "{name}: {within} of {compared} pixels within one step ({:.3} %), largest difference {worst}",
            100.0 * share
        );
        assert!(compared > 200, "{name}: only {compared} pixels compared");
        assert!(share >= 0.999, "{name}: {:.3} % within one step, largest difference {worst}", 100.0 * share);
    }
}
