//! Bad model files: a clear one-line error naming the file, or a
//! well-defined image — never a panic.

use std::path::PathBuf;

use crate::{check_clean_error, check_png, zline};

fn write(dir: &tempfile::TempDir, name: &str, text: &str) -> PathBuf {
    let p = dir.path().join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn render(model: &std::path::Path, png: &std::path::Path) -> std::process::Output {
    zline(&["render", model.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "64x48"])
}

#[test]
fn malformed_obj() {
    let dir = tempfile::tempdir().unwrap();
    let model = write(&dir, "broken.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n");
    let out = render(&model, &dir.path().join("o.png"));
    check_clean_error(&out, &["broken.obj", "line 2"]);
}

#[test]
fn face_index_out_of_range() {
    let dir = tempfile::tempdir().unwrap();
    let model = write(&dir, "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    let out = render(&model, &dir.path().join("o.png"));
    check_clean_error(&out, &["range.obj"]);
}

#[test]
fn missing_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = render(&dir.path().join("nowhere.obj"), &dir.path().join("o.png"));
    check_clean_error(&out, &["nowhere.obj", "cannot read file"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.matches("os error").count(), 1, "the cause is repeated: {stderr}");
}

#[test]
fn nan_coordinates() {
    let dir = tempfile::tempdir().unwrap();
    let model = write(&dir, "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
    let out = render(&model, &dir.path().join("o.png"));
    check_clean_error(&out, &["nan.obj", "line 3"]);
}

#[test]
fn huge_coordinates_give_a_well_defined_image() {
    let dir = tempfile::tempdir().unwrap();
    let text =
        "v -1e30 -1e30 0\nv 1e30 -1e30 0\nv 0 1e30 1e30\nv 0 0 -1e30\nf 1 2 3\nf 1 3 4\nf 2 4 3\nf 1 4 2\n";
    let model = write(&dir, "huge.obj", text);
    let png = dir.path().join("o.png");
    let img = check_png(&render(&model, &png), &png, (64, 48));
    let background = *img.get_pixel(0, 0);
    assert!(img.pixels().any(|p| *p != background), "the framed model is not visible");
}

#[test]
fn empty_obj() {
    let dir = tempfile::tempdir().unwrap();
    let model = write(&dir, "empty.obj", "# nothing here\n");
    let out = render(&model, &dir.path().join("o.png"));
    check_clean_error(&out, &["empty.obj", "no triangles"]);
}
