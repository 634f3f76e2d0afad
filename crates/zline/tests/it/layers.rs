//! `--transparent`, `--depth-image`, `--normal-image` and `--id-image`: what the files
//! hold, and the usage errors.

use zline::io::load_scene;
use zline::pipeline::{render, RenderOptions};

use crate::{check_error_line, check_png, repo, zline};

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
fn the_id_image_is_the_libraries_object_ids() {
    let dir = tempfile::tempdir().unwrap();
    let (out, ids) = (dir.path().join("a.png"), dir.path().join("ids.png"));
    let run =
        zline(&["demo", "-o", out.to_str().unwrap(), "--size", "80x60", "--id-image", ids.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    let mut scene = zline::scenes::demo_scene();
    (scene.settings.width, scene.settings.height) = (80, 60);
    let (want, _) = zline::pipeline::render_object_ids(&scene, &RenderOptions::default()).unwrap();
    let png = image::open(&ids).unwrap();
    assert_eq!(png.color(), image::ColorType::Rgb8);
    let got: Vec<i32> = png
        .to_rgb8()
        .pixels()
        .map(|p| i32::from(p[0]) + 256 * i32::from(p[1]) + 65536 * i32::from(p[2]) - 1)
        .collect();
    assert_eq!(got, want.ids);
    let seen = want.ids.iter().filter(|&&i| i >= 0).collect::<std::collections::BTreeSet<_>>().len();
    assert!(seen > 3, "{seen}");
    assert!(stderr.contains(&format!("{seen} of {} objects seen", scene.objects.len())), "{stderr}");
}

#[test]
fn overdraw_shows_what_the_top_left_rule_prevents() {
    let dir = tempfile::tempdir().unwrap();
    let (out, heat) = (dir.path().join("a.png"), dir.path().join("heat.png"));
    let scene = repo().join("docs/course/scenes/pixel_grid.toml");
    let run_rule = |rule: &str| {
        let run = zline(&[
            "render",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--overdraw",
            heat.to_str().unwrap(),
            "--tie-rule",
            rule,
        ]);
        let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
        assert!(run.status.success(), "{stderr}");
        let png = image::open(&heat).unwrap().to_rgb8();
        assert_eq!(png.dimensions(), (64, 64));
        let level = |l: usize| png.pixels().filter(|p| p.0 == zline::layers::HEAT[l]).count();
        (stderr, [level(0), level(1), level(2)])
    };
    // The 8 × 8 cells' diagonals run through 8 sample centres each: 512
    // samples on shared edges, drawn once, twice or never.
    let (_, levels) = run_rule("top-left");
    assert_eq!(levels, [0, 64 * 64, 0]);
    let (stderr, levels) = run_rule("closed");
    assert_eq!(levels, [0, 64 * 64 - 512, 512]);
    assert!(stderr.contains("512 fragments more and 0 fewer"), "{stderr}");
    let (stderr, levels) = run_rule("open");
    assert_eq!(levels, [512, 64 * 64 - 512, 0]);
    assert!(stderr.contains("0 fragments more and 512 fewer"), "{stderr}");
    // --tie-rule is an option of --overdraw.
    let run = zline(&["render", scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "--tie-rule", "open"]);
    assert_eq!(run.status.code(), Some(2));
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

#[test]
fn scene_files_set_a_transparent_background() {
    let dir = tempfile::tempdir().unwrap();
    let scene = repo().join("tests/scenes/wireframe_cube_dashed.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    let file = dir.path().join("t.toml");
    std::fs::write(&file, text.replace("[render]\n", "[render]\ntransparent_background = true\n")).unwrap();
    let loaded = load_scene(&file).unwrap();
    assert!(loaded.settings.transparent_background);
    let image = render(&loaded, &RenderOptions::default()).0;
    assert!(image.transparent);
    assert_eq!(image.alpha(0, 0), 0);
    // The same frame opaque: every pixel with any alpha keeps its colour
    // where the alpha is 255 (drawn without a partial cover).
    let opaque = render(&load_scene(&scene).unwrap(), &RenderOptions::default()).0;
    for y in 0..image.height {
        for x in 0..image.width {
            if image.alpha(x, y) == 255 {
                assert_eq!(image.pixel(x, y), opaque.pixel(x, y), "({x}, {y})");
            }
        }
    }
    std::fs::write(&file, text.replace("[render]\n", "[render]\ntransparent_background = 1\n")).unwrap();
    let err = load_scene(&file).unwrap_err().to_string();
    assert!(err.contains("boolean") && err.contains("t.toml") && err.contains("line 6"), "{err}");
    // The setting with JPEG output: refused when writing, naming the reason.
    let jpg = dir.path().join("t.jpg");
    std::fs::write(&file, text.replace("[render]\n", "[render]\ntransparent_background = true\n")).unwrap();
    let run = zline(&["render", file.to_str().unwrap(), "-o", jpg.to_str().unwrap()]);
    check_error_line(&run, 1, &["t.jpg", "alpha"]);
}
