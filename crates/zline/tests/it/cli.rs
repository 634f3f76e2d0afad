//! The commands README.md shows, and the promise of bit-identical output.

use crate::{check_clean_error, check_error_line, check_png, repo, zline};

#[test]
fn demo_renders_and_threads_do_not_change_the_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let one = dir.path().join("one.png");
    let two = dir.path().join("two.png");
    let a = zline(&["demo", "-o", one.to_str().unwrap(), "--size", "320x180", "--threads", "1"]);
    let b = zline(&[
        "demo",
        "-o",
        two.to_str().unwrap(),
        "--size",
        "320x180",
        "--threads",
        "2",
        "--tile-size",
        "13",
    ]);
    let img = check_png(&a, &one, (320, 180));
    check_png(&b, &two, (320, 180));
    assert_eq!(std::fs::read(&one).unwrap(), std::fs::read(&two).unwrap(), "PNG bytes differ");
    let distinct: std::collections::HashSet<_> = img.pixels().collect();
    assert!(distinct.len() > 100, "the demo looks empty ({} colours)", distinct.len());
}

#[test]
fn obj_renders_in_every_shading_mode() {
    let dir = tempfile::tempdir().unwrap();
    let model = repo().join("assets/obj/suzanne/suzanne.obj");
    for mode in ["flat", "gouraud", "phong"] {
        let png = dir.path().join(format!("{mode}.png"));
        let out = zline(&[
            "render",
            model.to_str().unwrap(),
            "-o",
            png.to_str().unwrap(),
            "--size",
            "96x64",
            "--shading",
            mode,
        ]);
        let img = check_png(&out, &png, (96, 64));
        let background = *img.get_pixel(0, 0);
        let covered = img.pixels().filter(|p| **p != background).count();
        assert!(covered > 96 * 64 / 10, "{mode}: model covers only {covered} pixels");
    }
}

#[test]
fn quiet_prints_nothing_on_success_and_still_names_errors() {
    let dir = tempfile::tempdir().unwrap();
    let (png, depth) = (dir.path().join("q.png"), dir.path().join("depth.png"));
    let model = repo().join("assets/ply/bunny_lowres.ply");
    let (model, png_arg) = (model.to_str().unwrap(), png.to_str().unwrap());
    let args = ["render", model, "-o", png_arg, "--size", "64x48", "--depth-image", depth.to_str().unwrap()];
    let loud = zline(&args);
    assert!(String::from_utf8_lossy(&loud.stderr).matches("wrote").count() == 2, "{loud:?}");
    let quiet = zline(&[&args[..], &["--quiet"]].concat());
    check_png(&quiet, &png, (64, 48));
    assert!(quiet.stderr.is_empty() && quiet.stdout.is_empty(), "{quiet:?}");
    let missing = dir.path().join("missing.obj");
    let out = zline(&["render", missing.to_str().unwrap(), "-o", png_arg, "-q"]);
    check_clean_error(&out, &["missing.obj", "cannot read file"]);
}

#[test]
fn example_scene_renders() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("scene.png");
    let scene = repo().join("examples/scene.toml");
    let args = ["render", scene.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "160x90"];
    // Its models are in assets/, outside its folder.
    let out = zline(&args);
    check_clean_error(&out, &["scene.toml", "leads outside the folder", "--allow-paths-outside"]);
    let out = zline(&[&args[..], &["--allow-paths-outside"]].concat());
    check_png(&out, &png, (160, 90));
}

#[test]
fn bad_arguments_are_reported() {
    let out = zline(&["render", "x.obj", "-o", "y.png", "--size", "0x10"]);
    assert_eq!(out.status.code(), Some(2), "clap rejects bad values with exit code 2");
    let out = zline(&["render", "model.3ds", "-o", "y.png"]);
    check_clean_error(&out, &["model.3ds", "unsupported"]);
    let out = zline(&["demo", "-o", "y.png", "--threads", "0"]);
    check_clean_error(&out, &["--threads"]);
}

#[test]
fn unwritable_output_is_a_clean_error() {
    let out = zline(&["demo", "-o", "/nonexistent-dir/x.png", "--size", "8x8"]);
    check_clean_error(&out, &["/nonexistent-dir/x.png"]);
}

#[test]
fn fog_flags_change_the_image_and_bad_ones_are_reported() {
    let dir = tempfile::tempdir().unwrap();
    let (plain, foggy) = (dir.path().join("plain.png"), dir.path().join("fog.png"));
    let size = ["--size", "160x90"];
    check_png(&zline(&[&["demo", "-o", plain.to_str().unwrap()][..], &size].concat()), &plain, (160, 90));
    let fog = ["--fog", "exp2:0.1", "--fog-color", "1,1,1", "--fog-coordinate", "radial"];
    let out = zline(&[&["demo", "-o", foggy.to_str().unwrap()][..], &size, &fog].concat());
    let (a, b) = (check_png(&out, &foggy, (160, 90)), image::open(&plain).unwrap().to_rgb8());
    let lighter = a.pixels().zip(b.pixels()).filter(|(f, p)| f[0] > p[0]).count();
    assert!(lighter > 160 * 90 / 4, "white fog lightened only {lighter} pixels");
    let out = zline(&["demo", "-o", "x.png", "--fog", "linear:9:3"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("end ≥ start"));
}

#[test]
fn the_filter_flag_changes_textured_output() {
    let dir = tempfile::tempdir().unwrap();
    let (near, tri) = (dir.path().join("nearest.png"), dir.path().join("trilinear.png"));
    let spot = repo().join("assets/obj/spot/spot.obj");
    let run = |png: &std::path::Path, filter: &str| {
        zline(&[
            "render",
            spot.to_str().unwrap(),
            "-o",
            png.to_str().unwrap(),
            "--size",
            "64x48",
            "--filter",
            filter,
        ])
    };
    check_png(&run(&near, "nearest"), &near, (64, 48));
    check_png(&run(&tri, "trilinear"), &tri, (64, 48));
    assert_ne!(std::fs::read(&near).unwrap(), std::fs::read(&tri).unwrap(), "filtering made no difference");
}

#[test]
fn convention_flags_change_the_image_and_override_the_scene_file() {
    // A transparent Gouraud sphere (culling off, so its inside shows through)
    // under a light bright enough to lift vertex colours above 1.
    let dir = tempfile::tempdir().unwrap();
    let body = "[camera]\neye = [0, 0, 4]\n\n[[lights]]\ntype = \"point\"\nposition = [1, 2, 3]\n\
                color = [2.5, 2.5, 2.5]\n\n[[objects]]\nprimitive = \"sphere\"\nrings = 8\nsegments = 12\n\
                shading = \"gouraud\"\n[objects.material]\ncolor = [0.6, 0.3, 0.2]\nks = [0.8, 0.8, 0.8]\n\
                opacity = 0.5\n";
    let plain = dir.path().join("plain.toml");
    std::fs::write(&plain, body).unwrap();
    let chosen = dir.path().join("chosen.toml");
    std::fs::write(
        &chosen,
        format!("[render]\ngouraud_clamp = \"sample\"\nlighting = \"one-sided\"\n\n{body}"),
    )
    .unwrap();
    let run = |scene: &std::path::Path, name: &str, flags: &[&str]| {
        let png = dir.path().join(name);
        let args =
            [&["render", scene.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "64x48"][..], flags];
        check_png(&zline(&args.concat()), &png, (64, 48));
        std::fs::read(&png).unwrap()
    };
    let default = run(&plain, "default.png", &[]);
    let sample = run(&plain, "sample.png", &["--gouraud-clamp", "sample"]);
    let one_sided = run(&plain, "one.png", &["--lighting", "one-sided"]);
    assert_ne!(default, sample, "--gouraud-clamp sample made no difference");
    assert_ne!(default, one_sided, "--lighting one-sided made no difference");
    let both = run(&plain, "both.png", &["--gouraud-clamp", "sample", "--lighting", "one-sided"]);
    assert_eq!(run(&chosen, "chosen.png", &[]), both, "the scene-file keys and the flags disagree");
    let overridden =
        run(&chosen, "overridden.png", &["--gouraud-clamp", "vertex", "--lighting", "two-sided"]);
    assert_eq!(overridden, default, "the flags do not override the scene file");
    let out = zline(&["demo", "-o", "x.png", "--lighting", "three-sided"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("one-sided"));
}

#[test]
fn the_shadows_flag_is_checked_and_warns_when_nothing_receives() {
    let out = zline(&["demo", "-o", "x.png", "--shadows", "bogus"]);
    check_error_line(&out, 2, &["bogus", "--shadows"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("planar"), "the valid names are listed");

    let dir = tempfile::tempdir().unwrap();
    let warning = "warning: --shadows planar: the scene has no shadow_plane objects";
    // A bare model has no shadow planes: planar shadows draw nothing, and say so.
    let suzanne = repo().join("assets/obj/suzanne/suzanne.obj");
    let png = dir.path().join("bare.png");
    let args = ["render", suzanne.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "32x24"];
    let out = zline(&[&args[..], &["--shadows", "planar"]].concat());
    check_png(&out, &png, (32, 24));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().filter(|l| *l == warning).count(), 1, "{stderr}");
    let out = zline(&[&args[..], &["--shadows", "none"]].concat());
    check_png(&out, &png, (32, 24));
    assert!(!String::from_utf8_lossy(&out.stderr).contains("warning:"));

    // A scene file with a receiving plane turns them on without a warning.
    let scene = dir.path().join("floor.toml");
    std::fs::write(
        &scene,
        "[[objects]]\nprimitive = \"plane\"\nsize = 4\ntranslate = [0, -1, 0]\nshadow_plane = true\n\
         [[objects]]\nprimitive = \"cube\"\n",
    )
    .unwrap();
    let png = dir.path().join("floor.png");
    let out = zline(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--size",
        "32x24",
        "--shadows",
        "planar",
    ]);
    check_png(&out, &png, (32, 24));
    assert!(!String::from_utf8_lossy(&out.stderr).contains("warning:"), "the scene has a shadow plane");
}

#[test]
fn shadow_map_flags_are_checked_and_map_mode_renders_a_bare_model() {
    for bad in ["9000", "8", "big"] {
        let out = zline(&["demo", "-o", "x.png", "--shadow-map-size", bad]);
        check_error_line(&out, 2, &[bad, "--shadow-map-size"]);
    }
    let out = zline(&["demo", "-o", "x.png", "--shadow-filter", "bilinear"]);
    check_error_line(&out, 2, &["bilinear", "--shadow-filter"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("nearest"), "the valid names are listed");

    // Shadow maps need no shadow planes: no warning on a bare model.
    let dir = tempfile::tempdir().unwrap();
    let suzanne = repo().join("assets/obj/suzanne/suzanne.obj");
    let png = dir.path().join("map.png");
    let args = ["render", suzanne.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "32x24"];
    for extra in [
        &["--shadows", "map"][..],
        &["--shadows", "map", "--shadow-map-size", "16", "--shadow-filter", "nearest"],
        &["--shadows", "map", "--shadow-map-size", "64", "--shadow-filter", "pcf"],
    ] {
        let out = zline(&[&args[..], extra].concat());
        check_png(&out, &png, (32, 24));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("warning:"), "{extra:?}: {stderr}");
    }
}

#[test]
fn demo_scene_room_renders_the_room_with_shadows_on_the_floor() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("room.png");
    let out = zline(&["demo", "--scene", "room", "-o", png.to_str().unwrap()]);
    // The room's own size, as README shows it.
    let room = check_png(&out, &png, (960, 540));
    let distinct: std::collections::HashSet<_> = room.pixels().collect();
    assert!(distinct.len() > 1000, "the room looks empty ({} colours)", distinct.len());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("warning"), "{stderr}");

    // The room is not the demo (the default), and its shadows are on by
    // default: turning them off brightens the floor and changes nothing
    // else's colour for the worse.
    let small = |name: &str, extra: &[&str]| {
        let p = dir.path().join(name);
        let args = [&["demo", "-o", p.to_str().unwrap(), "--size", "240x135"][..], extra].concat();
        check_png(&zline(&args), &p, (240, 135))
    };
    let demo = small("demo.png", &[]);
    assert_eq!(demo, small("demo-named.png", &["--scene", "demo"]), "--scene demo is the default");
    let shadowed = small("room.png", &["--scene", "room"]);
    assert_ne!(shadowed, demo);
    let lit = small("lit.png", &["--scene", "room", "--shadows", "none"]);
    let luma = |p: &image::Rgb<u8>| p.0.iter().map(|&c| u32::from(c)).sum::<u32>();
    let darker = shadowed.pixels().zip(lit.pixels()).filter(|(s, l)| luma(s) + 6 < luma(l)).count();
    let brighter = shadowed.pixels().zip(lit.pixels()).filter(|(s, l)| luma(s) > luma(l) + 6).count();
    assert!(darker > 240 * 135 / 50, "only {darker} pixels are in shadow");
    assert_eq!(brighter, 0, "a shadow brightened a pixel");
}

#[test]
fn an_unknown_built_in_scene_is_a_usage_error() {
    let out = zline(&["demo", "--scene", "bogus", "-o", "x.png"]);
    check_error_line(&out, 2, &["bogus", "--scene"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("demo") && stderr.contains("room"), "the valid names are listed:\n{stderr}");
    // Only the demo subcommand has built-in scenes.
    let out = zline(&["render", "x.obj", "--scene", "room", "-o", "x.png"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn bump_flags_map_the_model_and_name_a_bad_file() {
    let dir = tempfile::tempdir().unwrap();
    let model = repo().join("assets/bump/sphere.obj");
    let bumps = repo().join("assets/bump/bumps.png");
    let (m, b) = (model.to_str().unwrap(), bumps.to_str().unwrap());
    let render = |name: &str, extra: &[&str]| {
        let png = dir.path().join(name);
        let args = [&["render", m, "-o", png.to_str().unwrap(), "--size", "96x64"][..], extra].concat();
        let out = zline(&args);
        check_png(&out, &png, (96, 64))
    };
    // The MTL's own bump map, a stronger one from the flags, and none.
    let own = render("own.png", &[]);
    let strong = render("strong.png", &["--bump", b, "--bump-scale", "0.2"]);
    let smooth = render("smooth.png", &["--no-normal-maps"]);
    assert_ne!(own, smooth, "the MTL's bump map changes the image");
    assert_ne!(strong, own, "--bump-scale changes it");
    let png = dir.path().join("bad.png");
    let out = zline(&["render", m, "-o", png.to_str().unwrap(), "--bump", "/no/such/bumps.png"]);
    check_clean_error(&out, &["/no/such/bumps.png", "bump map"]);
    let out = zline(&["render", m, "-o", png.to_str().unwrap(), "--bump-scale", "2"]);
    assert_eq!(out.status.code(), Some(2), "--bump-scale needs --bump (a usage error)");
}
