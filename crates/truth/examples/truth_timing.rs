//! Times the truth against the fast renderer on big meshes and prints the
//! error statistics: a 1M-triangle UV sphere and the Stanford bunny (when
//! `assets/obj/bunny/bunny.obj` or the path given as the first argument
//! exists), at 640×360 with ssaa = 1 and 4. At ssaa = 1 it also counts the
//! pixels that break the property tests' bound (away from boundaries, more
//! than ½ + 0.01 step + the truth's sensitivity from the exact colour).
//! The fast renderer in this tree ignores `ssaa`, so its ssaa = 4 figures
//! compare a one-sample image with the supersampled truth.
//!
//! `cargo run --release -p zline-truth --example truth_timing [bunny.obj]`

use std::path::PathBuf;
use std::time::Instant;

use zline_io::{load_obj, scene_for_model};
use zline_pipeline::{render, RenderOptions};
use zline_scene::{uv_sphere, RenderSettings, Scene};
use zline_truth::{render_truth, render_truth_with, ErrorStats, TruthOptions};

fn main() {
    let settings = RenderSettings { width: 640, height: 360, ..RenderSettings::default() };
    let mut scenes = vec![("sphere 1M", scene_for_model(vec![uv_sphere(501, 1000, 1.0)], settings))];
    let bunny =
        std::env::args().nth(1).map(PathBuf::from).unwrap_or_else(|| "assets/obj/bunny/bunny.obj".into());
    match load_obj(&bunny) {
        Ok(meshes) => scenes.push(("bunny", scene_for_model(meshes, settings))),
        Err(e) => eprintln!("skipping the bunny: {e}"),
    }
    println!("threads: {}", rayon::current_num_threads());
    for (name, scene) in &scenes {
        let triangles: usize = scene.objects.iter().map(|o| o.mesh.triangle_count()).sum();
        for ssaa in [1, 4] {
            let scene = Scene { settings: RenderSettings { ssaa, ..scene.settings }, ..scene.clone() };
            let start = Instant::now();
            let truth = render_truth(&scene);
            let truth_time = start.elapsed();
            let start = Instant::now();
            let (image, _) = render(&scene, &RenderOptions::default());
            let fast_time = start.elapsed();
            let e = ErrorStats::of_rgb8(&image.to_rgb(), &truth);
            println!(
                "{name} ({triangles} triangles) ssaa={ssaa}: truth {:.2} s, fast {:.3} s; \
                 rmse {:.3}, max {}, exact {:.2} %, over 1 {:.3} %",
                truth_time.as_secs_f64(),
                fast_time.as_secs_f64(),
                e.rmse,
                e.max_abs,
                100.0 * e.share_exact,
                100.0 * e.share_over_1
            );
            if ssaa == 1 {
                beyond_bound(&scene, &image.to_rgb());
            }
        }
    }
}

/// Prints the pixels of `fast` beyond the property tests' bound.
fn beyond_bound(scene: &Scene, fast: &[u8]) {
    let truth = render_truth_with(scene, &TruthOptions { diagnostics: true, ..TruthOptions::default() });
    let Some(d) = &truth.diagnostics else { return };
    let mut count = 0;
    for (i, c) in truth.rgb.iter().enumerate() {
        if d.boundary_distance[i] < 1.0 {
            continue;
        }
        let excess = (0..3)
            .map(|k| (f64::from(fast[3 * i + k]) - c[k].clamp(0.0, 1.0) * 255.0).abs() - 0.5)
            .fold(f64::MIN, f64::max);
        if excess > 0.01 + f64::from(d.sensitivity[i]) {
            count += 1;
            let (x, y) = (i as u32 % truth.width, i as u32 / truth.width);
            if count <= 5 {
                println!(
                    "  beyond the bound: pixel ({x}, {y}) fast {:?} truth {}",
                    &fast[3 * i..3 * i + 3],
                    *c * 255.0
                );
            }
        }
    }
    println!("  {count} pixels beyond the bound");
}
