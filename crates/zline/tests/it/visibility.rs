//! The painter's algorithm against the z-buffer on the documented failure
//! scene, and the scene-file keys and flags of hidden-surface and
//! hidden-line drawing.

use zline::io::load_scene;
use zline::pipeline::{render, RenderOptions};
use zline::scene::{Visibility, WireframeMode};

use crate::{check_error_line, repo, zline};

/// `tests/scenes/visibility_painter_cyclic.toml` painted and z-buffered:
/// prints the share of wrong pixels (of the pixels either image draws)
/// that docs/visibility.md quotes, and checks that each failure is there:
/// the cycle is wrong at two of its three corners, the intersecting pair
/// where the first-painted triangle is nearer.
#[test]
fn painter_share_of_wrong_pixels() {
    let path = repo().join("tests/scenes/visibility_painter_cyclic.toml");
    let painter = load_scene(&path).unwrap();
    assert_eq!(painter.settings.visibility, Visibility::Painter);
    let mut zbuffer = painter.clone();
    zbuffer.settings.visibility = Visibility::ZBuffer;
    let reference = load_scene(&repo().join("tests/scenes/visibility_zbuffer_cyclic.toml")).unwrap();
    assert_eq!(reference, zbuffer, "the two regress scenes differ only in visibility");
    let (p, z) =
        (render(&painter, &RenderOptions::default()).0, render(&zbuffer, &RenderOptions::default()).0);
    let background = p.pixels[0];
    let (mut drawn, mut wrong, mut wrong_left, mut wrong_right) = (0, 0, 0, 0);
    for y in 0..p.height {
        for x in 0..p.width {
            let i = (y * p.width + x) as usize;
            if p.pixels[i] == background && z.pixels[i] == background {
                continue;
            }
            drawn += 1;
            if p.pixels[i] != z.pixels[i] {
                wrong += 1;
                // The cycle is left of x = 0 (pixel 128), the pair right of it.
                if x < p.width / 2 {
                    wrong_left += 1
                } else {
                    wrong_right += 1
                }
            }
        }
    }
    let share = 100.0 * f64::from(wrong) / f64::from(drawn);
    println!(
        "painter vs z-buffer: {wrong} of {drawn} drawn pixels wrong ({share:.1} %): {wrong_left} in the cycle, {wrong_right} in the intersecting pair"
    );
    assert!(wrong_left > 50 && wrong_right > 200, "both failures must show");
}

#[test]
fn flags_and_keys_reach_the_settings_and_bad_values_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cube.png");
    let scene = repo().join("tests/scenes/wireframe_cube_dashed.toml");
    let loaded = load_scene(&scene).unwrap();
    assert_eq!(loaded.settings.wireframe.mode, WireframeMode::HiddenDashed);
    assert_eq!(loaded.settings.wireframe.feature_angle, Some(30.0));
    let run = zline(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--visibility",
        "painter",
        "--wireframe",
        "hidden-removed",
        "--wireframe-only",
        "--feature-angle",
        "45",
    ]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(!String::from_utf8_lossy(&run.stderr).contains("blank"), "lines alone are not a blank image");
    let bad =
        zline(&["render", scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "--feature-angle", "200"]);
    check_error_line(&bad, 2, &["200"]);
    let file = dir.path().join("bad.toml");
    let text = std::fs::read_to_string(&scene).unwrap().replace("feature_angle = 30", "feature_angle = -5");
    std::fs::write(&file, text).unwrap();
    let err = load_scene(&file).unwrap_err().to_string();
    assert!(err.contains("render.feature_angle") && err.contains("bad.toml"), "{err}");
    let text = std::fs::read_to_string(&scene).unwrap().replace("hidden-dashed", "dotted");
    std::fs::write(&file, text).unwrap();
    let err = load_scene(&file).unwrap_err().to_string();
    assert!(err.contains("dotted") && err.contains("hidden-dashed") && err.contains("bad.toml"), "{err}");
}

#[test]
fn the_z_buffer_does_not_depend_on_the_order_and_culling_only_saves_work() {
    let dir = tempfile::tempdir().unwrap();
    let bunny = repo().join("assets/ply/bunny_lowres.ply");
    let render = |name: &str, extra: &[&str]| {
        let png = dir.path().join(name);
        let mut args =
            vec!["render", bunny.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "120x90"];
        args.extend(extra);
        let out = zline(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        (std::fs::read(&png).unwrap(), String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (plain, said) = render("plain.png", &[]);
    // The `wrote` line's count: "…, 2739 drawn, …".
    let drawn = |said: &str| {
        let wrote = said.lines().find(|l| l.starts_with("wrote ")).unwrap();
        wrote.split(" drawn").next().and_then(|s| s.rsplit(' ').next()).unwrap().to_string()
    };
    for seed in ["1", "7", "12345"] {
        let (shuffled, note) = render(&format!("s{seed}.png"), &["--shuffle", seed]);
        assert_eq!(shuffled, plain, "seed {seed}: the same PNG bytes");
        assert!(note.contains("note: --shuffle"), "{note}");
    }
    // A closed model: the same picture with its back faces drawn, and
    // more triangles drawn.
    let (unculled, note) = render("unculled.png", &["--no-culling"]);
    assert_eq!(unculled, plain);
    assert!(note.contains("note: --no-culling"), "{note}");
    let (a, b) = (drawn(&said).parse::<u64>().unwrap(), drawn(&note).parse::<u64>().unwrap());
    assert!(b > a, "{a} drawn culled, {b} not");
}

/// `--timings` says how many primitives hierarchical depth skipped: a
/// sphere behind a wall drawn first has some; drawn before the wall, or
/// without `--timings`, there is no such line.
#[test]
fn timings_count_what_hierarchical_depth_skipped() {
    let dir = tempfile::tempdir().unwrap();
    let wall = "[[objects]]\nprimitive = \"plane\"\nsize = 40\nrotate = [90, 0, 0]\n";
    let sphere = "[[objects]]\nprimitive = \"sphere\"\nrings = 24\nsegments = 32\ntranslate = [0, 0, -3]\n";
    let head = "[render]\nwidth = 256\nheight = 192\n\n[camera]\neye = [0, 0, 4]\ntarget = [0, 0, 0]\n\n";
    let run = |objects: &str, timings: bool| {
        let scene = dir.path().join("wall.toml");
        std::fs::write(&scene, format!("{head}{objects}")).unwrap();
        let out = dir.path().join("wall.png");
        let mut args = vec!["render", scene.to_str().unwrap(), "-o", out.to_str().unwrap()];
        if timings {
            args.push("--timings");
        }
        let run = zline(&args);
        let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
        assert!(run.status.success(), "{stderr}");
        stderr.lines().find(|l| l.starts_with("timings: hierarchical depth:")).map(str::to_owned)
    };
    let line = run(&format!("{wall}\n{sphere}"), true).expect("a line for the sphere behind the wall");
    let n: u64 = line.split_whitespace().nth(3).and_then(|n| n.parse().ok()).expect("a count");
    assert!(n > 100, "{line}");
    assert_eq!(run(&format!("{wall}\n{sphere}"), false), None, "only with --timings");
    assert_eq!(run(&format!("{sphere}\n{wall}"), true), None, "the wall last hides nothing drawn before it");
}
