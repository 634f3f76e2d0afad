//! Scene files: good files give the scene they describe; every bad value
//! gives an error naming the file, the line and column, the key and the
//! value.

use std::sync::Arc;

use glam::{Vec3, Vec4};
use zline_io::{default_lights, load_scene_with_options, LoadOptions, SceneError, DEFAULT_AMBIENT};
use zline_scene::{
    Attenuation, DepthMode, FogCoordinate, FogMode, GouraudClamp, Interpolation, Light, LightingSides,
    Projection, RenderSettings, Scene, ShadingMode, ShadowMode, Shadows, DEFAULT_SHADOW_MAP_SIZE,
    MAX_SHADOW_MAP_SIZE,
};

use crate::{check_message, data, repo, temp_file};

/// Loads a scene that may name models anywhere: these scenes are written
/// to temporary folders and name the fixtures by absolute paths (the
/// confinement to the scene's folder is tested in `safety`).
fn load_scene(path: &std::path::Path) -> Result<Scene, SceneError> {
    load_scene_with_options(path, LoadOptions { allow_outside: true })
}

/// A minimal valid scene body to which tests add or in which they replace.
const OBJECT: &str = "[[objects]]\nprimitive = \"cube\"\n";

#[track_caller]
fn check_scene_error(name: &str, text: &str, parts: &[&str]) {
    let path = temp_file(name, text);
    let e = load_scene(&path).expect_err("the scene must not load").to_string();
    check_message(&e, &[&[name][..], parts].concat());
}

#[test]
fn a_full_scene_is_read_as_written() {
    let model = data("two.obj");
    let text = format!(
        r#"background = [0.1, 0.2, 0.3]
ambient = [0.05, 0.05, 0.05]
[render]
width = 320
height = 200
shading = "gouraud"
interpolation = "linear"
[camera]
eye = [0, 1, 5]
target = [0, 1, 0]
fovy = 50
near = 0.5
far = 50
[[lights]]
type = "point"
position = [2, 3, 4]
color = [1, 0.9, 0.8]
attenuation = [1.0, 0.05, 0.01]
[[lights]]
type = "directional"
direction = [-1, -1, -1]
[[objects]]
model = {model:?}
translate = [1, 2, 3]
rotate = [0, 90, 0]
scale = [2, 2, 2]
shading = "flat"
[objects.material]
kd = [0.2, 0.3, 0.4]
ke = [0.0, 0.25, 0.5]
opacity = 0.5
[[objects]]
model = {model:?}
cull_back_faces = true
[[objects]]
primitive = "sphere"
rings = 4
segments = 6
radius = 2
"#
    );
    let scene = load_scene(&temp_file("full.toml", &text)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((scene.background, scene.ambient), (Vec3::new(0.1, 0.2, 0.3), Vec3::splat(0.05)));
    assert_eq!((scene.settings.width, scene.settings.height), (320, 200));
    assert_eq!(scene.settings.shading, ShadingMode::Gouraud);
    assert_eq!(scene.settings.interpolation, Interpolation::ScreenLinear);
    assert_eq!(
        (scene.camera.eye, scene.camera.target, scene.camera.up),
        (Vec3::new(0.0, 1.0, 5.0), Vec3::Y, Vec3::Y)
    );
    assert_eq!(scene.camera.projection, Projection::Perspective { fovy_degrees: 50.0, near: 0.5, far: 50.0 });
    assert_eq!(
        scene.lights,
        [
            Light::Point {
                position: Vec3::new(2.0, 3.0, 4.0),
                color: Vec3::new(1.0, 0.9, 0.8),
                attenuation: Attenuation { a0: 1.0, a1: 0.05, a2: 0.01 }
            },
            Light::Directional { direction: Vec3::splat(-1.0), color: Vec3::ONE },
        ]
    );
    // two.obj has two meshes: both objects get both, sharing the loaded meshes.
    assert_eq!(scene.objects.len(), 5);
    let (a, b) = (&scene.objects[0], &scene.objects[2]);
    assert!(Arc::ptr_eq(&a.mesh, &b.mesh), "a model file is loaded once");
    assert_eq!(a.shading, Some(ShadingMode::Flat));
    assert!(!a.cull_back_faces, "open and transparent: not culled by default");
    assert!(scene.objects[2].cull_back_faces, "explicitly culled");
    // The override keeps the mesh's other coefficients.
    let m = a.material.unwrap();
    assert_eq!(
        (m.kd, m.opacity, m.ka, m.ns, m.ke),
        (Vec3::new(0.2, 0.3, 0.4), 0.5, Vec3::new(0.1, 0.0, 0.0), 50.0, Vec3::new(0.0, 0.25, 0.5))
    );
    // Scale 2, then 90° about y (x → −z), then translate.
    let p = a.world_from_object.transform_point3(Vec3::X);
    assert!((p - Vec3::new(1.0, 2.0, 1.0)).length() < 1e-5, "{p}");
    let sphere = &scene.objects[4];
    assert_eq!((sphere.mesh.name.as_str(), sphere.mesh.triangle_count()), ("sphere", 36));
    assert!(sphere.cull_back_faces);
}

#[test]
fn gltf_models_keep_their_node_transforms_and_double_sided_materials() {
    let cube = repo("assets/gltf/Box/glTF-Binary/Box.glb");
    let quads = repo("assets/gltf/TextureCoordinateTest/glTF/TextureCoordinateTest.gltf");
    let text = format!(
        "[[objects]]\nmodel = {cube:?}\ntranslate = [5, 0, 0]\n[[objects]]\nmodel = {quads:?}\n\
         [[objects]]\nmodel = {cube:?}\n[objects.material]\nopacity = 0.5\n"
    );
    let scene = load_scene(&temp_file("gltf.toml", &text)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.objects.len(), 1 + 5 + 1);
    let (cube, glass) = (&scene.objects[0], &scene.objects[6]);
    // The file's root node turns y into −z; the object's translation follows.
    let p = cube.world_from_object.transform_point3(Vec3::Y);
    assert!((p - Vec3::new(5.0, 0.0, -1.0)).length() < 1e-5, "{p}");
    assert!(cube.cull_back_faces, "closed, opaque, single-sided");
    assert!(scene.objects[1..6].iter().all(|o| !o.cull_back_faces), "double-sided materials");
    assert!(!glass.cull_back_faces, "made transparent by the override");
    assert!(Arc::ptr_eq(&cube.mesh, &glass.mesh), "a model file is loaded once");
}

#[test]
fn without_camera_and_lights_the_scene_is_framed_and_lit() {
    let text = format!("{OBJECT}translate = [10, 0, 0]\n");
    let scene = load_scene(&temp_file("framed.toml", &text)).unwrap();
    // Framed tightly along the framing direction, looking into the
    // object's box around (10, 0, 0).
    let view = (scene.camera.eye - scene.camera.target).normalize();
    assert!((view - zline_io::VIEW_DIRECTION.normalize()).length() < 1e-5, "{view}");
    assert!(
        (scene.camera.target - Vec3::new(10.0, 0.0, 0.0)).abs().max_element() < 1.0,
        "{}",
        scene.camera.target
    );
    assert!(matches!(scene.camera.projection, Projection::Perspective { .. }));
    assert_eq!(scene.lights, default_lights());
    assert_eq!(scene.ambient, DEFAULT_AMBIENT);
    let dark = load_scene(&temp_file("dark.toml", &format!("lights = []\n{OBJECT}"))).unwrap();
    assert!(dark.lights.is_empty());
}

#[test]
fn default_near_and_far_hug_the_scene() {
    let text = format!("[camera]\neye = [0, 0, 10]\n{OBJECT}size = 2\n");
    let scene = load_scene(&temp_file("fitted.toml", &text)).unwrap();
    let Projection::Perspective { near, far, .. } = scene.camera.projection else { panic!() };
    // The cube's bounding sphere has radius √3 around the origin.
    let r = 3f32.sqrt() * 1.1;
    assert!((near - (10.0 - r)).abs() < 1e-4 && (far - (10.0 + r)).abs() < 1e-4, "{near} {far}");
    let text = format!("[camera]\neye = [0, 0, 10]\nprojection = \"orthographic\"\n{OBJECT}");
    let scene = load_scene(&temp_file("ortho.toml", &text)).unwrap();
    assert!(matches!(scene.camera.projection, Projection::Orthographic { height, .. } if height > 1.0));
}

#[test]
fn unknown_keys_are_located_and_the_expected_ones_listed() {
    check_scene_error(
        "colour.toml",
        &format!("{OBJECT}[objects.material]\n\ncolour = [1, 0, 0]\n"),
        &["line 5, column 1: unknown field `colour`, expected one of `color`"],
    );
    check_scene_error(
        "top.toml",
        &format!("backgroud = [0, 0, 0]\n{OBJECT}"),
        &["line 1, column 1", "backgroud"],
    );
}

#[test]
fn syntax_errors_are_located() {
    check_scene_error("syntax.toml", "background = [0, 0\n", &["line 2, column 1: invalid array"]);
    check_scene_error(
        "enum.toml",
        &format!("[render]\nshading = \"smooth\"\n{OBJECT}"),
        &["line 2, column 11", "unknown variant `smooth`, expected one of `flat`, `gouraud`, `phong`"],
    );
    check_scene_error("int.toml", &format!("[render]\nwidth = -5\n{OBJECT}"), &["line 2, column 9", "-5"]);
    check_scene_error(
        "scale.toml",
        &format!("{OBJECT}scale = \"big\"\n"),
        &["line 3, column 9", "a number or an array of 3 numbers"],
    );
}

#[test]
fn bad_camera_values_name_the_key_and_value() {
    let camera = |rest: &str| format!("[camera]\neye = [0, 0, 5]\n{rest}\n{OBJECT}");
    check_scene_error("near.toml", &camera("near = -1"), &["line 3, column 8: camera.near: must be > 0"]);
    check_scene_error(
        "far.toml",
        &camera("near = 2\nfar = 1"),
        &["line 4, column 7: camera.far: must be greater than camera.near (2), got 1"],
    );
    check_scene_error("fovy.toml", &camera("fovy = 180"), &["camera.fovy: must be in (0, 180)"]);
    check_scene_error(
        "nan.toml",
        &camera("target = [0, nan, 0]"),
        &["line 3, column 10: camera.target: must be finite"],
    );
    check_scene_error("up.toml", &camera("up = [0, 0, 2]"), &["camera.up: must not be parallel"]);
    check_scene_error("same.toml", &camera("target = [0, 0, 5]"), &["camera.eye: must differ"]);
    check_scene_error("noeye.toml", &format!("[camera]\nfovy = 30\n{OBJECT}"), &["missing field `eye`"]);
}

#[test]
fn bad_render_settings_are_rejected() {
    check_scene_error(
        "w0.toml",
        &format!("[render]\nwidth = 0\n{OBJECT}"),
        &["line 2, column 9: render.width: must be in 1..=16384, got 0"],
    );
    check_scene_error("h.toml", &format!("[render]\nheight = 20000\n{OBJECT}"), &["render.height", "20000"]);
    check_scene_error(
        "bg.toml",
        &format!("background = [2, 0, 0]\n{OBJECT}"),
        &["background: every component must be in [0, 1], got [2.0, 0.0, 0.0]"],
    );
    check_scene_error("amb.toml", &format!("ambient = [0, -1, 0]\n{OBJECT}"), &["ambient", "[0, ∞)"]);
}

#[test]
fn area_lights_become_their_samples() {
    let text = format!(
        "[[lights]]\ntype = \"rect\"\nposition = [0, 3, 0]\nu = [1, 0, 0]\nv = [0, 0, 0.5]\nsamples = 2\n\
         color = [0.8, 0.4, 1.6]\nattenuation = [1, 0.5, 0]\n\
         [[lights]]\ntype = \"disc\"\nposition = [0, 2, 0]\nnormal = [0, -1, 0]\nradius = 0.5\n{OBJECT}"
    );
    let scene = load_scene(&temp_file("area.toml", &text)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.lights.len(), 4 + 16, "2 × 2 rect samples and the disc's default 4 × 4");
    let attenuation = Attenuation { a0: 1.0, a1: 0.5, a2: 0.0 };
    let color = Vec3::new(0.2, 0.1, 0.4);
    for (light, (x, z)) in scene.lights.iter().zip([(-0.5, -0.25), (0.5, -0.25), (-0.5, 0.25), (0.5, 0.25)]) {
        assert_eq!(*light, Light::Point { position: Vec3::new(x, 3.0, z), color, attenuation });
    }
    for light in &scene.lights[4..] {
        let Light::Point { position, color, .. } = *light else { panic!("{light:?}") };
        let off_centre = Vec3::new(position.x, 0.0, position.z).length();
        assert!((position.y - 2.0).abs() < 1e-6 && off_centre <= 0.5 + 1e-6, "{position}");
        assert_eq!(color, Vec3::splat(1.0 / 16.0));
    }
}

#[test]
fn bad_area_lights_are_rejected() {
    let light = |body: &str| format!("[[lights]]\n{body}\n{OBJECT}");
    let rect = "type = \"rect\"\nposition = [0, 3, 0]\nu = [1, 0, 0]\nv = [0, 0, 1]";
    check_scene_error(
        "nov.toml",
        &light("type = \"rect\"\nposition = [0, 3, 0]\nu = [1, 0, 0]"),
        &["lights[0]: a rect light needs 'v'"],
    );
    check_scene_error(
        "zerou.toml",
        &light("type = \"rect\"\nposition = [0, 3, 0]\nu = [0, 0, 0]\nv = [0, 0, 1]"),
        &["lights[0].u: must not be [0, 0, 0]"],
    );
    check_scene_error(
        "samples0.toml",
        &light(&format!("{rect}\nsamples = 0")),
        &["lights[0].samples: must be \"auto\" or in 1..=16"],
    );
    check_scene_error(
        "samples17.toml",
        &light(&format!("{rect}\nsamples = 17")),
        &["lights[0].samples: must be \"auto\" or in 1..=16"],
    );
    check_scene_error(
        "noradius.toml",
        &light("type = \"disc\"\nposition = [0, 3, 0]\nnormal = [0, 1, 0]"),
        &["a disc light needs 'radius' > 0"],
    );
    check_scene_error(
        "pointu.toml",
        &light("type = \"point\"\nposition = [0, 3, 0]\nu = [1, 0, 0]"),
        &["lights[0].u: applies to rect and disc lights only"],
    );
    check_scene_error(
        "dirsamples.toml",
        &light("type = \"directional\"\ndirection = [0, -1, 0]\nsamples = 3"),
        &["lights[0].samples: applies to rect and disc lights only"],
    );
    check_scene_error(
        "sampleword.toml",
        &light(&format!("{rect}\nsamples = \"many\"")),
        &["lights[0].samples: must be \"auto\" or in 1..=16", "\"many\""],
    );
    check_scene_error(
        "tolfixed.toml",
        &light(&format!("{rect}\nsamples = 3\ntolerance = 2")),
        &["lights[0].tolerance: applies with samples = \"auto\" only"],
    );
    check_scene_error(
        "tolneg.toml",
        &light(&format!("{rect}\nsamples = \"auto\"\ntolerance = -1")),
        &["lights[0].tolerance: must be in 0..=255"],
    );
    check_scene_error(
        "tolpoint.toml",
        &light("type = \"point\"\nposition = [0, 3, 0]\ntolerance = 1"),
        &["lights[0].tolerance: applies to rect and disc lights only"],
    );
}

/// The repository's area-light scene with `samples = "auto"` and a
/// tolerance, its shadow mode replaced: the number of point lights it
/// becomes.
fn auto_samples(tolerance: f32, shadows: &str) -> usize {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/shadows_area.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let text = text
        .replace("samples = 4", &format!("samples = \"auto\"\ntolerance = {tolerance}"))
        .replace("shadows = \"planar\"", &format!("shadows = \"{shadows}\""));
    let scene = load_scene(&temp_file(&format!("auto-{tolerance}-{shadows}.toml"), &text)).unwrap();
    scene.lights.len()
}

#[test]
fn automatic_area_samples_model_what_the_scene_shows() {
    let count = |t, s| auto_samples(t, s);
    // Without shadows the light's diffuse term varies smoothly over the
    // floor, 2.4 units under a 1.2-unit square: one sample is within half
    // a step of 16 × 16.
    assert_eq!((count(4.0, "none"), count(0.5, "none")), (1, 1));
    // Penumbrae need more: the tighter the tolerance, the more samples.
    let (loose, tight) = (count(4.0, "planar"), count(0.5, "planar"));
    assert!(loose > 1 && loose < tight, "{loose} {tight}");
    // Half a step is out of reach of planar shadows' 32 bits: the choice
    // stops at 5 × 5 (with a warning) and every sample keeps its shadow.
    assert_eq!(tight, 25);
    let (loose_map, tight_map) = (count(4.0, "map"), count(0.5, "map"));
    assert!(loose_map > 1 && loose_map < tight_map && tight_map > 25, "{loose_map} {tight_map}");
}

fn settings_of(name: &str, render: &str) -> RenderSettings {
    let text = format!("[render]\n{render}\n{OBJECT}");
    load_scene(&temp_file(name, &text)).unwrap_or_else(|e| panic!("{e}")).settings
}

#[test]
fn supersampling_depth_and_adaptive_are_read_as_written() {
    let s = settings_of("all.toml", "ssaa = 4\ndepth = \"reversed\"\nadaptive = 0.5");
    assert_eq!((s.ssaa, s.depth, s.adaptive_tolerance), (4, DepthMode::ReversedFloat, Some(0.5)));
    let s = settings_of("none.toml", "width = 64");
    assert_eq!((s.ssaa, s.depth, s.adaptive_tolerance), (1, DepthMode::Normalized, None));
    for mode in [DepthMode::Normalized, DepthMode::ReversedFloat] {
        let s = settings_of("depth.toml", &format!("depth = {:?}", mode.name()));
        assert_eq!(s.depth, mode, "the scene-file name is DepthMode::name");
    }
    for (text, ssaa) in [("ssaa = 1", 1), ("ssaa = 8", 8)] {
        assert_eq!(settings_of("ssaa.toml", text).ssaa, ssaa);
    }
    for (text, tolerance) in [("adaptive = 0", 0.0), ("adaptive = 255", 255.0), ("adaptive = 2", 2.0)] {
        assert_eq!(settings_of("adaptive.toml", text).adaptive_tolerance, Some(tolerance));
    }
}

#[test]
fn bad_supersampling_depth_and_adaptive_are_rejected() {
    let render = |body: &str| format!("[render]\n{body}\n{OBJECT}");
    check_scene_error(
        "ssaa0.toml",
        &render("ssaa = 0"),
        &["line 2, column 8: render.ssaa: must be in 1..=8, got 0"],
    );
    check_scene_error("ssaa9.toml", &render("ssaa = 9"), &["line 2, column 8: render.ssaa", "got 9"]);
    check_scene_error("ssaaneg.toml", &render("ssaa = -2"), &["line 2, column 8", "-2"]);
    check_scene_error("ssaaf.toml", &render("ssaa = 2.5"), &["line 2, column 8", "2.5"]);
    check_scene_error(
        "depth.toml",
        &render("depth = \"inverted\""),
        &["line 2, column 9", "unknown variant `inverted`, expected `normalized` or `reversed`"],
    );
    check_scene_error(
        "adaptneg.toml",
        &render("adaptive = -1"),
        &["line 2, column 12: render.adaptive: must be in [0, 255], got -1"],
    );
    check_scene_error(
        "adaptbig.toml",
        &render("adaptive = 255.5"),
        &["render.adaptive: must be in [0, 255], got 255.5"],
    );
    check_scene_error(
        "adaptnan.toml",
        &render("adaptive = nan"),
        &["line 2, column 12: render.adaptive: must be finite, got NaN"],
    );
    check_scene_error("adaptinf.toml", &render("adaptive = inf"), &["render.adaptive: must be finite"]);
    check_scene_error("adaptstr.toml", &render("adaptive = \"low\""), &["line 2, column 12", "string"]);
}

#[test]
fn gouraud_clamp_and_lighting_sides_are_read_as_written() {
    let s = settings_of("conv.toml", "gouraud_clamp = \"sample\"\nlighting = \"one-sided\"");
    assert_eq!((s.gouraud_clamp, s.lighting_sides), (GouraudClamp::PerSample, LightingSides::OneSided));
    let s = settings_of("noconv.toml", "width = 64");
    assert_eq!((s.gouraud_clamp, s.lighting_sides), (GouraudClamp::PerVertex, LightingSides::TwoSided));
    for clamp in [GouraudClamp::PerVertex, GouraudClamp::PerSample] {
        let s = settings_of("clamp.toml", &format!("gouraud_clamp = {:?}", clamp.name()));
        assert_eq!(s.gouraud_clamp, clamp, "the scene-file name is GouraudClamp::name");
    }
    for sides in [LightingSides::TwoSided, LightingSides::OneSided] {
        let s = settings_of("sides.toml", &format!("lighting = {:?}", sides.name()));
        assert_eq!(s.lighting_sides, sides, "the scene-file name is LightingSides::name");
    }
}

#[test]
fn bad_gouraud_clamp_and_lighting_sides_are_rejected() {
    let render = |body: &str| format!("[render]\n{body}\n{OBJECT}");
    check_scene_error(
        "clamp.toml",
        &render("gouraud_clamp = \"pixel\""),
        &["line 2, column 17", "unknown variant `pixel`, expected `vertex` or `sample`"],
    );
    check_scene_error(
        "sides.toml",
        &render("lighting = \"two_sided\""),
        &["line 2, column 12", "unknown variant `two_sided`, expected `two-sided` or `one-sided`"],
    );
    check_scene_error("clampnum.toml", &render("gouraud_clamp = 1"), &["line 2, column 17", "wanted string"]);
}

#[test]
fn bad_lights_are_rejected() {
    let light = |body: &str| format!("[[lights]]\n{body}\n{OBJECT}");
    check_scene_error(
        "nopos.toml",
        &light("type = \"point\""),
        &["lights[0]: a point light needs 'position'"],
    );
    check_scene_error(
        "nodir.toml",
        &light("type = \"directional\"\ncolor = [1, 1, 1]"),
        &["needs 'direction'"],
    );
    check_scene_error(
        "zerodir.toml",
        &light("type = \"directional\"\ndirection = [0, 0, 0]"),
        &["line 3, column 13: lights[0].direction: must not be [0, 0, 0]"],
    );
    check_scene_error(
        "both.toml",
        &light("type = \"point\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]"),
        &["line 4, column 13: lights[0].direction: does not apply to point lights"],
    );
    check_scene_error(
        "att.toml",
        &light("type = \"point\"\nposition = [0, 1, 0]\nattenuation = [1, -1, 0]"),
        &["lights[0].attenuation"],
    );
    check_scene_error("kind.toml", &light("type = \"spot\""), &["unknown variant `spot`"]);
}

#[test]
fn bad_objects_are_rejected() {
    check_scene_error("none.toml", "background = [0, 0, 0]\n", &["no [[objects]]"]);
    check_scene_error(
        "neither.toml",
        "[[objects]]\ntranslate = [0, 0, 0]\n",
        &["objects[0]: needs 'model' or 'primitive'"],
    );
    check_scene_error("both.toml", "[[objects]]\nmodel = \"a.obj\"\nprimitive = \"cube\"\n", &["not both"]);
    check_scene_error(
        "rings.toml",
        &format!("{OBJECT}rings = 8\n"),
        &["line 3, column 9: objects[0].rings: does not apply to cubes"],
    );
    check_scene_error(
        "size.toml",
        "[[objects]]\nprimitive = \"sphere\"\nsize = 2\n",
        &["objects[0].size: does not apply to spheres"],
    );
    check_scene_error(
        "seg.toml",
        "[[objects]]\nprimitive = \"sphere\"\nsegments = 2\n",
        &["objects[0].segments: must be in 3..=4096, got 2"],
    );
    check_scene_error(
        "radius.toml",
        "[[objects]]\nprimitive = \"sphere\"\nradius = 0\n",
        &["must be > 0, got 0"],
    );
    check_scene_error(
        "zero.toml",
        &format!("{OBJECT}scale = [1, 0, 1]\n"),
        &["objects[0].scale: must be finite and non-zero"],
    );
    check_scene_error(
        "kd.toml",
        &format!("{OBJECT}[objects.material]\nkd = [0.5, 1.5, 0]\n"),
        &["line 4, column 6: objects[0].material.kd: every component must be in [0, 1]"],
    );
    check_scene_error("prim.toml", "[[objects]]\nprimitive = \"cone\"\n", &["unknown variant `cone`"]);
}

#[test]
fn model_errors_name_the_scene_and_the_model() {
    check_scene_error(
        "missing.toml",
        "[[objects]]\nprimitive = \"cube\"\n[[objects]]\nmodel = \"models/missing.obj\"\n",
        &["line 4, column 9: objects[1].model:", "models/missing.obj: cannot read file"],
    );
    let bad = data("nan.obj");
    check_scene_error(
        "badmodel.toml",
        &format!("[[objects]]\nmodel = {bad:?}\n"),
        &["objects[0].model", "nan.obj: line 3: vertex has non-finite coordinate 'nan'"],
    );
}

#[test]
fn a_missing_scene_file_is_named() {
    let e = load_scene(&data("no_such_scene.toml")).unwrap_err().to_string();
    check_message(&e, &["no_such_scene.toml: cannot read file"]);
}

#[test]
fn fog_is_read_as_written() {
    let text = format!(
        "[fog]\nmode = \"linear\"\nstart = 10\nend = 30\ncolor = [0.7, 0.75, 0.8]\ncoordinate = \"radial\"\n{OBJECT}"
    );
    let scene = load_scene(&temp_file("fog.toml", &text)).expect("loads");
    let fog = scene.fog.expect("fog");
    assert_eq!(fog.mode, FogMode::Linear { start: 10.0, end: 30.0 });
    assert_eq!(fog.color, Vec3::new(0.7, 0.75, 0.8));
    assert_eq!(fog.coordinate, FogCoordinate::Radial);
    let exp2 =
        load_scene(&temp_file("exp2.toml", &format!("[fog]\nmode = \"exp2\"\ndensity = 0.02\n{OBJECT}")))
            .expect("loads")
            .fog
            .expect("fog");
    assert_eq!(exp2.mode, FogMode::SquaredExponential { density: 0.02 });
    assert_eq!(exp2.coordinate, FogCoordinate::EyePlane);
    let none = load_scene(&temp_file("nofog.toml", OBJECT)).expect("loads");
    assert_eq!(none.fog, None);
}

#[test]
fn bad_fog_is_rejected() {
    let fog = |body: &str| format!("[fog]\n{body}\n{OBJECT}");
    check_scene_error(
        "order.toml",
        &fog("mode = \"linear\"\nstart = 5\nend = 2"),
        &["line 4", "fog.end: must be ≥ start"],
    );
    check_scene_error(
        "dens.toml",
        &fog("mode = \"linear\"\ndensity = 1"),
        &["fog.density: does not apply to linear fog"],
    );
    check_scene_error("neg.toml", &fog("mode = \"exp\"\ndensity = -1"), &["fog.density"]);
    check_scene_error("mode.toml", &fog("mode = \"fuzzy\""), &["unknown variant `fuzzy`"]);
    check_scene_error("col.toml", &fog("mode = \"exp\"\ncolor = [2, 0, 0]"), &["fog.color"]);
}

#[test]
fn shadows_and_shadow_planes_are_read() {
    let model = data("two.obj");
    let text = format!(
        "[render]\nshadows = \"planar\"\n\
         [[objects]]\nprimitive = \"cube\"\n\
         [[objects]]\nprimitive = \"plane\"\nsize = 4\nsubdivisions = 3\ntranslate = [0, -1, 0]\nshadow_plane = true\n\
         [[objects]]\nmodel = {model:?}\ntranslate = [0, 0, 2]\nshadow_plane = true\n\
         [[objects]]\nprimitive = \"plane\"\nshadow_plane = false\n"
    );
    let scene = load_scene(&temp_file("shadows.toml", &text)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.shadows.mode, ShadowMode::Planar);
    assert_eq!(scene.objects.len(), 1 + 1 + 2 + 1);
    // The plane, then each of the model's two meshes; not the cube, not
    // the plane with shadow_plane = false.
    let receivers: Vec<usize> = scene.shadows.planes.iter().map(|p| p.receiver).collect();
    assert_eq!(receivers, [1, 2, 3]);
    let close = |got: Vec4, want: Vec4| (got - want).abs().max_element() < 1e-6;
    // y = -1 with the plane's normal +Y: 0·x + 1·y + 0·z + 1 = 0.
    let floor = scene.shadows.planes[0].plane;
    assert!(close(floor, Vec4::new(0.0, 1.0, 0.0, 1.0)), "{floor}");
    // two.obj's meshes lie in z = 0, facing +Z; moved to z = 2.
    for p in &scene.shadows.planes[1..] {
        assert!(close(p.plane, Vec4::new(0.0, 0.0, 1.0, -2.0)), "{}", p.plane);
    }
    assert!(scene.shadows.receives(1) && !scene.shadows.receives(0) && !scene.shadows.receives(4));
}

#[test]
fn shadows_default_to_none_and_planes_are_kept_without_them() {
    let scene = load_scene(&temp_file("plain.toml", OBJECT)).expect("loads");
    assert_eq!(scene.shadows, Shadows::default());
    let text = "[render]\nshadows = \"none\"\n[[objects]]\nprimitive = \"plane\"\nshadow_plane = true\n";
    let scene = load_scene(&temp_file("kept.toml", text)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.shadows.mode, ShadowMode::None);
    assert_eq!(scene.shadows.planes.len(), 1, "the mode decides, the planes stay");
    assert!(!scene.shadows.receives(0));
    for mode in ShadowMode::ALL {
        let text = format!("[render]\nshadows = {:?}\n{OBJECT}", mode.name());
        let scene = load_scene(&temp_file("mode.toml", &text)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(scene.shadows.mode, mode, "the file's names are ShadowMode::name's");
    }
}

#[test]
fn bad_shadows_are_rejected() {
    check_scene_error(
        "soft.toml",
        &format!("[render]\nshadows = \"soft\"\n{OBJECT}"),
        &["line 2", "unknown variant `soft`", "`none`", "`planar`", "`map`"],
    );
    check_scene_error(
        "ball.toml",
        "[[objects]]\nprimitive = \"plane\"\nshadow_plane = true\n\
         [[objects]]\nprimitive = \"sphere\"\nshadow_plane = true\n",
        &["line 6", "objects[1].shadow_plane: needs a flat object: its vertices are not on one plane"],
    );
    check_scene_error(
        "type.toml",
        &format!("{OBJECT}shadow_plane = \"yes\"\n"),
        &["line 3", "invalid type: string \"yes\", expected a boolean"],
    );
    // A model with a flat mesh and a bent one: the bent one is named.
    let bent =
        temp_file("bent.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\ng flat\nf 1 2 3\ng bent\nf 1 2 3 4\n");
    check_scene_error(
        "model.toml",
        &format!("[[objects]]\nmodel = {bent:?}\nshadow_plane = true\n"),
        &["line 3", "objects[0].shadow_plane: needs a flat object: mesh 2 of 2 ('bent') is not"],
    );
    // A line has no plane at all.
    let line = temp_file("line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    check_scene_error(
        "line.toml",
        &format!("[[objects]]\nmodel = {line:?}\nshadow_plane = true\n"),
        &["objects[0].shadow_plane: needs a flat object: it has no triangle of positive area"],
    );
}

#[test]
fn shadow_maps_are_read_with_their_size_and_filter() {
    let render = |body: &str| format!("[render]\n{body}\n{OBJECT}");
    let load = |name: &str, text: &str| load_scene(&temp_file(name, text)).unwrap_or_else(|e| panic!("{e}"));

    // The defaults: 1024 texels, PCF, with or without map mode.
    let scene = load("map.toml", &render("shadows = \"map\""));
    assert_eq!(scene.shadows.mode, ShadowMode::Map);
    assert_eq!((scene.shadows.map_size, scene.shadows.pcf), (DEFAULT_SHADOW_MAP_SIZE, true));
    assert_eq!(DEFAULT_SHADOW_MAP_SIZE, 1024);
    assert!(scene.shadows.planes.is_empty());
    assert!(scene.shadows.receives(0), "with shadow maps every object receives");
    let scene = load("plain.toml", OBJECT);
    assert_eq!((scene.shadows.map_size, scene.shadows.pcf), (1024, true));

    let scene =
        load("full.toml", &render("shadows = \"map\"\nshadow_map_size = 256\nshadow_filter = \"nearest\""));
    assert_eq!(scene.shadows.mode, ShadowMode::Map);
    assert_eq!((scene.shadows.map_size, scene.shadows.pcf), (256, false));
    let scene = load("pcf.toml", &render("shadows = \"map\"\nshadow_filter = \"pcf\""));
    assert!(scene.shadows.pcf);

    // Both ends of the range; the keys are kept whatever the mode.
    for size in [16, MAX_SHADOW_MAP_SIZE] {
        let scene = load("ends.toml", &render(&format!("shadow_map_size = {size}")));
        assert_eq!(scene.shadows.map_size, size);
        assert_eq!(scene.shadows.mode, ShadowMode::None);
    }
}

#[test]
fn bad_shadow_map_keys_are_rejected() {
    let render = |body: &str| format!("[render]\n{body}\n{OBJECT}");
    check_scene_error(
        "small.toml",
        &render("shadow_map_size = 8"),
        &["line 2, column 19: render.shadow_map_size: must be in 16..=8192, got 8"],
    );
    check_scene_error(
        "large.toml",
        &render("shadows = \"map\"\nshadow_map_size = 9000"),
        &["line 3, column 19: render.shadow_map_size: must be in 16..=8192, got 9000"],
    );
    check_scene_error(
        "negative.toml",
        &render("shadow_map_size = -1"),
        &["line 2, column 19: render.shadow_map_size", "got -1"],
    );
    check_scene_error(
        "huge.toml",
        &render("shadow_map_size = 99999999999"),
        &["line 2, column 19: render.shadow_map_size", "got 99999999999"],
    );
    check_scene_error(
        "big.toml",
        &render("shadow_map_size = \"big\""),
        &["line 2, column 19: render.shadow_map_size: must be a whole number of texels in 16..=8192", "big"],
    );
    check_scene_error(
        "float.toml",
        &render("shadow_map_size = 512.0"),
        &["line 2, column 19: render.shadow_map_size: must be a whole number", "512"],
    );
    check_scene_error(
        "filter.toml",
        &render("shadow_filter = \"bilinear\""),
        &["line 2, column 17", "unknown variant `bilinear`", "`pcf`", "`nearest`"],
    );
    check_scene_error(
        "typo.toml",
        &render("shadow_map = 512"),
        &["line 2", "unknown field `shadow_map`", "shadow_map_size"],
    );
}
