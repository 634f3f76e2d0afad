//! Scene files: good files give the scene they describe; every bad value
//! gives an error naming the file, the line and column, the key and the
//! value.

use std::sync::Arc;

use glam::Vec3;
use zline_io::{default_lights, load_scene_with_options, LoadOptions, SceneError, DEFAULT_AMBIENT};
use zline_scene::{
    Attenuation, Cone, DepthMode, FogCoordinate, FogMode, GouraudClamp, Interpolation, Light, LightingSides,
    Projection, RenderSettings, Scene, ShadingMode,
};

use crate::{check_message, data, repo, temp_file};

/// Loads a scene that may name models anywhere: these scenes are written
/// to temporary folders and name the fixtures by absolute paths (the
/// confinement to the scene's folder is tested in `safety`).
pub(crate) fn load_scene(path: &std::path::Path) -> Result<Scene, SceneError> {
    load_scene_with_options(path, LoadOptions { allow_outside: true })
}

/// A minimal valid scene body to which tests add or in which they replace.
pub(crate) const OBJECT: &str = "[[objects]]\nprimitive = \"cube\"\n";

#[track_caller]
pub(crate) fn check_scene_error(name: &str, text: &str, parts: &[&str]) {
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
[[lights]]
type = "spot"
position = [0, 4, 0]
direction = [0, -1, 0]
range = 12
inner_angle = 20
outer_angle = 30
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
                attenuation: Attenuation::new(1.0, 0.05, 0.01)
            },
            Light::Directional { direction: Vec3::splat(-1.0), color: Vec3::ONE },
            Light::Spot {
                position: Vec3::new(0.0, 4.0, 0.0),
                direction: Vec3::NEG_Y,
                color: Vec3::ONE,
                attenuation: Attenuation::NONE.with_range(12.0),
                cone: Cone { inner: 20f32.to_radians(), outer: 30f32.to_radians() },
            },
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
    check_scene_error("kind.toml", &light("type = \"cone\""), &["unknown variant `cone`"]);
    check_scene_error(
        "spotdir.toml",
        &light("type = \"spot\"\nposition = [0, 1, 0]"),
        &["lights[0]: a spot light needs 'direction'"],
    );
    let spot = "type = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]";
    check_scene_error(
        "cone.toml",
        &light(&format!("{spot}\ninner_angle = 40\nouter_angle = 30")),
        &["line 5, column 15: lights[0].inner_angle: must be less than outer_angle, got 40 ≥ 30 degrees"],
    );
    check_scene_error(
        "wide.toml",
        &light(&format!("{spot}\nouter_angle = 120")),
        &["lights[0].outer_angle: must be in [0, 90], got 120"],
    );
    check_scene_error(
        "pointcone.toml",
        &light("type = \"point\"\nposition = [0, 1, 0]\nouter_angle = 30"),
        &["lights[0].outer_angle: does not apply to lights other than spot lights"],
    );
    check_scene_error(
        "range.toml",
        &light("type = \"point\"\nposition = [0, 1, 0]\nrange = 0"),
        &["lights[0].range: must be > 0, got 0"],
    );
    check_scene_error(
        "sunrange.toml",
        &light("type = \"directional\"\ndirection = [0, -1, 0]\nrange = 3"),
        &["lights[0].range: does not apply to directional lights"],
    );
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
