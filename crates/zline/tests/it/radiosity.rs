//! `--renderer radiosity`: the solver from the command line.

use std::path::Path;
use std::process::Output;

use crate::{check_clean_error, check_error_line, check_png, repo, zline};

/// `zline render` of the Cornell box by radiosity into `png` at `size`,
/// with `extra` flags.
fn cornell(png: &Path, size: &str, extra: &[&str]) -> Output {
    let scene = repo().join("assets/cornell/cornell_box.toml");
    let mut args = vec!["render", scene.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", size];
    args.extend(["--renderer", "radiosity"]);
    args.extend(extra);
    zline(&args)
}

#[test]
fn the_cornell_box_by_radiosity_is_the_same_for_any_thread_count_and_bleeds() {
    let dir = tempfile::tempdir().unwrap();
    let run = |png: &Path, threads: &str, solver: &str| {
        cornell(png, "128x128", &["--patch-size", "120", "--solver", solver, "--threads", threads])
    };
    let (one, two) = (dir.path().join("one.png"), dir.path().join("two.png"));
    let (a, b) = (run(&one, "1", "progressive"), run(&two, "2", "progressive"));
    let img = check_png(&a, &one, (128, 128));
    check_png(&b, &two, (128, 128));
    let said = String::from_utf8_lossy(&a.stderr);
    assert!(
        said.contains("radiosity:") && said.contains("patches") && said.contains("progressive"),
        "{said}"
    );
    assert_eq!(std::fs::read(&one).unwrap(), std::fs::read(&two).unwrap(), "PNG bytes differ across threads");
    // The left (red) wall reddens, the right (green) one greens.
    let (left, right) = (img.get_pixel(8, 64), img.get_pixel(119, 64));
    assert!(left[0] > 2 * left[1] && right[1] > 2 * right[0], "{left:?} {right:?}");
    // The sweeps converge to a picture like it.
    let jacobi = dir.path().join("jacobi.png");
    let c = run(&jacobi, "2", "gauss-seidel");
    check_png(&c, &jacobi, (128, 128));
}

#[test]
fn radiosity_flags_without_radiosity_and_a_billion_patches_are_clean_errors() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("out.png");
    let cornell = repo().join("assets/cornell/cornell_box.toml");
    let out =
        zline(&["render", cornell.to_str().unwrap(), "-o", png.to_str().unwrap(), "--patch-size", "10"]);
    check_clean_error(&out, &["--patch-size", "--renderer radiosity"]);
    let out = zline(&[
        "render",
        cornell.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--renderer",
        "radiosity",
        "--patch-size",
        "0.001",
    ]);
    check_clean_error(&out, &["patches", "more than", "--patch-size"]);
}

#[test]
fn a_cached_solution_is_reused_and_a_turntable_solves_once() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cornell.radiosity");
    let render = |png: &Path| {
        cornell(png, "96x96", &["--patch-size", "150", "--radiosity-cache", cache.to_str().unwrap()])
    };
    let (first, second, third) =
        (dir.path().join("1.png"), dir.path().join("2.png"), dir.path().join("3.png"));
    let a = render(&first);
    check_png(&a, &first, (96, 96));
    assert!(cache.exists());
    let b = render(&second);
    check_png(&b, &second, (96, 96));
    let said = String::from_utf8_lossy(&b.stderr);
    assert!(said.contains("read from"), "{said}");
    assert_eq!(std::fs::read(&first).unwrap(), std::fs::read(&second).unwrap());
    // A damaged file: a warning, solved again, the same picture.
    std::fs::write(&cache, b"zline radiosity 2\nshort").unwrap();
    let c = render(&third);
    check_png(&c, &third, (96, 96));
    let said = String::from_utf8_lossy(&c.stderr);
    assert!(
        said.contains("warning") && said.contains("cut short") && said.contains("solving again"),
        "{said}"
    );
    assert_eq!(std::fs::read(&first).unwrap(), std::fs::read(&third).unwrap());
    // Subdivided: the cuts are kept with the radiosities and replayed.
    let cut = dir.path().join("cut.radiosity");
    let subdivided = |png: &Path| {
        let extra = ["--patch-size", "150", "--subdivide", "1", "--radiosity-cache", cut.to_str().unwrap()];
        cornell(png, "96x96", &extra)
    };
    let (fourth, fifth) = (dir.path().join("4.png"), dir.path().join("5.png"));
    let d = subdivided(&fourth);
    check_png(&d, &fourth, (96, 96));
    let said = String::from_utf8_lossy(&d.stderr);
    assert!(said.contains("subdivision levels"), "{said}");
    let e = subdivided(&fifth);
    check_png(&e, &fifth, (96, 96));
    let said = String::from_utf8_lossy(&e.stderr);
    assert!(said.contains("read from"), "{said}");
    assert_eq!(std::fs::read(&fourth).unwrap(), std::fs::read(&fifth).unwrap());
    // A turntable of three frames: one solve.
    let gif = dir.path().join("turn.gif");
    let scene = repo().join("assets/cornell/cornell_box.toml");
    let out = zline(&[
        "turntable",
        scene.to_str().unwrap(),
        "-o",
        gif.to_str().unwrap(),
        "--frames",
        "3",
        "--size",
        "64x64",
        "--renderer",
        "radiosity",
        "--patch-size",
        "150",
    ]);
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{said}");
    assert_eq!(said.matches("radiosity:").count(), 1, "{said}");
}

#[test]
fn the_scenes_lights_shoot_unless_the_scene_file_or_the_flag_turns_them_off() {
    let dir = tempfile::tempdir().unwrap();
    // A grey floor and a cube under a point light, nothing emitting.
    let scene = dir.path().join("lit.toml");
    std::fs::write(
        &scene,
        r#"
background = [0, 0, 0]
[render]
renderer = "radiosity"
[radiosity]
patch_size = 1.0
hemicube = 32
lights = false
[camera]
eye = [0, 4, 6]
[[lights]]
type = "point"
position = [1, 3, 1]
[[objects]]
primitive = "plane"
size = 6
[[objects]]
primitive = "cube"
translate = [0, 0.5, 0]
"#,
    )
    .unwrap();
    let render = |png: &Path, extra: &[&str]| {
        let mut args =
            vec!["render", scene.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "48x48"];
        args.extend(extra);
        zline(&args)
    };
    let (off, on) = (dir.path().join("off.png"), dir.path().join("on.png"));
    let a = render(&off, &[]);
    let dark = check_png(&a, &off, (48, 48));
    let said = String::from_utf8_lossy(&a.stderr);
    assert!(said.contains("nothing lights the scene") && said.contains("lights are off"), "{said}");
    assert!(dark.pixels().all(|p| p[0] == 0 && p[1] == 0 && p[2] == 0), "lit without a source");
    let b = render(&on, &["--radiosity-lights", "on"]);
    let lit = check_png(&b, &on, (48, 48));
    let said = String::from_utf8_lossy(&b.stderr);
    assert!(!said.contains("nothing lights"), "{said}");
    assert!(lit.pixels().filter(|p| p[0] > 40).count() > 48 * 48 / 4, "the floor is lit");
    // Near form factors from the contour integral: lit all the same.
    let near = dir.path().join("near.png");
    let c = render(&near, &["--radiosity-lights", "on", "--analytic-near"]);
    let analytic = check_png(&c, &near, (48, 48));
    assert!(analytic.pixels().filter(|p| p[0] > 40).count() > 48 * 48 / 4, "the floor is lit");
    // A bad value for the flag, and in the scene file: clean errors.
    check_error_line(&render(&on, &["--radiosity-lights", "maybe"]), 2, &["on or off"]);
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[radiosity]\nhemicube = 1\n").unwrap();
    let out = zline(&["render", bad.to_str().unwrap(), "-o", on.to_str().unwrap()]);
    check_clean_error(&out, &["radiosity.hemicube", "2..=2048"]);
}
