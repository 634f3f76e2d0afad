//! `zline thumbnail` and `zline thumbnailer`: a square, framed, transparent
//! PNG; the caps; the installed files; and the thumbnail made inside the
//! sandbox GNOME's thumbnail factory runs thumbnailers in.

use std::path::Path;
use std::process::Command;

use crate::{check_clean_error, repo, zline};

fn bunny() -> String {
    repo().join("assets/ply/bunny_lowres.ply").to_str().unwrap().to_string()
}

/// Asserts `png` is a `side`-square RGBA thumbnail: transparent corners,
/// an opaque middle.
fn check_thumbnail(png: &Path, side: u32) {
    let img = image::open(png).expect("a PNG").to_rgba8();
    assert_eq!(img.dimensions(), (side, side));
    assert_eq!(img.get_pixel(0, 0)[3], 0, "a transparent corner");
    assert_eq!(img.get_pixel(side / 2, side / 2)[3], 255, "the model in the middle");
}

#[test]
fn a_thumbnail_is_square_framed_and_transparent_and_keeps_to_its_caps() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("bunny.png");
    let input = bunny();
    let out = zline(&["thumbnail", "-s", "96", &input, png.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    check_thumbnail(&png, 96);
    // On a background instead: opaque everywhere.
    let out = zline(&["thumbnail", &input, png.to_str().unwrap(), "--background", "0.5,0.5,0.5", "-s", "32"]);
    assert!(out.status.success());
    let img = image::open(&png).unwrap().to_rgba8();
    assert!(img.pixels().all(|p| p[3] == 255) && img.get_pixel(0, 0)[0] == 128);
    // Too large an input, a missing one, a scene that takes too long.
    let out = zline(&["thumbnail", &input, png.to_str().unwrap(), "--max-input-bytes", "1000"]);
    check_clean_error(&out, &["bytes, more than the thumbnail's limit", "--max-input-bytes"]);
    let out = zline(&["thumbnail", "missing.ply", png.to_str().unwrap()]);
    check_clean_error(&out, &["missing.ply", "cannot read"]);
    let slow = dir.path().join("slow.toml");
    std::fs::write(&slow, "[[objects]]\nprimitive = \"sphere\"\nrings = 1400\nsegments = 1400\n").unwrap();
    let out = zline(&["thumbnail", slow.to_str().unwrap(), png.to_str().unwrap(), "--timeout", "0.1"]);
    check_clean_error(&out, &["no thumbnail within 0.1 s", "--timeout"]);
}

#[test]
fn the_thumbnailer_installs_its_files_and_removes_them() {
    let dir = tempfile::tempdir().unwrap();
    let prefix = dir.path().to_str().unwrap();
    let out = zline(&["thumbnailer", "install", "--prefix", prefix]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let said = String::from_utf8_lossy(&out.stdout);
    let entry = std::fs::read_to_string(dir.path().join("thumbnailers/zline.thumbnailer")).unwrap();
    assert!(said.contains("zline.thumbnailer") && said.contains("zline-models.xml"), "{said}");
    assert!(entry.starts_with("[Thumbnailer Entry]\n"), "{entry}");
    assert!(entry.contains(" thumbnail -s %s %i %o\n"), "{entry}");
    for t in ["model/gltf-binary", "model/obj", "model/stl", "application/x-ply", "model/3mf"] {
        assert!(entry.contains(&format!("{t};")), "{t} in {entry}");
    }
    let package = std::fs::read_to_string(dir.path().join("mime/packages/zline-models.xml")).unwrap();
    assert!(package.contains("*.glb") && package.contains("*.obj") && package.contains("*.3mf"));
    let out = zline(&["thumbnailer", "uninstall", "--prefix", prefix]);
    assert!(out.status.success());
    assert!(!dir.path().join("thumbnailers/zline.thumbnailer").exists());
    assert!(!dir.path().join("mime/packages/zline-models.xml").exists());
}

#[test]
fn the_thumbnail_comes_out_of_the_file_managers_sandbox() {
    // GNOME's thumbnail factory (gnome-desktop-thumbnail-script.c) runs a
    // thumbnailer as below: read-only /usr, the usr-merged links, a private
    // /proc and /dev, every namespace unshared (no network, no display
    // socket), its own /tmp holding the input and the output. The display
    // variables are removed too, and the binary is bound read-only.
    if Command::new("bwrap").arg("--version").output().is_err() {
        eprintln!("skipped: bwrap (Debian's bubblewrap) is not installed");
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let input = bunny();
    let mut args: Vec<String> =
        ["--ro-bind", "/usr", "/usr", "--ro-bind-try", "/etc/ld.so.cache", "/etc/ld.so.cache"]
            .map(String::from)
            .to_vec();
    for dir in ["bin", "lib64", "lib", "sbin"] {
        let at = format!("/{dir}");
        match std::fs::read_link(&at) {
            Ok(_) => args.extend(["--symlink".into(), format!("/usr/{dir}"), at]),
            Err(_) if Path::new(&at).exists() => args.extend(["--ro-bind".into(), at.clone(), at]),
            Err(_) => {}
        }
    }
    let fixed = [
        "--proc",
        "/proc",
        "--dev",
        "/dev",
        "--chdir",
        "/",
        "--setenv",
        "GIO_USE_VFS",
        "local",
        "--unshare-all",
        "--die-with-parent",
        "--unsetenv",
        "DISPLAY",
        "--unsetenv",
        "WAYLAND_DISPLAY",
    ];
    args.extend(fixed.map(String::from));
    args.extend(["--bind".into(), tmp.path().to_str().unwrap().into(), "/tmp".into()]);
    args.extend(["--ro-bind".into(), input, "/tmp/gnome-desktop-file-to-thumbnail.ply".into()]);
    args.extend(["--ro-bind".into(), env!("CARGO_BIN_EXE_zline").into(), "/app/zline".into()]);
    // The .thumbnailer file's Exec line, %s %i %o filled in.
    let exec = "/app/zline thumbnail -s 128 /tmp/gnome-desktop-file-to-thumbnail.ply /tmp/gnome-desktop-thumbnailer.png";
    args.extend(exec.split(' ').map(String::from));
    let out = Command::new("bwrap").args(&args).output().unwrap();
    let said = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() && said.starts_with("bwrap:") {
        eprintln!("skipped: bwrap cannot make its sandbox here: {said}");
        return;
    }
    assert!(out.status.success(), "{said}");
    check_thumbnail(&tmp.path().join("gnome-desktop-thumbnailer.png"), 128);
}
