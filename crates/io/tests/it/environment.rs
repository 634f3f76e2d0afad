//! Environment maps (SPEC §5.3): Radiance HDR files read as written, the
//! built-in sky, errors naming the file and the problem, and the scene
//! file's `[environment]` table and `[render] tonemap`/`exposure` keys.

use std::sync::Arc;

use glam::Vec3;
use zline_io::{load_environment, read_panorama, write_panorama, SKY_NAME};
use zline_shading::{Panorama, ToneMap};

use crate::scene_file::{check_scene_error, load_scene, OBJECT};
use crate::temp_file;

/// A panorama written as Radiance HDR reads back within the format's
/// precision (8-bit mantissas sharing an exponent: 1/256 relative).
#[test]
fn hdr_files_read_back_as_written() {
    let sky = Panorama::sky(64, 32);
    let path = temp_file("sky.hdr", "");
    write_panorama(&path, &sky).unwrap();
    let (back, warnings) = read_panorama(&path).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!((back.width(), back.height()), (64, 32));
    for (a, b) in sky.texels().iter().zip(back.texels()) {
        let scale = a.max_element().max(1e-3);
        assert!((*a - *b).abs().max_element() <= scale / 128.0, "{a} vs {b}");
    }
    let (light, _) = load_environment(&path).unwrap();
    assert_eq!(light.panorama(), &back);
    // Loaded twice, prepared once.
    let (again, _) = load_environment(&path).unwrap();
    assert!(Arc::ptr_eq(&light, &again));
}

#[test]
fn the_sky_needs_no_file() {
    let (light, warnings) = load_environment(std::path::Path::new(SKY_NAME)).unwrap();
    assert!(warnings.is_empty());
    assert_eq!(light.panorama().width(), 2 * light.panorama().height());
    // The sun is there: the brightest irradiance faces it.
    let towards = light.irradiance(zline_shading::SKY_SUN);
    let away = light.irradiance(-zline_shading::SKY_SUN);
    assert!(towards.x > 2.0 * away.x, "{towards} vs {away}");
}

#[test]
fn bad_environment_files_are_errors_naming_the_file() {
    let missing = std::env::temp_dir().join("zline-no-such-environment.hdr");
    let e = load_environment(&missing).unwrap_err().to_string();
    assert!(e.contains("zline-no-such-environment.hdr") && e.contains("cannot read"), "{e}");
    let text = temp_file("notes.hdr", "just some text\n");
    let e = load_environment(&text).unwrap_err().to_string();
    assert!(e.contains("notes.hdr") && e.contains("Radiance HDR"), "{e}");
    let png = crate::repo("assets/bump/bumps.png");
    let e = load_environment(&png).unwrap_err().to_string();
    assert!(e.contains("bumps.png") && e.contains("not an environment map"), "{e}");
    // A header promising more than the limit is refused before decoding.
    let huge = temp_file("huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n");
    let e = load_environment(&huge).unwrap_err().to_string();
    assert!(e.contains("huge.hdr") && e.contains("larger than the limit"), "{e}");
    // A truncated body is corrupt, not a panic.
    let mut bytes = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n".to_vec();
    bytes.extend_from_slice(&[1, 2, 3]);
    let cut = temp_file("cut.hdr", "");
    std::fs::write(&cut, bytes).unwrap();
    let e = load_environment(&cut).unwrap_err().to_string();
    assert!(e.contains("cut.hdr"), "{e}");
}

#[test]
fn scene_files_read_the_environment_table() {
    let path = temp_file("sky.hdr", "");
    write_panorama(&path, &Panorama::sky(32, 16)).unwrap();
    let dir = path.parent().unwrap();
    let scene_path = dir.join("lit.toml");
    let text = format!(
        "[environment]\nfile = \"sky.hdr\"\nintensity = 0.5\nrotation = 90\nbackground = true\n\
         [render]\ntonemap = \"khr-pbr-neutral\"\nexposure = 1.5\n{OBJECT}"
    );
    std::fs::write(&scene_path, text).unwrap();
    let scene = load_scene(&scene_path).unwrap_or_else(|e| panic!("{e}"));
    let env = scene.environment.expect("an environment");
    assert_eq!((env.intensity, env.rotation_degrees, env.background), (0.5, 90.0, true));
    assert_eq!(env.light.panorama().width(), 32);
    assert_eq!(scene.settings.tone_mapping.operator, ToneMap::KhrPbrNeutral);
    assert_eq!(scene.settings.tone_mapping.exposure, 1.5);
    // The sky by name, defaults for the rest.
    let scene =
        load_scene(&temp_file("sky.toml", &format!("[environment]\nfile = \"sky\"\n{OBJECT}"))).unwrap();
    let env = scene.environment.expect("an environment");
    assert_eq!((env.intensity, env.rotation_degrees, env.background), (1.0, 0.0, false));
    assert!(env.light.irradiance(Vec3::Y).is_finite());
}

#[test]
fn bad_environment_keys_are_errors_naming_the_key() {
    check_scene_error(
        "negative.toml",
        &format!("[environment]\nfile = \"sky\"\nintensity = -1\n{OBJECT}"),
        &["environment.intensity"],
    );
    check_scene_error(
        "nofile.toml",
        &format!("[environment]\nfile = \"absent.hdr\"\n{OBJECT}"),
        &["environment.file", "absent.hdr"],
    );
    check_scene_error("nokey.toml", &format!("[environment]\nintensity = 2\n{OBJECT}"), &["file"]);
    check_scene_error(
        "tonemap.toml",
        &format!("[render]\ntonemap = \"filmic\"\n{OBJECT}"),
        &["tonemap", "filmic"],
    );
    check_scene_error("exposure.toml", &format!("[render]\nexposure = -2\n{OBJECT}"), &["render.exposure"]);
}
