//! `cargo xtask radiosity-report`: the Cornell box solved by the three
//! solvers to the same residual (steps, hemicubes, time), the residual
//! after each step as a convergence curve (a CSV beside the table), the
//! time to the first useful picture, and the ≈3,000-patch solve.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result};
use zline::radiosity::hemicube::Hemicube;
use zline::radiosity::{solve, Method, Options};

/// A unit square at `origin` spanned by `u`, `v` (front u × v), n × n
/// cells of two triangles, ρ = 0.5, emitting `e`.
fn square(
    origin: glam::Vec3,
    u: glam::Vec3,
    v: glam::Vec3,
    n: usize,
    e: f32,
) -> Vec<zline::radiosity::Patch> {
    let at = |i: usize, j: usize| origin + u * (i as f32 / n as f32) + v * (j as f32 / n as f32);
    let cells = (0..n).flat_map(|i| (0..n).map(move |j| (i, j)));
    cells
        .flat_map(|(i, j)| {
            [[at(i, j), at(i + 1, j), at(i + 1, j + 1)], [at(i, j), at(i + 1, j + 1), at(i, j + 1)]]
        })
        .filter_map(|corners| {
            zline::radiosity::Patch::new(corners, glam::Vec3::splat(0.5), glam::Vec3::splat(e))
        })
        .collect()
}

/// Form factors between unit squares against their closed forms: the
/// hemicube at two resolutions and the analytic point-to-polygon form
/// factor, each averaged over the source square's cells.
fn closed_forms() {
    use glam::Vec3;
    println!(
        "## Form factors against closed forms
"
    );
    println!("| squares | exact | hemicube 100² | hemicube 400² | analytic (Lambert) |");
    println!("|---|---:|---:|---:|---:|");
    let cases = [
        ("parallel, 1 apart", Vec3::new(0.0, 1.0, 1.0), Vec3::X, -Vec3::Y, 0.199_825),
        ("perpendicular, sharing an edge", Vec3::ZERO, Vec3::Z, Vec3::X, 0.200_044),
    ];
    for (name, origin, u, v, exact) in cases {
        let mut patches = square(Vec3::ZERO, Vec3::X, Vec3::Y, 16, 0.0);
        let from = patches.len();
        patches.extend(square(origin, u, v, 1, 0.0));
        let area: f64 = patches[..from].iter().map(|p| f64::from(p.area)).sum();
        let hemicube = |res: usize| {
            let mut cube = Hemicube::new(res);
            let mut row = vec![0.0f32; patches.len()];
            let mut sum = 0.0;
            for k in 0..from {
                row.fill(0.0);
                cube.gather(&patches, k, &mut row);
                sum += f64::from(patches[k].area) * row[from..].iter().map(|&f| f64::from(f)).sum::<f64>();
            }
            sum / area
        };
        let (h100, h400) = (hemicube(100), hemicube(400));
        let analytic: f64 = patches[..from]
            .iter()
            .map(|p| {
                f64::from(p.area)
                    * patches[from..]
                        .iter()
                        .map(|q| {
                            zline::radiosity::analytic::point_to_triangle(p.centre, p.normal, &q.corners)
                        })
                        .sum::<f64>()
            })
            .sum::<f64>()
            / area;
        println!("| {name} | {exact} | {h100:.6} | {h400:.6} | {analytic:.6} |");
    }
    println!();
}

/// The furnace (a closed unit cube seen from inside, E = 1 and ρ = 0.5
/// everywhere: B = 2 exactly) with near patches' form factors from the
/// hemicube and from the contour integral: the worst patch's error.
fn near_patches() {
    use glam::Vec3;
    println!("## Near patches: hemicube or analytic form factors (the furnace, B = 2)\n");
    println!("| cells a side | patches | solver | near form factors | worst patch | mean | time |");
    println!("|---:|---:|---|---|---:|---:|---:|");
    let (o, x, y, z) = (Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z);
    for n in [4, 8] {
        let patches: Vec<_> = [(o, x, y), (z, y, x), (o, z, x), (y, x, z), (o, y, z), (x, z, y)]
            .into_iter()
            .flat_map(|(origin, u, v)| square(origin, u, v, n, 1.0))
            .collect();
        for method in [Method::GaussSeidel, Method::Progressive] {
            for analytic_near in [false, true] {
                let options = Options { method, analytic_near, tolerance: 1e-6, ..Options::default() };
                let start = Instant::now();
                let b = match method {
                    Method::Progressive => {
                        solve::progressive(&patches, &mut Hemicube::new(100), &options, false).0
                    }
                    _ => {
                        let rows = solve::matrix(&patches, 100, analytic_near);
                        solve::sweep(&patches, &rows, true, 1e-6, 1000).0
                    }
                };
                let took = start.elapsed();
                let errors: Vec<f32> = b.iter().map(|b| (b.x - 2.0).abs() / 2.0).collect();
                let worst = errors.iter().copied().fold(0.0f32, f32::max);
                let mean = errors.iter().sum::<f32>() / errors.len() as f32;
                println!(
                    "| {n} | {} | {} | {} | {:.2} % | {:.2} % | {:.2} s |",
                    patches.len(),
                    method.name(),
                    if analytic_near { "analytic" } else { "hemicube" },
                    worst * 100.0,
                    mean * 100.0,
                    took.as_secs_f64()
                );
            }
        }
    }
    println!();
}

pub(crate) fn run(out: &Path) -> Result<()> {
    closed_forms();
    near_patches();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask lives in the workspace");
    let scene = zline::io::load_scene(&root.join("assets/cornell/cornell_box.toml"))?;
    crate::radiosity_subdivision::run(&scene)?;
    println!("## Radiosity: the Cornell box\n");
    println!(
        "Threads: {}. Residual: the power a step left to move over the source power (progressive: the unshot power).\n",
        rayon::current_num_threads()
    );
    println!("| patch size | patches | solver | steps to 10⁻³ | hemicubes (100²) | time |");
    println!("|---:|---:|---|---:|---:|---:|");
    let mut csv = String::from("patches,solver,step,residual\n");
    for (size, methods) in [
        (100.0, &[Method::Jacobi, Method::GaussSeidel, Method::Progressive][..]),
        (50.0, &[Method::GaussSeidel, Method::Progressive][..]),
    ] {
        for &method in methods {
            let options = Options { patch_size: Some(size), method, ..scene.settings.radiosity };
            let solution = solve(&scene, &options)?;
            let n = solution.patches.patches.len();
            for (step, r) in solution.convergence.residuals.iter().enumerate() {
                writeln!(csv, "{n},{},{},{r:e}", method.name(), step + 1)?;
            }
            println!(
                "| {size} | {n} | {} | {} | {} | {:.2} s |",
                method.name(),
                solution.convergence.residuals.len(),
                solution.convergence.hemicubes,
                solution.took.as_secs_f64()
            );
        }
    }
    // The first useful picture: every emitting patch shot once (the
    // ambient term standing for the rest), then one rasterized frame.
    let start = Instant::now();
    let world = zline::trace::world::World::new(&scene);
    let patches = zline::radiosity::Patches::new(&world, 50.0, zline::radiosity::MAX_PATCHES)?;
    let emitters = patches.patches.iter().filter(|p| p.emission != glam::Vec3::ZERO).count();
    let mut cube = Hemicube::new(100);
    let first_options = zline::radiosity::Options { max_steps: emitters, ..Default::default() };
    let (b, convergence) =
        zline::radiosity::solve::progressive(&patches.patches, &mut cube, &first_options, true);
    let solution = zline::radiosity::Solution {
        patches,
        radiosity: b,
        convergence,
        options: Options { patch_size: Some(50.0), ..scene.settings.radiosity },
        splits: Vec::new(),
        took: start.elapsed(),
    };
    let (image, _) = zline::pipeline::render(&solution.display_scene(&scene), &Default::default());
    let first = start.elapsed();
    println!(
        "\nFirst useful picture (patch size 50, {} patches): the {emitters} emitting patches shot once (residual {:.3}), plus one frame: {:.0} ms.",
        solution.patches.patches.len(),
        solution.convergence.residuals.last().copied().unwrap_or(0.0),
        first.as_secs_f64() * 1e3
    );
    std::fs::write(out, csv).with_context(|| format!("writing {}", out.display()))?;
    println!("Convergence curves: {} ({}×{} first picture)", out.display(), image.width, image.height);
    Ok(())
}
