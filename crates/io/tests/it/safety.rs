//! Bad input, limits and confinement: files named by a model or scene file
//! stay inside the folder of the file that names them unless the options
//! allow more; devices, directories and oversized files are refused before
//! they are read; oversized textures before they are decoded; malformed
//! glTF and MTL files give errors naming the file and the problem, never a
//! panic.

use std::path::{Path, PathBuf};

use zline_io::{
    load_gltf, load_gltf_with_options, load_gltf_with_warnings, load_obj, load_obj_with_options,
    load_obj_with_warnings, load_scene, load_scene_with_options, LoadOptions,
};

use crate::gltf::{edit, quad_gltf};
use crate::obj_textures::{fixture, png_3x2, QUAD_OBJ};
use crate::{check_message, temp_file};

const OPEN: LoadOptions = LoadOptions { allow_outside: true };

/// A fresh folder holding `model/`, for models that reach out of it.
fn nested(name: &str, files: &[(&str, &[u8])]) -> PathBuf {
    let dir = fixture(&format!("safety-{name}"), &[]).join("model");
    std::fs::create_dir_all(&dir).unwrap();
    for (file, bytes) in files {
        std::fs::write(dir.join(file), bytes).unwrap();
    }
    dir
}

#[cfg(unix)]
fn symlink(target: impl AsRef<Path>, link: impl AsRef<Path>) {
    std::os::unix::fs::symlink(target, link).unwrap();
}

// ---- glTF URIs ---------------------------------------------------------------

#[test]
fn gltf_buffer_uris_outside_the_folder_are_refused() {
    let path = quad_gltf("safety-gltf-abs", r#""nodes": [{"mesh": 0}]"#);
    edit(&path, r#""uri": "quad.bin""#, r#""uri": "/etc/passwd""#);
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: buffer 0: '/etc/passwd' is an absolute path", "--allow-paths-outside"]);
    // Allowed, the file is read (and is no buffer of 92 bytes, or is).
    if let Err(e) = load_gltf_with_options(&path, OPEN) {
        assert!(!e.to_string().contains("absolute path"), "{e}");
    }

    let path = quad_gltf("safety-gltf-up", r#""nodes": [{"mesh": 0}]"#);
    edit(&path, r#""uri": "quad.bin""#, r#""uri": "../../../../../../etc/passwd""#);
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: buffer 0: '../../../../../../etc/passwd' leads outside the folder"]);
    // Percent-escapes are decoded before the check.
    edit(&path, r#""uri": "../../../../../../etc/passwd""#, r#""uri": "%2E%2E/x.bin""#);
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: buffer 0: '../x.bin' leads outside the folder"]);
    // `..` that stays inside is fine.
    std::fs::create_dir_all(path.with_file_name("sub")).unwrap();
    edit(&path, r#""uri": "%2E%2E/x.bin""#, r#""uri": "sub/../quad.bin""#);
    load_gltf(&path).unwrap();
}

#[test]
fn gltf_image_uris_outside_the_folder_are_refused() {
    let members = r#""nodes": [{"mesh": 0}],
        "materials": [{"name": "tex", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}],
        "images": [{"uri": "../outside.png"}]"#;
    let path = quad_gltf("safety-gltf-image", members);
    std::fs::write(path.parent().unwrap().parent().unwrap().join("outside.png"), png_3x2()).unwrap();
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf", "material 'tex'", "image 0: '../outside.png' leads outside the folder"]);
    let (scene, _) = load_gltf_with_options(&path, OPEN).unwrap();
    assert!(scene.objects[0].mesh.diffuse_map.is_some(), "allowed, the image is used");
    // A texture error names the model, the material and the image.
    std::fs::write(path.with_file_name("bad.png"), b"not a png").unwrap();
    edit(&path, "../outside.png", "bad.png");
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: material 'tex': texture ", "bad.png: cannot decode image"]);
}

#[cfg(unix)]
#[test]
fn symlinks_out_of_the_folder_and_to_devices_are_refused() {
    let path = quad_gltf("safety-gltf-link", r#""nodes": [{"mesh": 0}]"#);
    let dir = path.parent().unwrap();
    symlink("/dev/zero", dir.join("zero.bin"));
    edit(&path, r#""uri": "quad.bin""#, r#""uri": "zero.bin""#);
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: buffer 0: 'zero.bin' leads outside the folder (to '/dev/zero')"]);
    // Allowed outside, a device is still no file.
    let e = load_gltf_with_options(&path, OPEN).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: buffer 0:", "zero.bin' is not a regular file"]);

    // The model itself, as a symlink to a device, and a directory.
    let dir = nested("link-model", &[]);
    symlink("/dev/zero", dir.join("zero.obj"));
    let e = load_obj(&dir.join("zero.obj")).unwrap_err().to_string();
    check_message(&e, &["zero.obj: is not a regular file"]);
    std::fs::create_dir_all(dir.join("dir.glb")).unwrap();
    let e = load_gltf(&dir.join("dir.glb")).unwrap_err().to_string();
    check_message(&e, &["dir.glb: is a directory"]);

    // An mtllib and a map_Kd that are symlinks to devices or out of the folder.
    let dir = nested("link-mtl", &[("quad.obj", QUAD_OBJ)]);
    symlink("/dev/zero", dir.join("quad.mtl"));
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(&e, &["quad.obj: mtllib: 'quad.mtl' leads outside the folder (to '/dev/zero')"]);
    let e = load_obj_with_options(&dir.join("quad.obj"), OPEN).unwrap_err().to_string();
    check_message(&e, &["quad.mtl: is not a regular file"]);
    let dir = nested("link-map", &[("quad.obj", QUAD_OBJ), ("quad.mtl", b"newmtl m\nmap_Kd t.png\n")]);
    std::fs::write(dir.parent().unwrap().join("secret.png"), png_3x2()).unwrap();
    symlink(dir.parent().unwrap().join("secret.png"), dir.join("t.png"));
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(&e, &["quad.mtl: material 'm': map_Kd: 't.png' leads outside the folder"]);
    let (meshes, _) = load_obj_with_options(&dir.join("quad.obj"), OPEN).unwrap();
    assert!(meshes[0].diffuse_map.is_some());
}

#[cfg(unix)]
#[test]
fn fifos_are_refused_without_waiting_for_a_writer() {
    let dir = nested("fifo", &[("quad.obj", QUAD_OBJ)]);
    let fifo = dir.join("quad.mtl");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("mkfifo unavailable; skipped");
        return;
    }
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(&e, &["quad.mtl: is not a regular file"]);
}

// ---- OBJ, MTL and scene files --------------------------------------------------

#[test]
fn mtllib_and_map_kd_outside_the_folder_are_refused() {
    let obj = b"mtllib ../../../../../../../etc/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let dir = nested("mtllib", &[("a.obj", obj)]);
    let e = load_obj(&dir.join("a.obj")).unwrap_err().to_string();
    check_message(&e, &["a.obj: mtllib: '../../../../../../../etc/passwd' leads outside the folder"]);
    let obj = b"mtllib /etc/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let dir = nested("mtllib-abs", &[("a.obj", obj)]);
    let e = load_obj(&dir.join("a.obj")).unwrap_err().to_string();
    check_message(&e, &["a.obj: mtllib: '/etc/passwd' is an absolute path"]);
    // Allowed, /etc/passwd is read as an MTL file: its lines are no MTL
    // statements, so no material comes of it, and the mesh still loads.
    if Path::new("/etc/passwd").is_file() {
        load_obj_with_options(&dir.join("a.obj"), OPEN).unwrap();
    }

    let dir = nested("map-kd", &[("quad.obj", QUAD_OBJ), ("quad.mtl", b"newmtl m\nmap_Kd ../t.png\n")]);
    std::fs::write(dir.parent().unwrap().join("t.png"), png_3x2()).unwrap();
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(&e, &["quad.mtl: material 'm': map_Kd: '../t.png' leads outside the folder"]);
    let (meshes, _) = load_obj_with_options(&dir.join("quad.obj"), OPEN).unwrap();
    assert!(meshes[0].diffuse_map.is_some(), "allowed, the texture is used");
    let dir = nested(
        "map-kd-abs",
        &[("quad.obj", QUAD_OBJ), ("quad.mtl", b"newmtl m\nmap_Kd -clamp on /etc/x.png\n")],
    );
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(&e, &["quad.mtl: material 'm': map_Kd: '/etc/x.png' is an absolute path"]);
}

#[test]
fn mtllib_statements_are_limited_in_number() {
    let mtl = b"newmtl m\nKd 1 0 0\n";
    let obj = "mtllib a.mtl\n".repeat(256) + "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
    let dir = nested("mtllibs", &[("a.obj", obj.as_bytes()), ("a.mtl", mtl)]);
    load_obj(&dir.join("a.obj")).unwrap();
    std::fs::write(dir.join("a.obj"), "mtllib a.mtl\n".to_owned() + &obj).unwrap();
    let e = load_obj(&dir.join("a.obj")).unwrap_err().to_string();
    check_message(&e, &["a.obj: more than 256 material libraries (mtllib)"]);
}

#[test]
fn scene_models_outside_the_folder_are_refused() {
    let cube = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let dir = nested("scene", &[("in.obj", cube)]);
    std::fs::write(dir.parent().unwrap().join("out.obj"), cube).unwrap();
    let scene = dir.join("s.toml");
    std::fs::write(&scene, "[[objects]]\nmodel = \"in.obj\"\n[[objects]]\nmodel = \"../out.obj\"\n").unwrap();
    let e = load_scene(&scene).unwrap_err().to_string();
    check_message(&e, &["s.toml: line 4, column 9: objects[1].model: '../out.obj' leads outside the folder"]);
    assert_eq!(load_scene_with_options(&scene, OPEN).unwrap().objects.len(), 2);
    std::fs::write(&scene, "[[objects]]\nmodel = \"/etc/passwd\"\n").unwrap();
    let e = load_scene(&scene).unwrap_err().to_string();
    check_message(&e, &["s.toml: line 2, column 9: objects[0].model: '/etc/passwd' is an absolute path"]);
}

#[test]
fn files_over_their_size_limit_are_refused_before_reading() {
    // Sparse files: the size is checked before a byte is read.
    let dir = nested("sizes", &[("quad.obj", QUAD_OBJ)]);
    std::fs::File::create(dir.join("quad.mtl")).unwrap().set_len((16 << 20) + 1).unwrap();
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(
        &e,
        &["quad.mtl: file of 16777217 bytes, more than the limit of 16 MiB for MTL and scene files"],
    );
    let big = dir.join("big.obj");
    std::fs::File::create(&big).unwrap().set_len((1 << 30) + 1).unwrap();
    let e = load_obj(&big).unwrap_err().to_string();
    check_message(&e, &["big.obj: file of 1073741825 bytes, more than the limit of 1 GiB"]);
    let toml = dir.join("big.toml");
    std::fs::File::create(&toml).unwrap().set_len(64 << 20).unwrap();
    check_message(&load_scene(&toml).unwrap_err().to_string(), &["big.toml: file of 67108864 bytes"]);
    let png = dir.join("big.png");
    std::fs::File::create(&png).unwrap().set_len((256 << 20) + 1).unwrap();
    std::fs::write(dir.join("quad.mtl"), "newmtl m\nmap_Kd big.png\n").unwrap();
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(&e, &["quad.obj: material 'm': texture", "big.png: file of 268435457 bytes", "256 MiB"]);
}

#[test]
fn textures_over_the_pixel_limit_are_refused_naming_model_material_and_size() {
    // A real 4097 × 4097 PNG is 50 MB to encode; a header is enough, as the
    // size is checked before decoding.
    let mut png = png_3x2();
    png[16..20].copy_from_slice(&12000u32.to_be_bytes());
    png[20..24].copy_from_slice(&12000u32.to_be_bytes());
    let crc = crc32fast::hash(&png[12..29]);
    png[29..33].copy_from_slice(&crc.to_be_bytes());
    let dir = nested(
        "pixels",
        &[("quad.obj", QUAD_OBJ), ("quad.mtl", b"newmtl m\nmap_Kd huge.png\n"), ("huge.png", &png)],
    );
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(
        &e,
        &[
            "quad.obj: material 'm': texture",
            "huge.png: image of 12000x12000 pixels",
            "limit of 16777216 pixels",
        ],
    );
}

#[test]
fn mtl_values_non_finite_are_errors_out_of_range_are_clamped_with_warnings() {
    let dir = nested("mtl-nan", &[("quad.obj", QUAD_OBJ), ("quad.mtl", b"newmtl m\nKd nan 1e300 -5\n")]);
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(&e, &["quad.mtl: line 2: Kd: non-finite value 'nan'"]);
    let mtl = b"newmtl m\nKd 0.5 1e300 -5\nNs -1\nd 7\n";
    let dir = nested("mtl-clamp", &[("quad.obj", QUAD_OBJ), ("quad.mtl", mtl)]);
    let (meshes, warnings) = load_obj_with_warnings(&dir.join("quad.obj")).unwrap();
    let m = meshes[0].material;
    assert_eq!(m.kd.to_array(), [0.5, 1.0, 0.0]);
    assert_eq!((m.ns, m.opacity), (0.0, 1.0));
    for (i, part) in
        ["line 2: Kd value 1e300", "line 2: Kd value -5", "line 3: Ns value -1", "line 4: d value 7"]
            .iter()
            .enumerate()
    {
        check_message(&warnings[i], &["quad.mtl: ", part, "clamped to"]);
    }
}

#[test]
fn partly_coloured_vertices_load_without_colours_and_warn() {
    let obj = b"v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
    let path = temp_file("colours.obj", std::str::from_utf8(obj).unwrap());
    let (meshes, warnings) = load_obj_with_warnings(&path).unwrap();
    assert_eq!(meshes[0].triangles.len(), 1);
    check_message(&warnings[0], &["colours.obj: only some vertices have a colour"]);
}

// ---- glTF structure --------------------------------------------------------------

#[test]
fn malformed_gltf_gives_errors_naming_the_file_never_a_panic() {
    let path = quad_gltf("safety-accessor", r#""nodes": [{"mesh": 0}]"#);
    edit(&path, r#""POSITION": 0"#, r#""POSITION": 99"#);
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(
        &e,
        &["quad.gltf: mesh 0, primitive 0: attribute POSITION names accessor 99, but the file has 3"],
    );

    let path = quad_gltf("safety-version", r#""nodes": [{"mesh": 0}]"#);
    edit(&path, r#""version": "2.0""#, r#""version": "1.0""#);
    check_message(
        &load_gltf(&path).unwrap_err().to_string(),
        &["quad.gltf: glTF version '1.0' is not supported"],
    );

    let glb = path.with_file_name("json.glb");
    std::fs::copy(&path, &glb).unwrap();
    check_message(
        &load_gltf(&glb).unwrap_err().to_string(),
        &["json.glb: not a GLB file (magic '{", "expected 'glTF'"],
    );
}

#[test]
fn gltf_buffers_over_the_size_limit_in_all_are_refused_before_reading() {
    let path = quad_gltf("safety-buffers", r#""nodes": [{"mesh": 0}]"#);
    let many = r#"{"uri": "quad.bin", "byteLength": 92}"#.to_owned()
        + &r#", {"uri": "quad.bin", "byteLength": 600000000}"#.repeat(2);
    edit(&path, r#"{"uri": "quad.bin", "byteLength": 92}"#, &many);
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(
        &e,
        &["quad.gltf: buffers of 1200000092 bytes in all", "more than the limit of 1073741824"],
    );
}

#[test]
fn gltf_nodes_with_zero_matrices_are_skipped_with_a_warning() {
    let path = quad_gltf(
        "safety-zero-matrix",
        r#""nodes": [{"mesh": 0}, {"mesh": 0, "matrix": [0,0,0,0, 0,0,0,0, 0,0,0,0, 0,0,0,0]}],
           "scenes": [{"nodes": [0, 1]}]"#,
    );
    let (scene, warnings) = load_gltf_with_warnings(&path).unwrap();
    assert_eq!(scene.objects.len(), 1);
    assert!(
        warnings.iter().any(|w| w.contains("node 1 has a transform that collapses everything")),
        "{warnings:?}"
    );
}

// ---- tessellation budget -----------------------------------------------------------

#[test]
fn scene_primitives_over_the_triangle_budget_are_refused_before_tessellating() {
    let one = "[[objects]]\nprimitive = \"sphere\"\nrings = 4096\nsegments = 4096\n";
    let e = load_scene(&temp_file("huge_sphere.toml", one)).unwrap_err().to_string();
    check_message(
        &e,
        &["huge_sphere.toml: line 2, column 13: objects[0]: this sphere makes 33546240 triangles", "4194304"],
    );
    let sphere = "[[objects]]\nprimitive = \"sphere\"\nrings = 1025\nsegments = 1025\n";
    let e = load_scene(&temp_file("spheres.toml", &sphere.repeat(8))).unwrap_err().to_string();
    check_message(&e, &["spheres.toml: line 6, column 13: objects[1]: this sphere makes 2099200 triangles"]);
    let torus = "[[objects]]\nprimitive = \"torus\"\nrings = 2048\nsegments = 1025\n";
    let e = load_scene(&temp_file("torus.toml", torus)).unwrap_err().to_string();
    check_message(&e, &["this torus makes 4198400 triangles"]);
    // Within the budget, a scene loads.
    let small = "[[objects]]\nprimitive = \"plane\"\nsubdivisions = 512\n";
    load_scene(&temp_file("plane.toml", small)).unwrap();
}
