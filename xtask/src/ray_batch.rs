//! `cargo xtask ray-batch`: runs the Ray recipe of docs/ray_batch.py on a
//! local Ray cluster with one worker killed mid-shard, then checks that the
//! folder it fills holds exactly the images of a one-machine
//! `zline batch`, byte for byte. Skipped, with a message, where Python or
//! Ray is missing (`pip install ray`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use anyhow::{bail, Context, Result};

/// The models of `assets/` the batch renders (every format zline reads).
const INPUTS: &[&str] = &[
    "assets/obj/spot/spot.obj",
    "assets/obj/suzanne/suzanne.obj",
    "assets/bump/sphere.obj",
    "assets/ply/bunny_lowres.ply",
    "assets/gltf/Box/glTF-Binary/Box.glb",
    "assets/gltf/BoxTextured/glTF/BoxTextured.gltf",
    "assets/gltf/VertexColorTest/glTF-Binary/VertexColorTest.glb",
    "assets/gltf/TextureCoordinateTest/glTF/TextureCoordinateTest.gltf",
];

/// Runs the recipe with `shards` Ray tasks at image size `size`.
pub(crate) fn run(shards: u32, size: &str) -> Result<()> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().context("the workspace root")?.to_path_buf();
    let has_ray = Command::new("python3").args(["-c", "import ray"]).output();
    if !has_ray.is_ok_and(|o| o.status.success()) {
        println!("skipped: Python 3 with Ray not found (pip install ray)");
        return Ok(());
    }
    let status = Command::new(env!("CARGO"))
        .args(["build", "--release", "--package", "zline", "--bin", "zline"])
        .current_dir(&root)
        .status()?;
    if !status.success() {
        bail!("cargo build of zline failed");
    }
    let target = std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root.join("target"), PathBuf::from);
    let zline = target.join("release/zline");
    let inputs: Vec<String> = INPUTS.iter().map(|p| root.join(p).display().to_string()).collect();
    let work = tempfile::tempdir()?;
    let (on_ray, alone) = (work.path().join("ray"), work.path().join("alone"));

    let started = Instant::now();
    let out = Command::new("python3")
        .arg(root.join("docs/ray_batch.py"))
        .args(["--zline", &zline.display().to_string(), "--shards", &shards.to_string()])
        .args(["-o", &on_ray.display().to_string(), "--kill-first-attempt"])
        .args(&inputs)
        .args(["--", "--size", size])
        .output()?;
    let ray_time = started.elapsed();
    let log = String::from_utf8_lossy(&out.stdout);
    for line in log.lines().filter(|l| l.contains("shard")) {
        println!("ray: {}", without_colours(line));
    }
    if !out.status.success() {
        bail!("the Ray recipe failed: {}\n{}", out.status, String::from_utf8_lossy(&out.stderr));
    }
    let killed =
        String::from_utf8_lossy(&out.stderr).contains("killed after") || log.contains("killed after");
    if !killed {
        bail!("the first attempt of shard 1 was not killed: the test did not test retries");
    }

    let status = Command::new(&zline)
        .arg("batch")
        .args(&inputs)
        .args(["-o", &alone.display().to_string(), "--quiet", "--size", size])
        .status()?;
    if !status.success() {
        bail!("zline batch on one machine failed");
    }
    let (a, b) = (images(&on_ray)?, images(&alone)?);
    println!(
        "{} images on Ray ({shards} shards, one worker killed and retried, {:.1} s with Ray's start-up), {} alone",
        a.len(),
        ray_time.as_secs_f64(),
        b.len()
    );
    if a.len() != INPUTS.len() || a != b {
        let differ: Vec<_> = b.keys().filter(|k| a.get(*k) != b.get(*k)).collect();
        bail!("the Ray batch differs from one machine's: {differ:?} (Ray has {:?})", a.keys());
    }
    println!("ok: the same {} PNGs byte for byte", a.len());
    Ok(())
}

/// The PNGs of `dir` by name (temporary files left by the killed worker
/// are dot files and not counted).
fn images(dir: &Path) -> Result<BTreeMap<String, Vec<u8>>> {
    let mut out = BTreeMap::new();
    for entry in std::fs::read_dir(dir).with_context(|| dir.display().to_string())? {
        let name = entry?.file_name().to_string_lossy().into_owned();
        if name.ends_with(".png") && !name.starts_with('.') {
            out.insert(name.clone(), std::fs::read(dir.join(&name))?);
        }
    }
    Ok(out)
}

/// `line` without its ANSI colour sequences (Ray colours its log prefixes).
fn without_colours(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut chars = line.chars();
    while let Some(c) = chars.next() {
        if c == '\u{1b}' {
            // ESC [ parameters, up to the final letter.
            for c in chars.by_ref() {
                if c.is_ascii_alphabetic() {
                    break;
                }
            }
        } else {
            out.push(c);
        }
    }
    out
}
