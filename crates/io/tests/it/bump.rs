//! Bump and normal maps from files: MTL `map_bump -bm`, the scene file's
//! `bump`/`bump_scale`, `apply_bump_map` (the CLI's `--bump`) and glTF
//! `normalTexture`, each with tangents for every vertex.

use zline_io::{apply_bump_map, load_gltf_with_warnings, load_obj, load_scene_with_options, LoadOptions};
use zline_scene::{Mesh, NormalEncoding};

use crate::gltf::quad_gltf;
use crate::{check_message, repo, temp_file};

#[track_caller]
fn check_map(mesh: &Mesh, encoding: NormalEncoding, scale: f32) {
    let map = mesh.normal_map.as_ref().expect("a map");
    assert_eq!((map.encoding, map.scale), (encoding, scale));
    assert_eq!(mesh.tangents.len(), mesh.positions.len(), "a tangent per vertex");
    assert_eq!(mesh.uvs.len(), mesh.positions.len());
    assert!(mesh.tangents.iter().all(|t| t.w.abs() == 1.0 && t.is_finite()));
}

#[test]
fn an_mtl_bump_statement_with_its_multiplier() {
    let meshes = load_obj(&repo("assets/bump/sphere.obj")).unwrap();
    check_map(&meshes[0], NormalEncoding::Height, 0.03);
}

#[test]
fn scene_file_bump_keys() {
    let sphere = repo("assets/bump/sphere.obj");
    let bumps = repo("assets/bump/bumps.png");
    let load = |text: &str| {
        let path = temp_file("bump.toml", text);
        load_scene_with_options(&path, LoadOptions { allow_outside: true }).map_err(|e| e.to_string())
    };
    let scene =
        load(&format!("[[objects]]\nmodel = {sphere:?}\nbump = {bumps:?}\nbump_scale = -0.5\n")).unwrap();
    check_map(&scene.objects[0].mesh, NormalEncoding::Height, -0.5);
    let e = load(&format!("[[objects]]\nprimitive = \"cube\"\nbump = {bumps:?}\n")).unwrap_err();
    check_message(&e, &["objects[0].bump", "needs texture coordinates"]);
    let e = load(&format!("[[objects]]\nmodel = {sphere:?}\nbump_scale = 2.0\n")).unwrap_err();
    check_message(&e, &["bump_scale"]);
    let e = load(&format!("[[objects]]\nmodel = {sphere:?}\nbump = \"/no/such/bumps.png\"\n")).unwrap_err();
    check_message(&e, &["objects[0].bump", "no/such/bumps.png"]);
}

#[test]
fn apply_bump_map_maps_every_mesh_with_coordinates() {
    let mut scene = load_scene_with_options(
        &temp_file("plain.toml", &format!("[[objects]]\nmodel = {:?}\n", repo("assets/bump/sphere.obj"))),
        LoadOptions { allow_outside: true },
    )
    .unwrap();
    assert_eq!(apply_bump_map(&mut scene, &repo("assets/bump/bumps.png"), 0.25).unwrap(), 1);
    check_map(&scene.objects[0].mesh, NormalEncoding::Height, 0.25);
    let e = apply_bump_map(&mut scene, &repo("assets/bump/bumps.png"), f32::NAN).unwrap_err().to_string();
    check_message(&e, &["bumps.png", "finite"]);
}

#[test]
fn gltf_normal_textures_get_mikktspace_tangents() {
    let path = quad_gltf(
        "normal-texture",
        r#""materials": [{"name": "bumpy", "normalTexture": {"index": 0, "scale": 0.5}}],
        "textures": [{"source": 0}], "images": [{"uri": "n.png"}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#,
    );
    let image = image::RgbaImage::from_raw(1, 1, vec![128, 128, 255, 255]).unwrap();
    image.save(path.with_file_name("n.png")).unwrap();
    let (scene, warnings) = load_gltf_with_warnings(&path).unwrap();
    assert!(warnings.iter().all(|w| !w.contains("normal")), "{warnings:?}");
    let mesh = &scene.objects[0].mesh;
    check_map(mesh, NormalEncoding::Tangent, 0.5);
    // The quad's s runs along +x and t = 1 − v along −y: T = +x, and B =
    // w·(N × T) = w·(z × x) = w·y must point along +t (−y): w = −1.
    for t in &mesh.tangents {
        assert!((t.truncate() - glam::Vec3::X).length() < 1e-6 && t.w == -1.0, "{t}");
    }
}

#[test]
fn gltf_tangents_from_the_file_are_kept() {
    let path = quad_gltf(
        "file-tangents",
        r#""materials": [{"name": "bumpy", "normalTexture": {"index": 0}}],
        "textures": [{"source": 0}], "images": [{"uri": "n.png"}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#,
    );
    image::RgbaImage::from_raw(1, 1, vec![128, 128, 255, 255])
        .unwrap()
        .save(path.with_file_name("n.png"))
        .unwrap();
    // A second buffer (a data: URI) with TANGENT = (0, 1, 0, −1) at every
    // vertex: kept as given, not replaced by MikkTSpace's (+x, −1).
    let tangents = "AAAAAAAAgD8AAAAAAACAvwAAAAAAAIA/AAAAAAAAgL8AAAAAAACAPwAAAAAAAIC/AAAAAAAAgD8AAAAAAACAvw==";
    crate::gltf::edit(
        &path,
        r#"{"uri": "quad.bin", "byteLength": 92}"#,
        &format!(
            r#"{{"uri": "quad.bin", "byteLength": 92}}, {{"uri": "data:application/octet-stream;base64,{tangents}", "byteLength": 64}}"#
        ),
    );
    crate::gltf::edit(
        &path,
        r#"{"buffer": 0, "byteOffset": 80, "byteLength": 12}"#,
        r#"{"buffer": 0, "byteOffset": 80, "byteLength": 12}, {"buffer": 1, "byteOffset": 0, "byteLength": 64}"#,
    );
    crate::gltf::edit(
        &path,
        r#"{"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}"#,
        r#"{"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}, {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC4"}"#,
    );
    crate::gltf::edit(&path, r#""TEXCOORD_0": 1}"#, r#""TEXCOORD_0": 1, "TANGENT": 3}"#);
    let (scene, warnings) = load_gltf_with_warnings(&path).unwrap();
    assert!(warnings.iter().all(|w| !w.contains("normal")), "{warnings:?}");
    let mesh = &scene.objects[0].mesh;
    check_map(mesh, NormalEncoding::Tangent, 1.0);
    assert_eq!(mesh.tangents, vec![glam::Vec4::new(0.0, 1.0, 0.0, -1.0); 4]);
}
