//! Scene files' reflection-model keys in `[objects.material]`: `model`,
//! `metallic`, `roughness` and `distribution` (SPEC §5.2), their defaults,
//! and errors naming the key and the value.

use glam::Vec3;
use zline_scene::Scene;
use zline_shading::{Distribution, Material, Microfacet, Model};

use crate::repo;
use crate::scene_file::{check_scene_error, load_scene, OBJECT};
use crate::temp_file;

/// The scene of one cube (a basic material) with `material` as its
/// `[objects.material]` table.
fn cube_with(name: &str, material: &str) -> Scene {
    let text = format!("{OBJECT}[objects.material]\n{material}\n");
    load_scene(&temp_file(name, &text)).unwrap_or_else(|e| panic!("{e}"))
}

/// The model `material` gives the cube.
fn cube_model(name: &str, material: &str) -> Model {
    cube_with(name, material).objects[0].material().model
}

fn cook_torrance(metallic: f32, roughness: f32, distribution: Distribution) -> Model {
    Model::CookTorrance(Microfacet { metallic, roughness, distribution })
}

#[test]
fn without_the_keys_the_meshes_keep_their_model() {
    let scene = cube_with("plain.toml", "kd = [0.5, 0.5, 0.5]");
    assert_eq!(scene.objects[0].material().model, Model::Basic);
    let scene = cube_with("nothing.toml", "");
    assert_eq!(scene.objects[0].material().model, Model::Basic);
    // glTF materials load as Cook–Torrance GGX and stay so.
    let text = format!("[[objects]]\nmodel = {:?}\n", repo("assets/gltf/Box/glTF-Binary/Box.glb"));
    let scene = load_scene(&temp_file("box.toml", &text)).unwrap_or_else(|e| panic!("{e}"));
    assert!(matches!(scene.objects[0].material().model, Model::CookTorrance(_)));
}

#[test]
fn a_basic_material_switched_is_a_smooth_ish_ggx_dielectric() {
    let expected = cook_torrance(0.0, 0.5, Distribution::Ggx);
    assert_eq!(cube_model("ct.toml", "model = \"cook-torrance\""), expected);
    // The coefficients given beside it are kept; kd is the base colour.
    let m = cube_with("ct_kd.toml", "model = \"cook-torrance\"\ncolor = [0.9, 0.6, 0.1]\nns = 8").objects[0]
        .material();
    assert_eq!(
        (m.kd, m.ka, m.ns, m.model),
        (Vec3::new(0.9, 0.6, 0.1), Vec3::new(0.9, 0.6, 0.1), 8.0, expected)
    );
    assert_eq!(cube_model("basic.toml", "model = \"basic\""), Model::Basic);
}

#[test]
fn each_parameter_key_is_read_and_implies_cook_torrance() {
    use Distribution::{Beckmann, Ggx};
    assert_eq!(cube_model("m.toml", "metallic = 0.98"), cook_torrance(0.98, 0.5, Ggx));
    assert_eq!(cube_model("r.toml", "roughness = 0.3"), cook_torrance(0.0, 0.3, Ggx));
    assert_eq!(cube_model("d.toml", "distribution = \"beckmann\""), cook_torrance(0.0, 0.5, Beckmann));
    assert_eq!(cube_model("g.toml", "distribution = \"ggx\""), cook_torrance(0.0, 0.5, Ggx));
    assert_eq!(
        cube_model(
            "all.toml",
            "model = \"cook-torrance\"\nmetallic = 1\nroughness = 0\ndistribution = \"beckmann\""
        ),
        cook_torrance(1.0, 0.0, Beckmann)
    );
    // The ends of the ranges are in them.
    assert_eq!(cube_model("ends.toml", "metallic = 0\nroughness = 1"), cook_torrance(0.0, 1.0, Ggx));
}

/// A glTF material keeps its own parameters but those the table gives,
/// and `model = "basic"` turns it basic with the ka, ks and ns the loader
/// gave it.
#[test]
fn a_cook_torrance_mesh_keeps_what_the_table_does_not_set() {
    let model = repo("assets/gltf/Box/glTF-Binary/Box.glb");
    let with = |name: &str, material: &str| {
        let text = format!("[[objects]]\nmodel = {model:?}\n[objects.material]\n{material}\n");
        load_scene(&temp_file(name, &text)).unwrap_or_else(|e| panic!("{e}")).objects[0].material()
    };
    let own: Material = with("own.toml", "");
    let Model::CookTorrance(own_params) = own.model else { panic!("glTF is Cook–Torrance: {own:?}") };
    let rough = with("rough.toml", "roughness = 0.25");
    assert_eq!(rough.model, Model::CookTorrance(Microfacet { roughness: 0.25, ..own_params }));
    let beckmann = with("beck.toml", "model = \"cook-torrance\"\ndistribution = \"beckmann\"");
    let params = Microfacet { distribution: Distribution::Beckmann, ..own_params };
    assert_eq!(beckmann.model, Model::CookTorrance(params));
    let basic = with("basic.toml", "model = \"basic\"");
    assert_eq!(basic, Material { model: Model::Basic, ..own });
}

#[test]
fn bad_model_keys_name_the_key_and_the_value() {
    let material = |rest: &str| format!("{OBJECT}[objects.material]\n{rest}\n");
    check_scene_error(
        "metal.toml",
        &material("metallic = 1.5"),
        &["line 4, column 12: objects[0].material.metallic: must be in [0, 1], got 1.5"],
    );
    check_scene_error(
        "rough.toml",
        &material("roughness = -0.1"),
        &["line 4, column 13: objects[0].material.roughness: must be in [0, 1], got -0.1"],
    );
    check_scene_error(
        "nan.toml",
        &material("roughness = nan"),
        &["objects[0].material.roughness: must be finite, got NaN"],
    );
    check_scene_error(
        "model.toml",
        &material("model = \"phong\""),
        &["line 4, column 9: objects[0].material.model: unknown model \"phong\", \
             expected \"basic\" or \"cook-torrance\""],
    );
    check_scene_error(
        "dist.toml",
        &material("distribution = \"blinn\""),
        &["line 4, column 16: objects[0].material.distribution: unknown distribution \"blinn\", \
             expected \"ggx\" or \"beckmann\""],
    );
    check_scene_error(
        "case.toml",
        &material("model = \"Cook-Torrance\""),
        &["unknown model \"Cook-Torrance\""],
    );
    check_scene_error(
        "type.toml",
        &material("model = 1"),
        &["line 4, column 9", "invalid type: integer `1`"],
    );
    for (key, value, column) in
        [("metallic", "0.5", 12), ("roughness", "0.5", 13), ("distribution", "\"ggx\"", 16)]
    {
        check_scene_error(
            &format!("basic_{key}.toml"),
            &material(&format!("model = \"basic\"\n{key} = {value}")),
            &[&format!(
                "line 5, column {column}: objects[0].material.{key}: does not apply to the basic model \
                 (model = \"basic\")"
            )],
        );
    }
    // With model = "basic", a parameter is refused whatever its value.
    check_scene_error(
        "basic_bad.toml",
        &material("model = \"basic\"\nmetallic = 2"),
        &["objects[0].material.metallic: does not apply to the basic model"],
    );
    check_scene_error(
        "second.toml",
        &format!("{OBJECT}{OBJECT}[objects.material]\nroughness = 2\n"),
        &["line 6, column 13: objects[1].material.roughness: must be in [0, 1], got 2"],
    );
}

/// The ray tracer's keys (SPEC §12): `kr` and `ior`, defaults 0 and 1,
/// errors naming the key and the value.
#[test]
fn mirror_and_refraction_keys() {
    let m = cube_with("plain_rt.toml", "").objects[0].material();
    assert_eq!((m.kr, m.ior), (Vec3::ZERO, 1.0));
    let m = cube_with("glass.toml", "kr = [0.1, 0.2, 0.3]\nior = 1.5\nopacity = 0.1").objects[0].material();
    assert_eq!((m.kr, m.ior, m.opacity), (Vec3::new(0.1, 0.2, 0.3), 1.5, 0.1));
    let bad = |name: &str, line: &str, parts: &[&str]| {
        check_scene_error(name, &format!("{OBJECT}[objects.material]\n{line}\n"), parts)
    };
    bad("ior0.toml", "ior = 0", &["objects[0].material.ior", "got 0"]);
    bad("iorneg.toml", "ior = -1.5", &["objects[0].material.ior", "got -1.5"]);
    bad("iornan.toml", "ior = nan", &["objects[0].material.ior", "finite"]);
    bad("kr.toml", "kr = [1.5, 0, 0]", &["objects[0].material.kr"]);
}
