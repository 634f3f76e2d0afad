//! Integration tests of zline-io: loaders against fixture files in
//! `tests/data/`, scene files written to a temporary directory, and the
//! repository's `examples/` and `assets/` (OBJ and glTF models).

mod bump;
mod environment;
mod examples;
mod fuzz_regressions;
mod gltf;
mod obj;
mod obj_textures;
mod safety;
mod scene_file;
mod scene_materials;
mod scene_raytrace;
mod scene_shadows;
mod threemf;

use std::path::{Path, PathBuf};

/// A fixture file under `tests/data/`.
pub(crate) fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

/// A file under the repository root.
pub(crate) fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(path)
}

/// Writes `text` to a fresh file `name` in a directory of its own under
/// this process's temporary directory and returns its path. Each call gets
/// its own directory, so tests running in parallel never share a file even
/// when they pick the same name.
pub(crate) fn temp_file(name: &str, text: &str) -> PathBuf {
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("zline-io-tests-{}/{call}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Asserts that the error message is one line and contains every part.
#[track_caller]
pub(crate) fn check_message(message: &str, parts: &[&str]) {
    assert!(!message.contains('\n'), "not one line: {message:?}");
    for part in parts {
        assert!(message.contains(part), "{message:?}\ndoes not contain {part:?}");
    }
}
