//! Camera flags and the framing of bare models.

use crate::{check_error_line, check_png, repo, zline};

/// Renders `args` after `render MODEL -o OUT --size WxH` and returns the image.
fn render(model: &str, size: (u32, u32), args: &[&str]) -> image::RgbImage {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("out.png");
    let model = repo().join(model);
    let size_arg = format!("{}x{}", size.0, size.1);
    let mut all = vec!["render", model.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", &size_arg];
    all.extend_from_slice(args);
    let out = zline(&all);
    check_png(&out, &png, size)
}

/// The model's pixels: those unlike the top-left corner.
fn covered(img: &image::RgbImage) -> Vec<(u32, u32)> {
    let background = *img.get_pixel(0, 0);
    img.enumerate_pixels().filter(|(_, _, p)| **p != background).map(|(x, y, _)| (x, y)).collect()
}

#[test]
fn a_framed_model_fills_the_frame_in_any_shape_and_stays_inside() {
    for size in [(160, 120), (240, 80), (80, 200)] {
        let img = render("assets/obj/spot/spot.obj", size, &[]);
        let pixels = covered(&img);
        let (w, h) = size;
        let x_span =
            pixels.iter().map(|p| p.0).max().unwrap() - pixels.iter().map(|p| p.0).min().unwrap() + 1;
        let y_span =
            pixels.iter().map(|p| p.1).max().unwrap() - pixels.iter().map(|p| p.1).min().unwrap() + 1;
        // Tight: one axis spans at least 85 % of the frame (the margin is
        // 5 % of each half); inside: no pixel on the border.
        assert!(x_span * 100 >= 85 * w || y_span * 100 >= 85 * h, "{size:?}: spans {x_span} × {y_span}");
        assert!(
            pixels.iter().all(|&(x, y)| x > 0 && y > 0 && x < w - 1 && y < h - 1),
            "{size:?}: touches the border"
        );
    }
}

#[test]
fn camera_flags_move_the_camera_and_bad_values_are_reported() {
    let base = render("assets/obj/suzanne/suzanne.obj", (96, 72), &[]);
    let turned =
        render("assets/obj/suzanne/suzanne.obj", (96, 72), &["--azimuth", "-90", "--elevation", "20"]);
    assert_ne!(base, turned, "--azimuth and --elevation change the view");
    let near = render("assets/obj/suzanne/suzanne.obj", (96, 72), &["--zoom", "2"]);
    assert!(covered(&near).len() > covered(&base).len(), "--zoom 2 makes the model larger");
    let far = render("assets/obj/suzanne/suzanne.obj", (96, 72), &["--distance", "40"]);
    assert!(covered(&far).len() * 4 < covered(&base).len(), "--distance 40 makes it small");
    let wide = render("assets/obj/suzanne/suzanne.obj", (96, 72), &["--fov", "90", "--background", "1,0,0"]);
    assert_eq!(wide.get_pixel(0, 0).0, [255, 0, 0], "--background");
    for (flag, value, needle) in [
        ("--zoom", "0", "expected a number > 0"),
        ("--fov", "180", "1..=179"),
        ("--up", "0,0,0", "not all zero"),
        ("--azimuth", "east", "expected an angle"),
        ("--background", "2,0,0", "each in [0, 1]"),
    ] {
        let out = zline(&["render", "m.obj", "-o", "o.png", flag, value]);
        check_error_line(&out, 2, &[flag, needle]);
    }
}
