//! `--transparent`, `--depth-image` and `--normal-image`: what the files
//! hold, and the usage errors.

use crate::{check_error_line, check_png, zline};

#[test]
fn demo_writes_rgba_depth_and_normals() {
    let dir = tempfile::tempdir().unwrap();
    let (out, depth, normals) =
        (dir.path().join("a.png"), dir.path().join("d.png"), dir.path().join("n.png"));
    let (o, d, n) = (out.to_str().unwrap(), depth.to_str().unwrap(), normals.to_str().unwrap());
    let run = zline(&[
        "demo",
        "-o",
        o,
        "--size",
        "64x48",
        "--transparent",
        "--depth-image",
        d,
        "--normal-image",
        n,
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(stderr.contains("65535 = near") && stderr.contains("1 = far"), "{stderr}");
    let rgba = image::open(&out).unwrap();
    assert_eq!(rgba.color(), image::ColorType::Rgba8);
    let rgba = rgba.to_rgba8();
    // The demo's top corner is background: transparent; its middle is drawn.
    assert_eq!(rgba.get_pixel(0, 0).0, [0, 0, 0, 0]);
    assert!(rgba.pixels().any(|p| p.0[3] == 255));
    let grey = image::open(&depth).unwrap();
    assert_eq!(grey.color(), image::ColorType::L16);
    let grey = grey.to_luma16();
    assert_eq!(grey.get_pixel(0, 0).0, [0]);
    assert!(grey.pixels().any(|p| p.0[0] == 65535) && grey.pixels().any(|p| p.0[0] == 1));
    // The normals follow --transparent: RGBA, empty where nothing is drawn.
    let normal = image::open(&normals).unwrap().to_rgba8();
    assert_eq!(normal.get_pixel(0, 0).0, [0, 0, 0, 0]);
    // Without --transparent, the same render is opaque RGB and the normals'
    // background black.
    let run = zline(&["demo", "-o", o, "--size", "64x48", "--normal-image", n]);
    let rgb = check_png(&run, &out, (64, 48));
    assert_ne!(rgb.get_pixel(0, 0).0, [0, 0, 0]);
    assert_eq!(image::open(&out).unwrap().color(), image::ColorType::Rgb8);
    let normal = image::open(&normals).unwrap();
    assert_eq!(normal.color(), image::ColorType::Rgb8);
    assert_eq!(normal.to_rgb8().get_pixel(0, 0).0, [0, 0, 0]);
}

#[test]
fn transparent_jpeg_and_non_png_layers_are_refused_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let jpg = dir.path().join("a.jpg");
    let run = zline(&["demo", "-o", jpg.to_str().unwrap(), "--transparent"]);
    check_error_line(&run, 2, &["--transparent", "JPEG"]);
    assert!(!jpg.exists());
    let png = dir.path().join("a.png");
    let depth = dir.path().join("d.jpg");
    let run = zline(&["demo", "-o", png.to_str().unwrap(), "--depth-image", depth.to_str().unwrap()]);
    check_error_line(&run, 1, &["d.jpg", "--depth-image", ".png"]);
    assert!(!png.exists());
    let missing = dir.path().join("no/such/n.png");
    let run = zline(&["demo", "-o", png.to_str().unwrap(), "--normal-image", missing.to_str().unwrap()]);
    check_error_line(&run, 1, &["n.png", "does not exist"]);
}
