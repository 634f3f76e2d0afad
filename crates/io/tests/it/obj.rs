//! OBJ loading: every malformed input gives a located, one-line error and
//! never a panic; good files give valid meshes.

use glam::Vec3;
use zline_io::{load_obj, load_obj_with_warnings};
use zline_scene::Material;

use crate::{check_message, data, repo};

#[track_caller]
fn check_obj_error(file: &str, parts: &[&str]) {
    let e = load_obj(&data(file)).expect_err("the file must not load");
    let message = e.to_string();
    check_message(&message, &[&[file][..], parts].concat());
}

#[test]
fn garbage_lines_are_located() {
    check_obj_error("garbage.obj", &["line 7: unknown statement 'this' in 'this is not obj'"]);
}

#[test]
fn bad_numbers_are_located() {
    check_obj_error("bad_number.obj", &["line 7: cannot parse vertex position 'v 1.0 abc 2'"]);
}

#[test]
fn face_indices_out_of_range_are_located() {
    check_obj_error(
        "index_out_of_range.obj",
        &["line 5: face refers to vertex 9, but the file defines 3 before this line: 'f 1 2 9'"],
    );
}

#[test]
fn texture_index_zero_does_not_reach_tobj() {
    // tobj would silently take index 0 as "no texture coordinate".
    check_obj_error("texcoord_index_zero.obj", &["line 7: face refers to texture coordinate 0"]);
}

#[test]
fn nan_coordinates_are_located() {
    check_obj_error("nan.obj", &["line 3: vertex has non-finite coordinate 'nan'"]);
}

#[test]
fn files_without_triangles_are_rejected() {
    check_obj_error("empty.obj", &["no triangles"]);
    check_obj_error("zero_bytes.obj", &["no triangles"]);
}

#[test]
fn missing_files_are_named() {
    check_obj_error("does_not_exist.obj", &["cannot read file", "No such file or directory"]);
}

#[test]
fn directories_and_binary_files_are_rejected() {
    let e = load_obj(&data("")).unwrap_err().to_string();
    check_message(&e, &["data", "is a directory, not a file"]);
    let e = load_obj(&repo("assets/obj/spot/spot_texture.png")).unwrap_err().to_string();
    check_message(&e, &["spot_texture.png", "not an OBJ"]);
}

#[test]
fn huge_coordinates_load_with_unit_normals() {
    let meshes = load_obj(&data("huge.obj")).unwrap();
    assert_eq!(meshes.len(), 1);
    let mesh = &meshes[0];
    assert_eq!(mesh.triangle_count(), 4);
    assert!(mesh.positions.iter().all(|p| p.is_finite() && p.abs().max_element() == 1e30));
    for n in &mesh.normals {
        assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-5, "{n}");
    }
    assert!(mesh.is_closed());
}

#[test]
fn missing_mtl_warns_and_uses_the_default_material() {
    let (meshes, warnings) = load_obj_with_warnings(&data("missing_mtl.obj")).unwrap();
    assert_eq!(meshes[0].material, Material::DEFAULT);
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    check_message(&warnings[0], &["nowhere.mtl", "cannot read material library", "default material"]);
}

#[test]
fn broken_mtl_warns_instead_of_panicking() {
    let (meshes, warnings) = load_obj_with_warnings(&data("broken_mtl.obj")).unwrap();
    assert_eq!(meshes[0].material, Material::DEFAULT);
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    check_message(&warnings[0], &["broken.mtl", "line 3", "a colour needs 3 numbers in 'Kd 0.5 0.5'"]);
}

#[test]
fn groups_and_materials_become_meshes() {
    let (meshes, warnings) = load_obj_with_warnings(&data("two.obj")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let names: Vec<&str> = meshes.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["first", "second"]);
    let (red, glass) = (meshes[0].material, meshes[1].material);
    assert_eq!((red.ka, red.kd, red.ns), (Vec3::new(0.1, 0.0, 0.0), Vec3::new(0.8, 0.1, 0.1), 50.0));
    assert_eq!((glass.kd, glass.ka, glass.opacity), (Vec3::splat(0.5), Vec3::splat(0.5), 0.25));
    // A quad and a pentagon, fan-triangulated.
    assert_eq!((meshes[0].triangle_count(), meshes[1].triangle_count()), (2, 3));
    // The file's normals (0, 0, 2) are re-normalized; the second group's are computed.
    assert!(meshes.iter().all(|m| m.normals.iter().all(|&n| (n - Vec3::Z).length() < 1e-6)));
}

#[test]
fn shipped_models_load() {
    let suzanne = load_obj(&repo("assets/obj/suzanne/suzanne.obj")).unwrap();
    assert_eq!(suzanne.iter().map(|m| m.triangle_count()).sum::<usize>(), 968);
    let (spot, warnings) = load_obj_with_warnings(&repo("assets/obj/spot/spot.obj")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(spot.iter().map(|m| m.triangle_count()).sum::<usize>(), 5856);
    assert_eq!(spot[0].material.ka, Vec3::splat(0.1));
    assert!(spot[0].is_closed(), "Spot is a closed genus-0 mesh");
    for mesh in suzanne.iter().chain(&spot) {
        assert!(mesh.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
    }
}
