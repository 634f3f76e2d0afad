//! Terrain tasks: `cargo xtask terrain-asset` writes the elevation files of
//! assets/terrain/ (deterministic fractal hills); `cargo xtask
//! terrain-bench` times a 4096 × 4096 terrain at 1920 × 1080: the error
//! pyramid, the simplified mesh and the render, separately.

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result};
use zline::pipeline::{RenderOptions, Renderer};
use zline::scene::HeightField;
use zline::scenes::terrain::{fit_camera, terrain_mesh, terrain_scene, ErrorPyramid, Surface, ViewError};

/// The benchmark terrain's cell size and relief: a 10 m elevation model of
/// 41 km with 1500 m from the lowest to the highest point.
const CELL: f32 = 10.0;
const RELIEF: f32 = 1500.0;

/// The seed of the asset's and the benchmark's height fields.
const SEED: u64 = 0x7E44_A1E5;

/// SplitMix64: the generator's random numbers.
struct Random(u64);

impl Random {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [−1, 1).
    fn signed(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 23) as f32 - 1.0
    }
}

/// Diamond-square fractal heights on a (2^n + 1)² grid, `roughness` the
/// amplitude ratio from one level to the next, shaped into hills and
/// valleys (normalized to [0, 1], then raised to the power 1.6: flatter
/// lowland, steeper peaks). Deterministic for a seed.
pub(crate) fn fractal(n: u32, seed: u64, roughness: f32) -> Vec<f32> {
    let side = (1usize << n) + 1;
    let mut h = vec![0.0f32; side * side];
    let mut random = Random(seed);
    for &(x, y) in &[(0, 0), (side - 1, 0), (0, side - 1), (side - 1, side - 1)] {
        h[y * side + x] = random.signed() * 0.5;
    }
    let mut step = side - 1;
    let mut amplitude = 1.0f32;
    while step > 1 {
        let half = step / 2;
        // Diamond step: square centres.
        for y in (half..side).step_by(step) {
            for x in (half..side).step_by(step) {
                let corners =
                    [(x - half, y - half), (x + half, y - half), (x - half, y + half), (x + half, y + half)];
                let mean = corners.iter().map(|&(a, b)| h[b * side + a]).sum::<f32>() / 4.0;
                h[y * side + x] = mean + random.signed() * amplitude;
            }
        }
        // Square step: edge midpoints.
        for y in (0..side).step_by(half) {
            let x0 = if (y / half).is_multiple_of(2) { half } else { 0 };
            for x in (x0..side).step_by(step) {
                let mut sum = 0.0;
                let mut count = 0.0;
                for (dx, dy) in [(-1isize, 0isize), (1, 0), (0, -1), (0, 1)] {
                    let (a, b) = (x as isize + dx * half as isize, y as isize + dy * half as isize);
                    if (0..side as isize).contains(&a) && (0..side as isize).contains(&b) {
                        sum += h[b as usize * side + a as usize];
                        count += 1.0;
                    }
                }
                h[y * side + x] = sum / count + random.signed() * amplitude;
            }
        }
        step = half;
        amplitude *= roughness;
    }
    let (lo, hi) = h.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(l, u), &v| (l.min(v), u.max(v)));
    h.iter_mut().for_each(|v| *v = ((*v - lo) / (hi - lo)).powf(1.6));
    h
}

/// Writes assets/terrain/hills.png (257 × 257, 16-bit greyscale) and
/// assets/terrain/hills-65.asc (its every fourth sample, 65 × 65, heights
/// in metres with 400 m of relief on 40 m cells).
pub(crate) fn write_assets(folder: &Path) -> Result<()> {
    std::fs::create_dir_all(folder).with_context(|| format!("cannot create {}", folder.display()))?;
    let heights = fractal(8, SEED, 0.55);
    let side = 257;
    let samples: Vec<u16> = heights.iter().map(|h| (h * 65535.0).round() as u16).collect();
    let image = image::ImageBuffer::<image::Luma<u16>, _>::from_raw(side as u32, side as u32, samples)
        .context("image size")?;
    let png = folder.join("hills.png");
    image.save(&png).with_context(|| format!("cannot write {}", png.display()))?;
    let mut text = String::from(
        "ncols 65\nnrows 65\nxllcorner 500000\nyllcorner 4100000\ncellsize 40\nNODATA_value -9999\n",
    );
    for row in 0..65 {
        let line: Vec<String> =
            (0..65).map(|col| format!("{:.1}", 200.0 + 400.0 * heights[row * 4 * side + col * 4])).collect();
        text.push_str(&line.join(" "));
        text.push('\n');
    }
    let asc = folder.join("hills-65.asc");
    std::fs::write(&asc, text).with_context(|| format!("cannot write {}", asc.display()))?;
    println!("wrote {} and {}", png.display(), asc.display());
    Ok(())
}

/// Times a 4096 × 4096 fractal terrain (the 4097² fractal cropped, [`CELL`]
/// and [`RELIEF`]) at `size`: error pyramid, simplified mesh,
/// and the median of `frames` renders.
pub(crate) fn bench(size: (u32, u32), error: f32, frames: usize) -> Result<()> {
    let side = 4097;
    let start = Instant::now();
    let full = fractal(12, SEED, 0.55);
    let heights: Vec<f32> =
        (0..4096).flat_map(|y| full[y * side..y * side + 4096].iter().map(|h| h * RELIEF)).collect();
    let field = HeightField::new(4096, 4096, heights, CELL).context("height field")?;
    let generated = start.elapsed();
    let start = Instant::now();
    let pyramid = ErrorPyramid::new(&field);
    let pyramid_time = start.elapsed();
    // The view-dependent steps, each the median of `frames` runs.
    let median = |f: &mut dyn FnMut()| {
        let mut times: Vec<_> = (0..frames.max(1))
            .map(|_| {
                let start = Instant::now();
                f();
                start.elapsed()
            })
            .collect();
        times.sort();
        times[times.len() / 2]
    };
    let aspect = size.0 as f32 / size.1 as f32;
    let camera = fit_camera(&field, aspect);
    let fit_time = median(&mut || {
        std::hint::black_box(fit_camera(&field, aspect));
    });
    let view = ViewError::new(&camera, size.0, size.1, error);
    let grid = pyramid.simplify(&view);
    let simplify_time = median(&mut || drop(std::hint::black_box(pyramid.simplify(&view))));
    let mesh_time =
        median(&mut || drop(std::hint::black_box(terrain_mesh(&field, &grid, &Surface::HeightRamp))));
    let scene_time = median(&mut || {
        drop(std::hint::black_box(terrain_scene(&field, &pyramid, &Surface::HeightRamp, size, error, true)))
    });
    let (scene, stats) = terrain_scene(&field, &pyramid, &Surface::HeightRamp, size, error, true)?;
    let mut renderer = Renderer::default();
    let options = RenderOptions::default();
    let mut times = Vec::new();
    let mut image = zline::pipeline::Image::empty();
    for _ in 0..frames.max(1) + 1 {
        let start = Instant::now();
        renderer.render_into(&scene, &options, &mut image);
        times.push(start.elapsed());
    }
    times.remove(0);
    times.sort();
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    println!(
        "terrain 4096x4096 at {}x{}, {} px error, {} threads: {} triangles drawn of the full grid's {} ({:.3} %)",
        size.0,
        size.1,
        error,
        rayon::current_num_threads(),
        stats.triangles,
        stats.full_grid_triangles,
        100.0 * stats.triangles as f64 / stats.full_grid_triangles as f64
    );
    println!(
        "generate {:.0} ms; error pyramid {:.0} ms; view-dependent: camera fit {:.1} ms, simplify {:.1} ms, \
         mesh {:.1} ms, all three (terrain_scene) {:.1} ms; render {:.1} ms (medians of {})",
        ms(generated),
        ms(pyramid_time),
        ms(fit_time),
        ms(simplify_time),
        ms(mesh_time),
        ms(scene_time),
        ms(times[times.len() / 2]),
        times.len()
    );
    Ok(())
}
