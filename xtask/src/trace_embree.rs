//! `cargo xtask trace-report --embree`: zline's BVH against Embree's on one
//! thread, the same scenes, cameras and frame size, alternated round by
//! round so that the machine's drift falls on both.
//!
//! Embree is Debian's `embree-tools` (its `viewer`, `--benchmark 4 16`,
//! which prints the mean Mrays/s of 16 frames after 4 warm-up frames):
//! camera rays with the `eyelight` shader (nearest hits, shaded) and with
//! the `occlusion` shader (any hit, the shadow-ray query). zline traces
//! the same camera rays in the viewer's order (8 × 8 tiles), nearest hits
//! with `closest` and any hit with `each_hit` stopping at the first, the
//! mean of 16 passes after 4 warm-up passes. The builds beside each other:
//! Embree's (`--rtcore verbose=2`: its BVH8's build time and SAH cost,
//! in its own cost units) and zline's (its binary tree's SAH cost,
//! [`Bvh::sah_cost`]: not the same units).

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, Result};
use zline::trace::accel::bvh::Bvh;
use zline::trace::accel::{Accelerator, Counters};
use zline::trace::ray::Ray;

use crate::trace_report::{frame, sphere_case, Case};

/// The viewer's tile edge, in pixels.
const TILE: usize = 8;

/// One scene: zline's case and the viewer's arguments for the same one.
struct Pair {
    case: Case,
    embree: Vec<String>,
}

pub(crate) fn run(rounds: usize) -> Result<()> {
    let rounds = rounds.max(1);
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask lives in the workspace");
    let cornell = root.join("assets/cornell");
    let args = |s: &str| s.split_whitespace().map(String::from).collect::<Vec<_>>();
    let mut cornell_args = vec!["-i".to_string(), cornell.join("cornell_box.obj").display().to_string()];
    cornell_args.extend(args("--vp 278 273 -800 --vi 278 273 0 --fov 39.3 --size 640 640"));
    let sphere = |n: u32| {
        args(&format!("--triangle-sphere 0 0 0 1 {n} --vp 0 0 3.2 --vi 0 0 0 --fov 42 --size 640 480"))
    };
    let pairs = vec![
        Pair {
            case: frame("Cornell box", &zline::io::load_scene(&cornell.join("cornell_box.toml"))?, 640),
            embree: cornell_args,
        },
        // Embree's sphere of 223 (707) has zline's 198,024 (1,996,568)
        // triangles.
        Pair { case: sphere_case("sphere 200k", 200_000, 640), embree: sphere(223) },
        Pair { case: sphere_case("sphere 2M", 2_000_000, 640), embree: sphere(707) },
    ];
    let embree = viewer_works();
    if !embree {
        println!("Embree's `viewer` (Debian's embree-tools) is not installed: zline's figures alone.\n");
    }
    println!("## zline against Embree, one thread\n");
    println!("Mrays/s, the median of {rounds} alternated rounds (each round's lowest and highest ratio in brackets).\n");
    println!(
        "| scene | triangles | Embree build (SAH) | zline build (SAH) | Embree camera | zline camera | ratio | Embree occlusion | zline any hit | ratio |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for pair in &pairs {
        let start = Instant::now();
        let bvh = Bvh::build(&pair.case.triangles);
        let build = start.elapsed().as_secs_f64();
        let embree_build = if embree { embree_build(&pair.embree)? } else { "—".into() };
        let rays = tiled(&pair.case.camera, 640);
        let mut figures: Vec<[f64; 4]> = Vec::new();
        for _ in 0..rounds {
            let e_camera = if embree { viewer(&pair.embree, "eyelight")? } else { f64::NAN };
            let z_camera = mrays(&rays, |r, c| bvh.closest(&pair.case.triangles, r, c).is_some());
            let e_any = if embree { viewer(&pair.embree, "occlusion")? } else { f64::NAN };
            let z_any = mrays(&rays, |r, c| !bvh.each_hit(&pair.case.triangles, r, c, &mut |_| false));
            figures.push([e_camera, z_camera, e_any, z_any]);
        }
        let median = |k: usize| {
            let mut v: Vec<f64> = figures.iter().map(|f| f[k]).collect();
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let spread = |z: usize, e: usize| {
            let r: Vec<f64> = figures.iter().map(|f| f[z] / f[e]).collect();
            let lo = r.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = r.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            format!("**{:.2}** ({lo:.2}–{hi:.2})", median(z) / median(e))
        };
        println!(
            "| {} | {} | {embree_build} | {:.1} ms, {:.2} Mprims/s ({:.1}) | {:.2} | {:.2} | {} | {:.2} | {:.2} | {} |",
            pair.case.name,
            pair.case.triangles.len(),
            build * 1e3,
            pair.case.triangles.len() as f64 / build / 1e6,
            bvh.sah_cost(),
            median(0),
            median(1),
            spread(1, 0),
            median(2),
            median(3),
            spread(3, 2),
        );
    }
    Ok(())
}

/// Whether Embree's viewer runs here.
fn viewer_works() -> bool {
    // Its --help exits with 1 and prints to stdout.
    Command::new("viewer")
        .arg("--help")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).contains("--shader"))
}

/// Embree's mean Mrays/s over 16 frames of the viewer with `shader`.
fn viewer(args: &[String], shader: &str) -> Result<f64> {
    let out = Command::new("viewer")
        .args(["--threads", "1", "--shader", shader, "--benchmark", "4", "16"])
        .args(args)
        .output()
        .context("running Embree's viewer")?;
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text
        .lines()
        .find_map(|l| l.strip_prefix("BENCHMARK_RENDER_MRAYPS_AVG "))
        .with_context(|| format!("no BENCHMARK_RENDER_MRAYPS_AVG in the viewer's output: {text}"))?;
    Ok(line.trim().parse()?)
}

/// Embree's build of the scene, from its verbose report: "T ms, R
/// Mprims/s (SAH)".
fn embree_build(args: &[String]) -> Result<String> {
    let out = Command::new("viewer")
        .args(["--threads", "1", "--rtcore", "verbose=2", "--benchmark", "0", "1"])
        .args(args)
        .output()
        .context("running Embree's viewer")?;
    let text = String::from_utf8_lossy(&out.stdout);
    // "finished BVH8<triangle4> : 82.1481ms, 2.4106 Mprim/s, 0.1502 GB/s"
    let finished =
        text.lines().find(|l| l.starts_with("finished BVH")).context("no build line from Embree")?;
    let mut figures = finished.split(':').nth(1).unwrap_or("").split(',');
    let ms: f64 = figures.next().unwrap_or("").trim().trim_end_matches("ms").parse()?;
    let rate: f64 = figures.next().unwrap_or("").trim().trim_end_matches(" Mprim/s").parse()?;
    // "  total            : sah =  14.019 (100.00%), ..."
    let sah = text
        .lines()
        .find(|l| l.trim_start().starts_with("total") && l.contains("sah ="))
        .and_then(|l| l.split("sah =").nth(1)?.split_whitespace().next()?.parse::<f64>().ok())
        .context("no SAH cost from Embree")?;
    Ok(format!("{ms:.1} ms, {rate:.2} Mprims/s ({sah:.1})"))
}

/// The row-major `rays` of a frame `width` pixels wide, in 8 × 8 tiles,
/// tiles and pixels row by row (the viewer's order).
fn tiled(rays: &[Ray], width: usize) -> Vec<Ray> {
    let height = rays.len() / width;
    let mut out = Vec::with_capacity(rays.len());
    for ty in (0..height).step_by(TILE) {
        for tx in (0..width).step_by(TILE) {
            for y in ty..(ty + TILE).min(height) {
                for x in tx..(tx + TILE).min(width) {
                    out.push(rays[y * width + x]);
                }
            }
        }
    }
    out
}

/// Mrays/s of `trace` over `rays`: the mean of 16 passes after 4.
fn mrays(rays: &[Ray], trace: impl Fn(&Ray, &mut Counters) -> bool) -> f64 {
    let mut count = Counters::default();
    let mut pass = || rays.iter().filter(|r| trace(r, &mut count)).count();
    for _ in 0..4 {
        std::hint::black_box(pass());
    }
    let start = Instant::now();
    for _ in 0..16 {
        std::hint::black_box(pass());
    }
    (16 * rays.len()) as f64 / start.elapsed().as_secs_f64() / 1e6
}
