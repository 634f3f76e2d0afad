//! Hostile command lines and output paths: a clean error (exit 1, or the
//! argument parser's exit 2), or a run clamped with a warning — never a
//! panic (exit 101), never a lost output file.

use std::path::Path;
use std::process::{Command, Output};

use crate::{check_clean_error, check_error_line, check_png, zline};

/// Asserts the argument parser refused a value: exit code 2, one `error:`
/// line containing every `needle`, no panic.
#[track_caller]
fn check_usage_error(out: &Output, needles: &[&str]) {
    check_error_line(out, 2, needles);
}

/// The demo with extra arguments, written to `png`, at 48×32 unless they
/// set a size.
fn demo(png: &Path, extra: &[&str]) -> Output {
    let size: &[&str] = if extra.contains(&"--size") { &[] } else { &["--size", "48x32"] };
    zline(&[&["demo", "-o", png.to_str().unwrap()][..], size, extra].concat())
}

#[test]
fn out_of_range_tile_sizes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("o.png");
    for size in ["4294967295", "0", "7", "1025", "4294967296", "-1"] {
        let arg = format!("--tile-size={size}");
        check_usage_error(&demo(&png, &[&arg]), &["--tile-size", size]);
    }
    assert!(!png.exists(), "a refused run wrote its output");
    let out = demo(&png, &["--tile-size", "4294967295"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("8..=1024"), "the range is not stated");
    for size in ["8", "1024"] {
        check_png(&demo(&png, &["--tile-size", size]), &png, (48, 32));
    }
}

#[test]
fn too_many_threads_are_clamped_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let (one, many) = (dir.path().join("one.png"), dir.path().join("many.png"));
    check_png(&demo(&one, &["--threads", "1"]), &one, (48, 32));
    for n in ["10000", "100000", "18446744073709551615"] {
        let out = demo(&many, &["--threads", n]);
        check_png(&out, &many, (48, 32));
        let stderr = String::from_utf8_lossy(&out.stderr);
        let warning =
            stderr.lines().find(|l| l.starts_with("warning:")).unwrap_or_else(|| panic!("{stderr}"));
        assert!(warning.contains(&format!("--threads {n}")) && warning.contains("256"), "{warning}");
        assert_eq!(std::fs::read(&one).unwrap(), std::fs::read(&many).unwrap(), "--threads {n}: other bytes");
    }
    let out = demo(&many, &["--threads", "256"]);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("warning:"), "256 threads are allowed");
    // Rayon's own variable, without the flag, is clamped the same way.
    let out = Command::new(env!("CARGO_BIN_EXE_zline"))
        .args(["demo", "-o", many.to_str().unwrap(), "--size", "48x32"])
        .env("RAYON_NUM_THREADS", "100000")
        .output()
        .unwrap();
    check_png(&out, &many, (48, 32));
    assert!(String::from_utf8_lossy(&out.stderr).contains("warning: RAYON_NUM_THREADS=100000"), "{out:?}");
    assert_eq!(std::fs::read(&one).unwrap(), std::fs::read(&many).unwrap(), "RAYON_NUM_THREADS: other bytes");
}

#[test]
fn images_beyond_the_sample_budget_are_refused_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("o.png");
    check_usage_error(&demo(&png, &["--size", "100000x100000"]), &["--size", "16384"]);
    check_usage_error(&demo(&png, &["--ssaa", "99"]), &["--ssaa", "1..=8"]);
    // Each side and the factor are allowed alone, not together: 2^30 and
    // 2^34 samples. Refused at once (the render would take minutes).
    for (size, ssaa) in [("16384x16384", "2"), ("16384x16384", "8"), ("4097x4096", "4")] {
        let out = demo(&png, &["--size", size, "--ssaa", ssaa]);
        check_clean_error(&out, &[size, &format!("ssaa {ssaa}"), "268435456", "--size or --ssaa"]);
    }
    // The limit itself is allowed (not rendered here: 2^28 samples).
    // The same from a scene file's own settings.
    let scene = dir.path().join("huge.toml");
    std::fs::write(
        &scene,
        "[render]\nwidth = 16384\nheight = 16384\nssaa = 8\n\n[camera]\neye = [0, 0, 4]\n\n\
         [[objects]]\nprimitive = \"cube\"\n",
    )
    .unwrap();
    let out = zline(&["render", scene.to_str().unwrap(), "-o", png.to_str().unwrap()]);
    check_clean_error(&out, &["16384x16384", "ssaa 8", "17179869184"]);
    assert!(!png.exists(), "a refused run wrote its output");
}

#[test]
fn bad_output_paths_are_refused_before_rendering_and_touch_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name);
    // Not a .png or .jpg: nothing written, an existing file kept (it was
    // truncated to 0 bytes, after the whole render).
    std::fs::write(path("existing.bmp"), b"old contents").unwrap();
    for name in ["out.gif", "existing.bmp", "out", "out.png.tmp"] {
        let p = path(name);
        let out = demo(&p, &[]);
        check_clean_error(&out, &[p.to_str().unwrap(), ".png"]);
    }
    assert!(!path("out.gif").exists() && !path("out").exists());
    assert_eq!(std::fs::read(path("existing.bmp")).unwrap(), b"old contents");
    // Any case of the extension is PNG.
    check_png(&demo(&path("upper.PNG"), &[]), &path("upper.PNG"), (48, 32));
    // A folder that does not exist, a folder as the output, a file as the
    // folder: all fail at once, under root too.
    let out = demo(Path::new("/nonexistent/dir/out.png"), &[]);
    check_clean_error(&out, &["/nonexistent/dir/out.png", "does not exist"]);
    std::fs::create_dir(path("folder.png")).unwrap();
    std::fs::write(path("folder.png/inside"), b"kept").unwrap();
    check_clean_error(&demo(&path("folder.png"), &[]), &["folder.png", "is a folder"]);
    assert_eq!(std::fs::read(path("folder.png/inside")).unwrap(), b"kept");
    let out = demo(&path("existing.bmp/out.png"), &[]);
    check_clean_error(&out, &["existing.bmp/out.png", "not a folder"]);
    // Nothing left behind: only the files made here.
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["existing.bmp", "folder.png", "upper.PNG"]);
}

/// Runs the demo at 512×512 (a PNG of tens of KB) into `png` through
/// `sh` with files limited to 1 KiB (`ulimit -f 2`, 512-byte blocks in
/// POSIX sh), after the shell commands `setup`.
#[cfg(unix)]
fn demo_with_a_file_size_limit(png: &Path, setup: &str) -> Output {
    let script = format!("{setup} ulimit -f 2 && exec \"$0\" demo -o \"$1\" --size 512x512");
    Command::new("sh")
        .args(["-c", &script, env!("CARGO_BIN_EXE_zline"), png.to_str().unwrap()])
        .output()
        .expect("sh runs")
}

/// An existing output whose bytes a failed write must keep: a small PNG.
#[cfg(unix)]
fn old_output(dir: &Path) -> (std::path::PathBuf, Vec<u8>) {
    let png = dir.join("old.png");
    check_png(&zline(&["demo", "-o", png.to_str().unwrap(), "--size", "8x8"]), &png, (8, 8));
    let bytes = std::fs::read(&png).unwrap();
    assert!(bytes.len() < 1024, "the old PNG must fit the limit ({} bytes)", bytes.len());
    (png, bytes)
}

#[cfg(unix)]
#[test]
fn a_failed_write_is_an_error_and_leaves_the_old_file_whole() {
    let dir = tempfile::tempdir().unwrap();
    let (png, old) = old_output(dir.path());
    // SIGXFSZ ignored: writing past the limit fails with EFBIG.
    let out = demo_with_a_file_size_limit(&png, "trap '' XFSZ &&");
    check_clean_error(&out, &[png.to_str().unwrap(), "cannot write the image"]);
    assert_eq!(std::fs::read(&png).unwrap(), old, "the old PNG was changed");
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left, ["old.png"], "the temporary file was left behind");
}

#[cfg(unix)]
#[test]
fn an_interrupted_write_leaves_the_old_file_byte_for_byte() {
    use std::os::unix::process::ExitStatusExt;
    let dir = tempfile::tempdir().unwrap();
    let (png, old) = old_output(dir.path());
    // SIGXFSZ at its default: the process is killed in the middle of the write.
    let out = demo_with_a_file_size_limit(&png, "");
    assert_eq!(out.status.signal(), Some(25), "not killed by SIGXFSZ: {:?}", out.status);
    assert_eq!(std::fs::read(&png).unwrap(), old, "the old PNG was changed");
}

#[test]
fn blank_images_say_why() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("o.png");
    let cases = [
        ("huge.obj", "v -3e38 0 0\nv 3e38 0 0\nv 0 3e38 0\nf 1 2 3\n", "more than f32 can measure"),
        ("tiny.obj", "v 0 0 0\nv 1e-40 0 0\nv 0 1e-40 0\nf 1 2 3\n", "a size of (1e-40, 1e-40, 0)"),
    ];
    for (name, text, why) in cases {
        let model = dir.path().join(name);
        std::fs::write(&model, text).unwrap();
        let out = zline(&["render", model.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "32x24"]);
        check_png(&out, &png, (32, 24));
        let stderr = String::from_utf8_lossy(&out.stderr);
        let warnings: Vec<&str> = stderr.lines().filter(|l| l.starts_with("warning:")).collect();
        assert_eq!(warnings.len(), 1, "{name}: expected one warning:\n{stderr}");
        for needle in [name, "blank", "one triangle", why] {
            assert!(warnings[0].contains(needle), "{name}: the warning lacks '{needle}': {}", warnings[0]);
        }
    }
    let out = demo(&png, &[]);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("warning:"), "the demo is not blank");
}
