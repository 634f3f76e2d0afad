//! `cargo xtask versus`: zline against Mesa's llvmpipe on glref's benchmark
//! scenes, timed interleaved in one run.
//!
//! Each scene exists twice: as glref's JSON (`<glref>/scenes/*.json`) and as
//! a zline scene file with the same camera, lights, meshes and materials
//! (`benches/glref/*.toml`, whose meshes are glref's generated ones). A round
//! times every scene with zline at each thread count (in this process, warm
//! frames) and then with glref under llvmpipe (a child process that prints
//! the median of its own warm frames); the table reports the median of the
//! round medians and llvmpipe's time divided by zline's. The machine's speed
//! drifts over minutes, so only ratios from one interleaved run mean much.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, Context, Result};
use zline::pipeline::{RenderOptions, RenderStats};
use zline::scene::Scene;

/// The benchmark scenes, in the order of issue 9's table: glref's JSON name
/// and a label.
const SCENES: [(&str, &str); 6] = [
    ("sphere_flat", "sphere flat"),
    ("sphere_gouraud", "sphere Gouraud"),
    ("sphere_phong", "sphere Phong"),
    ("textured_plane_fog", "textured plane + fog (bilinear)"),
    ("transparent", "transparent spheres"),
    ("big", "1M-triangle sphere"),
];

/// What `versus` is asked to do (its command-line arguments).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// glref's folder (its setup.sh builds glref and the meshes).
    #[arg(long, default_value = "../shared/tools/glref")]
    pub glref: PathBuf,
    /// Interleaved rounds.
    #[arg(long, default_value_t = 3)]
    pub rounds: usize,
    /// Warm frames timed per scene and renderer in a round.
    #[arg(long, default_value_t = 15)]
    pub frames: usize,
    /// zline's thread counts; the ratio uses the last.
    #[arg(long, value_delimiter = ',', default_value = "1,2")]
    pub threads: Vec<usize>,
    /// llvmpipe's rasterizer threads (LP_NUM_THREADS).
    #[arg(long, default_value_t = 2)]
    pub lp_threads: usize,
    /// Only scenes whose name contains this text.
    #[arg(long)]
    pub filter: Option<String>,
    /// Time zline alone (llvmpipe's columns stay empty): for comparing
    /// two builds of zline run alternately.
    #[arg(long)]
    pub zline_only: bool,
    /// Also print zline's stage times (geometry, binning, raster;
    /// medians) per scene and thread count.
    #[arg(long)]
    pub stages: bool,
    /// Draw every back face, as glref asks llvmpipe to (no culling):
    /// the same work on both sides. By default zline culls the closed,
    /// opaque meshes, as it does for any user (SPEC §2).
    #[arg(long)]
    pub no_culling: bool,
}

/// The zline scene files, next to the workspace root.
fn scene_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../benches/glref")
}

/// How the scene files name glref's folder: its default place, relative
/// to `benches/glref`.
const GLREF_IN_SCENES: &str = "../../../shared/tools/glref/";

/// Scene `name` with its meshes and textures read from `glref` (the scene
/// files name glref's default place): a copy with the paths rewritten,
/// loaded from the temporary folder.
fn load_scene(name: &str, glref: &Path) -> Result<Scene> {
    let toml = scene_dir().join(format!("{name}.toml"));
    let text = std::fs::read_to_string(&toml).with_context(|| format!("{}: cannot read", toml.display()))?;
    let folder = glref.canonicalize().with_context(|| format!("{}: no such folder", glref.display()))?;
    let folder = folder.to_str().context("glref's path is not UTF-8")?.replace('\\', "/");
    if folder.contains('"') {
        bail!("{folder}: a quote in glref's path cannot go into a scene file");
    }
    let copy = std::env::temp_dir().join(format!("zline-versus-{}-{name}.toml", std::process::id()));
    std::fs::write(&copy, text.replace(GLREF_IN_SCENES, &format!("{folder}/")))
        .with_context(|| format!("{}: cannot write", copy.display()))?;
    let options = zline::io::LoadOptions { allow_outside: true };
    let scene = zline::io::load_scene_with_options(&copy, options);
    // The copy is only read here; a failed removal leaves a small file.
    let _ = std::fs::remove_file(&copy);
    scene.with_context(|| {
        format!("{} with glref at {folder}: (the meshes come from glref's setup.sh)", toml.display())
    })
}

struct Entry {
    label: &'static str,
    json: PathBuf,
    scene: Scene,
    triangles: usize,
    /// Per thread count (in `Args::threads` order), the median of each round.
    zline: Vec<Vec<f64>>,
    /// Per thread count, each round's median geometry, binning and raster ms.
    stages: Vec<Vec<[f64; 3]>>,
    llvmpipe: Vec<f64>,
}

pub(crate) fn run(args: &Args) -> Result<()> {
    let program = args.glref.join("glref");
    if !program.exists() && !args.zline_only {
        bail!(
            "{} is missing: build glref first ({}/setup.sh installs Mesa and makes it)",
            program.display(),
            args.glref.display()
        );
    }
    let mut entries = Vec::new();
    for (name, label) in SCENES {
        if args.filter.as_deref().is_some_and(|f| !name.contains(f) && !label.contains(f)) {
            continue;
        }
        let mut scene = load_scene(name, &args.glref)?;
        if args.no_culling {
            scene.objects.iter_mut().for_each(|o| o.cull_back_faces = false);
        }
        let triangles = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
        entries.push(Entry {
            label,
            json: args.glref.join("scenes").join(format!("{name}.json")),
            scene,
            triangles,
            zline: vec![Vec::new(); args.threads.len()],
            stages: vec![Vec::new(); args.threads.len()],
            llvmpipe: Vec::new(),
        });
    }
    let pools = args
        .threads
        .iter()
        .map(|&t| rayon::ThreadPoolBuilder::new().num_threads(t).build().context("thread pool"))
        .collect::<Result<Vec<_>>>()?;
    for round in 1..=args.rounds {
        for entry in &mut entries {
            eprintln!("round {round}/{}: {}", args.rounds, entry.label);
            for ((pool, times), stages) in pools.iter().zip(&mut entry.zline).zip(&mut entry.stages) {
                let (time, split) = time_zline(&entry.scene, pool, args.frames);
                times.push(time);
                stages.push(split);
            }
            if !args.zline_only {
                entry.llvmpipe.push(time_llvmpipe(&program, &entry.json, args)?);
            }
        }
    }

    let mut header = String::from("| scene | triangles |");
    let mut rule = String::from("|---|---:|");
    for t in &args.threads {
        header += &format!(" zline {t} thread{} |", if *t == 1 { "" } else { "s" });
        rule += "---:|";
    }
    header += &format!(
        " llvmpipe {} threads | llvmpipe ÷ zline ({} threads) |",
        args.lp_threads,
        last(&args.threads)
    );
    rule += "---:|---:|";
    println!("{header}\n{rule}");
    for entry in &entries {
        let mut row = format!("| {} | {} |", entry.label, entry.triangles);
        for times in &entry.zline {
            row += &format!(" {:.2} ms |", median(times));
        }
        if args.zline_only {
            row += " – | – |";
        } else {
            let lp = median(&entry.llvmpipe);
            let ours = median(entry.zline.last().map_or(&[][..], |v| &v[..]));
            row += &format!(" {lp:.2} ms | {:.2} |", lp / ours);
        }
        println!("{row}");
    }
    if args.stages {
        println!("\n| scene | threads | geometry ms | binning ms | raster ms |\n|---|---:|---:|---:|---:|");
        for entry in &entries {
            for (t, stages) in args.threads.iter().zip(&entry.stages) {
                let m = |k: usize| median(&stages.iter().map(|s| s[k]).collect::<Vec<_>>());
                println!("| {} | {t} | {:.2} | {:.2} | {:.2} |", entry.label, m(0), m(1), m(2));
            }
        }
    }
    println!(
        "\n{} rounds; a round times each scene with zline ({} warm frames per thread count, median) then llvmpipe (glref -n {}, LP_NUM_THREADS={}); the table shows the median of the round medians.",
        args.rounds, args.frames, args.frames, args.lp_threads
    );
    let culled: Vec<String> = entries
        .iter()
        .map(|e| {
            let culled = e.scene.objects.iter().filter(|o| o.cull_back_faces).count();
            format!("{} {culled} of {}", e.label, e.scene.objects.len())
        })
        .collect();
    println!(
        "Objects whose back faces zline culls (closed, opaque meshes, SPEC §2; llvmpipe draws every back face{}): {}.",
        if args.no_culling { "; --no-culling: zline too" } else { "; --no-culling draws them in zline too" },
        culled.join(", ")
    );
    Ok(())
}

fn last(threads: &[usize]) -> usize {
    threads.last().copied().unwrap_or(1)
}

/// Median ms of `frames` warm frames of `scene` drawn in `pool`, and the
/// medians of its stages (geometry, binning, raster).
fn time_zline(scene: &Scene, pool: &rayon::ThreadPool, frames: usize) -> (f64, [f64; 3]) {
    let runs = crate::bench::time_frames(scene, (pool, None), &RenderOptions::default(), frames);
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    let stage = |f: fn(&RenderStats) -> std::time::Duration| {
        median(&runs.iter().map(|(_, s)| ms(f(s))).collect::<Vec<_>>())
    };
    (runs[runs.len() / 2].0 * 1e3, [stage(|s| s.geometry), stage(|s| s.binning), stage(|s| s.raster)])
}

/// glref's own median over `frames` warm frames under llvmpipe.
fn time_llvmpipe(program: &Path, json: &Path, args: &Args) -> Result<f64> {
    let out = Command::new(program)
        .arg(json)
        .args(["-n", &args.frames.max(1).to_string(), "-q", "--size", "1920x1080"])
        .env("GALLIUM_DRIVER", "llvmpipe")
        .env("LP_NUM_THREADS", args.lp_threads.to_string())
        .output()
        .with_context(|| format!("running {}", program.display()))?;
    let text = String::from_utf8_lossy(&out.stdout);
    if !out.status.success() {
        bail!(
            "{} {} failed: {}{}",
            program.display(),
            json.display(),
            text,
            String::from_utf8_lossy(&out.stderr)
        );
    }
    parse_median(&text).with_context(|| format!("no median_ms in glref's output: {text}"))
}

/// The number after `median_ms:` in glref's summary line.
fn parse_median(text: &str) -> Option<f64> {
    let mut words = text.split_whitespace();
    words.by_ref().find(|w| *w == "median_ms:")?;
    words.next()?.parse().ok()
}

fn median(values: &[f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted[sorted.len() / 2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_glref_summary() {
        let line =
            "frames: 15 size: 1920x1080 median_ms: 4.903 min_ms: 4.7 first_ms: 30.1 renderer: llvmpipe";
        assert_eq!(parse_median(line), Some(4.903));
        assert_eq!(parse_median("frames: 15"), None);
    }

    #[test]
    fn every_scene_has_its_zline_file() {
        for (name, _) in SCENES {
            let text = std::fs::read_to_string(scene_dir().join(format!("{name}.toml"))).unwrap();
            // Every file it reads is glref's, named the way `load_scene` rewrites.
            assert!(text.contains(GLREF_IN_SCENES), "{name}.toml");
            let models = text.lines().filter(|l| l.trim_start().starts_with("model")).count();
            let glref = text.lines().filter(|l| l.contains(GLREF_IN_SCENES)).count();
            assert!(models >= 1 && glref >= models, "{name}.toml");
        }
    }

    #[test]
    fn a_missing_glref_folder_is_named() {
        let err = load_scene("sphere_flat", Path::new("/nonexistent/glref")).unwrap_err();
        assert!(format!("{err:#}").contains("/nonexistent/glref: no such folder"), "{err:#}");
    }
}
