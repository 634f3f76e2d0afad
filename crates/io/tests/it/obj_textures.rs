//! OBJ textures: `vt` coordinates and `map_Kd` images; a missing texture is
//! a warning with an untextured fallback, a corrupt one an error naming the
//! image file.

use std::path::PathBuf;
use std::sync::Arc;

use glam::{Vec2, Vec3};
use zline_io::{load_obj, load_obj_with_warnings};
use zline_scene::Mesh;
use zline_shading::{Sampler, Wrap};

use crate::{check_message, repo};

/// A fresh directory `name` in this process's temporary directory holding
/// the given files.
pub(crate) fn fixture(name: &str, files: &[(&str, &[u8])]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("zline-io-tests-{}", std::process::id())).join(name);
    std::fs::create_dir_all(&dir).unwrap();
    for (file, bytes) in files {
        std::fs::write(dir.join(file), bytes).unwrap();
    }
    dir
}

/// A textured quad (two triangles, one `vt` per corner) using material
/// `m` of `quad.mtl`.
pub(crate) const QUAD_OBJ: &[u8] = b"mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3 4/4\n";

/// A 3 × 2 RGB PNG.
pub(crate) fn png_3x2() -> Vec<u8> {
    let image = image::RgbImage::from_fn(3, 2, |x, y| image::Rgb([x as u8 * 80, y as u8 * 200, 7]));
    let mut bytes = Vec::new();
    image.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png).unwrap();
    bytes
}

#[track_caller]
fn check_one_mesh(meshes: &[Mesh]) -> &Mesh {
    assert_eq!(meshes.len(), 1);
    &meshes[0]
}

#[test]
fn spot_has_uvs_and_its_texture() {
    let (meshes, warnings) = load_obj_with_warnings(&repo("assets/obj/spot/spot.obj")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let spot = check_one_mesh(&meshes);
    assert_eq!(spot.uvs.len(), spot.positions.len());
    // The file's vt values, as they are: from −0.052 to 1.00065.
    let (lo, hi) = spot.uvs.iter().fold((Vec2::MAX, Vec2::MIN), |(lo, hi), &t| (lo.min(t), hi.max(t)));
    assert!(lo.min_element() == -0.0522421 && hi.max_element() == 1.00065, "{lo} {hi}");
    let map = spot.diffuse_map.as_ref().expect("map_Kd spot_texture.png");
    assert_eq!((map.texture.width(), map.texture.height()), (1024, 1024));
    assert_eq!(map.sampler, Sampler::default());
    assert_eq!(spot.material.kd, Vec3::ONE);
}

#[test]
fn uvs_keep_obj_orientation() {
    let dir = fixture(
        "uvs",
        &[("quad.obj", QUAD_OBJ), ("quad.mtl", b"newmtl m\nKd 1 0 0\nmap_Kd t.png\n"), ("t.png", &png_3x2())],
    );
    let meshes = load_obj(&dir.join("quad.obj")).unwrap();
    let quad = check_one_mesh(&meshes);
    // One vertex per (v, vt) pair, in file order: t is not flipped.
    let corners: Vec<(Vec3, Vec2)> = quad.positions.iter().copied().zip(quad.uvs.iter().copied()).collect();
    for (p, t) in corners {
        assert_eq!(p.truncate(), t, "OBJ t runs up like y here");
    }
    let texture = &quad.diffuse_map.as_ref().unwrap().texture;
    assert_eq!((texture.width(), texture.height()), (3, 2));
}

#[test]
fn clamp_option_selects_clamp_to_edge_and_other_options_warn() {
    let mtl = b"newmtl m\nmap_Kd -clamp on -s 2 2 1 t.png\n";
    let dir = fixture("clamp", &[("quad.obj", QUAD_OBJ), ("quad.mtl", mtl), ("t.png", &png_3x2())]);
    let (meshes, warnings) = load_obj_with_warnings(&dir.join("quad.obj")).unwrap();
    let map = check_one_mesh(&meshes).diffuse_map.as_ref().unwrap();
    assert_eq!((map.sampler.wrap_s, map.sampler.wrap_t), (Wrap::ClampToEdge, Wrap::ClampToEdge));
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    check_message(&warnings[0], &["quad.mtl", "material 'm'", "option '-s 2 2 1' is not supported"]);
}

#[test]
fn a_missing_texture_warns_and_falls_back_to_kd() {
    let dir = fixture(
        "missing",
        &[("quad.obj", QUAD_OBJ), ("quad.mtl", b"newmtl m\nKd 0.2 0.4 0.6\nmap_Kd gone.png\n")],
    );
    let (meshes, warnings) = load_obj_with_warnings(&dir.join("quad.obj")).unwrap();
    let quad = check_one_mesh(&meshes);
    assert!(quad.diffuse_map.is_none());
    assert_eq!(quad.uvs.len(), 4, "the coordinates are still the model's");
    assert_eq!(quad.material.kd, Vec3::new(0.2, 0.4, 0.6));
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    check_message(&warnings[0], &["gone.png", "cannot read texture", "drawn untextured"]);
}

#[test]
fn a_corrupt_texture_is_an_error_naming_the_image() {
    let dir = fixture(
        "corrupt",
        &[
            ("quad.obj", QUAD_OBJ),
            ("quad.mtl", b"newmtl m\nmap_Kd bad.png\n"),
            ("bad.png", b"not a png at all"),
        ],
    );
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(&e, &["bad.png", "cannot decode image"]);
    let dir = fixture(
        "unknown",
        &[("quad.obj", QUAD_OBJ), ("quad.mtl", b"newmtl m\nmap_Kd bad.tex\n"), ("bad.tex", b"??")],
    );
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(&e, &["bad.tex", "not a PNG or JPEG image"]);
    let mut truncated = png_3x2();
    truncated.truncate(60);
    let dir = fixture(
        "truncated",
        &[("quad.obj", QUAD_OBJ), ("quad.mtl", b"newmtl m\nmap_Kd cut.png\n"), ("cut.png", &truncated)],
    );
    let e = load_obj(&dir.join("quad.obj")).unwrap_err().to_string();
    check_message(&e, &["cut.png", "cannot decode image"]);
}

#[test]
fn a_map_without_texture_coordinates_warns() {
    let obj = b"mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl m\nf 1 2 3\n";
    let dir = fixture(
        "no_vt",
        &[("tri.obj", obj), ("quad.mtl", b"newmtl m\nmap_Kd t.png\n"), ("t.png", &png_3x2())],
    );
    let (meshes, warnings) = load_obj_with_warnings(&dir.join("tri.obj")).unwrap();
    let tri = check_one_mesh(&meshes);
    assert!(tri.uvs.is_empty() && tri.diffuse_map.is_none());
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    check_message(&warnings[0], &["tri.obj", "diffuse map but no texture coordinates"]);
}

#[test]
fn an_image_shared_by_materials_is_decoded_once() {
    let obj = b"mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n\
usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 3/3 2/2 1/1\n";
    let mtl = b"newmtl a\nmap_Kd t.png\nnewmtl b\nKd 0 1 0\nmap_Kd -clamp on t.png\n";
    let dir = fixture("shared", &[("two.obj", obj), ("quad.mtl", mtl), ("t.png", &png_3x2())]);
    let meshes = load_obj(&dir.join("two.obj")).unwrap();
    assert_eq!(meshes.len(), 2);
    let [a, b] = [0, 1].map(|i| meshes[i].diffuse_map.clone().unwrap());
    assert!(Arc::ptr_eq(&a.texture, &b.texture));
    assert_ne!(a.sampler, b.sampler, "the sampler is the material's own");
}
