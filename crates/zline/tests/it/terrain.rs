//! `zline terrain`: the asset renders as a landscape, the triangle counts
//! are reported, and bad elevation files fail with the file and line.

use crate::{check_clean_error, check_png, repo, zline};

/// The share of pixels that are not the sky.
fn ground_share(img: &image::RgbImage) -> f64 {
    let sky = image::Rgb([168u8, 194, 224]);
    let ground = img.pixels().filter(|p| p.0.iter().zip(sky.0).any(|(a, b)| a.abs_diff(b) > 6)).count();
    ground as f64 / (img.width() * img.height()) as f64
}

#[test]
fn the_asset_renders_and_reports_its_triangles() {
    let dir = tempfile::tempdir().unwrap();
    let heights = repo().join("assets/terrain/hills.png");
    let png = dir.path().join("hills.png");
    let run = |png: &std::path::Path, extra: &[&str]| {
        let mut args =
            vec!["terrain", heights.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "320x180"];
        args.extend_from_slice(extra);
        zline(&args)
    };
    let out = run(&png, &["--threads", "1"]);
    let img = check_png(&out, &png, (320, 180));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("triangles drawn of the full grid's 131072"), "{stderr}");
    let share = ground_share(&img);
    assert!((0.3..0.95).contains(&share), "the terrain covers {share} of the image");
    // The image does not depend on the thread count.
    let two = dir.path().join("two.png");
    check_png(&run(&two, &["--threads", "2", "--tile-size", "24"]), &two, (320, 180));
    assert_eq!(std::fs::read(&png).unwrap(), std::fs::read(&two).unwrap(), "PNG bytes differ");
    // Error 0 draws the full grid but where 16-bit samples lie exactly on
    // a plane (a few flat spots of the lowland).
    let full = dir.path().join("full.png");
    let out = run(&full, &["--terrain-error", "0"]);
    check_png(&out, &full, (320, 180));
    let stderr = String::from_utf8_lossy(&out.stderr);
    let drawn: usize = stderr
        .split("terrain: 257x257 samples; ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no triangle count in {stderr}"));
    assert!((131_000..=131_072).contains(&drawn), "{stderr}");
}

#[test]
fn an_ascii_grid_takes_a_draped_texture_without_fog() {
    let dir = tempfile::tempdir().unwrap();
    let heights = repo().join("assets/terrain/hills-65.asc");
    let texture = repo().join("assets/gltf/BoxTextured/glTF/CesiumLogoFlat.png");
    let png = dir.path().join("draped.png");
    let out = zline(&[
        "terrain",
        heights.to_str().unwrap(),
        "--texture",
        texture.to_str().unwrap(),
        "--no-fog",
        "--height-scale",
        "2",
        "-o",
        png.to_str().unwrap(),
        "--size",
        "200x150",
    ]);
    let img = check_png(&out, &png, (200, 150));
    assert!(String::from_utf8_lossy(&out.stderr).contains("of the full grid's 8192"));
    assert!(ground_share(&img) > 0.2);
}

#[test]
fn bad_elevation_files_name_the_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("out.png");
    let bad = dir.path().join("bad.asc");
    std::fs::write(&bad, "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n1 2 3\n4 five 6\n")
        .unwrap();
    let out = zline(&["terrain", bad.to_str().unwrap(), "-o", png.to_str().unwrap()]);
    check_clean_error(&out, &["bad.asc: line 7, column 3: 'five' is not a number"]);
    let short = dir.path().join("short.asc");
    std::fs::write(&short, "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n1 2 3\n4\n").unwrap();
    let out = zline(&["terrain", short.to_str().unwrap(), "-o", png.to_str().unwrap()]);
    check_clean_error(&out, &["short.asc: line 7: the grid ends after 4 values"]);
    let other = dir.path().join("heights.txt");
    std::fs::write(&other, "1 2 3").unwrap();
    let out = zline(&["terrain", other.to_str().unwrap(), "-o", png.to_str().unwrap()]);
    check_clean_error(&out, &["heights.txt: unsupported elevation file"]);
    let missing = dir.path().join("missing.png");
    let out = zline(&["terrain", missing.to_str().unwrap(), "-o", png.to_str().unwrap()]);
    check_clean_error(&out, &["missing.png: cannot read file"]);
    let hills = repo().join("assets/terrain/hills-65.asc");
    let out =
        zline(&["terrain", hills.to_str().unwrap(), "--cell-size", "1e30", "-o", png.to_str().unwrap()]);
    check_clean_error(&out, &["hills-65.asc: the terrain spans", "keep it below 1e15"]);
    let out =
        zline(&["terrain", hills.to_str().unwrap(), "--height-scale", "1e38", "-o", png.to_str().unwrap()]);
    check_clean_error(&out, &["hills-65.asc: "]);
    assert!(!png.exists());
}
