//! `--renderer raytrace`: the ray tracer from the command line.

use crate::{check_clean_error, check_png, repo, zline};

#[test]
fn the_demo_ray_traces_the_same_for_any_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    let (one, two) = (dir.path().join("one.png"), dir.path().join("two.png"));
    let run = |png: &std::path::Path, threads: &str| {
        zline(&[
            "demo",
            "-o",
            png.to_str().unwrap(),
            "--size",
            "160x90",
            "--renderer",
            "raytrace",
            "--threads",
            threads,
        ])
    };
    let (a, b) = (run(&one, "1"), run(&two, "2"));
    let img = check_png(&a, &one, (160, 90));
    check_png(&b, &two, (160, 90));
    let said = String::from_utf8_lossy(&a.stderr);
    assert!(said.contains("ray traced") && said.contains("shadow rays"), "{said}");
    assert_eq!(std::fs::read(&one).unwrap(), std::fs::read(&two).unwrap(), "PNG bytes differ");
    let distinct: std::collections::HashSet<_> = img.pixels().collect();
    assert!(distinct.len() > 100, "the ray-traced demo looks empty ({} colours)", distinct.len());
}

#[test]
fn ray_tracing_flags_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("out.png");
    let out = png.to_str().unwrap();
    check_clean_error(&zline(&["demo", "-o", out, "--ray-depth", "3"]), &["--renderer raytrace"]);
    let model = repo().join("assets/obj/suzanne/suzanne.obj");
    check_clean_error(
        &zline(&["turntable", model.to_str().unwrap(), "-o", out, "--renderer", "raytrace"]),
        &["rasterizes only"],
    );
    check_clean_error(
        &zline(&["demo", "-o", out, "--renderer", "raytrace", "--depth-image", "d.png"]),
        &["raytrace"],
    );
    // A depth of a billion is clamped with a warning, and the image is written.
    let deep =
        zline(&["demo", "-o", out, "--size", "32x18", "--renderer", "raytrace", "--ray-depth", "1000000000"]);
    check_png(&deep, &png, (32, 18));
    assert!(String::from_utf8_lossy(&deep.stderr).contains("warning: a ray-tracing depth of 1000000000"));
    check_clean_error(
        &zline(&["demo", "-o", out, "--renderer", "raytrace", "--rays-per-axis", "3", "--adaptive-aa"]),
        &["two ways to anti-alias"],
    );
    check_clean_error(&zline(&["demo", "-o", out, "--aa-depth", "2"]), &["--renderer raytrace"]);
}

/// Adaptive supersampling traces the corners and centres, more where the
/// image has edges, and never more than its depth allows.
#[test]
fn adaptive_supersampling_from_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("out.png");
    let out = png.to_str().unwrap();
    let run = zline(&["demo", "-o", out, "--size", "64x36", "--renderer", "raytrace", "--aa-depth", "2"]);
    check_png(&run, &png, (64, 36));
    let said = String::from_utf8_lossy(&run.stderr);
    let camera: u64 = said
        .split(" camera")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no camera ray count in {said}"));
    let corners_and_centres = 65 * 37 + 64 * 36;
    // Two cuts: the centre, 4 midpoints, and per quarter its centre and
    // 4 midpoints.
    let most = 65 * 37 + 64 * 36 * (1 + 4 + 4 * 5);
    assert!(camera > corners_and_centres && camera <= most, "{camera} camera rays: {said}");
}

/// Whitted's scene: the ray tracer shows the floor in the mirror sphere,
/// where the rasterizer draws its dark plastic.
#[test]
fn the_mirror_of_the_whitted_scene_reflects_the_floor() {
    let dir = tempfile::tempdir().unwrap();
    let (traced, raster) = (dir.path().join("traced.png"), dir.path().join("raster.png"));
    let size = (160, 120);
    let run = |png: &std::path::Path, extra: &[&str]| {
        let mut args = vec!["demo", "--scene", "whitted", "-o", png.to_str().unwrap(), "--size", "160x120"];
        args.extend_from_slice(extra);
        check_png(&zline(&args), png, size)
    };
    let (t, r) = (run(&traced, &["--renderer", "raytrace"]), run(&raster, &[]));
    // The mirror's lower half, projected: below its centre by 0.6 radius.
    let scene = zline::scenes::whitted_scene();
    let m = &scene.objects[1];
    let centre = m.world_from_object.transform_point3(glam::Vec3::ZERO);
    let below = m.world_from_object.transform_point3(glam::Vec3::new(0.0, -0.6, 0.0));
    let aspect = size.0 as f32 / size.1 as f32;
    let clip_from_world = scene.camera.clip_from_eye(aspect) * scene.camera.eye_from_world();
    let pixel = |p: glam::Vec3| {
        let nc = clip_from_world.project_point3(p);
        (((nc.x + 1.0) * 0.5 * size.0 as f32) as u32, ((1.0 - nc.y) * 0.5 * size.1 as f32) as u32)
    };
    let (x, y) = pixel(below);
    let (cx, _) = pixel(centre);
    assert!(x.abs_diff(cx) <= 1);
    let warm = |p: &image::Rgb<u8>| p[0] > 120 && i32::from(p[0]) - i32::from(p[2]) > 80;
    let count = |img: &image::RgbImage| (0..5).filter(|d| warm(img.get_pixel(x + d - 2, y))).count();
    assert_eq!(count(&r), 0, "the rasterized mirror is dark plastic");
    assert!(count(&t) >= 3, "the traced mirror shows the red and yellow floor: {:?}", t.get_pixel(x, y));
}

/// A scene file's `renderer = "raytrace"` and `[raytrace]` table pick the
/// ray tracer and its settings; `--renderer raster` wins over the file,
/// and ray-tracing flags on a rasterized scene file are refused.
#[test]
fn a_scene_file_asks_for_the_ray_tracer() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, head: &str| {
        let path = dir.path().join(name);
        let text = format!(
            "{head}\n[[objects]]\nprimitive = \"sphere\"\n[objects.material]\nkr = [0.5, 0.5, 0.5]\n"
        );
        std::fs::write(&path, text).unwrap();
        path
    };
    let traced = write("traced.toml", "[render]\nrenderer = \"raytrace\"\n[raytrace]\ndepth = 1");
    let raster = write("raster.toml", "");
    let png = dir.path().join("out.png");
    let out = png.to_str().unwrap();
    let run = |scene: &std::path::Path, extra: &[&str]| {
        let mut args = vec!["render", scene.to_str().unwrap(), "-o", out, "--size", "24x16"];
        args.extend_from_slice(extra);
        zline(&args)
    };
    let t = run(&traced, &[]);
    check_png(&t, &png, (24, 16));
    let said = String::from_utf8_lossy(&t.stderr);
    assert!(said.contains("ray traced") && said.contains("0 reflected"), "depth 1 from the file: {said}");
    let deeper = run(&traced, &["--ray-depth", "2"]);
    check_png(&deeper, &png, (24, 16));
    assert!(!String::from_utf8_lossy(&deeper.stderr).contains(" 0 reflected"), "the flag wins");
    let r = run(&traced, &["--renderer", "raster"]);
    check_png(&r, &png, (24, 16));
    assert!(!String::from_utf8_lossy(&r.stderr).contains("ray traced"));
    check_clean_error(&run(&raster, &["--ray-depth", "2"]), &["need --renderer raytrace", "scene file"]);
}

/// Every acceleration structure gives the same image, byte for byte.
#[test]
fn every_structure_draws_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let bytes: Vec<Vec<u8>> = ["bvh", "kd", "grid", "none"]
        .iter()
        .map(|accel| {
            let png = dir.path().join(format!("{accel}.png"));
            let args = [
                "demo",
                "-o",
                png.to_str().unwrap(),
                "--size",
                "96x54",
                "--renderer",
                "raytrace",
                "--accel",
                accel,
            ];
            check_png(&zline(&args), &png, (96, 54));
            std::fs::read(&png).unwrap()
        })
        .collect();
    for (accel, b) in ["kd", "grid", "none"].iter().zip(&bytes[1..]) {
        assert!(*b == bytes[0], "--accel {accel} draws another image than the BVH");
    }
}

/// The shipped Cornell box loads and draws its red left and green right
/// walls, ray-traced and rasterized.
#[test]
fn the_cornell_box_draws_its_coloured_walls() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("cornell.png");
    let scene = repo().join("assets/cornell/cornell_box.toml");
    for extra in [&["--renderer", "raytrace"][..], &[][..]] {
        let mut args =
            vec!["render", scene.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "64x64"];
        args.extend_from_slice(extra);
        let img = check_png(&zline(&args), &png, (64, 64));
        let (left, right) = (img.get_pixel(4, 32), img.get_pixel(59, 32));
        assert!(left[0] > 2 * left[1] && left[0] > 40, "{extra:?}: left wall {left:?}");
        assert!(right[1] > 2 * right[0] && right[1] > 40, "{extra:?}: right wall {right:?}");
    }
}
