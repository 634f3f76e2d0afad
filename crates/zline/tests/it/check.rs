//! `zline check`: exact by default, tolerances, the heat map and JSON on a
//! failure, `--update`, and the folder mode's GitHub annotations.

use std::path::Path;

use crate::{check_error_line, repo, zline};

/// A copy of the regression scene `name` (its TOML and reference PNG) in
/// `dir`.
fn scene(dir: &Path, name: &str) -> std::path::PathBuf {
    for ext in ["toml", "png"] {
        let from = repo().join(format!("tests/scenes/{name}.{ext}"));
        std::fs::copy(from, dir.join(format!("{name}.{ext}"))).unwrap();
    }
    dir.join(format!("{name}.toml"))
}

#[test]
fn an_unchanged_scene_passes_exactly_and_a_changed_one_fails_with_its_heat_map() {
    let dir = tempfile::tempdir().unwrap();
    let toml = scene(dir.path(), "shading_phong");
    let path = toml.to_str().unwrap();
    let out = zline(&["check", path]);
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success() && said.contains("ok ") && said.contains("0 of 30000 pixels differ"),
        "{said}"
    );
    // The verdict only: no line about the render's temporary image.
    assert!(!said.contains("wrote"), "{said}");
    // Supersampled: the edges change. Exit 1, the picture and the heat
    // map kept, the JSON says why.
    let json = dir.path().join("result.json");
    let out = zline(&["check", path, "--json", json.to_str().unwrap(), "--", "--ssaa", "2"]);
    check_error_line(&out, 1, &["1 of 1 checks failed"]);
    let result: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let first = &result[0];
    assert_eq!(first["passed"], false);
    let c = &first["comparison"];
    let (failing, largest) = (c["failing_pixels"].as_u64().unwrap(), c["max_difference"].as_u64().unwrap());
    assert!(failing > 0 && largest > 0, "{c}");
    for kept in ["shading_phong.actual.png", "shading_phong.diff.png"] {
        let img = image::open(dir.path().join(kept)).expect(kept).to_rgb8();
        assert_eq!(img.dimensions(), (200, 150));
    }
    // The heat map is black where nothing changed.
    let heat = image::open(dir.path().join("shading_phong.diff.png")).unwrap().to_rgb8();
    let black = heat.pixels().filter(|p| p.0 == [0, 0, 0]).count() as u64;
    assert_eq!(black, 200 * 150 - c["differing_pixels"].as_u64().unwrap());
    // Tolerances: the largest difference allowed, or the share of pixels.
    let past = largest.to_string();
    let out = zline(&["check", path, "--max-difference", &past, "--", "--ssaa", "2"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let share = format!("{}", (failing as f64 / 300.0).ceil());
    let out = zline(&["check", path, "--max-percent", &share, "--min-ssim", "0.9", "--", "--ssaa", "2"]);
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && said.contains("SSIM"), "{said}");
    // --update accepts the new picture; the next check passes.
    let out = zline(&["check", path, "--update", "--", "--ssaa", "2"]);
    assert!(out.status.success());
    assert!(zline(&["check", path, "--", "--ssaa", "2"]).status.success());
}

#[test]
fn a_folder_is_checked_scene_by_scene_with_github_annotations() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path(), "shading_gouraud");
    scene(dir.path(), "fog_linear");
    // One reference spoiled, one missing.
    let spoiled = dir.path().join("fog_linear.png");
    let mut img = image::open(&spoiled).unwrap().to_rgb8();
    img.put_pixel(3, 4, image::Rgb([255, 0, 255]));
    img.save(&spoiled).unwrap();
    std::fs::copy(repo().join("tests/scenes/lights_spot.toml"), dir.path().join("lights_spot.toml")).unwrap();
    let out_dir = dir.path().join("out");
    let folder = dir.path().to_str().unwrap();
    let out = zline(&["check", "--folder", folder, "--github", "--out", out_dir.to_str().unwrap()]);
    check_error_line(&out, 1, &["2 of 3 checks failed"]);
    let annotations = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = annotations.lines().collect();
    assert_eq!(lines.len(), 2, "{annotations}");
    assert!(lines[0].starts_with("::error file=") && lines[0].contains("fog_linear.toml"), "{}", lines[0]);
    assert!(lines[0].contains("1 of") && lines[0].contains("pixels differ"), "{}", lines[0]);
    assert!(lines[1].contains("lights_spot.toml") && lines[1].contains("--update writes it"), "{}", lines[1]);
    assert!(out_dir.join("fog_linear.diff.png").exists());
    // Nothing to check: a clean error.
    let empty = tempfile::tempdir().unwrap();
    check_error_line(&zline(&["check", "--folder", empty.path().to_str().unwrap()]), 1, &["no *.toml"]);
}
