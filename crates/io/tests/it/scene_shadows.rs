//! Scene files: area lights, automatic area samples and shadows — read as
//! written, every bad value an error naming the file, the key and the value.

use glam::{Vec3, Vec4};
use zline_scene::{Attenuation, Light, ShadowMode, Shadows, DEFAULT_SHADOW_MAP_SIZE, MAX_SHADOW_MAP_SIZE};

use crate::scene_file::{check_scene_error, load_scene, OBJECT};
use crate::{data, temp_file};

#[test]
fn area_lights_become_their_samples() {
    let text = format!(
        "[[lights]]\ntype = \"rect\"\nposition = [0, 3, 0]\nu = [1, 0, 0]\nv = [0, 0, 0.5]\nsamples = 2\n\
         color = [0.8, 0.4, 1.6]\nattenuation = [1, 0.5, 0]\n\
         [[lights]]\ntype = \"disc\"\nposition = [0, 2, 0]\nnormal = [0, -1, 0]\nradius = 0.5\n{OBJECT}"
    );
    let scene = load_scene(&temp_file("area.toml", &text)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.lights.len(), 4 + 16, "2 × 2 rect samples and the disc's default 4 × 4");
    let attenuation = Attenuation::new(1.0, 0.5, 0.0);
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
