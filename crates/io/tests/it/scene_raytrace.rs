//! `[render] renderer` and the `[raytrace]` table (SPEC §12).

use zline_scene::trace_options::{AccelKind, Adaptive, Renderer, ShadowRays, TraceOptions};

use crate::scene_file::{check_scene_error, load_scene, OBJECT};
use crate::temp_file;

fn settings(name: &str, text: &str) -> zline_scene::RenderSettings {
    load_scene(&temp_file(name, &format!("{text}\n{OBJECT}"))).unwrap_or_else(|e| panic!("{e}")).settings
}

#[test]
fn the_renderer_and_the_ray_tracers_options_are_read_as_written() {
    let s = settings("none.toml", "");
    assert_eq!((s.renderer, s.trace), (Renderer::Raster, TraceOptions::DEFAULT));
    let s = settings(
        "all.toml",
        "[render]\nrenderer = \"raytrace\"\n[raytrace]\ndepth = 3\nmin_weight = 0.25\n\
         shadow_rays = \"opaque\"\naccel = \"none\"\nrays_per_axis = 4",
    );
    assert_eq!(s.renderer, Renderer::RayTrace);
    let want = TraceOptions {
        max_depth: 3,
        min_weight: 0.25,
        shadows: ShadowRays::Opaque,
        accel: AccelKind::None,
        samples: 4,
        adaptive: None,
    };
    assert_eq!(s.trace, want);
    let s = settings("adaptive.toml", "[raytrace]\nadaptive_depth = 2");
    assert_eq!(s.trace.adaptive, Some(Adaptive { depth: 2, threshold: Adaptive::default().threshold }));
    let s = settings("on.toml", "[raytrace]\nadaptive = true\nadaptive_threshold = 0.5");
    assert_eq!(s.trace.adaptive, Some(Adaptive { depth: Adaptive::default().depth, threshold: 0.5 }));
    let s = settings("off.toml", "[raytrace]\nadaptive = false\nadaptive_depth = 2");
    assert_eq!(s.trace.adaptive, None);
    assert_eq!(settings("raster.toml", "[render]\nrenderer = \"raster\"").renderer, Renderer::Raster);
    assert_eq!(settings("rad.toml", "[render]\nrenderer = \"radiosity\"").renderer, Renderer::Radiosity);
}

#[test]
fn bad_ray_tracing_settings_name_their_key() {
    let rt = |body: &str| format!("[raytrace]\n{body}\n{OBJECT}");
    check_scene_error(
        "d0.toml",
        &rt("depth = 0"),
        &["line 2, column 9: raytrace.depth: must be in 1..=64, got 0"],
    );
    check_scene_error("dbig.toml", &rt("depth = 1000000000"), &["raytrace.depth", "1..=64", "1000000000"]);
    check_scene_error("w.toml", &rt("min_weight = -1"), &["raytrace.min_weight", "[0, 1]"]);
    check_scene_error("wnan.toml", &rt("min_weight = nan"), &["raytrace.min_weight", "finite"]);
    check_scene_error("n.toml", &rt("rays_per_axis = 17"), &["raytrace.rays_per_axis", "1..=16"]);
    check_scene_error("ad.toml", &rt("adaptive_depth = 5"), &["raytrace.adaptive_depth", "0..=4"]);
    check_scene_error("at.toml", &rt("adaptive_threshold = 2"), &["raytrace.adaptive_threshold", "[0, 1]"]);
    check_scene_error(
        "both.toml",
        &rt("rays_per_axis = 4\nadaptive = true"),
        &["raytrace.rays_per_axis", "two ways to anti-alias"],
    );
    check_scene_error("acc.toml", &rt("accel = \"octree\""), &["line 2", "unknown variant `octree`"]);
    check_scene_error("key.toml", &rt("dpeth = 3"), &["unknown field `dpeth`"]);
    check_scene_error(
        "r.toml",
        &format!("[render]\nrenderer = \"pathtracer\"\n{OBJECT}"),
        &["unknown variant `pathtracer`, expected one of `raster`, `raytrace`, `radiosity`"],
    );
}
