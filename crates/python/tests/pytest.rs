//! Runs the Python package's pytest suite (`tests/test_*.py`) on the module
//! this build made: `cargo test` builds the extension (`lib_zline.so`, the
//! test profile) beside this test, which lays it out as the `zline`
//! package in a temporary folder and runs `python -m pytest` there.
//!
//! The interpreter is `ZLINE_PYTHON` (default `python3`) and needs numpy
//! and pytest (`pip install numpy pytest pillow trimesh`; `.ci/run` makes
//! a virtual environment with them). Without them the suite is skipped
//! with a message, unless `ZLINE_REQUIRE_PYTHON=1` (CI) makes that a
//! failure. The tests that compare with `zline render`'s PNGs run the
//! `zline` binary of the same build (`ZLINE_BIN`).

use std::path::{Path, PathBuf};
use std::process::Command;

fn required() -> bool {
    std::env::var("ZLINE_REQUIRE_PYTHON").is_ok_and(|v| v == "1")
}

fn skip(why: &str) {
    assert!(!required(), "ZLINE_REQUIRE_PYTHON=1 but {why}");
    eprintln!("skipped: {why} (see crates/python/tests/pytest.rs)");
}

/// The profile's output folder (`target/debug` for the test profile) and
/// its `deps`, where this test runs from.
fn out_dirs() -> (PathBuf, PathBuf) {
    let exe = std::env::current_exe().expect("the test's path");
    // target/<profile>/deps/pytest-<hash>
    let deps = exe.parent().expect("target/<profile>/deps").to_path_buf();
    (deps.parent().expect("target/<profile>").to_path_buf(), deps)
}

#[test]
fn pytest_suite_passes_on_the_built_module() {
    let python = std::env::var("ZLINE_PYTHON").unwrap_or_else(|_| "python3".into());
    let probe = Command::new(&python).args(["-c", "import numpy, pytest, PIL"]).output();
    match probe {
        Ok(o) if o.status.success() => {}
        Ok(o) => {
            return skip(&format!(
                "{python} lacks numpy, pytest or pillow: {}",
                String::from_utf8_lossy(&o.stderr).trim()
            ))
        }
        Err(e) => return skip(&format!("{python} did not start: {e}")),
    }
    let (dir, deps) = out_dirs();
    // Built for this test in deps/ (a cdylib's name has no hash).
    let module = deps.join("lib_zline.so");
    assert!(module.is_file(), "{}: the extension module is missing", module.display());
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = tempfile::tempdir().expect("a temporary folder");
    let package = root.path().join("zline");
    std::fs::create_dir(&package).unwrap();
    std::fs::copy(manifest.join("python/zline/__init__.py"), package.join("__init__.py")).unwrap();
    std::fs::copy(&module, package.join("_zline.abi3.so")).unwrap();
    let zline = dir.join("zline");
    let mut pytest = Command::new(&python);
    pytest
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs"])
        .arg(manifest.join("tests"))
        .env("PYTHONPATH", root.path())
        .env("PYTHONDONTWRITEBYTECODE", "1")
        .env("ZLINE_REPO", manifest.join("../.."));
    if zline.is_file() {
        pytest.env("ZLINE_BIN", &zline);
    } else if required() {
        panic!("{}: the zline binary is missing (run the workspace's tests)", zline.display());
    }
    let run = pytest.output().expect("pytest runs");
    let (stdout, stderr) = (String::from_utf8_lossy(&run.stdout), String::from_utf8_lossy(&run.stderr));
    eprintln!("{stdout}{stderr}");
    assert!(run.status.success(), "the pytest suite failed:\n{stdout}\n{stderr}");
}
