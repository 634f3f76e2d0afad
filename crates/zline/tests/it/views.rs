//! `--view`, `--projection` and `--views`: named views, orthographic
//! framing and the contact sheet; `-o -`, the image on standard output.

use std::path::Path;

use crate::{check_error_line, check_png, repo, zline};

fn bunny() -> String {
    repo().join("assets/ply/bunny_lowres.ply").to_str().unwrap().to_string()
}

fn render(png: &Path, extra: &[&str]) -> std::process::Output {
    let input = bunny();
    let mut args = vec!["render", input.as_str(), "-o", png.to_str().unwrap(), "--size", "64x48"];
    args.extend(extra);
    zline(&args)
}

/// The bounding box of the pixels that differ from the top-left one (the
/// background): (x0, y0, x1, y1).
fn drawn(img: &image::RgbImage) -> (u32, u32, u32, u32) {
    let ground = *img.get_pixel(0, 0);
    let mut b = (u32::MAX, u32::MAX, 0, 0);
    for (x, y, p) in img.enumerate_pixels() {
        if *p != ground {
            b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
        }
    }
    b
}

#[test]
fn named_views_differ_and_an_orthographic_view_fills_its_frame() {
    let dir = tempfile::tempdir().unwrap();
    let mut images = Vec::new();
    for view in ["front", "top", "iso"] {
        let png = dir.path().join(format!("{view}.png"));
        let out = render(&png, &["--view", view]);
        images.push(check_png(&out, &png, (64, 48)));
    }
    assert_ne!(images[0], images[1]);
    assert_ne!(images[1], images[2]);
    // Orthographic, framed: the model's tight box with a 5 % margin, so
    // the drawing reaches within a few pixels of two opposite edges.
    let png = dir.path().join("ortho.png");
    let ortho = check_png(&render(&png, &["--view", "front", "--projection", "ortho"]), &png, (64, 48));
    let (x0, y0, x1, y1) = drawn(&ortho);
    let fills_height = y0 <= 4 && y1 >= 43;
    let fills_width = x0 <= 5 && x1 >= 58;
    assert!(fills_height || fills_width, "drawn in {x0},{y0}..{x1},{y1}");
    // And not the perspective picture.
    assert_ne!(ortho, images[0]);
}

#[test]
fn a_contact_sheet_has_a_named_cell_per_view() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("sheet.png");
    let out = render(&png, &["--views", "front,back,top,iso"]);
    // Two columns of 64 × 48 cells under 20-pixel labels, 4-pixel gutters.
    let sheet = check_png(&out, &png, (4 + 2 * 68, 4 + 2 * (48 + 24 + 4)));
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(said.contains("4 views: front, back, top, iso"), "{said}");
    // The first cell is the --view front picture.
    let single = dir.path().join("front.png");
    let front = check_png(&render(&single, &["--view", "front"]), &single, (64, 48));
    for (x, y, p) in front.enumerate_pixels() {
        assert_eq!(sheet.get_pixel(4 + x, 4 + y), p, "at {x},{y}");
    }
    // Bad names, and commands that write no sheet: clean errors.
    check_error_line(&render(&png, &["--views", "front,sideways"]), 2, &["no view named 'sideways'"]);
    let gif = dir.path().join("t.gif");
    let input = bunny();
    let out = zline(&["turntable", &input, "-o", gif.to_str().unwrap(), "--views", "all"]);
    check_error_line(&out, 1, &["--views", "render and demo"]);
}

#[test]
fn dash_writes_the_png_to_standard_output() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("file.png");
    let file = render(&png, &[]);
    assert!(file.status.success());
    let input = bunny();
    let piped = zline(&["render", input.as_str(), "-o", "-", "--size", "64x48"]);
    assert!(piped.status.success(), "{}", String::from_utf8_lossy(&piped.stderr));
    assert_eq!(piped.stdout, std::fs::read(&png).unwrap(), "the same PNG bytes");
    assert!(String::from_utf8_lossy(&piped.stderr).contains("wrote -"));
}

#[test]
fn a_shipped_3mf_sample_renders_with_its_colours() {
    // assets/3mf/assembly.3mf: a tetrahedron coloured per triangle,
    // placed three times through components (one mirrored).
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("assembly.png");
    let input = repo().join("assets/3mf/assembly.3mf");
    let out = zline(&["render", input.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "96x96"]);
    let img = check_png(&out, &png, (96, 96));
    let ground = *img.get_pixel(0, 0);
    let colours: std::collections::HashSet<[u8; 3]> =
        img.pixels().filter(|p| **p != ground).map(|p| p.0).filter(|p| p[0].abs_diff(p[1]) > 40).collect();
    assert!(colours.len() > 10, "coloured faces drawn: {}", colours.len());
}
