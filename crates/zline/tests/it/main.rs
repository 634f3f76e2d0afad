//! End-to-end tests of the `zline` binary: what a user types, what they get.

#[cfg(unix)]
mod bad_corpus;
mod bad_input;
mod batch;
mod camera;
mod check;
mod cli;
mod course;
mod formats;
mod hard_cases;
mod hostile;
mod inspect;
mod layers;
mod lighting_model;
mod radiosity;
mod raytrace;
mod scan;
mod terrain;
mod thumbnail;
mod turntable;
#[cfg(feature = "view")]
mod view;
mod views;
mod visibility;

use std::path::Path;
use std::process::{Command, Output};

/// Runs the `zline` binary with `args`.
fn zline(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_zline")).args(args).output().expect("zline binary runs")
}

/// Asserts a run failed cleanly: exit code 1, one `error:` line on stderr
/// containing every `needle`, and no panic (zline reports one as an
/// `error: internal error` line with exit code 1).
#[track_caller]
fn check_clean_error(out: &Output, needles: &[&str]) {
    check_error_line(out, 1, needles);
}

/// Asserts a run stopped with exit code `code`, one `error:` line on
/// stderr containing every `needle`, and no panic.
#[track_caller]
fn check_error_line(out: &Output, code: i32, needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(code), "expected exit code {code}; stderr:\n{stderr}");
    assert!(!stderr.contains("panicked") && !stderr.contains("internal error"), "panic:\n{stderr}");
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "expected one error line, got:\n{stderr}");
    for n in needles {
        assert!(errors[0].contains(n), "error line lacks '{n}': {}", errors[0]);
    }
}

/// Asserts a run succeeded and wrote a PNG of the given size.
#[track_caller]
fn check_png(out: &Output, png: &Path, size: (u32, u32)) -> image::RgbImage {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "zline failed:\n{stderr}");
    let img = image::open(png).expect("output PNG readable").to_rgb8();
    assert_eq!(img.dimensions(), size);
    img
}

/// The repository's root.
fn repo() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}
