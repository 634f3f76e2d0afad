//! `--model basic|cook-torrance|beckmann`: one reflection model forced on
//! every material (docs/SPEC.md §5.2), on every command that renders; the
//! environment map and tone mapping flags (§5.3, §10).

use std::path::Path;

use crate::{check_png, repo, zline};

const SIZE: &str = "96x72";

/// Renders `args` (a command and its input) to `png` at [`SIZE`] with
/// `extra` flags and returns the PNG's bytes.
fn render(args: &[&str], png: &Path, extra: &[&str]) -> Vec<u8> {
    let all = [args, &["-o", png.to_str().unwrap(), "--size", SIZE], extra].concat();
    check_png(&zline(&all), png, (96, 72));
    std::fs::read(png).unwrap()
}

/// A glTF model (Cook–Torrance GGX by default) rendered with `--model
/// basic` is the same image as a scene file that turns its material basic;
/// `--model cook-torrance` is the file's own model, so it changes nothing,
/// and `--model basic` changes the picture.
#[test]
fn model_basic_on_gltf_matches_a_scene_of_basic_materials() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let model = repo().join("assets/gltf/Box/glTF-Binary/Box.glb");
    let model = model.to_str().unwrap();
    let scene = d.join("basic.toml");
    std::fs::write(
        &scene,
        format!("[[objects]]\nmodel = {model:?}\n[objects.material]\nmodel = \"basic\"\n"),
    )
    .unwrap();
    let scene = scene.to_str().unwrap();
    let flagged = render(&["render", model], &d.join("flag.png"), &["--model", "basic"]);
    let basic_scene = render(&["render", scene, "--allow-paths-outside"], &d.join("scene.png"), &[]);
    assert!(flagged == basic_scene, "--model basic differs from the scene's model = \"basic\"");
    let own = render(&["render", model], &d.join("own.png"), &[]);
    let ggx = render(&["render", model], &d.join("ggx.png"), &["--model", "cook-torrance"]);
    assert!(own == ggx, "--model cook-torrance changed a GGX material");
    assert!(own != flagged, "--model basic changed nothing on a Cook–Torrance model");
}

/// On the demo (basic materials): `--model basic` changes nothing,
/// `--model cook-torrance` and `--model beckmann` change many pixels and
/// differ from each other.
#[test]
fn model_cook_torrance_changes_a_basic_scene() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let plain = render(&["demo"], &d.join("plain.png"), &[]);
    let basic = render(&["demo"], &d.join("basic.png"), &["--model", "basic"]);
    assert!(plain == basic, "--model basic changed a basic scene");
    render(&["demo"], &d.join("ggx.png"), &["--model", "cook-torrance"]);
    render(&["demo"], &d.join("beckmann.png"), &["--model", "beckmann"]);
    let image = |name: &str| image::open(d.join(name)).unwrap().to_rgb8();
    let (plain, ggx, beckmann) = (image("plain.png"), image("ggx.png"), image("beckmann.png"));
    let differing =
        |a: &image::RgbImage, b: &image::RgbImage| a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
    let changed = differing(&plain, &ggx);
    assert!(changed > 96 * 72 / 10, "--model cook-torrance changed only {changed} pixels");
    assert!(differing(&ggx, &beckmann) > 0, "beckmann and ggx gave the same image");
}

/// The flag is one of the shared rendering flags: `turntable`, `batch`,
/// `terrain` and `view` take it too, and a bad value is clap's usage error.
#[test]
fn model_is_shared_and_checked() {
    let mut commands = vec!["render", "demo", "turntable", "batch", "terrain"];
    if cfg!(feature = "view") {
        commands.push("view");
    }
    for command in commands {
        let out = zline(&[command, "--help"]);
        let help = String::from_utf8_lossy(&out.stdout);
        assert!(help.contains("--model <MODEL>"), "{command} --help lacks --model:\n{help}");
        assert!(help.contains("cook-torrance"), "{command} --help lacks the values:\n{help}");
    }
    let out = zline(&["demo", "-o", "x.png", "--model", "phong"]);
    assert_eq!(out.status.code(), Some(2), "clap rejects bad values with exit code 2");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("basic") && stderr.contains("cook-torrance") && stderr.contains("beckmann"),
        "{stderr}"
    );
}

/// `turntable` applies it to its frames: frame 0 of a turntable with
/// `--model cook-torrance` is `render --model cook-torrance`.
#[test]
fn turntable_frames_take_the_model() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let model = repo().join("assets/obj/suzanne/suzanne.obj");
    let model = model.to_str().unwrap();
    let flag = ["--model", "cook-torrance"];
    let folder = d.join("frames/");
    let args =
        [&["turntable", model, "-o", folder.to_str().unwrap(), "--size", SIZE, "--frames", "2"][..], &flag];
    let out = zline(&args.concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let single = render(&["render", model], &d.join("single.png"), &flag);
    let plain = render(&["render", model], &d.join("plain.png"), &[]);
    let frame = std::fs::read(folder.join("frame-0000.png")).unwrap();
    assert!(frame == single, "turntable's frame 0 is not render's image with the same --model");
    assert!(frame != plain, "--model cook-torrance changed nothing on suzanne");
}

/// `--environment sky` lights a glTF model and, with
/// `--environment-background`, replaces the background; `--tonemap` and
/// `--exposure` change the picture; a bad environment file is an error
/// naming it, and the adjusting flags without an environment a warning.
#[test]
fn environment_and_tone_mapping_flags() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let model = repo().join("assets/gltf/Box/glTF-Binary/Box.glb");
    let args = ["render", model.to_str().unwrap()];
    let plain = render(&args, &d.join("plain.png"), &[]);
    let lit = render(&args, &d.join("lit.png"), &["--environment", "sky", "--environment-intensity", "0.7"]);
    assert_ne!(plain, lit, "the environment changed nothing");
    let sky = ["--environment", "sky", "--environment-background"];
    let behind = render(&args, &d.join("sky.png"), &sky);
    let corner = |bytes: &[u8]| image::load_from_memory(bytes).unwrap().to_rgb8().get_pixel(0, 0).0;
    assert_ne!(corner(&lit), corner(&behind), "the background did not change");
    let turned =
        render(&args, &d.join("turned.png"), &[&sky[..], &["--environment-rotation", "120"]].concat());
    assert_ne!(behind, turned, "the rotation changed nothing");
    let mapped =
        render(&args, &d.join("aces.png"), &[&sky[..], &["--tonemap", "aces", "--exposure", "0.8"]].concat());
    assert_ne!(behind, mapped, "the tone mapping changed nothing");

    let out =
        zline(&[&args[..], &["-o", d.join("x.png").to_str().unwrap(), "--environment", "none.hdr"]].concat());
    assert_ne!(out.status.code(), Some(0));
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("none.hdr"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = zline(
        &[&args[..], &["-o", d.join("y.png").to_str().unwrap(), "--environment-intensity", "2"]].concat(),
    );
    assert_eq!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no environment map"));
    let out = zline(&[&args[..], &["-o", d.join("z.png").to_str().unwrap(), "--tonemap", "filmic"]].concat());
    assert_eq!(out.status.code(), Some(2));
}
